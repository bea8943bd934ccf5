#pragma once
// SPP branches of a parametric system (issue "parametric systems", paper §6): every SPP of a window followed
// as the parameter mu runs over its range.
//   - A branch is a curve in (t1, t2, mu) on which eqs. (5.1a-b) hold. It is traced by pseudo-arclength
//     continuation of two smooth scalar equations: s = 0, s the bordering scalar of [[N, b], [b^T, 0]] (zero
//     exactly when N(t1, t2; mu) is singular, b the previous null vector carried over in physical
//     coordinates so that modal sign and ordering changes do not matter), and z^T cos(W t1) a = 0 (the null
//     vector a of the bordered solve). Variables scaled by the window and the range.
//   - Seeds: solve() at `seeds` parameter values across the range; a seed already crossed by a traced branch
//     is not traced again, and every crossing of a seed value by a branch is matched with solve()'s solutions
//     there (a branch that solve() does not confirm, or a seed no branch reaches, is a warning).
//   - Events, located by bisection along the branch: the window's or the range's edge (the branch stops), a
//     fold in mu, admissibility lost or gained (admissibility_margin changes sign), and the gap closing at
//     rest, u^T W^-1 p0 = 0: for g0 = 0 these are the SPPs of paper §6.1 (their scale is free: unit energy),
//     for g0 != 0 the orbit's amplitude diverges there; a Floquet multiplier crossing the unit circle
//     (spectral_radius - 1 changes sign, docs/stability.md), classified by the multiplier that crosses: +1, -1
//     (period doubling) or a complex pair exp(+-i theta) (Neimark-Sacker).
// Branches that exist only between two seed values (born and dying at folds in between) are not seen: raise
// `seeds` to narrow that gap.

#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "spp/core/parametric.hpp"
#include "spp/modal/modal.hpp"
#include "spp/orbit/solution.hpp"

namespace spp {

struct ContinueOptions {
  double t1_max = 0.0, t2_max = 0.0;  ///< window (required, > 0)
  double t1_min = 0.0, t2_min = 0.0;  ///< 0: as solve() (a small fraction of the fastest quarter period)
  int seeds = 9;                      ///< parameter values (min, max and evenly between) where solve() seeds branches
  double max_step = 0.02;             ///< largest step, in arclength of (t1/t1_max, t2/t2_max, mu/(max - min))
  double min_step = 1e-9;             ///< a branch whose step falls below this stops with a "stalled" event
  double max_turn = 0.25;             ///< largest angle (rad) between successive tangents
  int max_points = 5000;              ///< per branch and direction
  double locate_tol = 1e-13;          ///< events located to this, in the same scaled arclength
  int threads = 0;                    ///< for the seeding solves
  /// Point: branches of the point-symmetric potential SPPs (det T2 = 0, paper §6.2); their gap_closure
  /// events are where the normal velocity at onset vanishes (with g0 = 0: a fixed obstacle).
  Symmetry symmetry = Symmetry::Axial;
  /// Called before each branch point and about every 0.2 s of each seed solve, from the thread that called
  /// continue_branches() (so a Python callback may take the GIL): returning false stops the continuation; the branches
  /// traced so far are kept (the one being traced ends with a Stalled event "interrupted"), the status is Incomplete
  /// and `interrupted` is set. Empty: never called.
  std::function<bool()> progress;

  /// Throws std::invalid_argument naming the field, its value and the rule.
  void validate() const;
};

enum class BranchEventKind {
  LeavesWindow,         ///< t1 or t2 reaches the window's edge (the branch stops there)
  RangeEnd,             ///< mu reaches min or max (the branch stops there)
  Fold,                 ///< dmu/ds changes sign: two SPPs meet and disappear
  AdmissibilityLost,    ///< admissibility_margin goes from >= 0 to < 0 (in the direction of the branch)
  AdmissibilityGained,  ///< and back
  GapClosure,           ///< u^T W^-1 p0 = 0: with g0 = 0, an SPP (paper §6.1); with g0 != 0, amplitude diverges.
                        ///< Symmetry::Point: u^T W^-1 p0' = 0, zero normal velocity at onset (§6.2, fixed obstacle)
  ClosedLoop,           ///< the branch came back to its first point: an isola, traced once
  Stalled,              ///< the step fell below min_step or max_points was reached
  StabilityLost,        ///< a Floquet multiplier leaves the unit circle (spectral_radius goes above 1)
  StabilityGained,      ///< and back (stability/floquet.hpp; axial branches with g0 != 0)
};
const char* to_string(BranchEventKind kind);
/// Its values: 0 .. 9 (StabilityGained last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(BranchEventKind) {
  return 10;
}

struct BranchPoint {
  double mu = 0.0, t1 = 0.0, t2 = 0.0, period = 0.0;
  bool admissible = false;  ///< margin >= 0
  double margin = 0.0;      ///< admissibility_margin (NaN where the orbit is undefined)
  double closure = 0.0;     ///< u^T W^-1 p0 / |W^-1 a|, continuous along the branch: zero where the gap closes at rest
  double energy = 0.0;
  Eigen::VectorXd x0, v0;  ///< state at contact onset (g0 = 0: scaled to unit energy)
  /// Largest |Floquet multiplier| but the two structural 1s (stability/floquet.hpp, docs/stability.md), whether the
  /// SPP is admissible or not; NaN where not computed (g0 = 0, point symmetry, undefined orbit).
  double spectral_radius = std::numeric_limits<double>::quiet_NaN();
  /// Its error bound (Floquet::spectral_radius_error: rounding and the point's location error at its parameter value,
  /// large near a fold); NaN where not computed, infinite where unbounded.
  double spectral_radius_error = std::numeric_limits<double>::quiet_NaN();
};

