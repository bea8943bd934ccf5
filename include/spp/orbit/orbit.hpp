#pragma once
// One potential SPP as a trajectory: initial conditions (eqs. 5.2a-b), the flows of both phases (eq. 3.12),
// gap, contact force (eq. 2.7) and admissibility (ineqs. 5.3). Time origin at the onset of contact, as in the
// paper: contact on [0, 2 t2], flight on [2 t2, T] (= [-2 t1, 0] shifted by one period T = 2 t1 + 2 t2).

#include <Eigen/Dense>

#include "spp/modal/equation_set.hpp"
#include "spp/modal/modal.hpp"

namespace spp {

struct Orbit {
  double t1 = 0.0, t2 = 0.0;
  Eigen::VectorXd a;           ///< modal p at mid-flight (t = -t1), scaled so that the gap closes at t = 0
  Eigen::VectorXd c;           ///< modal p at mid-contact (t = t2)
  Eigen::VectorXd p0, p0dot;   ///< modal p, p' at contact onset
  Eigen::VectorXd x0, v0;      ///< physical x(0), x'(0)
  double closure_ratio = 0.0;  ///< |u^T W^-1 p0| / |W^-1 p0|: near 0, the gap cannot close at g0 != 0
  double energy = 0.0;         ///< 1/2 v^T M v + 1/2 x^T K x (conserved in both phases)
  Symmetry symmetry = Symmetry::Axial;
  /// Point symmetry only: w^T x moves at this constant normal velocity during contact (w^T x'' = 0 under K~),
  /// from -g0 at onset through 0 at t2: equal to g0 / t2, so the obstacle must move with it unless g0 = 0.
  double obstacle_velocity = 0.0;
  double period() const { return 2.0 * (t1 + t2); }
};

/// Builds the orbit from the null vector a of eq's N(t1, t2) (N_T for point symmetry); a's scale is irrelevant:
/// it is scaled so that w^T x0 = -g0 (eq. 5.2). Point symmetry (paper §6.2): x(-t1) = 0, x(t2) = 0, and the
/// obstacle moves at obstacle_velocity during contact. Throws std::invalid_argument for g0 = 0 or when the gap
/// cannot be closed (check gap_can_close first). a: (m), modal; cost O(m^2 + n m).
Orbit make_orbit(const EquationSet& eq, double t1, double t2, const Eigen::VectorXd& a);
/// Whether eq. (5.2) can scale the null vector a (m) at t1 into an orbit with w^T x0 = -g0: false exactly when
/// u^T W^-1 p0 = 0 (no scale closes the gap; a numerical outcome, checked before make_orbit). Cost O(m).
bool gap_can_close(const EquationSet& eq, double t1, const Eigen::VectorXd& a);

/// The orbit when its scale is free (g0 = 0, paper §6.1: eq. 5.2 does not fix it): scaled to unit energy, its
/// sign chosen so that the contact force is >= 0 at eq.force_probe(t2): mid-contact (axial: the only sign that can
/// be admissible) or t2 / 2 (point symmetry, where the force vanishes at t2).
Orbit make_unit_energy_orbit(const EquationSet& eq, double t1, double t2, const Eigen::VectorXd& a);

struct OrbitState {
  Eigen::VectorXd x, v;
  double gap = 0.0, force = 0.0;
};

/// The orbit with its modal coordinates (a, c, p0, p0dot) in `modal`'s basis. They belong to the modal form that
/// computed them: eigenvectors are defined up to sign (and up to a rotation within a repeated frequency), and another
/// machine's LAPACK may choose others for the same system, while x0, v0 do not depend on that choice. When
/// Phi W^-1 p0, Phi W^-1 p0dot give x0, v0 (relative 1e-8) the orbit is returned as it is (O(n m)); otherwise (e.g. an
/// orbit read from a result file written on another machine) p0, p0dot are rebuilt from x0, v0 by least squares on
/// the coupled mode shapes and a, c by the flows (O(n m^2)). Every function below that takes an orbit calls it, so a
/// loaded orbit gives the same trajectory, admissibility and multipliers on any machine.
/// Throws std::invalid_argument naming `where` when x0, v0 do not have n entries or are not a motion of the coupled
/// modes (an orbit of another system).
Orbit in_modal_basis(const ModalForm& modal, const Orbit& orbit, const char* where = "in_modal_basis");
/// State at time t in [0, T] (t = 0: contact onset; force is 0 in flight). x, v: (n); cost O(m^2 + n m).
OrbitState orbit_state(const ModalForm& modal, const Orbit& orbit, double t);

/// One period sampled at `samples` (>= 2) equally spaced times t_k = T k / (samples - 1), both ends included: the
/// rows of spp trajectory's CSV and of Python's spp.trajectory.
struct OrbitSamples {
  Eigen::VectorXd t, gap, force;  ///< (samples)
  Eigen::MatrixXd x, v;           ///< (samples, n)
};
OrbitSamples sample_orbit(const ModalForm& modal, const Orbit& orbit, int samples);

struct Admissibility {
  bool admissible = false;
  double min_gap = 0.0;            ///< smallest gap over the whole flight (0 at its tangent ends); certified
                                   ///< (axial), sampled on 2000 points per phase (point symmetry)
  double min_force = 0.0;          ///< smallest normal force over the whole contact phase; as min_gap
  double mid_flight_gap = 0.0;     ///< gap at t = -t1
  double mid_contact_force = 0.0;  ///< force at t = t2
  double onset_force_rate = 0.0;   ///< lambda'(0+): must be >= 0 (equals minus the gap jerk times a positive factor)
  bool ends_ok = false;            ///< leading Taylor terms at the phase ends have the admissible sign
  /// The verdict `admissible` is proved: axial, both minima certified to tolerance; point symmetry, "not
  /// admissible" is structural (the force is odd about t2), while its minima are only sampled.
  bool certified = false;
};

/// Axial symmetry: checks ineqs. (5.3) with a certified global minimum of each cosine sum (gap over the flight,
/// force over the contact phase); rel_tol scales the tolerance on the amplitude (sum |terms|) of each sum.
/// Cost: O(m) per evaluation of a sum, a few hundred evaluations per sum (detail::minimize).
Admissibility check_admissibility(const ModalForm& modal, const Orbit& orbit, double rel_tol = 1e-9);

/// Point symmetry (Remark 3.1): the force is odd about t2 (it changes sign in the contact phase), so the orbit is
/// never admissible; min_gap, min_force sampled (2000 points per phase, O(m^2) each: not proved minima); certified
/// is the structural "not admissible" verdict. Only a force zero at every sample gives admissible = true, and that
/// verdict rests on the samples alone (certified = false).
Admissibility sample_point_admissibility(const ModalForm& modal, const Orbit& orbit);

/// Signed admissibility margin, continuous in (t1, t2) and in the system: the smaller of
///   min over the flight of  g / (s / t1)^3  and  min over the contact phase of  lambda / (s / t2),
/// s the time to the phase's nearer end, each divided by its amplitude (|g0| + sum |gap terms|, sum |force
/// terms|). The end zeros of g (order 3) and lambda (order 1) are divided out analytically, so the margin is
/// >= 0 exactly when ineqs. (5.3) hold, ends included, and it crosses zero where admissibility is lost or
/// gained (an interior minimum touching zero, or a leading end coefficient changing sign). Sampled and refined
/// (not certified like check_admissibility): meant for locating boundaries along branches. Cost O(m) per sample,
/// 200 to 200000 samples per phase (40 per half-period of its fastest term).
double admissibility_margin(const ModalForm& modal, const Orbit& orbit);

/// Relative periodicity error |X(T) - X(0)| / |X(0)| of (x0, v0) after one period, propagated with the
/// physical first-order flows exp(t A) of M x'' + K x = 0 and M x'' + K~ x = 0 (paper's eqs. 3.9-3.13),
/// independently of the modal form. Cost O(n^3): two matrix exponentials of size 2n.
double return_error(const System& system, const Orbit& orbit);

}  // namespace spp
