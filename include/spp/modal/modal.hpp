#pragma once
// Modal, symmetric form of the SPP equations (shared design note "modal form", §1-2).
//   K phi = omega^2 M phi, Phi^T M Phi = I, x = Phi q, p = W q, u = Phi^T w / |Phi^T w|, z = W u.
//   free flight  p'' = -W^2 p;   contact phase (K~ of eq. 2.4)  p'' = -S p,  S = W^2 - z z^T = G D^2 G^T.
//   SPP equations: H(t1,t2) p0 = 0, z^T p0 = 0 with H = W tan(W t1) + G D tan(D t2) G^T   (eqs. 5.1a-b).
//   Pole-free form: N(t1,t2) a = 0, N = G D sin(D t2) G^T cos(W t1) + G cos(D t2) G^T W sin(W t1),
//   where a = p(-t1) is the modal position at mid-flight and p0 = cos(W t1) a.
// Modes that do not see the contact (u_k = 0, after rotating repeated frequencies so that only one mode of
// each repeated group couples) are set apart: they keep the same frequency in both phases and take no part in
// an SPP (their amplitude must be zero for the gap to close at rest position g0 != 0).

#include <Eigen/Dense>
#include <vector>

#include "spp/core/system.hpp"

namespace spp {

/// Which of Theorem 3.1's two cases: axes of symmetry at -t1 and t2 (every generic SPP, eqs. 5.1), or points of
/// symmetry there (det T2 = 0, paper §6.2 and Remark 3.1: potential SPPs only, never admissible).
/// Point form (x(-t1) = 0, x(t2) = 0): H_T(t1, t2) v = 0, v = p'(0), z^T p0 = 0, with
///   H_T = W^-1 tan(W t1) + G tan(D t2) D^-1 G^T  (tan(d t)/d -> t at d = 0), symmetric, PSD derivatives,
///   pole-free N_T = cos(S^1/2 t2) W^-1 sin(W t1) + S^-1/2 sin(S^1/2 t2) cos(W t1), v = cos(W t1) a,
///   p0 = W^-1 sin(W t1) a = -G tan(D t2) D^-1 G^T v.
enum class Symmetry { Axial, Point };
const char* to_string(Symmetry s);

class ModalForm {
 public:
  /// decoupling_tol: a mode with |u_k| below it is treated as not seeing the contact.
  /// repeat_tol: relative gap below which two frequencies are treated as one repeated frequency.
  explicit ModalForm(const System& system, double decoupling_tol = 1e-10, double repeat_tol = 1e-9);

  int n() const { return n_; }                               ///< dofs of the system
  int m() const { return static_cast<int>(omega_.size()); }  ///< modes that see the contact
  const Eigen::VectorXd& omega() const { return omega_; }    ///< coupled free-flight frequencies, ascending
  const Eigen::VectorXd& u() const { return u_; }            ///< unit coupling vector (coupled modes)
  const Eigen::VectorXd& z() const { return z_; }            ///< z = W u
  const Eigen::VectorXd& d() const { return d_; }            ///< contact-phase frequencies, d(0) = 0
  const Eigen::MatrixXd& G() const { return G_; }            ///< S = G D^2 G^T
  const Eigen::MatrixXd& Phi() const { return Phi_; }        ///< n x m coupled mode shapes, M-normalised
  const Eigen::VectorXd& omega_decoupled() const { return omega_dec_; }
  const Eigen::MatrixXd& Phi_decoupled() const { return Phi_dec_; }
  double beta() const { return beta_; }  ///< |Phi^T w| = sqrt(w^T M^{-1} w)
  double g0() const { return g0_; }
  /// Number of repeated-frequency groups that were rotated (diagnostic).
  int repeated_groups() const { return repeated_groups_; }

