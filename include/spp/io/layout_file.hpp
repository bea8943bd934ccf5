#pragma once
// Finite-element layout files (issue 13): where the dofs of a model move, so that an animation can draw the model
// itself (python/spp/animate.py, layout "fe") rather than a stem plot of its dofs. Written by `spp generate bar`
// beside the model (<stem>.layout.json) and carried through `spp reduce --layout` to each reduced model, with the
// rows of the reduction basis that give those dofs' displacements from the reduced coordinates:
//   {"dofs": [d_0, d_1, ...],                 0-based dofs of the full model, one per row below
//    "coordinates": [[x (, y (, z))], ...],   where the node the dof belongs to is (1 to 3 numbers, the same count
//                                            in every row; dofs of one node repeat its coordinates)
//    "directions": [[...], ...],              the direction the dof moves the node in (as many numbers, not zero)
//    "basis": [[...], ...],                   optional: row r gives dof d_r's displacement as basis_r . q, q the
//                                            reduced model's coordinates; absent: the displacement is x[d_r]
//    "model_dofs": n}                         optional: the full model's dofs (a layout of another model is then
//                                            refused by spp reduce --layout, not drawn over the wrong one)
// A file written by hand for any model (a Matrix Market model from an FE code: its node coordinates and dof
// directions) is read the same way.

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace spp {

struct FeLayout {
  std::vector<long> dofs;
  Eigen::MatrixXd coordinates;  ///< one row per entry of dofs, 1 to 3 columns
  Eigen::MatrixXd directions;   ///< as coordinates
  Eigen::MatrixXd basis;        ///< empty, or one row per entry of dofs (the reduced model's dofs columns)
  long model_dofs = 0;          ///< the full model's dofs (0: not given)
};

/// Reads and checks a layout file (std::invalid_argument naming the file and the field): its model_dofs (when given)
/// equal to model_dofs, dofs in [0, model_dofs),
/// no dof twice, coordinates and directions of one shape with 1 to 3 finite columns, directions not zero, basis
/// (when present) one finite row per dof.
FeLayout read_fe_layout(const std::string& path, long model_dofs);

/// The JSON text of a layout (17 significant digits).
std::string fe_layout_json(const FeLayout& layout);

/// The entries r = 0, s, 2s, ... (at most `max_rows` of them, the last one included) of a layout.
FeLayout sample_fe_layout(const FeLayout& layout, long max_rows);

}  // namespace spp
