#pragma once
// CSV (header line, then one row per item; doubles with 17 significant digits).
// Cost: linear in the rows written (result: solutions x (2n + 11) numbers; trajectory: samples x (2n + 3), each
// sample O(m^2 + n m) through orbit_state), ~25 characters per number.

#include <string>

#include "spp/modal/modal.hpp"
#include "spp/orbit/orbit.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/simulator.hpp"

namespace spp {

/// One row per SPP: t1, t2, period, admissible (0/1), min_gap, min_force, energy, residual, return_error, x0_1..n,
/// v0_1..n.
std::string result_to_csv(const SolveResult& result);
/// Most values one CSV of spp holds (it is built in memory, then written atomically): 2e7 numbers of ~24 characters
/// are ~0.5 GB of text, held twice while written. 10^6 samples of a 5-dof orbit fit; finer sampling is refused.
inline constexpr double kMaxCsvValues = 2e7;
/// Refuses `samples` rows of a trajectory of an n-dof system, samples x (2n + 3) values, beyond kMaxCsvValues:
/// std::invalid_argument naming `what` (e.g. "--samples"), before anything is allocated.
void check_trajectory_csv_size(long samples, long n, const std::string& what);
/// One period of an orbit, `samples` rows: t, x1..xn, v1..vn, gap, force (checked by check_trajectory_csv_size).
std::string trajectory_csv(const ModalForm& modal, const Orbit& orbit, int samples);
/// Simulation samples: t, x1..xn, v1..vn, gap, force, contact (0/1).
std::string simulation_csv(const SimulationResult& result);
/// Events: t, event, normal velocity before and after, force, x1..xn, v1..vn (after the event).
std::string events_csv(const SimulationResult& result);

}  // namespace spp
