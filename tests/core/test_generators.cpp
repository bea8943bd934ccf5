#include <gtest/gtest.h>

#include <cmath>

#include "spp/core/generators.hpp"
#include "spp/detail/out_of_memory.hpp"
#include "spp/io.hpp"

using namespace spp;

TEST(Generators, ChainMatchesPaperEq54AndBundledExample) {
  const System g = chain(5, {1.0}, {1.0}, 4, ContactSide::Upper, 1.0);
  const System e = load_system(std::string(SPP_SOURCE_DIR) + "/examples/chain5.json");
  EXPECT_EQ((g.M() - e.M()).norm(), 0.0);
  EXPECT_EQ((g.K() - e.K()).norm(), 0.0);
  EXPECT_EQ((g.w() - e.w()).norm(), 0.0);
  EXPECT_EQ(g.g0(), e.g0());
}

TEST(Generators, ChainWithListsAndLowerSide) {
  const System g = chain(3, {1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}, 1, ContactSide::Lower, 0.5);
  Eigen::MatrixXd K(3, 3);
  K << 9, -5, 0, -5, 11, -6, 0, -6, 6;
  EXPECT_EQ((g.K() - K).norm(), 0.0);
  EXPECT_EQ(g.M()(2, 2), 3.0);
  EXPECT_EQ(g.w()(1), 1.0);
  EXPECT_THROW(chain(3, {1.0, 2.0}, {1.0}, 0, ContactSide::Upper, 1.0), std::invalid_argument);
  EXPECT_THROW(chain(3, {1.0}, {1.0}, 3, ContactSide::Upper, 1.0), std::invalid_argument);
  EXPECT_THROW(chain(3, {-1.0}, {1.0}, 0, ContactSide::Upper, 1.0), std::invalid_argument);
  // beyond the dense solver: refused before the n x n matrices (n = 20000 took 6.4 GB first; an independent attack)
  try {
    chain(2000000, {1.0}, {1.0}, 0, ContactSide::Upper, 1.0);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("chain: n must be at most 10000"), std::string::npos) << e.what();
  }
}

TEST(Generators, RodMatchesPaperEq57AndBundledExampleUpToG0) {
  // obstacle 4y = 1 - x: a = -1/4, b = 1/4, w = [0 -1 -4 0]/sqrt(17) as printed in §5.3
  const System g = rod_with_slip(-0.25, 0.25);
  const System e = load_system(std::string(SPP_SOURCE_DIR) + "/examples/rod4.json");
  EXPECT_LT((g.w() - e.w()).norm(), 1e-15);
  EXPECT_EQ((g.M() - e.M()).norm(), 0.0);
  EXPECT_EQ((g.K() - e.K()).norm(), 0.0);
  // eq. (5.7) gives g0 = b / sqrt(1 + a^2) = 1/sqrt(17); the paper prints 1/17 (bundled as printed)
  EXPECT_NEAR(g.g0(), 1.0 / std::sqrt(17.0), 1e-15);
  EXPECT_NEAR(e.g0(), 1.0 / 17.0, 1e-15);
}

TEST(Generators, TwoDofMatchesPaperEq25) {
  const System g = two_dof(2.0, 3.0, 5.0, 7.0, 1.0);
  EXPECT_EQ(g.K()(0, 0), 12.0);
  EXPECT_EQ(g.K()(0, 1), -7.0);
  EXPECT_EQ(g.M()(1, 1), 3.0);
  EXPECT_EQ(g.w()(1), -1.0);
}

namespace {
Eigen::VectorXd bar_frequencies(const SparseSystem& s) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(s.K()), Eigen::MatrixXd(s.M()),
                                                               Eigen::EigenvaluesOnly);
  return es.eigenvalues().cwiseSqrt();
}
}  // namespace

TEST(Generators, BarMatchesTheExactDiscreteFrequencies) {
  // A uniform fixed-free mesh has the modes x_j = sin(j theta_k), theta_k = (2k - 1) pi / (2n) (the free end's row is
  // half an interior row): lambda_k = 6 (1 - cos theta) / (h^2 (2 + cos theta)) with consistent mass,
  // 4 sin^2(theta / 2) / h^2 lumped.
  const int n = 50;
  const double h = 1.0 / n;
  const Eigen::VectorXd consistent = bar_frequencies(bar(n, BarMass::Consistent, n, ContactSide::Upper, 1.0));
  const Eigen::VectorXd lumped = bar_frequencies(bar(n, BarMass::Lumped, n, ContactSide::Upper, 1.0));
  for (int k = 1; k <= n; ++k) {
    const double theta = (2 * k - 1) * M_PI / (2 * n);
    EXPECT_NEAR(consistent(k - 1), std::sqrt(6 * (1 - std::cos(theta)) / (h * h * (2 + std::cos(theta)))),
                1e-10 * consistent(k - 1));
    EXPECT_NEAR(lumped(k - 1), 2 * std::sin(theta / 2) / h, 1e-10 * lumped(k - 1));
  }
}