  /// H(t1,t2) (symmetric m x m) and its partial derivatives; all PSD derivatives (design note §3).
  /// With Symmetry::Point the same quantities of the point form (H_T, N_T: see Symmetry).
  Eigen::MatrixXd H(double t1, double t2, Symmetry sym = Symmetry::Axial) const;
  Eigen::MatrixXd contact_part(double t2, Symmetry sym = Symmetry::Axial) const;  ///< G D tan(D t2) G^T
  Eigen::VectorXd contact_eigs(double t2, Symmetry sym = Symmetry::Axial) const;  ///< diagonal of D tan(D t2)
  Eigen::VectorXd flight_part(double t1, Symmetry sym = Symmetry::Axial) const;   ///< diagonal of W tan(W t1)
  Eigen::VectorXd dflight_dt1(double t1, Symmetry sym = Symmetry::Axial) const;   ///< diagonal of W^2 sec^2(W t1)
  /// Eigenvalues of d(contact_part)/dt2 in the G basis: D^2 sec^2(D t2) (point: sec^2(D t2)).
  Eigen::VectorXd dcontact_eigs(double t2, Symmetry sym = Symmetry::Axial) const;
  Eigen::MatrixXd dcontact_dt2(double t2, Symmetry sym = Symmetry::Axial) const;  ///< G D^2 sec^2(D t2) G^T
  /// Pole-free N(t1,t2) and derivatives (design note §2).
  Eigen::MatrixXd N(double t1, double t2, Symmetry sym = Symmetry::Axial) const;
  Eigen::MatrixXd dN_dt1(double t1, double t2, Symmetry sym = Symmetry::Axial) const;
  Eigen::MatrixXd dN_dt2(double t1, double t2, Symmetry sym = Symmetry::Axial) const;
  /// Modal position and velocity at contact onset from the null vector a of N: axial p0 = cos(W t1) a,
  /// p0' = -W sin(W t1) a; point p0 = W^-1 sin(W t1) a, p0' = cos(W t1) a.
  Eigen::VectorXd onset_position(double t1, const Eigen::VectorXd& a, Symmetry sym = Symmetry::Axial) const;
  Eigen::VectorXd onset_velocity(double t1, const Eigen::VectorXd& a, Symmetry sym = Symmetry::Axial) const;
  /// d/dt1 of onset_position.
  Eigen::VectorXd onset_position_dt1(double t1, const Eigen::VectorXd& a, Symmetry sym = Symmetry::Axial) const;
  /// c(t2) with z^T p0 = c^T b for the null vector b of H: axial z; point -G tan(D t2) D^-1 G^T z (then
  /// b = v). And dc/dt2.
  Eigen::VectorXd onset_direction(double t2, Symmetry sym = Symmetry::Axial) const;
  Eigen::VectorXd onset_direction_dt2(double t2, Symmetry sym = Symmetry::Axial) const;

  /// Matrix functions of the contact phase, G f(D) G^T, for the flows.
  Eigen::MatrixXd contact_cos(double t) const;   ///< cos(S^{1/2} t)
  Eigen::MatrixXd contact_sinc(double t) const;  ///< S^{-1/2} sin(S^{1/2} t)  (t at d = 0)
  Eigen::MatrixXd contact_msin(double t) const;  ///< S^{1/2} sin(S^{1/2} t)

  /// Poles of tan(W t1) (flight) and tan(D t2) (contact) in the open interval (lo, hi), ascending, merged
  /// when closer than merge_tol (relative).
  std::vector<double> flight_poles(double lo, double hi) const;
  std::vector<double> contact_poles(double lo, double hi) const;

 private:
  int n_ = 0;
  Eigen::VectorXd omega_, u_, z_, d_, omega_dec_;
  Eigen::MatrixXd G_, Phi_, Phi_dec_;
  double beta_ = 0.0, g0_ = 0.0;
  int repeated_groups_ = 0;
};

/// Poles (k + 1/2) pi / f for every positive frequency f in freqs, within (lo, hi), ascending and merged (closer
/// than 1e-12 relative). Throws std::invalid_argument naming the count when there are more than max_count, or when
/// hi is so far out that consecutive poles are not distinct doubles. Cost O(count); no allocation before the check.
std::vector<double> tangent_poles(const Eigen::VectorXd& freqs, double lo, double hi, double max_count = 1e8);
/// Number of poles tangent_poles would list (before merging), without listing them: O(freqs).
double count_tangent_poles(const Eigen::VectorXd& freqs, double lo, double hi);

}  // namespace spp