/// How a Floquet multiplier crosses the unit circle at a StabilityLost / StabilityGained event.
enum class MultiplierCrossing {
  None,         ///< not a stability event (or the multipliers could not be computed at the located point)
  PlusOne,      ///< a real multiplier through +1
  MinusOne,     ///< a real multiplier through -1: period doubling (flip)
  ComplexPair,  ///< a conjugate pair through exp(+-i theta), 0 < theta < pi: Neimark-Sacker
};
const char* to_string(MultiplierCrossing c);
/// Its values: 0 .. 3 (ComplexPair last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(MultiplierCrossing) {
  return 4;
}

struct BranchEvent {
  BranchEventKind kind = BranchEventKind::Stalled;
  BranchPoint at;
  std::string detail;
  /// Stability events: which multiplier crosses. Classified at the located point by Floquet::leading (the coupled
  /// modes' multiplier of largest modulus, i.e. the one whose modulus crosses 1 there): real (the eigensolver's real
  /// Schur form gives real multipliers with imaginary part exactly 0) and positive or negative, or a pair.
  MultiplierCrossing crossing = MultiplierCrossing::None;
  /// The crossing multiplier(s) at the located point: one real, or a conjugate pair (positive imaginary part
  /// first); moduli within the location's resolution of 1.
  std::vector<std::complex<double>> crossing_multipliers = {};
  /// arg of the crossing multiplier, in [0, pi] (rad): 0 for +1, pi for -1, theta for exp(+-i theta). NaN: None.
  double crossing_angle = std::numeric_limits<double>::quiet_NaN();
};

struct Branch {
  std::vector<BranchPoint> points;  ///< in the order traced
  std::vector<BranchEvent> events;  ///< in the same order
};

/// Success: every seed solve succeeded, every branch was followed to an end (range end, closed loop, window edge,
/// fold or admissibility events), and every crossing of a seed value is one of solve()'s SPPs there.
enum class ContinuationStatus { Success, Incomplete };
const char* to_string(ContinuationStatus s);
/// Its values: 0 .. 1 (Incomplete last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(ContinuationStatus) {
  return 2;
}

struct ContinuationResult {
  ContinuationStatus status = ContinuationStatus::Success;
  long incomplete_seed_solves = 0;  ///< seed solves that ended Incomplete (branches through their misses are lost)
  long stalled_branches = 0;        ///< branch ends that stalled (step below min_step, max_points, no progress)
  long unlisted_crossings = 0;      ///< seed-value crossings at a point solve() there does not list
  Parameter parameter;
  Symmetry symmetry = Symmetry::Axial;
  double t1_min = 0.0, t1_max = 0.0, t2_min = 0.0, t2_max = 0.0;
  std::vector<Branch> branches;
  std::vector<std::string> warnings;
  long seed_spps = 0;         ///< SPPs solve() found at the seed values
  long seed_crossings = 0;    ///< branch crossings of a seed value, each matched with one of those SPPs
  long corrector_solves = 0;  ///< Newton solves on the branch equations
  bool interrupted = false;   ///< ContinueOptions::progress stopped the continuation (status Incomplete)
  double seconds = 0.0;
  /// One line: status, branches, points, events by kind, counted causes, warnings, time.
  std::string brief_report() const;
};

/// Every branch through the SPPs solve() finds at the seed values, followed over the parameter's range. Cost:
/// `seeds` solves, then per branch step a few corrector iterations, each a few bordered solves and modal forms of
/// size n (O(n^3)); corrector_solves counts them. Throws std::invalid_argument for invalid options.
ContinuationResult continue_branches(const ParametricSystem& system, const ContinueOptions& options);

/// The one branch through `solution`, an SPP of system.at(mu) (as solve() or solution_at() give it, from any
/// machine: its orbit is taken in this modal basis, orbit/orbit.hpp in_modal_basis), followed both ways over the
/// parameter's range within options' window. First the point is corrected at fixed mu (Newton on the branch
/// equations); a solution that is no SPP there (it does not converge within 1e-3 (t1 + t2) of it) is refused. The
/// result holds one branch; its status is Incomplete when an end stalled. No seed solves (seeds is ignored): the
/// cost is the branch's alone. Throws std::invalid_argument for invalid options, a mu outside the range, a solution
/// of another size or symmetry, or one that is no SPP at mu.
ContinuationResult continue_branch(const ParametricSystem& system, double mu, const Solution& solution,
                                   const ContinueOptions& options);

/// The GapClosure events of a result (one per SPP), sorted by mu: with g0 = 0, the SPPs of paper §6.1.
std::vector<BranchPoint> gap_closures(const ContinuationResult& result);

}  // namespace spp
