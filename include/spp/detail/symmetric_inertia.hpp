#pragma once
// Inertia of a dense symmetric matrix shifted by x, from one symmetric indefinite factorisation
// P (A - x I) P^T = L D L^T (LAPACK's blocked Bunch–Kaufman dsytrf: ~m^3/3 flops, against ~4m^3/3 for the Householder
// tridiagonal form of SymmetricTridiagonal). Sylvester's law gives the inertia of A - x I + E exactly from the 1x1 and
// 2x2 blocks of D, with E the backward error of the computed factors; Higham (Accuracy and Stability of Numerical
// Algorithms, 2nd ed., Thm 11.3): |E| <= p(m) u (|A - x I| + P^T |L||D||L^T| P) + O(u^2), p a linear polynomial.
// The bound returned takes p(m) = 8 m (the constant the tridiagonal path assumes for its own 8 m eps |A|) and measures
// |L||D||L^T| a posteriori (O(m^2), after LAPACK's dsyconv has applied the pivots to L), so element growth shows in
// it instead of being assumed away. No Debian library returns this bound; the O(m^2) sums are ours.

#include <Eigen/Dense>
#include <limits>

namespace spp::detail {

struct ShiftedInertia {
  bool ok = false;  ///< the factorisation ran and D is nonsingular (else nothing below holds)
  int below = 0;    ///< number of eigenvalues of A + E strictly below x (negative eigenvalues of D)
  /// Bound on |E|_2 (first order in eps): 8 m eps (|| |A - x I| ||_inf + || |L||D||L^T| ||_inf).
  double error_bound = std::numeric_limits<double>::infinity();
  double growth = std::numeric_limits<double>::infinity();  ///< || |L||D||L^T| ||_inf / || |A - x I| ||_inf
};

/// Eigenvalues of A (symmetric, only its lower triangle is read) below x, by dsytrf of A - x I, with the bound above.
ShiftedInertia count_below_ldlt(const Eigen::MatrixXd& A, double x);

}  // namespace spp::detail
