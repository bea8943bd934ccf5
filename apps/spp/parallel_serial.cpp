// build/spp: one process.
#include "parallel.hpp"

namespace spp::cli {

Runtime::Runtime(int&, char**&) {}
Runtime::~Runtime() = default;
int ranks() {
  return 1;
}
int rank() {
  return 0;
}
bool is_root() {
  return true;
}
bool distributed(const std::string&) {
  return true;
}
int end_on_error(int code) {
  return code;
}
bool every_rank_failed(double) {
  return true;
}

SolveResult solve_window(const System& system, const ModalForm& modal, const SolveOptions& options) {
  return solve(system, modal, options);
}

std::vector<SweepItemOutcome> sweep_items(const Sweep& sweep, const SolveOptions& options,
                                          const std::function<void(size_t, const SweepItemOutcome&)>& on_done) {
  return run_sweep(sweep, options, on_done);
}

}  // namespace spp::cli
