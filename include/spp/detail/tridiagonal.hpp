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
  /// k-th smallest eigenvalue (0-based), to absolute accuracy ~ eps * |A|: bisection on the Sturm count, two halvings
  /// per pass over T (bit for bit eigenvalue_by_bisection's result, about half its time).
  double eigenvalue(int k) const;
  /// The same by plain bisection, one Sturm count per halving (the reference eigenvalue() reproduces).
  double eigenvalue_by_bisection(int k) const;
  /// Unit eigenvector for an eigenvalue lambda (from eigenvalue()), in the basis of A.
  Eigen::VectorXd eigenvector(double lambda) const;
  double norm_bound() const { return bound_; }  ///< Gershgorin bound on |eigenvalues|

 private:
  void count_below3(const double x[3], int count[3]) const;  // count_below at three points in one pass
  Eigen::MatrixXd householder_;  // packed Householder reflectors (Eigen's Tridiagonalization storage)
  Eigen::VectorXd hcoeffs_;      // their coefficients (LAPACK's tau when lapack_)
  bool lapack_ = false;          // reduced by LAPACK's dsytrd (m >= kLapackFrom) rather than Eigen
  Eigen::VectorXd a_, b_;        // diagonal, sub-diagonal of T
  double bound_ = 0.0, pivmin_ = 0.0;
};

}  // namespace spp::detail
