#pragma once
// Result files of spp continue: {"system", "symmetry", "window", "warnings", "stats", "branches": [{"points": [...],
// "events": [...]}]}, each point {"<parameter>", "t1", "t2", "period", "closure", "energy", "x0", "v0", "margin",
// "admissible"}; and of the zero-gap solve (g0 = 0, paper §6.1) as a solve result, each solution with
// "parameter": {"name", "value"}.
// Cost: linear in the output (points x n numbers, ~20 characters each); times in the system's unit.

#include <string>

#include "spp/continuation/continuation.hpp"
#include "spp/core/parametric.hpp"

namespace spp {

/// indent < 0: one line.
std::string continuation_json(const ParametricSystem& system, const ContinuationResult& result, int indent = 1);
std::string zero_gap_json(const ParametricSystem& system, const ContinuationResult& result, int indent = 2);

}  // namespace spp
