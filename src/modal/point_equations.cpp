// Point symmetry (Theorem 3.1's second case, det T2 = 0; paper §6.2 and Remark 3.1): x(-t1) = 0, x(t2) = 0. Potential
// SPPs only, never admissible (the force is odd about t2).
//   H_T = W^-1 tan(W t1) + G tan(D t2) D^-1 G^T  (tan(d t)/d -> t at d = 0), symmetric, PSD derivatives,
//   N_T = cos(S^1/2 t2) W^-1 sin(W t1) + S^-1/2 sin(S^1/2 t2) cos(W t1),  v = p'(0) = cos(W t1) a,
//   p0 = W^-1 sin(W t1) a = -G tan(D t2) D^-1 G^T v,  so z^T p0 = c(t2)^T v with c = -G tan(D t2) D^-1 G^T z.

#include <cmath>

#include "modal/equation_sets.hpp"

namespace spp {

namespace {

// tan(d t) / d, with its limit t at d = 0.
double tan_over(double d, double t) {
  return d > 0 ? std::tan(d * t) / d : t;
}

class PointEquations final : public EquationSet {
 public:
  using EquationSet::EquationSet;
  Symmetry symmetry() const override { return Symmetry::Point; }

  Eigen::VectorXd flight_part(double t1) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    return ((w * t1).tan() / w).matrix();
  }

  Eigen::VectorXd dflight_dt1(double t1) const override {
    const Eigen::ArrayXd sec2 = 1.0 / (md_.omega().array() * t1).cos().square();
    return Eigen::VectorXd(sec2.matrix());
  }

  Eigen::VectorXd contact_eigs(double t2) const override {
    const Eigen::VectorXd& d = md_.d();
    Eigen::VectorXd e(d.size());
    for (Eigen::Index j = 0; j < d.size(); ++j) e(j) = tan_over(d(j), t2);
    return e;
  }

  Eigen::VectorXd dcontact_eigs(double t2) const override {
    const Eigen::ArrayXd sec2 = 1.0 / (md_.d().array() * t2).cos().square();
    return Eigen::VectorXd(sec2.matrix());
  }

  Eigen::MatrixXd N(double t1, double t2) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    const Eigen::ArrayXd c1 = (w * t1).cos(), s1 = (w * t1).sin();
    return md_.contact_cos(t2) * (s1 / w).matrix().asDiagonal() + md_.contact_sinc(t2) * c1.matrix().asDiagonal();
  }

  Eigen::MatrixXd dN_dt1(double t1, double t2) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    const Eigen::ArrayXd c1 = (w * t1).cos(), s1 = (w * t1).sin();
    return md_.contact_cos(t2) * c1.matrix().asDiagonal() - md_.contact_sinc(t2) * (w * s1).matrix().asDiagonal();
  }

  Eigen::MatrixXd dN_dt2(double t1, double t2) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    const Eigen::ArrayXd c1 = (w * t1).cos(), s1 = (w * t1).sin();
    return -md_.contact_msin(t2) * (s1 / w).matrix().asDiagonal() + md_.contact_cos(t2) * c1.matrix().asDiagonal();
  }

  Eigen::VectorXd onset_position(double t1, const Eigen::VectorXd& a) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    return Eigen::VectorXd(((w * t1).sin() / w * a.array()).matrix());
  }

  Eigen::VectorXd onset_velocity(double t1, const Eigen::VectorXd& a) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    return Eigen::VectorXd(((w * t1).cos() * a.array()).matrix());
  }

  Eigen::VectorXd onset_position_dt1(double t1, const Eigen::VectorXd& a) const override {
    return onset_velocity(t1, a);  // both cos(W t1) a
  }

  Eigen::VectorXd onset_direction(double t2) const override { return -(contact_part(t2) * md_.z()); }
  Eigen::VectorXd onset_direction_dt2(double t2) const override { return -(dcontact_dt2(t2) * md_.z()); }

  PhaseShape phase_shape() const override { return PhaseShape::TanOverF; }
  double min_flight_slope() const override { return 1.0; }  // sec^2 >= 1
  bool onset_direction_fixed() const override { return false; }
  bool can_be_admissible() const override { return false; }
  bool moving_obstacle() const override { return true; }             // w^T x' = g0 / t2 during contact
  double force_probe(double t2) const override { return 0.5 * t2; }  // the force vanishes at t2
  const char* solution_flag() const override { return "point_symmetric"; }
};

}  // namespace

std::unique_ptr<EquationSet> detail::make_point_equations(const ModalForm& modal) {
  return std::make_unique<PointEquations>(modal);
}

}  // namespace spp
