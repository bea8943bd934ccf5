#pragma once
// Result files of spp continue: {"system", "symmetry", "window", "warnings", "stats", "branches": [{"points": [...],
// "events": [...]}]}, each point {"<parameter>", "t1", "t2", "period", "closure", "energy", "x0", "v0", "margin",
// "admissible", "spectral_radius"}, each event a point with "event", "detail" and, for stability_lost /
// stability_gained, "crossing" ("plus_one", "minus_one", "complex_pair"), "crossing_multipliers" ([re, im] pairs) and
// "crossing_angle" (rad, in [0, pi]); and of the zero-gap solve (g0 = 0, paper §6.1) as a solve result, each solution with
// "parameter": {"name", "value"}.
// Cost: linear in the output (points x n numbers, ~20 characters each); times in the system's unit.

#include <string>

#include "spp/continuation/continuation.hpp"
#include "spp/core/parametric.hpp"

namespace spp {

/// indent < 0: one line.
std::string continuation_json(const ParametricSystem& system, const ContinuationResult& result, int indent = 1);
/// A continuation file as written: the parametric system and the ContinuationResult.
struct ContinuationFile {
  ParametricSystem system;
  ContinuationResult result;
};
/// The system and the result that continuation_json wrote, every field (tested: write, read, compare); files written
/// before the stability crossing was recorded read with crossing None. Throws std::invalid_argument naming the file
/// and the field it cannot read.
ContinuationFile load_continuation_file(const std::string& path);
/// The same from the file's text (`where` names it in errors).
ContinuationFile parse_continuation_file(const std::string& text, const std::string& where);
std::string zero_gap_json(const ParametricSystem& system, const ContinuationResult& result, int indent = 2);

}  // namespace spp
