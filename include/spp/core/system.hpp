#pragma once
// The mechanical system of the paper (Thorin, Delezoide, Legrand 2017, eqs. 1.1-1.2):
//   M x'' + K x = w lambda,  g(x) = w^T x + g0 >= 0,  lambda >= 0,  g lambda = 0.
// An immutable value, validated once when built. Units: any consistent set (x in length, M in mass, K in
// mass / time^2); every time the library reports (t1, t2, periods) is in the time unit of M and K, every frequency
// in rad per that unit.

#include <Eigen/Dense>
#include <string>

namespace spp {

/// A linear n-dof system with one affine unilateral constraint; w is stored unit-length.
class System {
 public:
  /// Validates and stores the system; w and g0 are divided by |w| (the gap keeps its sign and zero set).
  /// M, K: n x n symmetric positive definite, n <= kMaxDenseDofs; w: n, not zero. Cost O(n^3) (the definiteness
  /// test: eigenvalues).
  /// Throws std::invalid_argument naming the field and the rule on any invalid input.
  System(Eigen::MatrixXd M, Eigen::MatrixXd K, Eigen::VectorXd w, double g0, std::string name = "");

  /// A system stored with w already unit-length (the system a result file embeds): w and g0 are kept bit for bit
  /// (|w| must be 1 to 1e-12), and input_norm (> 0) is the |w| of the original input. Validated like the constructor.
  static System normalized(Eigen::MatrixXd M, Eigen::MatrixXd K, Eigen::VectorXd w, double g0, double input_norm,
                           std::string name = "");

  int n() const { return static_cast<int>(M_.rows()); }
  const Eigen::MatrixXd& M() const { return M_; }
  const Eigen::MatrixXd& K() const { return K_; }
  const Eigen::VectorXd& w() const { return w_; }        ///< unit contact direction
  double g0() const { return g0_; }                      ///< gap at rest, in the units of x (after normalising w)
  double w_input_norm() const { return w_input_norm_; }  ///< |w| as given; 1 means w was already unit
  const std::string& name() const { return name_; }

  /// K~ of Theorem 2.1, eq. (2.4): the stiffness that mimics the contact phase (n x n, O(n^3): solves with M).
  Eigen::MatrixXd contact_stiffness() const;

  /// Gap g(x) = w^T x + g0 (w unit, g0 divided by |w| as given). The contact force of eq. (2.7) is in orbit.hpp
  /// (OrbitState::force).
  double gap(const Eigen::VectorXd& x) const { return w_.dot(x) + g0_; }

 private:
  Eigen::MatrixXd M_, K_;
  Eigen::VectorXd w_;
  double g0_ = 0.0;
  double w_input_norm_ = 1.0;
  std::string name_;
};

/// Largest n a (dense) System takes. Its O(n^3) steps (the definiteness test, the modal form's two eigenproblems) take
/// ~25 min at this size on one core (extrapolated as n^3 from the 1.5 s measured at n = 1000, not measured here) and
/// each n x n matrix 0.8 GB; beyond, a model is reduced first (spp reduce,
/// reduction/craig_bampton.hpp: sparse, to its contact coordinate plus m modes). The constructor refuses more.
inline constexpr int kMaxDenseDofs = 10000;

/// Relative difference below which two values that should be equal are the same to rounding: a unit w's norm, a
/// system compared with the one a result file holds (written with 17 digits), a parametric system's affine parts
/// (each a sum of a few rounded terms: ~1e-15 apart; 1e-12 leaves room for n-term sums, and is far below any
/// meaningful change of a model).
inline constexpr double kSameToRounding = 1e-12;

/// Whether a and b are one system to rounding: same n, and M, K, w, g0 equal to kSameToRounding relative to each
/// one's largest entry (at least 1). A result file's system against the one a caller passes with it. Cost O(n^2).
bool same_system(const System& a, const System& b);

/// Relative tolerance used to accept M and K as symmetric: |A - A^T|_max <= tol * |A|_max.
inline constexpr double kSymmetryTolerance = 1e-10;
/// M and K are positive definite when the smallest eigenvalue of their unit-diagonal scaling exceeds this many
/// n eps times the largest: below, the matrix is singular to rounding and the modal form meaningless.
inline constexpr double kDefinitenessMargin = 1e3;

}  // namespace spp
