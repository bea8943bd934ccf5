// One eigenpair and the inertia through the tridiagonal form, and the full decompositions of
// spp::detail::symmetric_eigen, against Eigen's dense symmetric solver: below and above kLapackFrom (the sizes from
// which LAPACK's dsytrd / dsyevd / dsygvd are called).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

#include "spp/detail/dense_products.hpp"
#include "spp/detail/symmetric_eigen.hpp"
#include "spp/detail/symmetric_inertia.hpp"
#include "spp/detail/tridiagonal.hpp"

using spp::detail::SymmetricTridiagonal;

namespace {

Eigen::MatrixXd random_symmetric(int m, std::mt19937& rng) {
  std::normal_distribution<double> nd;
  Eigen::MatrixXd A(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) A(i, j) = nd(rng);
  return A + A.transpose();
}

}  // namespace

TEST(SymmetricEigen, DecompositionsMatchEigenOnBothSidesOfTheLapackSize) {
  static_assert(spp::detail::kLapackFrom > 100 && spp::detail::kLapackFrom < 200);
  std::mt19937 rng(11);
  for (int m : {1, 7, 100, 200}) {
    const Eigen::MatrixXd A = random_symmetric(m, rng);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ref(A);
    const double scale = ref.eigenvalues().cwiseAbs().maxCoeff();
    const spp::detail::SymmetricEigen es = spp::detail::symmetric_eigen(A);
    ASSERT_TRUE(es.ok);
    EXPECT_LT((es.values - ref.eigenvalues()).cwiseAbs().maxCoeff(), 1e-13 * scale * m) << "m = " << m;
    const Eigen::MatrixXd& U = es.vectors;
    EXPECT_LT((U.transpose() * U - Eigen::MatrixXd::Identity(m, m)).norm(), 1e-13 * m) << "m = " << m;
    EXPECT_LT((A * U - U * es.values.asDiagonal()).norm(), 1e-13 * scale * m) << "m = " << m;
    const spp::detail::SymmetricEigen values_only = spp::detail::symmetric_eigen(A, false);
    ASSERT_TRUE(values_only.ok);
    EXPECT_EQ(values_only.vectors.size(), 0);
    EXPECT_LT((values_only.values - ref.eigenvalues()).cwiseAbs().maxCoeff(), 1e-13 * scale * m) << "m = " << m;

    // K v = lambda M v, M positive definite: V^T M V = I, K V = M V diag(lambda)
    const Eigen::MatrixXd B = random_symmetric(m, rng);
    const Eigen::MatrixXd M = B * B.transpose() + m * Eigen::MatrixXd::Identity(m, m);
    const spp::detail::SymmetricEigen ges = spp::detail::generalized_symmetric_eigen(A, M);
    ASSERT_TRUE(ges.ok);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> gref(A, M);
    EXPECT_LT((ges.values - gref.eigenvalues()).cwiseAbs().maxCoeff(), 1e-12 * scale * m) << "m = " << m;
    const Eigen::MatrixXd& V = ges.vectors;
    EXPECT_LT((V.transpose() * M * V - Eigen::MatrixXd::Identity(m, m)).norm(), 1e-12 * m) << "m = " << m;
    EXPECT_LT((A * V - M * V * ges.values.asDiagonal()).norm(), 1e-11 * scale * m) << "m = " << m;
  }
}

