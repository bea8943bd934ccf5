#pragma once
// Families of symmetric k-IPPs (kipp.hpp) continued in energy: the nonsmooth modes of the paper's refs [15], [16] and
// their backbone curves on the frequency-energy plot (docs/modes.md).
//   - Starts: for each k, each symmetric type (symmetries_for) and each linear mode j that sees the obstacle, the
//     grazing start (the mode of amplitude g0 / |b_j| traversed k times). From it the family is the k-fold repetition
//     of mode j's 1-IPP family (observed, docs/modes.md §3; that no other curve leaves it is not proved): its points
//     have multiplicity k. Genuine k-IPPs (multiplicity 1) branch off these repetitions where the augmented Jacobian
//     [J; tangent^T] is singular (a simple branch point, located by bisection on the sign of its determinant); both
//     directions of the other branch are followed as families of their own (one level: branch points on those are
//     not followed). Families reached from none of these starts (isolas) are not found.
//   - Continuation: pseudo-arclength with the project's corrector (continuation/corrector.hpp) on the unknowns of
//     kipp.hpp scaled by g0 / |b| (positions), g0 omega_max / |b| (speed) and 2 pi / omega_min (durations).
//   - Grazing continuations: where a family with k impacts ends at a flight_grazing event inside a flight of its half
//     orbit, that orbit is also a solution with k + 2 impacts (the tangency and its mirror, at zero speed); the
//     family with k + 2 impacts is followed from there when k + 2 is requested (and so on: k + 4, ...). A tangency at
//     a symmetric point (it would add one impact and change the symmetry type) is not followed.
//   - k >= 2 beyond these (docs/modes.md §3, ModesOptions::branch_points): the 1-IPP families repeated k times and
//     the symmetric families, traced in the symmetric equations and in equations with no symmetry assumed
//     (KippSymmetry::None), their branch points switched; families ending at one tangency continued with k + 1
//     impacts. A family found there is listed when genuine and on no family listed already.
//   - Seeds (ModesOptions::seed_period_max > 0): the symmetric k-IPPs with one impact inside the half orbit (k = 2,
//     3, 4) from the sign changes of det [A c] on a grid of their two flight durations; one family per new curve.
//   - Events, located by bisection along the arclength: admissibility lost (an impact speed reaches 0: ImpactGrazing;
//     the gap touches 0 inside a flight: FlightGrazing), energy_max reached; the family ends there.
// Units: energy 1/2 v^T M v + 1/2 x^T K x, times and periods in the time unit of M and K, frequency 2 pi / T (rad per
// time unit).

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "spp/core/system.hpp"
#include "spp/modes/kipp.hpp"

