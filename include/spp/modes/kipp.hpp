#pragma once
// Symmetric periodic orbits with k elastic impacts per period (k-IPPs, the "nonsmooth modes" of Thorin, Delezoide,
// Legrand, the paper's refs [15], [16]) of M x'' + K x = 0 with g(x) = w^T x + g0 >= 0 and the impact law e = 1:
//   v+ = v- - 2 (w^T v-) / (w^T M^-1 w) M^-1 w   at g = 0.
// Derivation and conventions: docs/modes.md. In the modal coordinates x = Phi q (K Phi = M Phi W^2, Phi^T M Phi = I,
// the m modes that see the obstacle) the flight is q'' = -W^2 q, the gap b^T q + g0 with b = Phi^T w, and the impact
// reflects the modal velocity in the hyperplane b^perp: q'+ = R q'-, R = I - 2 b b^T / |b|^2. The system is
// time-reversible (t -> -t, q' -> -q' maps orbits to orbits, an impact to an impact), and a reversible periodic orbit
// has two symmetric points per period: a turning point in flight (q' = 0) or an impact whose velocity is normal (q'-
// parallel to b). Half an orbit, from one to the other, determines it (docs/modes.md §2): the unknowns are the
// symmetric point's state and the durations tau_0..tau_m of the m + 1 flights of the half orbit; the equations are
// linear in the state given the durations. Non-reversible k-IPPs, if any, are not computed.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "spp/core/system.hpp"

namespace spp::modes {

/// The two symmetric points of the half orbit: F a turning point in flight, I an impact with normal velocity.
/// k = 2m (FlightFlight), 2m + 1 (FlightImpact), 2m + 2 (ImpactImpact), m the impacts strictly inside the half orbit.
/// None: no symmetry assumed (docs/modes.md §2, "The general equations"): the whole period, k flights from an impact;
/// it also holds the non-reversible k-IPPs and the (I, I) m = 0 2-IPPs that are no 1-IPP traversed twice.
enum class KippSymmetry { FlightFlight, FlightImpact, ImpactImpact, None };
const char* to_string(KippSymmetry s);  ///< "flight-flight", "flight-impact", "impact-impact", "none"

/// The symmetric point types that give k impacts per period (k >= 1): k odd, FlightImpact; k even, FlightFlight
/// and ImpactImpact (k = 2: ImpactImpact with m = 0 is the 1-IPP traversed twice, docs/modes.md §2: not listed).
std::vector<KippSymmetry> symmetries_for(int k);
/// m, the impacts strictly inside the half orbit, for k and s (k must suit s: symmetries_for); None: k - 1 (the
/// impacts after the first one of the period, the flights numbering k).
int interior_impacts(int k, KippSymmetry s);

/// The free flow of the system in its modal coordinates, computed once (model/workspace split). Cost O(n^3).
/// Only the coupled modes (b_i = phi_i^T w != 0, after aligning each group of repeated frequencies so that one of its
/// modes takes all of w, as ModalForm does) are k-IPP unknowns: a decoupled mode never sees the obstacle, so any of
/// its free motions can be superposed on a k-IPP whose period is a multiple of its own; kept among the unknowns, it
/// made the equations singular there and its continua were listed as families (issue 15, D2: M = K = I, w = (1, 1, 0)).
/// Throws std::invalid_argument when g0 <= 0 (no equilibrium in flight: no grazing start; docs/modes.md §5).
class KippModel {
 public:
  explicit KippModel(const System& system);
  const System& system() const { return system_; }
  int coupled_modes() const { return static_cast<int>(omega_.size()); }  ///< m <= n: the modal unknowns per state
  const Eigen::VectorXd& omega() const { return omega_; }  ///< (m) coupled free frequencies, ascending, rad / time unit
  const Eigen::MatrixXd& Phi() const { return Phi_; }      ///< n x m, M-normalised coupled mode shapes
  const Eigen::VectorXd& b() const { return b_; }          ///< (m) Phi^T w: modal gap weights, none 0
  const Eigen::MatrixXd& tangent_basis() const { return Q_; }  ///< m x (m-1) orthonormal basis of b^perp
  /// Q^T X for Q = tangent_basis() (m x c), by the Householder reflection that defines Q: O(m c), where the product
  /// with the dense Q was O(m^2 c), the largest cost of kipp_residual for a large m.
  Eigen::MatrixXd tangential(const Eigen::MatrixXd& X) const;
  /// (n) every free frequency, coupled or not, ascending (the linear frequencies of the frequency-energy plot)
  const Eigen::VectorXd& omega_all() const { return omega_all_; }
  /// The linear mode number (1 = lowest frequency, of all n) of coupled mode i (0-based in omega())
  int linear_mode(int i) const { return linear_mode_.at(static_cast<size_t>(i)); }
  double g0() const { return system_.g0(); }

