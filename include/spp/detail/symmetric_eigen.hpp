#pragma once
// Full symmetric eigendecompositions, dense: A = U diag(values) U^T (values ascending, U orthonormal), and the
// generalised K v = lambda M v (M positive definite, V^T M V = I). From m = kLapackFrom on they call LAPACK's
// divide and conquer (dsyevd, dsygvd: blocked, level-3 BLAS), below it Eigen's QR iteration, which has less
// overhead for small matrices. Both are backward stable: |A - U diag(values) U^T| <= c m eps |A|.
// Measured (this 2-core machine, OpenBLAS serial): `build/bench/bench_linalg`, figures in README "Speed".
// Cost: O(m^3) time, O(m^2) memory; the vectors cost ~3x the values alone.

#include <Eigen/Dense>

namespace spp::detail {

/// Size from which LAPACK's divide and conquer is used (measured crossover with Eigen's solver, ~100-150).
inline constexpr Eigen::Index kLapackFrom = 128;

struct SymmetricEigen {
  Eigen::VectorXd values;   ///< ascending
  Eigen::MatrixXd vectors;  ///< columns; empty when only the values were asked for
  bool ok = false;          ///< false when the solver did not converge (values and vectors are then unusable)
};

/// Eigenpairs of the symmetric A (only its lower triangle is read).
SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& A, bool vectors = true);

/// K v = lambda M v with K symmetric and M symmetric positive definite: values ascending, vectors M-normalised.
SymmetricEigen generalized_symmetric_eigen(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M);

}  // namespace spp::detail
