// build/spp: one process.
#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <string>

#include "parallel.hpp"
#include "spp/detail/blas_core.hpp"

namespace spp::cli {

Runtime::Runtime(int&, char**&) {}
Runtime::~Runtime() = default;
// OpenBLAS picks its kernels when it is loaded; where it fell back to its generic ones on a CPU it does not know, the
// process re-executes itself asking for the right ones (detail::blas_core_advice; the variable, once set, by the user
// or by the first round, stops a second round). execv returns only on failure: the run goes on with the kernels it
// has. SPP_TRACE_BLAS (any value) says on stderr what was decided (tests/cli).
void prefer_fast_blas(char** argv) {
  const char* core = detail::blas_core_advice();
  if (std::getenv("SPP_TRACE_BLAS") != nullptr)
    std::cerr << "spp: OpenBLAS kernels: "
              << (*core != '\0' ? std::string("re-executing with OPENBLAS_CORETYPE=") + core : std::string("kept"))
              << "\n"
              << std::flush;
  if (*core != '\0' && setenv("OPENBLAS_CORETYPE", core, 0) == 0) execv("/proc/self/exe", argv);
}
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
