#include <gtest/gtest.h>

#include <cmath>

#include "spp/core/generators.hpp"
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
