// ParametricSystem: the affine family, validation at the ends of the range, errors naming the parameter.
#include <gtest/gtest.h>

#include <cmath>

#include "spp/core/parametric.hpp"

using namespace spp;

TEST(Parametric, AffineInTheParameter) {
  Eigen::MatrixXd K0(2, 2), K1(2, 2);
  K0 << 1, 0, 0, 0;
  K1 << 1, -1, -1, 1;
  const ParametricSystem ps(Eigen::MatrixXd::Identity(2, 2), {}, K0, K1, Eigen::Vector2d(0, -2), {}, 0.0,
                            {"k2", 1.0, 10.0});
  const System s = ps.at(5.716);
  EXPECT_DOUBLE_EQ(s.K()(0, 0), 6.716);
  EXPECT_DOUBLE_EQ(s.K()(0, 1), -5.716);
  EXPECT_DOUBLE_EQ(s.K()(1, 1), 5.716);
  EXPECT_TRUE(s.M().isIdentity());
  EXPECT_DOUBLE_EQ(s.w()(1), -1.0);  // normalised
  EXPECT_EQ(ps.parameter().name, "k2");
}

TEST(Parametric, RefusesWhatIsNotAFamilyOfSystems) {
  Eigen::MatrixXd K0(2, 2), K1(2, 2);
  K0 << 1, 0, 0, 0;
  K1 << 1, -1, -1, 1;
  auto make = [&](double lo, double hi, Eigen::MatrixXd k1) {
    return ParametricSystem(Eigen::MatrixXd::Identity(2, 2), {}, K0, std::move(k1), Eigen::Vector2d(0, -1), {}, 1.0,
                            {"k2", lo, hi});
  };
  auto message = [&](double lo, double hi, Eigen::MatrixXd k1) {
    try {
      make(lo, hi, std::move(k1));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(0.0, 10.0, K1).find("at k2 = 0"), std::string::npos) << message(0.0, 10.0, K1);  // K singular
  EXPECT_NE(message(5.0, 1.0, K1).find("min < max"), std::string::npos);
  EXPECT_NE(message(1.0, 2.0, Eigen::MatrixXd::Zero(2, 2)).find("do not depend"), std::string::npos);
  EXPECT_NE(message(1.0, 2.0, Eigen::MatrixXd::Zero(3, 3)).find("3 x 3"), std::string::npos);
}

// Issue 11 (found by an independent attack): the parameter's name and the system's are checked by the constructor as
// the system-file reader checks them (core/names.hpp): a parametric system built in Python or C++ can be written.
// Found by an independent attack (issue 11): at(nan) blamed M[0][0] ("must be finite, got nan"), not the value asked
// for.
TEST(Parametric, ANonFiniteParameterValueIsNamed) {
  const ParametricSystem ps(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd(), Eigen::MatrixXd::Identity(2, 2),
                            Eigen::MatrixXd::Identity(2, 2), Eigen::Vector2d(0, 1), Eigen::VectorXd(), 1.0,
                            {"k2", 0.0, 1.0});
  for (const double mu : {std::nan(""), static_cast<double>(INFINITY)}) {
    try {
      ps.at(mu);
      ADD_FAILURE() << "accepted mu = " << mu;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("parametric system: the parameter k2 must be a finite number, got "),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(ps.at(0.5).n(), 2);
}

TEST(Parametric, NamesAreCheckedAsTheReaderChecksThem) {
  Eigen::MatrixXd K0(2, 2), K1(2, 2);
  K0 << 1, 0, 0, 0;
  K1 << 1, -1, -1, 1;
  auto message = [&](const std::string& parameter, const std::string& name) {
    try {
      ParametricSystem(Eigen::MatrixXd::Identity(2, 2), {}, K0, K1, Eigen::Vector2d(0, -1), {}, 1.0,
                       {parameter, 1.0, 2.0}, name);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("k2", std::string(4096, 'a')), "no error");
  EXPECT_EQ(message("k\t2", ""),
            "parametric system: parameter name: expected printable text, got the control "
            "character 9 at byte 1");
  EXPECT_EQ(message(std::string(4097, 'k'), ""),
            "parametric system: parameter name: expected at most 4096 bytes, got 4097 (a name is a title)");
  EXPECT_EQ(message("k2", std::string(4097, 'a')),
            "parametric system: name: expected at most 4096 bytes, got 4097 (a name is a title)");
}
