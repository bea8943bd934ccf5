#pragma once
// Result files of spp modes (issue 15): {"system": <system file>, "linear_frequencies": [...], "status", "stats",
// "families": [{"k", "label", "symmetry", "mode" (1-based), "multiplicity", "points": [{"energy", "frequency",
// "period", "impact_times", "x0", "v0", "admissible", "margin", "multiplicity"}, ...], "events": [{"kind", "detail",
// "energy", "frequency", "period"}, ...]}, ...]}. x0, v0: the state just after the first impact (time 0 of
// impact_times); frequency 2 pi / period in rad per time unit; energy 1/2 v^T M v + 1/2 x^T K x.

#include <string>

#include "spp/core/system.hpp"
#include "spp/modes/nonsmooth_modes.hpp"

namespace spp {

/// The JSON text of a result (17 significant digits). indent < 0: one line. Cost O(size of the result).
std::string modes_json(const System& system, const modes::ModesResult& result, int indent = 1);

}  // namespace spp
