#include <gtest/gtest.h>

#include <random>

#include "spp/detail/cosine_sum.hpp"

using spp::detail::CosineSum;

TEST(CosineSum, DerivativesMatchFiniteDifferences) {
  CosineSum f{0.3, Eigen::Vector3d(1.0, -0.5, 0.25), Eigen::Vector3d(1.0, 2.7, 5.1)};
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
  CosineSum f{1.0, Eigen::Vector2d(-0.6, -0.4005), Eigen::Vector2d(1.0, 1000.0)};
  // minimum near t = 0 where both cosines are 1: 1 - 1.0005 < 0; shift the window so the dip is interior
  double coarse = 1e300;
  for (int i = 0; i <= 100; ++i) coarse = std::min(coarse, f.value(-0.5 + 1.0 * i / 100.0 + 0.00314));
  const auto m = spp::detail::minimize(f, -0.5, 0.5, 1e-12);
  EXPECT_GT(coarse, 0.0);
  EXPECT_LT(m.value, 0.0);
  EXPECT_NEAR(m.value, -0.0005, 1e-9);
}
