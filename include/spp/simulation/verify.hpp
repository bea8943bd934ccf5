#pragma once
// Independent verification of SPPs with the event-driven simulator: an admissible SPP must come back to its
// initial state after each period with the expected events (contact onset at 0, release at 2 t2); a potential
// but inadmissible one must be seen to leave (an impact where its flight penetrates, or an early release where
// its force would turn negative). Every one, admissible or not, must also come back along its potential orbit
// (the exact contact and flight flows, events ignored): x0, v0 are then the orbit at (t1, t2). With a perturbation, the
// distance to the orbit is followed period by period: a measured indication of stability under the given impact law.

#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "spp/modal/modal.hpp"
#include "spp/orbit/solution.hpp"
#include "spp/simulation/simulator.hpp"

namespace spp {

struct VerifyOptions {
  int periods = 1;            ///< simulated periods (>= 1)
  double perturbation = 0.0;  ///< relative size of the perturbation of the mid-flight state; 0: none
  double restitution = 0.0;   ///< Newton's e for the simulations (matters only once the orbit is left)
  // Every tolerance below is a floor: verify() raises each to what the problem's own error allows (docs/result-files.md,
  // "Tolerances"). Per SPP, the relative error expected of its state and of the simulator's flows over its period is
  // eps_s = eps (max(cond M, cond K) + omega_max T) + data_error + frequency_error (ModalForm), and the tolerances
  // used are: state (onset, potential orbit) 100 eps_s, the simulator's event tolerance eps_s; return after one period
  // 10 eps_s^(2/3) (an SPP's touchdown is tangent to third order: a state error e moves it by ~e^(1/3) in time and
  // leaves a normal velocity ~e^(2/3), removed as a plastic impact); event_time_tol is used as given. Bare
  // numbers failed both ways (issue 11): genuine SPPs of the paper's chain in coordinates with cond M 1e8, or with a
  // spring 1e6 times the others, were called inconsistent, while x0 edited by 1e-7 passed on the paper's chain.
  double return_tol = 1e-9;   ///< an admissible SPP must come back to this relative error after one period
  double follow_tol = 1e-6;   ///< later periods count as followed while the return error stays below this
  /// Every SPP (either symmetry), admissible or not, must come back to this relative error along its potential orbit
  /// (contact flow for 2 t2, then free flight for 2 t1, events ignored), and its onset state must satisfy its
  /// equations to it. 0: the derived tolerance alone (measured: 2e-14 on the paper's chain, 100 eps_s = 1e-12; an x0
  /// edited by 1e-9 of its size is seen).
  double potential_return_tol = 0.0;
  double event_time_tol = 1e-6;  ///< relative to the period: events within it of the expected times match
  /// Called before each SPP and every 256 events of its simulations, from the thread that called verify() (so a
  /// Python callback may take the GIL): returning false stops verify; the SPP being checked and the later ones are
  /// left out (VerifyResult::unchecked counts them). Empty: never called.
  std::function<bool()> progress;
  /// Throws std::invalid_argument naming the field, its value and the rule.
  void validate() const;
};

enum class Verdict {
  Returns,  ///< over the first period: the expected events, and a return error below return_tol
  Leaves,   ///< the simulation departs from the orbit within the first period (departure_* say when and how)
};
const char* to_string(Verdict v);
/// Its values: 0 .. 1 (Leaves last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(Verdict) {
  return 2;
}

struct SppCheck {
  Solution spp;  ///< the SPP checked (verify's copy of it): its t1(), t2(), x0(), v0() and the solver's admissible()
  Verdict verdict = Verdict::Leaves;
  /// admissible <=> Returns, and the potential orbit returns (potential_return_error <= state_tolerance)
  bool consistent = false;
  /// The tolerances verify used for this SPP (VerifyOptions: the options' floors raised to what the problem's own
  /// error allows): on the onset state and the potential orbit, and on the return after one period.
  double state_tolerance = 0.0, return_tolerance = 0.0;
  std::vector<double> return_errors;  ///< |X(kT) - X(0)| / |X(0)|, k = 1..periods
  /// |X(T) - X(0)| / |X(0)| along the potential orbit (Simulator::follow_contact_then_flight for 2 t2 and 2 t1,
  /// events ignored): whether x0, v0 are the periodic orbit the solver claims at (t1, t2), admissible or not. Above
  /// state_tolerance the check is inconsistent whatever the simulation says (an edited result,
  /// or another system's). Point symmetry too: the contact flow carries the normal velocity at onset (the moving
  /// obstacle). NaN when not computed (the onset state was already refused: see departure).
  double potential_return_error = std::numeric_limits<double>::quiet_NaN();
  /// Leading periods followed: expected events and return error <= return_tolerance for the first, return error
  /// <= follow_tol (at least return_tolerance) for the next ones.
  int periods_followed = 0;
  double departure_time = 0.0;  ///< first event that does not match the orbit's (none: departure is empty)
  std::string departure;        ///< what happened there
  long impacts = 0, contact_onsets = 0, releases = 0;
  /// With a perturbation (a random direction without its first-order energy change: the energy's multiplier 1 is
  /// neutral and would drift linearly): distance of the perturbed state to the orbit (energy norm, relative to the
  /// orbit's, minimum over the phase), at k = 0..periods periods after the perturbation; and the mean growth factor
  /// per period over the periods while the distance stays below 1e-3 (the linear regime; at least the first period):
  /// compare with spectral_radius.
  std::vector<double> perturbed_distances;
  double growth_per_period = 0.0;
};

