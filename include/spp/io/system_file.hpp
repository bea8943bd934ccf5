#pragma once
// System files: {"name", "description", "M", "K", "w", "g0"} (M, K n x n lists of rows, or {"matrix_market":
// "file.mtx"} relative to the JSON file; w a list of n numbers), and parametric system files (the same with
// "parameter": {"name": "k2", "min": 1, "max": 10} and each of M, K, w either a value or {"constant": value,
// "k2": value}, affine in the parameter). Unknown fields and keys given twice are refused.
// Units are the user's (consistent ones: spp is invariant under their change). Cost: linear in the file; a dense
// system holds M and K (16 n^2 bytes), and reading holds the text and its JSON tree at once (~3x the file's size).

#include <string>
#include <vector>

#include "spp/core/parametric.hpp"
#include "spp/core/sparse_system.hpp"
#include "spp/core/system.hpp"

namespace spp {

/// Throws std::invalid_argument naming the file and the field (and refuses a parametric file, with a pointer to
/// load_parametric_system).
System load_system(const std::string& path);
/// Throws std::invalid_argument naming the file and the field.
ParametricSystem load_parametric_system(const std::string& path);
/// True when the JSON file declares a "parameter" (read it with load_parametric_system).
bool file_declares_parameter(const std::string& path);
/// The files that loading the system file `path` reads: itself and each Matrix Market file it names, resolved as the
/// loaders resolve them (an output must be none of them). Empty for an empty path; throws like load_system when the
/// file cannot be read as JSON.
std::vector<std::string> system_file_inputs(const std::string& path);

/// The same system file held sparse (a large finite-element model: any size; Matrix Market files are read sparse, lists
/// of rows converted). Throws std::invalid_argument naming the file and the field; refuses a parametric file.
SparseSystem load_sparse_system(const std::string& path);
/// The Matrix Market files write_sparse_system writes next to `json_path`: "<stem>.M.mtx" and "<stem>.K.mtx".
std::vector<std::string> sparse_system_matrix_files(const std::string& json_path);
/// Writes the system file `json_path` with "M" and "K" as {"matrix_market": "<stem>.M.mtx"} (symmetric coordinate
/// files beside it, 17 digits) and w as a list of n numbers: load_system (small n) and load_sparse_system read it.
/// Each file is written atomically, the matrices first.
void write_sparse_system(const SparseSystem& system, const std::string& json_path, const std::string& description = "");

/// The system file's text (load_system reads it back). indent < 0: one line.
std::string system_json(const System& system, int indent = 2);
std::string parametric_system_json(const ParametricSystem& system, int indent = 2);

}  // namespace spp
