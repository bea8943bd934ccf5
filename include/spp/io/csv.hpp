#pragma once
// CSV (header line, then one row per item; doubles with 17 significant digits).

#include <string>

#include "spp/modal/modal.hpp"
#include "spp/orbit/orbit.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/simulator.hpp"

namespace spp {

/// One row per SPP: t1, t2, period, admissible (0/1), min_gap, min_force, energy, residual, return_error, x0_1..n,
/// v0_1..n.
std::string result_to_csv(const SolveResult& result);
/// One period of an orbit, `samples` rows: t, x1..xn, v1..vn, gap, force.
std::string trajectory_csv(const ModalForm& modal, const Orbit& orbit, int samples);
/// Simulation samples: t, x1..xn, v1..vn, gap, force, contact (0/1).
std::string simulation_csv(const SimulationResult& result);
/// Events: t, event, normal velocity before and after, force, x1..xn, v1..vn (after the event).
std::string events_csv(const SimulationResult& result);

}  // namespace spp