namespace spp::modes {

/// Largest k accepted (the half orbit then has up to 21 flights): a bound on the work, not a measured accuracy limit.
inline constexpr int kMaxImpactsPerPeriod = 40;
/// Largest ModesOptions::period_multiples: a bound on the work (one start per coupled mode and multiple).
inline constexpr int kMaxPeriodMultiples = 100;
/// ModesOptions::through_inadmissible follows an inadmissible stretch up to this many times energy_max (the curve may
/// rise above energy_max there and come back below it): a bound on the work.
inline constexpr double kInadmissibleEnergyFactor = 10.0;

/// What a running nonsmooth_modes() reports to ModesOptions::progress (before each family point).
struct ModesProgress {
  int k = 0;             ///< impacts per period of the families being traced now
  int k_last = 0;        ///< the largest k traced (every k from 1 to it is traced)
  long families = 0;     ///< families found so far (of every k traced, those not requested included)
  long steps = 0;        ///< family points tried so far (calls of the callback)
  double seconds = 0.0;  ///< since nonsmooth_modes() started
  /// "tracing k = 3 (k up to 12): 57 families, 12345 steps, 12.3 s elapsed": the line the CLI and Python show.
  std::string line() const;
};

struct ModesOptions {
  /// impacts per period, each in [1, kMaxImpactsPerPeriod], no repeats (required). Every k from 1 to the largest is
  /// traced (the families with k impacts are reached from those with fewer), only these are listed: the families
  /// listed for a k do not depend on which other k are requested (--k 5 costs as much as --k 1..5).
  std::vector<int> k_values;
  double energy_max = 0.0;    ///< families end where the energy reaches it (required, > 0)
  double max_step = 0.05;     ///< largest continuation step, in scaled arclength
  double min_step = 1e-9;     ///< a family whose step falls below this ends with a Stalled event
  double max_turn = 0.3;      ///< largest angle (rad) between successive tangents
  int max_points = 4000;      ///< per family
  double locate_tol = 1e-12;  ///< events located to this, in scaled arclength
  /// Follow the genuine k-IPPs that branch off the k-fold repetitions; and, when some k >= 2 is requested, the k >= 2
  /// searches of docs/modes.md §3: every 1-IPP family repeated k
  /// times with its branch points, in the symmetric equations and with no symmetry assumed (KippSymmetry::None: the
  /// non-reversible k-IPPs), the symmetric families' symmetry-breaking branch points, and the families ending at one
  /// tangency continued with k + 1 impacts. Their cost: chain5 --k 1..5 --energy-max 150 took 46 s, 1.4 s without.
  bool branch_points = true;
  /// 1-IPP families also start from the grazing orbit of each mode seen with period
  /// j * 2 pi / omega for j = 2..period_multiples (one impact every j touches, the others tangencies in flight;
  /// kipp.hpp grazing_start_multiple): every symmetric 1-IPP of period T lies on the family through the start of some
  /// mode and j <= T omega / (2 pi) + 1 (docs/modes.md §3). 1: only the grazing starts (j = 1). Both sides of such a
  /// start are followed, each as a family, where admissible. In [1, kMaxPeriodMultiples].
  int period_multiples = 1;
  /// Where a family loses admissibility (or a start has no admissible side), keep following the solution curve
  /// through its inadmissible orbits (not listed) until it is admissible again: there a new family starts (event
  /// admissibility_regained) and is traced like any other. The inadmissible stretch is followed for at most
  /// max_points steps and up to kInadmissibleEnergyFactor * energy_max. false: a family ends at its first
  /// admissibility event (docs/modes.md §5: admissible stretches beyond are then missed).
  bool through_inadmissible = false;
  /// > 0: families also seeded from the plane of their two flight durations, for the k-IPPs whose durations given,
  /// the equations are square in the state ([A c], docs/modes.md §3 "Seeds"): the symmetric ones with one impact
  /// inside the half orbit (k = 2 flight-flight, k = 3 flight-impact, k = 4 impact-impact); every curve of
  /// such k-IPPs of period <= seed_period_max that crosses an edge of a 200 x 200 grid there is found (one family
  /// per curve, traced both ways from its seed). 0: no seeds.
  double seed_period_max = 0.0;
  /// Called before each family point, from the thread that called nonsmooth_modes() (so a Python callback may take
  /// the GIL): returning false stops the tracing; the families traced so far are kept (the one being traced ends
  /// with an Interrupted event) and the status is Incomplete with `interrupted` set. Empty: never called.
  std::function<bool(const ModesProgress&)> progress;
  /// Throws std::invalid_argument naming the field, its value and the rule.
  void validate() const;
};

struct ModePoint {
  double energy = 0.0, period = 0.0, frequency = 0.0;  ///< frequency = 2 pi / period
  std::vector<double> impact_times;                    ///< k, first 0 (kipp.hpp KippOrbit)
  Eigen::VectorXd x0, v0;                              ///< state just after the first impact
  bool admissible = false;                             ///< margin >= 0
  double margin = 0.0;                                 ///< KippOrbit::margin
  int multiplicity = 1;                                ///< KippOrbit::multiplicity
  Eigen::VectorXd y;                                   ///< the unknowns of kipp.hpp (half orbit)
};

enum class ModeEventKind {
  GrazingStart,  ///< the family's first point: a linear mode touching the obstacle (impact speeds 0)
  BranchStart,   ///< the family's first point: a branch point on a k-fold repetition
  /// the family's first point: the flight_grazing end of a family with k - 2 impacts, whose tangency inside a flight
  /// (and its mirror image) are counted as two impacts of zero speed
  GrazingContinuation,
  BranchPoint,       ///< a branch point met along the family (a family of genuine k-IPPs leaves it there)
  ImpactGrazing,     ///< admissibility lost: an impact's incoming speed reaches 0 (the family ends)
  FlightGrazing,     ///< admissibility lost: the gap touches 0 inside a flight, an extra contact (the family ends)
  EnergyMax,         ///< the energy reached energy_max (the family ends)
  Stalled,           ///< the step fell below min_step or max_points was reached (the family ends)
  NoAdmissibleSide,  ///< neither direction from the start is admissible (the family is its start only)
  /// the family's first point: the solution curve of an earlier family (ModesOptions::through_inadmissible), followed
  /// through inadmissible orbits from that family's admissibility event, is admissible again here
  AdmissibilityRegained,
  Interrupted,  ///< ModesOptions::progress stopped the tracing here (the family is not followed further)
  /// the family came back to its first point in the direction it left it: a closed loop, traced once (the family
  /// ends; it was traced round and round until max_points and then reported as stalled)
  ClosedLoop,
  /// a point of the family (not an end): its seed in the plane of the flight durations (ModesOptions::seed_period_max);
  /// the family was traced both ways from it, its first event is the end of the side traced first
  Seeded
};
const char* to_string(ModeEventKind kind);
/// Its values: 0 .. Seeded (the last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(ModeEventKind) {
  return static_cast<int>(ModeEventKind::Seeded) + 1;
}

