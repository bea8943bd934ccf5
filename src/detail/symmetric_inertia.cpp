#include "spp/detail/symmetric_inertia.hpp"

#include <climits>
#include <cmath>
#include <vector>

#include "detail/lapack.hpp"

namespace spp::detail {

ShiftedInertia count_below_ldlt(const Eigen::MatrixXd& A, double x) {
  ShiftedInertia r;
  const Eigen::Index m = A.rows();
  if (m == 0 || m > INT_MAX) return r;
  const int n = static_cast<int>(m);
  Eigen::MatrixXd a = A;
  a.diagonal().array() -= x;
  // || |A - x I| ||_inf from the lower triangle (the part LAPACK reads): row i is row i of the lower part plus
  // column i below the diagonal
  Eigen::VectorXd rows = Eigen::VectorXd::Zero(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    rows(j) += std::abs(a(j, j));
    for (Eigen::Index i = j + 1; i < m; ++i) {
      const double v = std::abs(a(i, j));
      rows(i) += v;
      rows(j) += v;
    }
  }
  const double norm_a = rows.maxCoeff();
  std::vector<int> ipiv(static_cast<std::size_t>(n));
  const char uplo = 'L';
  int info = 0;
  const bool factored = call_with_workspace([&](double* work, const int* lwork, int*, const int*, int* inf) {
    dsytrf_(&uplo, &n, a.data(), &n, ipiv.data(), work, lwork, inf, 1);
    info = *inf;
  });
  if (!factored) return r;  // info > 0: an exactly singular D (x on an eigenvalue of the computed factors)
  // Inertia of D: a 1x1 block by its sign; a 2x2 block [[a, b], [b, c]] by its determinant and trace (Bunch–Kaufman
  // chooses one only where |a c| < alpha^2 b^2, alpha ~ 0.64, so its determinant is negative and of certain sign).
  int below = 0;
  for (int k = 0; k < n;) {
    if (ipiv[static_cast<std::size_t>(k)] > 0) {
      const double d = a(k, k);
      if (d == 0.0) return r;
      below += d < 0.0;
      ++k;
    } else {
      const double p = a(k, k), q = a(k + 1, k), s = a(k + 1, k + 1), det = p * s - q * q;
      if (det == 0.0) return r;
      below += det < 0.0 ? 1 : (p + s < 0.0 ? 2 : 0);
      k += 2;
    }
  }
  // L with the pivots applied (unit lower triangular, strictly below the diagonal of a), D's off-diagonal in e
  std::vector<double> e(static_cast<std::size_t>(n));
  const char way = 'C';
  dsyconv_(&uplo, &way, &n, a.data(), &n, ipiv.data(), e.data(), &info, 1, 1);
  if (info != 0) return r;
  // row sums of |L| |D| |L|^T: v = |L|^T 1, w = |D| v, then |L| w
  Eigen::VectorXd v = Eigen::VectorXd::Ones(m), w(m), u(m);
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = j + 1; i < m; ++i) v(j) += std::abs(a(i, j));
  for (Eigen::Index k = 0; k < m; ++k) {
    w(k) = std::abs(a(k, k)) * v(k);
    if (k + 1 < m) w(k) += std::abs(e[static_cast<std::size_t>(k)]) * v(k + 1);
    if (k > 0) w(k) += std::abs(e[static_cast<std::size_t>(k - 1)]) * v(k - 1);
  }
  u = w;
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = j + 1; i < m; ++i) u(i) += std::abs(a(i, j)) * w(j);
  const double norm_ldl = u.maxCoeff();
  r.ok = true;
  r.below = below;
  r.growth = norm_a > 0 ? norm_ldl / norm_a : std::numeric_limits<double>::infinity();
  r.error_bound = 8.0 * static_cast<double>(m) * std::numeric_limits<double>::epsilon() * (norm_a + norm_ldl);
  return r;
}

}  // namespace spp::detail
