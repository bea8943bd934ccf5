#pragma once
// The equation sets behind make_equations (spp/modal/equation_set.hpp), one file each; their classes are private.

#include <memory>

#include "spp/modal/equation_set.hpp"

namespace spp::detail {

std::unique_ptr<EquationSet> make_axial_equations(const ModalForm& modal);  ///< axial_equations.cpp
std::unique_ptr<EquationSet> make_point_equations(const ModalForm& modal);  ///< point_equations.cpp

}  // namespace spp::detail