struct ModeEvent {
  ModeEventKind kind = ModeEventKind::Stalled;
  ModePoint at;
  std::string detail;
};

struct ModeFamily {
  int k = 1;
  KippSymmetry symmetry = KippSymmetry::FlightImpact;
  /// The linear mode of the grazing start (of the repetition it branches from), numbered from 1 (the lowest of all n
  /// frequencies, decoupled modes counted), as in the label, the JSON and Python (it was 0-based here, 1-based there).
  /// 0: a seeded family (ModesOptions::seed_period_max), from no linear mode.
  int mode = 0;
  int multiplicity = 1;  ///< of its points past the start: k for a repetition of a 1-IPP, 1 for a genuine k-IPP
  std::string label;
  std::vector<ModePoint> points;  ///< in the order traced from its start (its energy need not be monotone)
  std::vector<ModeEvent> events;
};

/// Traced: every family found was followed to a located end (an admissibility or energy_max event, or back to its
/// first point: closed_loop); Incomplete: some
/// stalled. Neither is a claim that every k-IPP family was found: only the families connected to the grazing starts
/// are (docs/modes.md §5); an independent brute force found admissible 1-IPP branches of the 2-dof system and of the
/// chain that are not connected to them (they leave grazing orbits at multiples of their period). Hence not "success".
enum class ModesStatus { NotRun, Traced, Incomplete };
const char* to_string(ModesStatus s);
/// Its values: 0 .. 2 (Incomplete last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(ModesStatus) {
  return 3;
}

struct ModesResult {
  ModesStatus status = ModesStatus::NotRun;
  std::vector<ModeFamily> families;
  /// (n) omega of every mode, decoupled ones included, rad per time unit (ascending: mode j is entry j - 1; the
  /// backbones' low-energy ends are omega / k)
  Eigen::VectorXd linear_frequencies;
  long corrector_solves = 0;
  long stalled_families = 0;
  /// Inadmissible stretches followed (ModesOptions::through_inadmissible); those that became admissible again start
  /// the families whose first event is admissibility_regained.
  long inadmissible_stretches = 0;
  bool interrupted = false;  ///< ModesOptions::progress stopped the tracing (status Incomplete)
  double seconds = 0.0;
  /// One line: status, families (genuine / repetitions), points, events by kind, time.
  std::string brief_report() const;
};

/// Every family from the grazing starts of the requested k and their branch points. Cost: per family and step a few
/// corrector iterations of O(n k (n + k)) each, plus O(k) certified gap minimisations per point.
/// Throws std::invalid_argument for invalid options or g0 <= 0.
ModesResult nonsmooth_modes(const System& system, const ModesOptions& options);

}  // namespace spp::modes
