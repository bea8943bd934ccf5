#pragma once
// Modal, symmetric form of the SPP equations (shared design note "modal form", §1-2).
//   K phi = omega^2 M phi, Phi^T M Phi = I, x = Phi q, p = W q, u = Phi^T w / |Phi^T w|, z = W u.
//   free flight  p'' = -W^2 p;   contact phase (K~ of eq. 2.4)  p'' = -S p,  S = W^2 - z z^T = G D^2 G^T.
//   The SPP equations written on it (H, N, the onset state of each case of Theorem 3.1) are equation sets:
//   equation_set.hpp. This class is data only.
// Modes that do not see the contact (u_k = 0, after rotating repeated frequencies so that only one mode of
// each repeated group couples) are set apart: they keep the same frequency in both phases and take no part in
// an SPP (their amplitude must be zero for the gap to close at rest position g0 != 0).

#include <Eigen/Dense>
#include <optional>
#include <string_view>
#include <vector>

#include "spp/core/system.hpp"

namespace spp {

/// Which of Theorem 3.1's two cases: axes of symmetry at -t1 and t2 (every generic SPP, eqs. 5.1), or points of
/// symmetry there (det T2 = 0, paper §6.2 and Remark 3.1: potential SPPs only, never admissible). The user-facing
/// option; make_equations (equation_set.hpp) turns it into the equations of its case.
enum class Symmetry { Axial, Point };
const char* to_string(Symmetry s);
/// The Symmetry whose to_string is `name` ("axial", "point"); nullopt for any other name (the one parser of the CLI,
/// the result files and Python).
std::optional<Symmetry> symmetry_named(std::string_view name);

/// Two frequencies closer than this (relative) are one repeated frequency: the eigensolver's rounding on omega^2 is
/// ~eps omega_max^2 (1e-16 relative at best), so a gap below 1e-9 is no gap a search could use.
inline constexpr double kRepeatedFrequency = 1e-9;

/// Repeated frequencies (groups within repeat_tol relative, omega ascending): each group's M-normalised shapes
/// (columns of Phi) rotated by one reflection so that only the group's first couples to w (Phi^T w zero on the
/// others), and its frequencies set to their mean. Any basis of a repeated eigenspace is one; this one makes the
/// modes that never see the contact explicit (they are dropped, or reported as decoupled). Returns the number of
/// groups. O(n g^2) for groups of size g. Used by ModalForm and by the k-IPP model (modes/kipp.hpp).
int align_repeated_frequencies(Eigen::VectorXd& omega, Eigen::MatrixXd& Phi, const Eigen::VectorXd& w,
                               double repeat_tol);

class ModalForm {
 public:
  /// decoupling_tol: a mode with |u_k| below it is treated as not seeing the contact.
  /// repeat_tol: relative gap below which two frequencies are treated as one repeated frequency.
  /// Cost O(n^3) (two symmetric eigenproblems, ~1 s at n = 1000): build it once and pass it on.
  /// Throws std::invalid_argument when double precision cannot resolve the spectrum: omega_max / omega_min above
  /// ~6.7e4 (the slowest omega^2 would keep fewer than 6 digits), or omega^2 not positive and finite.
  explicit ModalForm(const System& system, double decoupling_tol = 1e-10, double repeat_tol = kRepeatedFrequency);

