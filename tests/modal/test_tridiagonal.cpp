// One eigenpair and the inertia through the tridiagonal form, against Eigen's dense symmetric solver.
#include <gtest/gtest.h>

#include <random>

#include "spp/detail/tridiagonal.hpp"

using spp::detail::SymmetricTridiagonal;

TEST(Tridiagonal, EigenpairsAndCountsMatchDenseSolver) {
  std::mt19937 rng(5);
  std::normal_distribution<double> nd;
  for (int m : {1, 2, 5, 30, 100}) {
    Eigen::MatrixXd A(m, m);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) A(i, j) = nd(rng);
    A = (A + A.transpose()).eval();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
    const SymmetricTridiagonal T(A);
    const double scale = es.eigenvalues().cwiseAbs().maxCoeff();
    for (int k = 0; k < m; ++k) {
      const double l = T.eigenvalue(k);
      EXPECT_NEAR(l, es.eigenvalues()(k), 1e-13 * scale * m) << "m = " << m << ", k = " << k;
      const Eigen::VectorXd v = T.eigenvector(l);
      EXPECT_NEAR(v.norm(), 1.0, 1e-14);
      EXPECT_LT((A * v - l * v).norm(), 1e-12 * scale * m) << "m = " << m << ", k = " << k;
    }
    // Sylvester inertia: eigenvalues below x, at x between consecutive eigenvalues
    for (int k = 0; k + 1 < m; ++k)
      EXPECT_EQ(T.count_below(0.5 * (es.eigenvalues()(k) + es.eigenvalues()(k + 1))), k + 1);
    EXPECT_EQ(T.count_below(es.eigenvalues()(0) - 1.0), 0);
    EXPECT_LE(es.eigenvalues().cwiseAbs().maxCoeff(), T.norm_bound() * (1 + 1e-14));
  }
}

TEST(Tridiagonal, InertiaOfAnIndefiniteMatrixWithAZeroPivot) {
  // [[0, 1], [1, 0]] has eigenvalues -1 and 1; the first Sturm pivot at x = 0 is exactly zero.
  Eigen::MatrixXd A(2, 2);
  A << 0, 1, 1, 0;
  const SymmetricTridiagonal T(A);
  EXPECT_EQ(T.count_below(0.0), 1);
  EXPECT_NEAR(T.eigenvalue(0), -1.0, 1e-15);
  EXPECT_NEAR(T.eigenvalue(1), 1.0, 1e-15);
}
