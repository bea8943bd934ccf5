#pragma once
// Exact physical flows of the two phases, X = (x, x'), by matrix exponential of the first-order systems of
// the paper (eqs. 3.9-3.11), independent of the modal form: used by tests to check orbits.

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include "spp/core/system.hpp"

namespace spp::ref {

class PhysicalFlow {
 public:
  explicit PhysicalFlow(const System& s) : s_(s), n_(s.n()) {
    A1_ = Eigen::MatrixXd::Zero(2 * n_, 2 * n_);
    A1_.topRightCorner(n_, n_).setIdentity();
    A2_ = A1_;
    const auto llt = s.M().llt();
    A1_.bottomLeftCorner(n_, n_) = -llt.solve(s.K());
    A2_.bottomLeftCorner(n_, n_) = -llt.solve(s.contact_stiffness());
    Minv_w_ = llt.solve(s.w());
    force_row_ = (s.K() * Minv_w_).transpose() / s.w().dot(Minv_w_);  // eq. (2.7)
  }
  /// State at time t from X0 at t = 0, in flight (t <= 0 typically) or in contact.
  Eigen::VectorXd flight(const Eigen::VectorXd& X0, double t) const { return (t * A1_).exp() * X0; }
  Eigen::VectorXd contact(const Eigen::VectorXd& X0, double t) const { return (t * A2_).exp() * X0; }
  double gap(const Eigen::VectorXd& X) const { return s_.w().dot(X.head(n_)) + s_.g0(); }
  double force(const Eigen::VectorXd& X) const { return force_row_.dot(X.head(n_)); }
  double normal_acceleration_free(const Eigen::VectorXd& X) const { return (A1_ * X).tail(n_).dot(s_.w()); }

 private:
  const System& s_;
  int n_;
  Eigen::MatrixXd A1_, A2_;
  Eigen::VectorXd Minv_w_, force_row_;
};

}  // namespace spp::ref