  int n() const { return n_; }                               ///< dofs of the system
  int m() const { return static_cast<int>(omega_.size()); }  ///< modes that see the contact
  const Eigen::VectorXd& omega() const { return omega_; }    ///< (m) coupled free-flight frequencies, ascending
  const Eigen::VectorXd& u() const { return u_; }            ///< unit coupling vector (coupled modes)
  const Eigen::VectorXd& z() const { return z_; }            ///< z = W u
  const Eigen::VectorXd& d() const { return d_; }            ///< (m) contact-phase frequencies, d(0) = 0
  const Eigen::MatrixXd& G() const { return G_; }            ///< m x m orthogonal, S = G D^2 G^T
  const Eigen::MatrixXd& Phi() const { return Phi_; }        ///< n x m coupled mode shapes, M-normalised
  const Eigen::VectorXd& omega_decoupled() const { return omega_dec_; }
  const Eigen::MatrixXd& Phi_decoupled() const { return Phi_dec_; }
  double beta() const { return beta_; }  ///< |Phi^T w| = sqrt(w^T M^{-1} w)
  double g0() const { return g0_; }
  /// Number of repeated-frequency groups that were rotated (diagnostic).
  int repeated_groups() const { return repeated_groups_; }
  /// The modal form's backward error from the conditioning of M (dimensionless; 0 when the equilibrated mass matrix
  /// M~ = D^-1/2 M D^-1/2, D = diag M, has a condition number of at most 1e2, where the stability bound's own terms
  /// cover the eigensolvers' error). Else measured (modal.cpp, modal_data_error; error-free split products in double,
  /// O(n^3) in BLAS, ~3.7x the eigensolve at n = 1000, with their rounding bounded and added): omega and u are exact
  /// for the system written in its M-orthonormal modal coordinates with the stiffness off by data_error()
  /// omega_max^2 (Frobenius norm) and u off by data_error(). The eigensolver goes through a Cholesky factor of M and
  /// its error grows with cond(M): found by issue 14's attack (the chain written as x = T y with a dense T of cond 1e3,
  /// cond M 1e6, had Floquet radii off by up to 50 times their bound). Used by the stability bound (floquet.cpp).
  double data_error() const { return data_error_; }
  /// With data_error(): the largest relative error of an omega_k^2 that the stiffness error can cause: of each mode's
  /// row, its diagonal entry plus the rest of its row squared over the gap to the neighbouring omega^2 (Kato-Temple),
  /// or the rest of its row where the gap is not proved, over its own omega_k^2 (measured likewise; 0 with data_error()
  /// 0).
  double frequency_error() const { return frequency_error_; }

  /// Matrix functions of the contact phase, G f(D) G^T, for the flows: m x m, O(m^3) each.
  Eigen::MatrixXd contact_cos(double t) const;   ///< cos(S^{1/2} t)
  Eigen::MatrixXd contact_sinc(double t) const;  ///< S^{-1/2} sin(S^{1/2} t)  (t at d = 0)
  Eigen::MatrixXd contact_msin(double t) const;  ///< S^{1/2} sin(S^{1/2} t)

  /// Poles of tan(W t1) (flight) and tan(D t2) (contact) in the open interval (lo, hi), ascending, merged
  /// as tangent_poles merges them.
  std::vector<double> flight_poles(double lo, double hi) const;
  std::vector<double> contact_poles(double lo, double hi) const;

  /// The same modal form in the time tau = rate t (rate > 0, rad per time unit): every frequency (omega, d, z and the
  /// decoupled ones) divided by rate; shapes, u, G, beta and g0 unchanged. It is the modal form of the system with K
  /// divided by rate^2, without a new eigen-decomposition: O(n m). Throws std::invalid_argument for a rate not
  /// positive and finite.
  ModalForm in_time_unit(double rate) const;

 private:
  int n_ = 0;
  Eigen::VectorXd omega_, u_, z_, d_, omega_dec_;
  Eigen::MatrixXd G_, Phi_, Phi_dec_;
  double beta_ = 0.0, g0_ = 0.0, data_error_ = 0.0, frequency_error_ = 0.0;
  int repeated_groups_ = 0;
};

/// Poles (k + 1/2) pi / f for every positive frequency f in freqs, within (lo, hi), ascending and merged (closer
/// than 1e-12 relative). Throws std::invalid_argument naming the count when there are more than max_count, or when
/// hi is so far out that consecutive poles are not distinct doubles. Cost O(count); no allocation before the check.
std::vector<double> tangent_poles(const Eigen::VectorXd& freqs, double lo, double hi, double max_count = 1e8);
/// Number of poles tangent_poles would list (before merging), without listing them: O(freqs).
double count_tangent_poles(const Eigen::VectorXd& freqs, double lo, double hi);

}  // namespace spp
