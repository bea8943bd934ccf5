#pragma once
// The bordered form of H over a box (docs/modal-form.md §3c): the same zero set, with every entry bounded next to
// pole lines.
//
// Next to a pole of one flight mode i, H = H' + f_i e_i e_i^T with f_i = omega_i tan(omega_i t1) unbounded; next to a
// pole of a contact mode j, H = H' + c_j g_j g_j^T (g_j = G e_j, c_j = d_j tan(d_j t2)). For any set of such "pole
// modes", with U = [e_i ..., g_j ...] and Lambda = diag(f_i ..., c_j ...),
//
//     B = [[H', U], [U^T, -Lambda^-1]]
//
// is the bordered form: its Schur complement on the border block is H' + U Lambda U^T = H, so
//  - B [b; nu] = 0 iff H b = 0 with nu = Lambda U^T b (same null vectors, extended; same sign of c^T b);
//  - inertia(B) = inertia(H) + inertia(-Lambda^-1);
//  - -1/f_i = -cot(omega_i t1) / omega_i = tan(omega_i t1 - pi/2) / omega_i is increasing, bounded and analytic
//    through the pole of f_i: B grows with t1 and t2 (Loewner) like H, with derivatives that stay O(1) where those of
//    H grow like 1 / distance^2.
// B keeps the structure of H: B = K0 + diag(phi(t1)) + Gx diag(psi(t2)) Gx^T with K0 constant, Gx with orthonormal
// columns and every phase a tan(w t + shift) (or 0), so the bounds of step_certificate apply to it unchanged.
// Written here because no library provides this structured matrix family.

#include <Eigen/Dense>
#include <vector>

#include "spp/modal/equation_set.hpp"

namespace spp::search {

/// Phase functions a_k tan(w_k t + shift_k) (a_k = 0: the constant 0; linear_k: the function t, point symmetry's
/// zero frequency; reciprocal_k: -a_k / t, its border), one per coordinate (flight, in t1) or per column of Gx
/// (contact, in t2). Each is increasing with a monotone second derivative on an interval without pole (t > 0 for the
/// reciprocal), so its extremes over an interval are at the ends.
struct PhaseFamily {
  Eigen::VectorXd amp, freq, shift;
  Eigen::Array<bool, Eigen::Dynamic, 1> linear, reciprocal;
  Eigen::Index size() const { return amp.size(); }
  /// Phase k at t (inside one of its pole intervals): value, first and second derivative.
  struct Point {
    double v, d1, d2;
  };
  Point at(Eigen::Index k, double t) const;
  Eigen::VectorXd value(double t) const;
  Eigen::VectorXd d1(double t) const;  ///< first derivative
  /// A family of `size` constant zero phases.
  static PhaseFamily zeros(Eigen::Index size);
  /// The phases of H itself: omega tan(omega t) (PhaseShape::FTan) or tan(omega t) / omega (TanOverF).
  static PhaseFamily of_modes(const Eigen::VectorXd& freqs, PhaseShape shape);
};

class BorderedForm {
 public:
  /// Borders the modes that stay next to their pole over [lo1, hi1] x [lo2, hi2] (|tan| >= 1 at both ends of the
  /// box's interval, no zero of tan between): there -1/f is bounded by the mode's own scale, and f is not. The box
  /// holds no pole line.
  /// Where the onset direction moves with t2 (EquationSet::onset_direction_fixed false, e.g. point symmetry's
  /// c(t2) = -G diag(tan(d t2) / d) G^T z), every contact mode is bordered (the zero frequency's phase t2 by -1/t2),
  /// which makes it constant: c^T b = -(G^T z)^T nu. Valid only where no tan(d_j t2) vanishes in [lo2, hi2] (and
  /// t2 > 0): valid() says.
  BorderedForm(const EquationSet& eq, double lo1, double hi1, double lo2, double hi2);

  bool valid() const { return valid_; }
  int size() const { return static_cast<int>(flight_.size()); }
  int bordered() const { return size() - m_; }
  Eigen::MatrixXd matrix(double t1, double t2) const;
  const PhaseFamily& flight() const { return flight_; }    ///< diag(phi(t1)), one phase per coordinate
  const PhaseFamily& contact() const { return contact_; }  ///< Gx diag(psi(t2)) Gx^T, one phase per column
  const Eigen::MatrixXd& Gx() const { return Gx_; }
  /// The onset direction extended by zeros: c^T [b; nu] = z^T b / |z|.
  const Eigen::VectorXd& onset() const { return c_; }
  /// The bordered modes: flight modes, then m + contact modes (two forms with the same key are the same matrices).
  std::vector<int> key() const;
  /// Lambda at (t1, t2): f_i (bordered flight modes), then c_j (bordered contact modes), in border order.
  Eigen::VectorXd border_values(double t1, double t2) const;
  /// [b; Lambda U^T b], the null vector of B for a null vector b of H at (t1, t2).
  Eigen::VectorXd extend(const Eigen::VectorXd& b, double t1, double t2) const;
  /// Number of positive border values at (t1, t2): B's count of negative eigenvalues exceeds H's by it (Haynsworth).
  int positive_border_values(double t1, double t2) const;

 private:
  const EquationSet& eq_;
  bool valid_ = true;
  int m_ = 0;
  std::vector<int> flight_modes_, contact_modes_;  // bordered, in border order (flight first)
  PhaseFamily flight_, contact_;
  Eigen::MatrixXd Gx_, K0_;
  Eigen::VectorXd c_;
};

/// Eigenvalue k of H read in the bordered form (docs/modal-form.md §3c): lambda_{k + p}(B) at (t1, t2), p the number
/// of positive border values. By Haynsworth's inertia additivity it has the sign of lambda_k(H) and vanishes with it,
/// and on a zero curve of det H its vector is H's null vector extended, x = [b; nu] / |[b; nu]|. Next to a pole line
/// H's normwise error bound (8 m eps |H|, |H| ~ 1 / distance) is 1e6-1e9 times the gap of the slowest modes of a
/// clustered chain, while B's entries, hence its error, stay O(1): a root placed in B is placed to B's accuracy.
struct BorderedEigen {
  bool ok = false;        ///< false: no eigenvalue k + p, or a border value is not finite (use H)
  double lam = 0;         ///< lambda_{k + p}(B), with the sign of lambda_k(H)
  double error = 0;       ///< absolute error bound of the computed eigenvalues of B (8 (m + nb) eps |B|)
  double scale = 0;       ///< a bound of |B|_2 (Gershgorin)
  double l1 = 0, l2 = 0;  ///< x^T dB/dt1 x and x^T dB/dt2 x (>= 0: B grows with t1 and t2)
  Eigen::VectorXd b;      ///< x's first m entries, normalised (H's unit null vector where lam = 0)
};
/// The above for curve k (0-based, ascending) of H. Cost: one Householder tridiagonalisation of the (m + nb)-square B
/// (~4/3 (m + nb)^3), bisection for one eigenvalue and inverse iteration for its vector; O(m^2) memory.
BorderedEigen bordered_eigenpair(const BorderedForm& bf, double t1, double t2, int k);

}  // namespace spp::search
