#include <gtest/gtest.h>

#include <random>

#include "spp/detail/cosine_sum.hpp"

using spp::detail::CosineSum;

TEST(CosineSum, DerivativesMatchFiniteDifferences) {
  CosineSum f{0.3, Eigen::Vector3d(1.0, -0.5, 0.25), Eigen::Vector3d(1.0, 2.7, 5.1), {}};
  const double t = 0.77, h = 1e-5;
  for (int k = 1; k <= 4; ++k) {
    const double fd = (f.derivative(t + h, k - 1) - f.derivative(t - h, k - 1)) / (2 * h);
    EXPECT_NEAR(f.derivative(t, k), fd, 1e-6 * f.bound(k));
  }
}

TEST(CosineSum, MinimumMatchesDenseSampling) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> a(-1, 1), w(0.1, 20);
  for (int trial = 0; trial < 20; ++trial) {
    CosineSum f;
    f.c0 = a(rng);
    f.amp.resize(8);
    f.freq.resize(8);
    for (int k = 0; k < 8; ++k) {
      f.amp(k) = a(rng);
      f.freq(k) = w(rng);
    }
    const auto m = spp::detail::minimize(f, 0.0, 3.0, 1e-10);
    ASSERT_TRUE(m.certified);
    double sampled = 1e300;
    for (int i = 0; i <= 300000; ++i) sampled = std::min(sampled, f.value(3.0 * i / 300000.0));
    EXPECT_LE(m.value, sampled + 1e-12);             // at least as low as any sample
    EXPECT_LE(m.lower_bound, sampled);               // the certified bound holds at every sample
    EXPECT_GE(m.lower_bound, m.value - 1.0001e-10);  // and is tight to the tolerance
  }
}

TEST(CosineSum, FindsANarrowNegativeDipThatCoarseSamplingMisses) {
  // 1 + 0.02 - ... : a high-frequency component makes a dip of width ~1e-3 between coarse samples
  CosineSum f{1.0, Eigen::Vector2d(-0.6, -0.4005), Eigen::Vector2d(1.0, 1000.0), {}};
  // minimum near t = 0 where both cosines are 1: 1 - 1.0005 < 0; shift the window so the dip is interior
  double coarse = 1e300;
  for (int i = 0; i <= 100; ++i) coarse = std::min(coarse, f.value(-0.5 + 1.0 * i / 100.0 + 0.00314));
  const auto m = spp::detail::minimize(f, -0.5, 0.5, 1e-12);
  EXPECT_GT(coarse, 0.0);
  EXPECT_LT(m.value, 0.0);
  EXPECT_NEAR(m.value, -0.0005, 1e-9);
}

TEST(CosineSum, PhaseFormMatchesCosSin) {
  const Eigen::Vector2d a(0.7, -0.2), b(-0.4, 0.9), w(1.3, 3.1);
  const CosineSum f = CosineSum::from_cos_sin(0.1, a, b, w);
  for (double t : {0.0, 0.4, 2.5}) {
    double ref = 0.1;
    for (int k = 0; k < 2; ++k) ref += a(k) * std::cos(w(k) * t) + b(k) * std::sin(w(k) * t);
    EXPECT_NEAR(f.value(t), ref, 1e-15);
  }
}

TEST(CosineSum, FirstCrossingOfASimpleCosine) {
  // 0.5 + cos t crosses zero first at t = 2 pi / 3
  const CosineSum f{0.5, Eigen::VectorXd::Constant(1, 1.0), Eigen::VectorXd::Constant(1, 1.0), {}};
  const auto c = spp::detail::first_crossing_below_zero(f, 0.0, 10.0, 1e-12);
  ASSERT_TRUE(c.found);
  EXPECT_NEAR(c.t, 2.0 * std::acos(-1.0) / 3.0, 1e-14);
  EXPECT_FALSE(spp::detail::first_crossing_below_zero(f, 0.0, 2.0, 1e-12).found);
}

TEST(CosineSum, FirstCrossingDoesNotStepOverANarrowDip) {
  // 1 - 0.6 cos(t - 3) - 0.4005 cos(100 (t - 3)): one dip below zero, of width ~3e-3, around t = 3
  CosineSum f;
  f.c0 = 1.0;
  f.amp = Eigen::Vector2d(-0.6, -0.4005);
  f.freq = Eigen::Vector2d(1.0, 100.0);
  f.phase = Eigen::Vector2d(-3.0, -300.0);
  const auto c = spp::detail::first_crossing_below_zero(f, 0.0, 6.0, 1e-12);
  ASSERT_TRUE(c.found);
  EXPECT_LT(std::abs(c.t - 3.0), 2e-3);
  EXPECT_NEAR(f.value(c.t), 0.0, 1e-13);
  EXPECT_LT(c.t, 3.0);  // the first of the two zeros
}

TEST(CosineSum, FirstCrossingIgnoresATangentStartAndFindsTheLaterOne) {
  // f = (1 - cos t) - 0.6 (1 - cos(t/2)) starts at zero, tangent (as after a release), positive, and crosses
  // later: the start must not count as a crossing.
  CosineSum f;
  f.c0 = 1.0 - 0.6;
  f.amp = Eigen::Vector2d(-1.0, 0.6);
  f.freq = Eigen::Vector2d(1.0, 0.5);
  const auto c = spp::detail::first_crossing_below_zero(f, 0.0, 12.0, 1e-12);
  ASSERT_TRUE(c.found);
  EXPECT_GT(c.t, 1.0);
  EXPECT_NEAR(f.value(c.t), 0.0, 1e-13);
}
