#pragma once
// The paper's two examples as bundled in examples/ (the files README's quick start uses): §5.2's 5-mass chain and
// §5.3's 4-dof rod with slip. Every test that needs them reads them here.
#include <string>

#include "spp/core/parametric.hpp"
#include "spp/core/system.hpp"
#include "spp/io/system_file.hpp"
#include "spp/search/solver.hpp"

namespace spp::test {

inline System chain5() {
  return load_system(std::string(SPP_SOURCE_DIR) + "/examples/chain5.json");
}
inline System rod4() {
  return load_system(std::string(SPP_SOURCE_DIR) + "/examples/rod4.json");
}

/// §5.2's chain with the last spring's stiffness k5 as the parameter, k5 in [lo, hi] (M = I, unit springs, the
/// obstacle on the last mass, g0 = 1): the continuation tests and the continuation-file tests.
inline ParametricSystem paper_chain_k5(double lo, double hi) {
  Eigen::MatrixXd K0(5, 5), K1 = Eigen::MatrixXd::Zero(5, 5);
  K0 << 2, -1, 0, 0, 0, -1, 2, -1, 0, 0, 0, -1, 2, -1, 0, 0, 0, -1, 1, 0, 0, 0, 0, 0, 0;
  K1(3, 3) = K1(4, 4) = 1;
  K1(3, 4) = K1(4, 3) = -1;
  Eigen::VectorXd w = Eigen::VectorXd::Zero(5);
  w(4) = -1;
  return ParametricSystem(Eigen::MatrixXd::Identity(5, 5), {}, K0, K1, w, {}, 1.0, {"k5", lo, hi});
}

/// The search on (0, t1max] x (0, t2max] with the default options.
inline SolveResult solve_window(const System& s, double t1max, double t2max) {
  SolveOptions o;
  o.t1_max = t1max;
  o.t2_max = t2max;
  return solve(s, o);
}

}  // namespace spp::test
