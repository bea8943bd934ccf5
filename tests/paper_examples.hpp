#pragma once
// The paper's two examples as bundled in examples/ (the files README's quick start uses): §5.2's 5-mass chain and
// §5.3's 4-dof rod with slip. Every test that needs them reads them here.
#include <string>

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

/// The search on (0, t1max] x (0, t2max] with the default options.
inline SolveResult solve_window(const System& s, double t1max, double t2max) {
  SolveOptions o;
  o.t1_max = t1max;
  o.t2_max = t2max;
  return solve(s, o);
}

}  // namespace spp::test
