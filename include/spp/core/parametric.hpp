#pragma once
// A system affine in one named parameter mu (issue: parametric systems, paper §6):
//   M(mu) = M_constant + mu M_mu,  K(mu) = K_constant + mu K_mu,  w(mu) = w_constant + mu w_mu,  g0 fixed,
// over a declared range [min, max]. An immutable value, validated once when built: SPD at both ends of the
// range, hence (the SPD matrices form a convex cone) everywhere in it.

#include <Eigen/Dense>
#include <string>

#include "spp/core/system.hpp"

namespace spp {

struct Parameter {
  std::string name;
  double min = 0.0, max = 0.0;
};

class ParametricSystem {
 public:
  /// Empty M_mu, K_mu or w_mu mean "does not depend on the parameter". Throws std::invalid_argument naming the
  /// part and the rule (sizes, symmetry, finite values, min < max, SPD at min and max, w != 0).
  ParametricSystem(Eigen::MatrixXd M_constant, Eigen::MatrixXd M_mu, Eigen::MatrixXd K_constant, Eigen::MatrixXd K_mu,
                   Eigen::VectorXd w_constant, Eigen::VectorXd w_mu, double g0, Parameter parameter,
                   std::string name = "");

  /// The system at mu (need not lie in the range), validated like any System (O(n^3)); throws
  /// std::invalid_argument naming the parameter value (a mu that is not finite: naming the parameter).
  System at(double mu) const;

  int n() const { return static_cast<int>(M0_.rows()); }
  const Parameter& parameter() const { return parameter_; }
  double g0() const { return g0_; }
  const std::string& name() const { return name_; }
  const Eigen::MatrixXd& M_constant() const { return M0_; }
  const Eigen::MatrixXd& M_mu() const { return M1_; }  ///< n x n (zero if M does not depend on mu)
  const Eigen::MatrixXd& K_constant() const { return K0_; }
  const Eigen::MatrixXd& K_mu() const { return K1_; }
  const Eigen::VectorXd& w_constant() const { return w0_; }
  const Eigen::VectorXd& w_mu() const { return w1_; }

 private:
  Eigen::MatrixXd M0_, M1_, K0_, K1_;
  Eigen::VectorXd w0_, w1_;
  double g0_ = 0.0;
  Parameter parameter_;
  std::string name_;
};

}  // namespace spp