TEST(Tridiagonal, EigenpairsAndCountsMatchDenseSolver) {
  std::mt19937 rng(5);
  std::normal_distribution<double> nd;
  for (int m : {1, 2, 5, 30, 100, 200}) {  // 200: LAPACK's dsytrd (kLapackFrom)
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

TEST(SymmetricEigen, ConcurrentLapackCallsFromSolverThreadsGiveTheSingleThreadResults) {
  // The solver's threads call BLAS / LAPACK at the same time (m >= kLapackFrom), with OpenBLAS's own threads set to
  // 1 (as the solver does). Debian's serial OpenBLAS shares buffers between concurrent calls and failed this in most
  // runs; the pthread build is linked for that reason. Each thread must get, bit for bit, what one thread gets.
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  std::mt19937 rng(3);
  const int m = 160;
  const Eigen::MatrixXd A = random_symmetric(m, rng), B = random_symmetric(m, rng);
  const spp::detail::SymmetricEigen ref = spp::detail::symmetric_eigen(A);
  const Eigen::MatrixXd ref_product = spp::detail::product(A, false, B, true);
  const SymmetricTridiagonal ref_t(A);
  const Eigen::VectorXd ref_v = ref_t.eigenvector(ref_t.eigenvalue(m / 2));
  const spp::detail::ShiftedInertia ref_ldlt = spp::detail::count_below_ldlt(A, 0.1);
  const int threads = 4, rounds = 40;
  std::vector<int> mismatches(threads, 0);
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (int r = 0; r < rounds; ++r) {
        const spp::detail::SymmetricEigen es = spp::detail::symmetric_eigen(A);
        const Eigen::MatrixXd p = spp::detail::product(A, false, B, true);
        const SymmetricTridiagonal T(A);
        const Eigen::VectorXd v = T.eigenvector(T.eigenvalue(m / 2));
        const spp::detail::ShiftedInertia ldlt = spp::detail::count_below_ldlt(A, 0.1);
        mismatches[t] += !es.ok || es.values != ref.values || es.vectors != ref.vectors || p != ref_product ||
                         v != ref_v || ldlt.below != ref_ldlt.below || ldlt.error_bound != ref_ldlt.error_bound;
      }
    });
  for (std::thread& th : pool) th.join();
  for (int t = 0; t < threads; ++t) EXPECT_EQ(mismatches[t], 0) << "thread " << t;
}

TEST(Tridiagonal, TwoHalvingsPerPassGiveThePlainBisectionBitForBit) {
  // eigenvalue() counts three midpoints per pass; it must take exactly the steps of one-at-a-time bisection: random,
  // clustered (eigenvalues equal or 1e-14 apart, where the last halvings decide between them), graded (1 to 1e12),
  // diagonal (zero sub-diagonal: the pivmin guard), zero and 1 x 1 matrices.
  std::mt19937 rng(12);
  std::normal_distribution<double> nd;
  std::vector<Eigen::MatrixXd> cases;
  for (int m : {2, 5, 20, 30, 60}) cases.push_back(random_symmetric(m, rng));
  for (int m : {6, 20, 40}) {
    Eigen::VectorXd lam(m);
    for (int i = 0; i < m; ++i) lam(i) = 1.0 + (i % 3 == 0 ? 0.0 : (i % 3) * 1e-14) + (i / 3);  // clusters of three
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(random_symmetric(m, rng));
    const Eigen::MatrixXd Q = qr.householderQ();
    cases.push_back(Q * lam.asDiagonal() * Q.transpose());
    Eigen::VectorXd graded(m);
    for (int i = 0; i < m; ++i) graded(i) = (i % 2 ? -1.0 : 1.0) * std::pow(10.0, 12.0 * i / (m - 1));
    cases.push_back(Q * graded.asDiagonal() * Q.transpose());
    cases.push_back(lam.asDiagonal());
  }
  cases.push_back(Eigen::MatrixXd::Zero(4, 4));
  cases.push_back(Eigen::MatrixXd::Constant(1, 1, -3.5));
  for (size_t c = 0; c < cases.size(); ++c) {
    const SymmetricTridiagonal T(cases[c]);
    for (int k = 0; k < T.size(); ++k) {
      const double fast = T.eigenvalue(k), plain = T.eigenvalue_by_bisection(k);
      EXPECT_EQ(std::memcmp(&fast, &plain, sizeof(double)), 0)
          << "case " << c << ", k = " << k << ": " << fast << " vs " << plain;
    }
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