TEST(Generators, FineBarApproachesTheContinuousBar) {
  // continuous fixed-free bar (unit length, wave speed 1): omega_k = (2k - 1) pi / 2. Consistent mass bounds it from
  // above, lumped from below, each within (omega h)^2 / 12 relative (the O(h^2) dispersion error of linear elements).
  const int n = 400;
  const double h = 1.0 / n;
  const Eigen::VectorXd consistent = bar_frequencies(bar(n, BarMass::Consistent, n, ContactSide::Upper, 1.0));
  const Eigen::VectorXd lumped = bar_frequencies(bar(n, BarMass::Lumped, n, ContactSide::Upper, 1.0));
  for (int k = 1; k <= 10; ++k) {
    const double exact = (2 * k - 1) * M_PI / 2, bound = std::pow(exact * h, 2) / 12;
    EXPECT_GT(consistent(k - 1), exact);
    EXPECT_LT(consistent(k - 1) / exact - 1, bound) << k;
    EXPECT_LT(lumped(k - 1), exact);
    EXPECT_LT(1 - lumped(k - 1) / exact, bound) << k;
  }
}

TEST(Generators, BarIsSparseAndChecksItsArguments) {
  const SparseSystem b = bar(100000, BarMass::Consistent, 100000, ContactSide::Upper, 1.0);
  EXPECT_EQ(b.n(), 100000);
  EXPECT_EQ(b.K().nonZeros(), 3 * 100000 - 2);
  EXPECT_EQ(b.w()(99999), -1.0);
  EXPECT_DOUBLE_EQ(b.K().coeff(99999, 99999), 100000.0);  // the free end: half an interior row
  EXPECT_THROW(bar(0, BarMass::Consistent, 1, ContactSide::Upper, 1.0), std::invalid_argument);
  EXPECT_THROW(bar(10, BarMass::Consistent, 11, ContactSide::Upper, 1.0), std::invalid_argument);
}

TEST(Generators, OutOfMemoryNamesWhatWasTooLarge) {
  // a std::bad_alloc said only "std::bad_alloc"; naming_allocation names the object and its size (the CLI prints it,
  // pybind11 raises MemoryError with it); an inner, more precise name passes through
  try {
    spp::detail::naming_allocation("chain: M and K of n = 100000 dofs, each " + spp::detail::dense_size(1e5, 1e5),
                                   []() -> int { throw std::bad_alloc(); });
    ADD_FAILURE() << "no exception";
  } catch (const std::bad_alloc& e) {
    EXPECT_EQ(std::string(e.what()),
              "out of memory: chain: M and K of n = 100000 dofs, each a 100000 x 100000 matrix of doubles (80 GB)");
  }
  try {
    spp::detail::naming_allocation("outer", []() -> int { throw spp::detail::OutOfMemory("out of memory: inner"); });
    ADD_FAILURE() << "no exception";
  } catch (const std::bad_alloc& e) {
    EXPECT_EQ(std::string(e.what()), "out of memory: inner");
  }
}

// One seed, one system; M's and K's spectra in their documented ranges; n refused outside [1, kMaxDenseDofs] before
// any allocation. (The benchmarks and test_evaluator had their own copies of this generator.)
TEST(Generators, RandomDenseIsReproducibleWithItsSpectraInRange) {
  const System a = random_dense(7, 3), b = random_dense(7, 3), c = random_dense(7, 4);
  EXPECT_EQ((a.M() - b.M()).norm(), 0.0);
  EXPECT_EQ((a.K() - b.K()).norm(), 0.0);
  EXPECT_EQ((a.w() - b.w()).norm(), 0.0);
  EXPECT_GT((a.K() - c.K()).norm(), 0.1);
  const Eigen::VectorXd em = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a.M()).eigenvalues();
  const Eigen::VectorXd ek = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a.K()).eigenvalues();
  EXPECT_GE(em.minCoeff(), 0.5 - 1e-12);
  EXPECT_LE(em.maxCoeff(), 2.0 + 1e-12);
  EXPECT_GE(ek.minCoeff(), 0.5 - 1e-12);
  EXPECT_LE(ek.maxCoeff(), 14.0 + 1e-12);
  EXPECT_GT(ek.maxCoeff() - ek.minCoeff(), 1.0);  // K drawn over [0.5, 2 n], not M's range
  EXPECT_NEAR(a.g0() * a.w_input_norm(), 1.0, 1e-15);  // g0 as given (System divides it by |w|)
  const System q = random_dense(3, 1, 0.25);
  EXPECT_NEAR(q.g0() * q.w_input_norm(), 0.25, 1e-15);
  // The system the benchmarks' own copy drew for n = 3 (printed by that copy, built with GCC 12): the draw order
  // w, K, M keeps the systems README's benchmark rows were measured on.
  const System r3 = random_dense(3, 3);
  const Eigen::Vector3d m3 = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(r3.M()).eigenvalues();
  const Eigen::Vector3d k3 = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(r3.K()).eigenvalues();
  EXPECT_LT((m3 - Eigen::Vector3d(0.530922, 0.714076, 0.987959)).norm(), 1e-5) << m3.transpose();
  EXPECT_LT((k3 - Eigen::Vector3d(2.71298, 4.71205, 5.85507)).norm(), 1e-4) << k3.transpose();
  EXPECT_THROW(random_dense(0, 1), std::invalid_argument);
  EXPECT_THROW(random_dense(kMaxDenseDofs + 1, 1), std::invalid_argument);
}
