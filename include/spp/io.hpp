#pragma once
// Files: the system JSON (dense, or M/K from Matrix Market), result JSON and CSV, trajectory CSV.
// Every writer goes through write_file_atomic: a temporary file renamed over the target, so that a failure
// never leaves a half-written output.

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <string>

#include "spp/continuation.hpp"
#include "spp/parametric.hpp"
#include "spp/simulator.hpp"
#include "spp/solver.hpp"
#include "spp/system.hpp"
#include "spp/verify.hpp"

namespace spp {

/// Reads {"name", "M", "K", "w", "g0"}; "M"/"K" may be {"matrix_market": "file.mtx"} (relative to the JSON).
/// Throws std::invalid_argument naming the file and the field.
System load_system(const std::string& path);
System system_from_json(const nlohmann::json& j, const std::string& where, const std::string& base_dir = ".");
nlohmann::json system_to_json(const System& system);

/// A parametric system file: a system file with "parameter": {"name": "k2", "min": 1, "max": 10} in which each
/// of M, K and w is either a value or {"constant": value, "k2": value} (affine in the parameter). Throws
/// std::invalid_argument naming the file and the field. load_system refuses such a file with a pointer here.
ParametricSystem load_parametric_system(const std::string& path);
ParametricSystem parametric_system_from_json(const nlohmann::json& j, const std::string& where,
                                             const std::string& base_dir = ".");
bool declares_parameter(const nlohmann::json& j);
nlohmann::json parametric_system_to_json(const ParametricSystem& system);

/// Branches, their points and events, and the §6.1 zero-gap SPPs (gap closures when g0 = 0).
nlohmann::json continuation_to_json(const ParametricSystem& system, const ContinuationResult& result);
/// Human-readable: one row per branch event.
std::string continuation_table(const ContinuationResult& result);
/// Zero-gap SPPs (g0 = 0, paper §6.1) as a solve result: each solution with "parameter": {"name", "value"}.
nlohmann::json zero_gap_to_json(const ParametricSystem& system, const ContinuationResult& result);
std::string zero_gap_table(const ContinuationResult& result);

/// Matrix Market "matrix array|coordinate real|integer general|symmetric".
Eigen::MatrixXd read_matrix_market(const std::string& path);

/// The result embeds the whole system (M, K, w, g0: after normalising w), so that it can be verified, plotted or
/// animated alone.
nlohmann::json result_to_json(const System& system, const SolveResult& result);
/// Parses a result JSON of spp solve: its system and its solutions. Throws std::invalid_argument naming the field.
nlohmann::json read_json_file(const std::string& path);
System result_system(const nlohmann::json& result, const std::string& where);
std::vector<SppCandidate> result_candidates(const nlohmann::json& result, const std::string& where);
/// The SolveResult that result_to_json wrote (every field; the system: result_system). Throws std::invalid_argument
/// naming the field it cannot read.
SolveResult result_from_json(const nlohmann::json& result, const std::string& where);
/// Reads a result file of spp solve: load_result(path) after writing result_to_json gives back the same SolveResult.
SolveResult load_result(const std::string& path);
std::string result_to_csv(const SolveResult& result);
/// Human-readable table (t1, t2, period, admissible, min gap, min force).
std::string result_table(const SolveResult& result);

/// Samples one period of an orbit: t, x1..xn, v1..vn, gap, force.
std::string trajectory_csv(const ModalForm& modal, const Orbit& orbit, int samples);

/// Simulation samples: t, x1..xn, v1..vn, gap, force, contact (0/1).
std::string simulation_csv(const SimulationResult& result);
/// Events: t, event, normal velocity before and after, force, x1..xn, v1..vn (after the event).
std::string events_csv(const SimulationResult& result);

nlohmann::json verify_to_json(const VerifyResult& result);
/// Human-readable verification table.
std::string verify_table(const VerifyResult& result);

void write_file_atomic(const std::string& path, const std::string& content);
std::string read_file(const std::string& path);

}  // namespace spp
