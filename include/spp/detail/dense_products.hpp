#pragma once
// The dense m x m products of an evaluation and of a step certificate (G diag(e) G^T, U diag(e) U^T, A B). From
// m = kLapackFrom on they call BLAS's dgemm (OpenBLAS: blocked, vectorised for the running CPU: 4-5x Eigen's own
// product at m = 300-1000 in a build without -march=native, see `build/bench/bench_linalg`); below it they are
// Eigen's expressions, unchanged, so small systems give the same numbers bit for bit as without BLAS.
// Cost: O(m^3) time (m^2 n for rectangular factors), one m x m result.

#include <Eigen/Dense>

namespace spp::detail {

/// While alive, OpenBLAS runs its calls on the calling thread only (openblas_set_num_threads(1)); the previous
/// setting is restored at the end. For the solver's worker threads, which call BLAS at the same time: OpenBLAS's
/// own threads would oversubscribe the cores (measured: 4 threads x 40 decompositions at m = 160 took 33-118 s
/// instead of 1 s). A process-wide setting: Python code calling numpy during a solve runs single-threaded too.
/// No effect with another BLAS. Nested guards are no-ops.
class SingleThreadedBlas {
 public:
  SingleThreadedBlas();
  ~SingleThreadedBlas();
  SingleThreadedBlas(const SingleThreadedBlas&) = delete;
  SingleThreadedBlas& operator=(const SingleThreadedBlas&) = delete;

 private:
  int saved_ = 0;
};

/// op(A) * op(B), op the transpose where asked.
Eigen::MatrixXd product(const Eigen::MatrixXd& A, bool transpose_a, const Eigen::MatrixXd& B, bool transpose_b);

/// G diag(e) G^T (symmetric).
Eigen::MatrixXd congruence(const Eigen::MatrixXd& G, const Eigen::VectorXd& e);

/// G^T diag(e) G (symmetric).
Eigen::MatrixXd congruence_transposed(const Eigen::MatrixXd& G, const Eigen::VectorXd& e);

}  // namespace spp::detail
