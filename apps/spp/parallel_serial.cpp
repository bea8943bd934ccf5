// build/spp: one process.
#include <unistd.h>

#include <cstdlib>

#include "parallel.hpp"
#include "spp/detail/blas_core.hpp"

namespace spp::cli {

// OpenBLAS picks its kernels when it is loaded; where it fell back to its generic ones on a CPU it does not know, the
// process re-executes itself asking for the right ones (detail::blas_core_advice; the variable, once set, stops a
// second round). execv returns only on failure: the run goes on with the kernels it has.
Runtime::Runtime(int&, char**& argv) {
  const char* core = detail::blas_core_advice();
  if (*core != '\0' && setenv("OPENBLAS_CORETYPE", core, 0) == 0) execv("/proc/self/exe", argv);
}
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