 private:
  System system_;
  Eigen::VectorXd omega_, b_, omega_all_;
  Eigen::MatrixXd Phi_, Q_;
  Eigen::HouseholderQR<Eigen::MatrixXd> b_reflection_;  // of b: its Q (one reflector) is [b / |b|-ish, Q_]
  std::vector<int> linear_mode_;
};

/// The unknowns y of a symmetric half orbit: y = (q_A (n), [s,] tau_0..tau_m), with s only for ImpactImpact
/// (post-impact modal velocity s b / |b| at A). size = n + m + 1 (+1 for ImpactImpact); the equations number
/// size - 1: a one-parameter family (the energy). None: y = (q (n), q' (n), tau_1..tau_k), the state just after an
/// impact and the k flights of the period; size 2n + k.
struct KippShape {
  int k = 1;
  KippSymmetry symmetry = KippSymmetry::FlightImpact;
  int n = 0;  ///< modal coordinates: the model's coupled modes (KippModel::coupled_modes())
  int m() const { return interior_impacts(k, symmetry); }
  int unknowns() const { return first_tau() + m() + 1; }
  int equations() const { return unknowns() - 1; }
  int first_tau() const {
    return symmetry == KippSymmetry::None ? 2 * n : n + (symmetry == KippSymmetry::ImpactImpact ? 1 : 0);
  }
};

/// F(y) (equations) and its Jacobian J (equations x unknowns), analytic (forward mode through the flows and
/// reflections). None: the start on the obstacle, the gap 0 after each flight, and after the k-th impact the state
/// back: its position (n) and its tangential velocity (n - 1); the normal velocity back follows from the energy
/// (conserved) and is not an equation (it would make J rank deficient). Units: q in the units of x times sqrt(mass);
/// tau in time. Cost O(n (m + 1) unknowns).
void kipp_residual(const KippModel& model, const KippShape& shape, const Eigen::VectorXd& y, Eigen::VectorXd& F,
                   Eigen::MatrixXd& J);

/// One k-IPP in physical terms, time origin at its first impact (the first impact after the symmetric point A).
struct KippOrbit {
  double period = 0.0;                ///< T, time units
  double energy = 0.0;                ///< 1/2 v^T M v + 1/2 x^T K x
  std::vector<double> impact_times;   ///< k times in [0, T), first 0, ascending
  Eigen::VectorXd x0, v0;             ///< (n) state just after the first impact (v0: post-impact velocity)
  std::vector<double> impact_speeds;  ///< k incoming normal speeds -w^T v- (> 0: towards the obstacle)
  /// Smallest gap over the open flights, certified by Taylor bounds (docs/modes.md §4); 0 when a speed is <= 0
  /// (the flight ends are then not separated from zero).
  double min_flight_gap = 0.0;
  bool gap_certified = false;
  /// Where min_flight_gap is reached: the flight of the half orbit (0..m, from the symmetric point A) and the time
  /// from that flight's start; -1 when no flight was minimised.
  int min_gap_flight = -1;
  double min_gap_time = 0.0;
  /// Signed admissibility margin, continuous along a family: min(min_flight_gap / g0, min speed / speed scale),
  /// speed scale = g0 * omega_max. >= 0 admissible (to the tolerance of the minimisation).
  double margin = 0.0;
  bool speed_limited = false;  ///< the margin is set by an impact speed (else by a flight gap)
  /// r > 1 when the orbit is an r-fold repetition of an orbit with k / r impacts (its least period is T / r).
  int multiplicity = 1;
};

/// The orbit of a solution y of kipp_residual (F(y) ~ 0). rel_tol: the gap minimisation's tolerance relative to g0.
/// Cost O(n k) plus a few hundred O(n) gap evaluations per flight.
KippOrbit kipp_orbit(const KippModel& model, const KippShape& shape, const Eigen::VectorXd& y, double rel_tol = 1e-10);

/// The grazing start: coupled mode `coupled` (0-based index into omega(), b(coupled) != 0) of amplitude
/// g0 / |b_coupled|, whose extreme just touches the obstacle, traversed k times (period 2 pi k / omega_coupled) and
/// written as a solution y of shape (F(y) = 0 to rounding). Throws std::invalid_argument for an index out of range.
Eigen::VectorXd grazing_start(const KippModel& model, const KippShape& shape, int coupled);

/// The grazing orbit of coupled mode `coupled` seen with period `multiple` * 2 pi / omega_coupled and one impact
/// (k = 1, FlightImpact): half period tau = multiple * pi / omega, A a turning point, B the touch at tau, the other
/// multiple - 1 touches tangencies inside the flight. The explicit 1-IPP family (docs/modes.md §2) passes through it
/// continuously (its q_A is c (W sin W tau)^-1 b, c -> 0 as sin(omega tau) -> 0), and each tau-interval between two
/// zeros of sum_i b_i^2 cot(omega_i tau) / omega_i holds exactly one such point: every symmetric 1-IPP lies on the
/// family through one of them (docs/modes.md §3). multiple = 1 is grazing_start. Throws std::invalid_argument for a
/// shape other than k = 1 or multiple < 1.
Eigen::VectorXd grazing_start_multiple(const KippModel& model, const KippShape& shape, int coupled, int multiple);

/// The 1-dof closed form (issue 15): x'' + x = 0 against a stop at g0, e = 1, amplitude A >= g0:
/// frequency 2 pi / T = pi / (pi - arccos(g0 / A)); energy A^2 / 2 (unit mass and stiffness).
double one_dof_frequency(double g0, double amplitude);

}  // namespace spp::modes
