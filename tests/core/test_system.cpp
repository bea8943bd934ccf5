#include <gtest/gtest.h>

#include "spp/core/names.hpp"
#include "spp/core/system.hpp"

using spp::System;

namespace {
Eigen::MatrixXd I2() {
  return Eigen::MatrixXd::Identity(2, 2);
}
Eigen::MatrixXd K2() {
  Eigen::MatrixXd K(2, 2);
  K << 2, -1, -1, 1;
  return K;
}
Eigen::VectorXd w2() {
  return Eigen::Vector2d(0, -1);
}

void expect_error(const std::function<void()>& f, const std::string& part) {
  try {
    f();
    FAIL() << "expected std::invalid_argument containing \"" << part << "\"";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(System, NormalisesContactDirectionAndGap) {
  const System s(I2(), K2(), Eigen::Vector2d(0, -2), 3.0);
  EXPECT_DOUBLE_EQ(s.w().norm(), 1.0);
  EXPECT_DOUBLE_EQ(s.g0(), 1.5);
  EXPECT_DOUBLE_EQ(s.w_input_norm(), 2.0);
}

TEST(System, ContactStiffnessMatchesPaperEq26) {
  // paper eq. (2.6): K~ = [[k1 + k2, -k2], [0, 0]] for the 2-dof system with contact on mass 2
  Eigen::MatrixXd M(2, 2), K(2, 2);
  M << 2, 0, 0, 3;
  K << 5, -4, -4, 4;
  const System s(M, K, w2(), 1.0);
  Eigen::MatrixXd expected(2, 2);
  expected << 5, -4, 0, 0;
  EXPECT_LT((s.contact_stiffness() - expected).norm(), 1e-14);
}

TEST(System, RejectsBadSizes) {
  expect_error([] { System(Eigen::MatrixXd::Identity(2, 3), K2(), w2(), 1); }, "M must be square, got 2 x 3");
  expect_error([] { System(I2(), Eigen::MatrixXd::Identity(3, 3), w2(), 1); }, "K must be 2 x 2 like M, got 3 x 3");
  expect_error([] { System(I2(), K2(), Eigen::Vector3d(1, 0, 0), 1); }, "w must have 2 entries like M, got 3");
  expect_error([] { System(Eigen::MatrixXd(0, 0), Eigen::MatrixXd(0, 0), Eigen::VectorXd(0), 1); }, "at least one row");
}

TEST(System, RejectsNonFinite) {
  Eigen::MatrixXd K = K2();
  K(1, 0) = std::nan("");
  expect_error([&] { System(I2(), K, w2(), 1); }, "K[1][0] must be finite");
  expect_error([] { System(I2(), K2(), Eigen::Vector2d(0, INFINITY), 1); }, "w[1] must be finite");
  expect_error([] { System(I2(), K2(), w2(), INFINITY); }, "g0 must be finite");
}

TEST(System, RejectsNonSymmetricAndIndefinite) {
  Eigen::MatrixXd K = K2();
  K(0, 1) = -1.1;
  expect_error([&] { System(I2(), K, w2(), 1); }, "K must be symmetric");
  Eigen::MatrixXd M(2, 2);
  M << 1, 2, 2, 1;
  expect_error([&] { System(M, K2(), w2(), 1); }, "M must be positive definite");
  expect_error([] { System(I2(), Eigen::MatrixXd::Zero(2, 2), w2(), 1); }, "K must be positive definite");
}

// Found by an independent attack (issue 11): the entries were printed with 6 digits, "K[1][0] = -1 but K[0][1] = -1",
// which hid the difference the check refused.
TEST(System, AsymmetryIsShownWithEveryDigit) {
  Eigen::MatrixXd K = K2();
  K(0, 1) = -1.0000001;
  expect_error([&] { System(I2(), K, w2(), 1); }, "K[1][0] = -1 but K[0][1] = -1.0000001000000001");
}

TEST(System, RejectsZeroContactDirection) {
  expect_error([] { System(I2(), K2(), Eigen::Vector2d(0, 0), 1); }, "w must be non-zero");
}

TEST(System, AcceptsSymmetryWithinRelativeTolerance) {
  Eigen::MatrixXd K = K2() * 1e6;
  K(0, 1) += 1e-6;  // relative 1e-12
  EXPECT_NO_THROW(System(I2(), K, w2(), 1));
}

TEST(System, GapThatUnderflowsWhenDividedByNormWIsRefused) {
  // g0 = 1e-200 with |w| = 1e200 divided to 0 and was then refused as a zero-gap system ("g0 = 0 ... declare a
  // parameter"), a message about another case; a denormal quotient kept a few digits of g0.
  expect_error([] { System(I2(), K2(), Eigen::Vector2d(0, -1e200), 1e-200); }, "g0 / |w| = 1e-200 / 1e+200 underflows");
  expect_error([] { System(I2(), K2(), Eigen::Vector2d(0, -1e10), 1e-300); }, "underflows");
  EXPECT_EQ(System(I2(), K2(), Eigen::Vector2d(0, -1e200), 0.0).g0(), 0.0);  // a zero gap stays a zero gap
  // g0 / |w| = 1e-300 is a normal double, but energies ~ g0^2 |K| underflow: refused with the energy scale
  expect_error([] { System(I2(), K2(), Eigen::Vector2d(0, -1e200), 1e-100); }, "the energy scale (g0 / |w|)^2 max|K|");
}

// Found by an independent attack: g0 = 1e155 passed every check, and solve reported success with wrong spectral radii
// ("stable" for an unstable SPP): energies ~ g0^2 |K| overflowed. Within [1e-200, 1e200] the system is taken.
TEST(System, EnergyScaleBeyondDoublesIsRefusedNamingTheRemedy) {
  expect_error([] { System(I2(), K2(), Eigen::Vector2d(0, -1), 1e155); }, "expected the system in units where g0");
  expect_error([] { System(I2(), 1e100 * K2(), Eigen::Vector2d(0, -1), 1e60); }, "is outside [1e-200, 1e200]");
  expect_error([] { System(I2(), K2(), Eigen::Vector2d(0, -1), 1e-120); }, "the energy scale");
  EXPECT_NO_THROW(System(I2(), K2(), Eigen::Vector2d(0, -1), 1e90));
  EXPECT_NO_THROW(System(I2(), K2(), Eigen::Vector2d(0, -1), 1e-90));
}

// Found by an independent attack (issue 11): masses of 1e308 were reported as "the eigenvalues of M did not converge"
// (the symmetrised copy 0.5 (M + M^T) overflowed to inf). Such a system is valid as far as its matrices go; the
// frequencies it leads to are judged where they are computed (the modal form), with their range.
TEST(System, EntriesNearTheLargestDoubleAreNoEigenvalueFailure) {
  const System s(1e308 * I2(), K2(), w2(), 1.0);
  EXPECT_EQ(s.M()(0, 0), 1e308);
  EXPECT_EQ(s.M()(1, 0), 0.0);
}

// Found by an independent attack (issue 11): spp.System(name=5000 characters) was built, and the result file written
// with it was refused by load_result (its reader limits names to 4096 bytes, printable). The constructor checks the
// name as the readers do (core/names.hpp), so nothing is built that a file cannot hold.
TEST(System, NameALongerThanAFileHoldsOrWithAControlCharacterIsRefusedByTheConstructor) {
  EXPECT_EQ(System(I2(), K2(), w2(), 1.0, std::string(spp::kMaxNameBytes, 'a')).name().size(), spp::kMaxNameBytes);
  expect_error([] { System(I2(), K2(), w2(), 1.0, std::string(spp::kMaxNameBytes + 1, 'a')); },
               "system: name: expected at most 4096 bytes, got 4097 (a name is a title)");
  expect_error([] { System(I2(), K2(), w2(), 1.0, std::string("two\nlines")); },
               "system: name: expected printable text, got the control character 10 at byte 3");
  expect_error([] { System(I2(), K2(), w2(), 1.0, std::string("a\0b", 3)); },
               "system: name: expected printable text, got the control character 0 at byte 1");
}
