// Axial symmetry (Theorem 3.1, axes of symmetry at -t1 and t2): the SPPs of eqs. (5.1), every generic one.
//   H = W tan(W t1) + G D tan(D t2) G^T,   N = S^1/2 sin(S^1/2 t2) cos(W t1) + cos(S^1/2 t2) W sin(W t1),
//   p0 = cos(W t1) a,  p0' = -W sin(W t1) a,  onset direction z (eq. 5.1b: z^T p0 = 0).

#include <cmath>

#include "modal/equation_sets.hpp"
#include "spp/detail/dense_products.hpp"

namespace spp {

namespace {

class AxialEquations final : public EquationSet {
 public:
  using EquationSet::EquationSet;
  Symmetry symmetry() const override { return Symmetry::Axial; }

  Eigen::VectorXd flight_part(double t1) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    return (w * (w * t1).tan()).matrix();
  }

  Eigen::VectorXd dflight_dt1(double t1) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    const Eigen::ArrayXd sec2 = 1.0 / (w * t1).cos().square();
    return Eigen::VectorXd((w.square() * sec2).matrix());
  }

  Eigen::VectorXd contact_eigs(double t2) const override {
    const Eigen::VectorXd& d = md_.d();
    Eigen::VectorXd e(d.size());
    for (Eigen::Index j = 0; j < d.size(); ++j) e(j) = d(j) * std::tan(d(j) * t2);
    return e;
  }

  Eigen::VectorXd dcontact_eigs(double t2) const override {
    const Eigen::ArrayXd& d = md_.d().array();
    const Eigen::ArrayXd sec2 = 1.0 / (d * t2).cos().square();
    return Eigen::VectorXd((d.square() * sec2).matrix());
  }

  Eigen::MatrixXd N(double t1, double t2) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    const Eigen::ArrayXd c1 = (w * t1).cos(), s1 = (w * t1).sin();
    return md_.contact_msin(t2) * c1.matrix().asDiagonal() + md_.contact_cos(t2) * (w * s1).matrix().asDiagonal();
  }

  Eigen::MatrixXd dN_dt1(double t1, double t2) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    const Eigen::ArrayXd c1 = (w * t1).cos(), s1 = (w * t1).sin();
    return -md_.contact_msin(t2) * (w * s1).matrix().asDiagonal() +
           md_.contact_cos(t2) * (w.square() * c1).matrix().asDiagonal();
  }

  Eigen::MatrixXd dN_dt2(double t1, double t2) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    const Eigen::ArrayXd c1 = (w * t1).cos(), s1 = (w * t1).sin();
    const Eigen::ArrayXd& d = md_.d().array();
    const Eigen::VectorXd e2 = (d.square() * (d * t2).cos()).matrix();
    const Eigen::MatrixXd SC = detail::congruence(md_.G(), e2);  // S cos(S^1/2 t2)
    return SC * c1.matrix().asDiagonal() - md_.contact_msin(t2) * (w * s1).matrix().asDiagonal();
  }

  Eigen::VectorXd onset_position(double t1, const Eigen::VectorXd& a) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    return Eigen::VectorXd(((w * t1).cos() * a.array()).matrix());
  }

  Eigen::VectorXd onset_velocity(double t1, const Eigen::VectorXd& a) const override {
    const Eigen::ArrayXd& w = md_.omega().array();
    return Eigen::VectorXd((-w * (w * t1).sin() * a.array()).matrix());
  }

  Eigen::VectorXd onset_position_dt1(double t1, const Eigen::VectorXd& a) const override {
    return onset_velocity(t1, a);  // both -W sin(W t1) a
  }

  Eigen::VectorXd onset_direction(double) const override { return md_.z(); }
  Eigen::VectorXd onset_direction_dt2(double) const override { return Eigen::VectorXd::Zero(md_.z().size()); }

  PhaseShape phase_shape() const override { return PhaseShape::FTan; }
  double min_flight_slope() const override { return md_.omega().cwiseProduct(md_.omega()).minCoeff(); }  // sec^2 >= 1
  bool onset_direction_fixed() const override { return true; }
  bool can_be_admissible() const override { return true; }
  bool moving_obstacle() const override { return false; }      // the gap velocity vanishes at onset by symmetry
  double force_probe(double t2) const override { return t2; }  // mid-contact
  const char* solution_flag() const override { return nullptr; }
};

}  // namespace

std::unique_ptr<EquationSet> detail::make_axial_equations(const ModalForm& modal) {
  return std::make_unique<AxialEquations>(modal);
}

}  // namespace spp
