#pragma once
// Step "polish": Newton on the pole-free bordered system N(t1, t2) a = 0, c^T p0(a) = 0, a_ref^T a = 1 (modal form
// §2), from a candidate of the trace or of the pairing.

#include <Eigen/Dense>

#include "spp/modal/equation_set.hpp"

namespace spp::search {

struct Polished {
  bool converged = false;  ///< relative residual below 1e-10
  double t1 = 0, t2 = 0, residual = 1.0;
  Eigen::VectorXd a;  ///< modal position at mid-flight (axial) / velocity at onset (point), up to scale
};

/// The SPP equations F = (N a, z^T p0(a)) (m + 1) at (t1, t2, a) and their Jacobian J (m + 1) x (m + 2) in the
/// unknowns (t1, t2, a): what polish solves (with a row fixing a's scale), and what the location error of a computed
/// SPP is estimated from (stability/floquet.hpp). O(m^3).
void spp_equations(const EquationSet& eq, double t1, double t2, const Eigen::VectorXd& a, Eigen::VectorXd& F,
                   Eigen::MatrixXd& J);

/// Relative residual of N a = 0 and z^T p0 = 0 at (t1, t2).
double residual_of(const EquationSet& eq, double t1, double t2, const Eigen::VectorXd& a);

/// Newton with a trust region (stays within 1e-3 (t1 + t2) of the start and keeps t1, t2 > 0); b: the traced null
/// vector of H, or empty (then the SVD of N). 12 iterations at most, O(m^3) each.
Polished polish(const EquationSet& eq, double t1, double t2, const Eigen::VectorXd& b = Eigen::VectorXd());

}  // namespace spp::search
