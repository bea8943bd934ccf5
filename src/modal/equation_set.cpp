#include "spp/modal/equation_set.hpp"

#include <stdexcept>
#include <string>

#include "modal/equation_sets.hpp"
#include "spp/detail/dense_products.hpp"
#include "spp/detail/invalid.hpp"

namespace spp {

Eigen::MatrixXd EquationSet::contact_part(double t2) const {
  return detail::congruence(md_.G(), contact_eigs(t2));
}

Eigen::MatrixXd EquationSet::dcontact_dt2(double t2) const {
  return detail::congruence(md_.G(), dcontact_eigs(t2));
}

Eigen::MatrixXd EquationSet::H(double t1, double t2) const {
  Eigen::MatrixXd Hm = contact_part(t2);
  Hm.diagonal() += flight_part(t1);
  return Hm;
}

std::unique_ptr<EquationSet> make_equations(const ModalForm& modal, Symmetry sym) {
  switch (sym) {
    case Symmetry::Axial: return detail::make_axial_equations(modal);
    case Symmetry::Point: return detail::make_point_equations(modal);
  }
  detail::invalid("make_equations: expected Symmetry::Axial or Symmetry::Point, got Symmetry(" +
                              std::to_string(static_cast<int>(sym)) + ")");
}

}  // namespace spp
