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
//    "model_dofs": n,                         optional: the full model's dofs (a layout of another model is then
//                                            refused by spp reduce --layout, not drawn over the wrong one)
//    "model_fingerprint": [m, f_M, f_K, f_w, g0]}  optional: the reduced model's fingerprint (model_fingerprint
//                                            below), written by spp reduce --layout: a layout of another reduced
//                                            model with as many dofs is refused (check_fe_layout), not drawn
// A file written by hand for any model (a Matrix Market model from an FE code: its node coordinates and dof
// directions) is read the same way.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "spp/core/system.hpp"

namespace spp {

struct FeLayout {
  std::vector<long> dofs;
  Eigen::MatrixXd coordinates;  ///< one row per entry of dofs, 1 to 3 columns
  Eigen::MatrixXd directions;   ///< as coordinates
  Eigen::MatrixXd basis;        ///< empty, or one row per entry of dofs (the reduced model's dofs columns)
  long model_dofs = 0;          ///< the full model's dofs (0: not given)
  Eigen::VectorXd fingerprint;  ///< the reduced model's model_fingerprint (empty: not given)
};

/// Reads and checks a layout file (std::invalid_argument naming the file and the field): its model_dofs (when given)
/// equal to model_dofs, dofs in [0, model_dofs),
/// no dof twice, coordinates and directions of one shape with 1 to 3 finite columns, directions not zero, basis
/// (when present) one finite row per dof. model_dofs < 0: not known (a reduced model's layout read for its reduced
/// system): the dofs are bounded by the file's own model_dofs when it gives one.
FeLayout read_fe_layout(const std::string& path, long model_dofs);
/// The same from a layout's JSON text (Python's fe_layout= dict), `where` naming it in messages.
FeLayout parse_fe_layout(const std::string& text, const std::string& where, long model_dofs);

/// Five numbers that tell reduced models apart and survive the JSON round trips of their files (a bitwise hash of
/// M, K, w did not need to: w is normalised again when read): m, then sum_ij c_ij M_ij, sum_ij c_ij K_ij,
/// sum_i c_i w_i with fixed weights c = cos(1 + index) (so that a permutation or one entry changed shows), and g0.
Eigen::VectorXd model_fingerprint(const System& system);
/// Two fingerprints of one model: m equal, the others within 1e-9 of their weights' scale (sum |c M|, ...).
bool same_fingerprint(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const System& system);

/// A layout drawn over `system` (read with model_dofs < 0 when it has a basis): std::invalid_argument naming both,
/// `layout_where` and `system_where`, when it belongs to another model: without a basis, dofs beyond the system's;
/// with one, basis columns other than the system's dofs, or a fingerprint (when the layout has one) of another
/// model.
void check_fe_layout(const FeLayout& layout, const System& system, const std::string& layout_where,
                     const std::string& system_where);

/// The JSON text of a layout (17 significant digits).
std::string fe_layout_json(const FeLayout& layout);

/// The entries r = 0, s, 2s, ... (at most `max_rows` of them, the last one included) of a layout.
FeLayout sample_fe_layout(const FeLayout& layout, long max_rows);

}  // namespace spp
