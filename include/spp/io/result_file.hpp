#pragma once
// Result files of spp solve: {"system": {...}, "window", "status", "symmetry", "warnings", "stats", "uncertified",
// "solutions": [{"t1", "t2", "period", "admissible", "min_gap", "min_force", "x0", "v0", "energy", "residual",
// "return_error", ..., "orbit": {"a", "c", "p0", "p0dot", "closure_ratio", "energy"}}]}. The whole system is embedded
// (after normalising w) so that a result can be verified, plotted or animated alone.
// The modal coordinates ("orbit") belong to the modal basis of the machine that wrote the file; every function that
// takes an orbit rebuilds them from x0, v0 where the basis differs (in_modal_basis, orbit/orbit.hpp), so a file is
// read alike on any machine, and a file without "orbit" is read with empty modal coordinates. Cost: linear in the file (the system's 2 n^2 + n numbers plus
// solutions x ~(4n + 4m) numbers); reading holds the text and its JSON tree at once (~3x the file's size).

#include <string>
#include <vector>

#include "spp/core/system.hpp"
#include "spp/search/solver.hpp"

namespace spp {

/// The result file's text. indent < 0: one line.
std::string result_json(const System& system, const SolveResult& result, int indent = 2);
/// A result file as written: the system it was solved for and the SolveResult.
struct ResultFile {
  System system;
  SolveResult result;
};
/// The system and the SolveResult that result_json wrote, every field (tested: write, read, compare), the file read
/// and parsed once. Throws std::invalid_argument naming the file and the field it cannot read, and the fields that
/// contradict each other (a "success" beside unproved work, fewer SPPs listed than roots counted when non-admissible
/// ones are kept, a residual the solver would not accept, a period other than 2 (t1 + t2), a window end <= 0, ...).
/// A pure reader, linear in the file: it does not check an SPP against the system's equations (x0, v0 edited by
/// 1e-3 read as written), which needs the modal form (O(n^3), ~1 s at n = 1000, on every read). spp verify (state
/// mismatch, exit 3), verify() and spp trajectory --result recompute x0, v0 from (t1, t2) and refuse an edited file.
ResultFile load_result_file(const std::string& path);
/// The same from the file's text (`where` names it in errors): what Python's pickling reads back.
ResultFile parse_result_file(const std::string& text, const std::string& where);
/// Parts of the above, for a caller that needs one.
SolveResult load_result(const std::string& path);
SolveResult parse_result(const std::string& text, const std::string& where);
System load_result_system(const std::string& path);

}  // namespace spp
