#pragma once
// One eigenpair and the inertia of a dense symmetric matrix through its Householder tridiagonal form
// (Eigen's, or LAPACK's blocked dsytrd from m = kLapackFrom on; ~4/3 m^3): Sturm counts give the number of eigenvalues
// below any x (Sylvester's law on the LDL^T of T - x I), bisection the k-th eigenvalue to rounding level, inverse
// iteration its vector. The full decomposition with vectors costs 5-10x more (measured: m = 30: 126 us vs 9 us for the
// tridiagonalisation; m = 100: 2650 us vs 267 us).

#include <Eigen/Dense>

namespace spp::detail {

class SymmetricTridiagonal {
 public:
  explicit SymmetricTridiagonal(const Eigen::MatrixXd& A);

  int size() const { return static_cast<int>(a_.size()); }
  /// Number of eigenvalues strictly below x.
  int count_below(double x) const;
  /// k-th smallest eigenvalue (0-based), to absolute accuracy ~ eps * |A|.
  double eigenvalue(int k) const;
  /// Unit eigenvector for an eigenvalue lambda (from eigenvalue()), in the basis of A.
  Eigen::VectorXd eigenvector(double lambda) const;
  double norm_bound() const { return bound_; }  ///< Gershgorin bound on |eigenvalues|

 private:
  Eigen::MatrixXd householder_;  // packed Householder reflectors (Eigen's Tridiagonalization storage)
  Eigen::VectorXd hcoeffs_;      // their coefficients (LAPACK's tau when lapack_)
  bool lapack_ = false;          // reduced by LAPACK's dsytrd (m >= kLapackFrom) rather than Eigen
  Eigen::VectorXd a_, b_;        // diagonal, sub-diagonal of T
  double bound_ = 0.0, pivmin_ = 0.0;
};

}  // namespace spp::detail