/// Success: every simulation agrees with the solver's admissibility (an admissible SPP returns, an inadmissible one
/// leaves); Inconsistent: at least one disagrees (spp verify exits 3); Interrupted: VerifyOptions::progress stopped
/// verify before every SPP was checked and none of those checked disagrees (an interrupted run read "success" with
/// 57 of 64 SPPs unchecked; found by an attack on issue 13); Incomplete: an SPP could not be checked because its
/// simulation (periods x its period) would pass the simulator's limit (Simulator::max_duration: 1e8 periods of the
/// fastest mode), a warning naming each, and none checked disagrees (spp verify --periods 2200 aborted with exit 1 on
/// one such SPP of a chain with a 1e-8 mass; issue 11 finding). spp verify exits 3 unless Success.
enum class VerifyStatus { Success, Inconsistent, Interrupted, Incomplete };
const char* to_string(VerifyStatus s);
/// Its values: 0 .. 3 (Incomplete last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(VerifyStatus) {
  return 4;
}

struct VerifyResult {
  VerifyStatus status = VerifyStatus::Success;
  std::vector<SppCheck> checks;
  int returned = 0, left = 0, inconsistent = 0;
  /// Why the inconsistent ones are (an SPP may count in several): the simulation's verdict is not the solver's
  /// admissibility; x0, v0 are not the orbit at (t1, t2) (potential_return_error); the stability claimed (spectral
  /// radius, verdict, multipliers) is not what floquet() recomputes from (t1, t2) and the system.
  int admissibility_mismatches = 0, state_mismatches = 0, stability_mismatches = 0;
  /// SPPs not checked because VerifyOptions::progress stopped verify (0: every one was; else the status is Interrupted
  /// unless an SPP checked is inconsistent).
  long unchecked = 0;
  /// Of unchecked: those whose simulation would pass the simulator's limit (status Incomplete; a warning each).
  long beyond_simulator_limit = 0;
  /// Caveats on reading the results, one sentence each (e.g. a perturbation simulated with restitution 1, where the
  /// Floquet multipliers, derived for e < 1, do not apply).
  std::vector<std::string> warnings;
  /// Every SPP checked and none inconsistent.
  bool all_consistent() const { return inconsistent == 0 && unchecked == 0; }
  /// One line; it always ends by saying that the completeness of the list (no SPP deleted from a result file with
  /// its count) is not checked: only a re-solve checks it (docs/result-files.md).
  std::string brief_report() const;
};

/// The relative error expected of the state (x0, v0) of an SPP of period T of this system, as the solver computes it
/// through the modal form `modal` (of `system`), and of the simulator's flows over T: eps_s = eps (max(cond M, cond K)
/// + omega_max T) + data_error + frequency_error (docs/result-files.md, "Tolerances"; VerifyOptions). Cost O(n^3) (two
/// Cholesky factorisations).
double expected_state_error(const System& system, const ModalForm& modal, double period);

/// Each SPP's onset state is first checked against its symmetry's equation set (make_equations; the first SPP builds
/// the modal form, O(n^3)): x0 on the obstacle, the normal velocity w^T v0 the symmetry requires (0 axial, g0 / t2
/// point) and the obstacle_velocity claimed, each to state_tolerance of the state; one that fails is a state
/// mismatch (not simulated). Then re-simulates each SPP from its state at contact onset (x0, v0, both (n)) for
/// `periods` periods: one Simulator (O(n^3)), then O(n^2) per event, a few events per period; with a perturbation, the
/// orbit sampled at 512 points and one golden-section search of the nearest point per period. Throws
/// std::invalid_argument on sizes that do not match the system.
VerifyResult verify(const System& system, const std::vector<Solution>& spps, const VerifyOptions& options);

}  // namespace spp
