// build/spp-mpi: the ranks of MPI_COMM_WORLD (mpirun -n P build/spp-mpi solve|sweep ...).
#include <mpi.h>

#include <iostream>

#include "parallel.hpp"
#include "spp/distributed/mpi.hpp"

namespace spp::cli {

Runtime::Runtime(int& argc, char**& argv) {
  int provided = 0;
  // SERIALIZED: the worker threads of a rank call MPI one at a time (distributed/mpi.hpp)
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
}
Runtime::~Runtime() {
  MPI_Finalize();
}
int ranks() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}
int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
bool is_root() {
  return rank() == 0;
}
bool distributed(const std::string& subcommand) {
  return subcommand == "solve" || subcommand == "sweep";
}
int end_on_error(int code) {
  if (ranks() > 1) {
    std::cerr.flush();
    MPI_Abort(MPI_COMM_WORLD, code);
  }
  return code;
}

SolveResult solve_window(const System& system, const ModalForm& modal, const SolveOptions& options) {
  if (ranks() == 1) return solve(system, modal, options);  // progress and Ctrl-C as in spp
  return solve_mpi(system, modal, options, MPI_COMM_WORLD);
}

std::vector<SweepItemOutcome> sweep_items(const Sweep& sweep, const SolveOptions& options,
                                          const std::function<void(size_t, const SweepItemOutcome&)>& on_done) {
  if (ranks() == 1) return run_sweep(sweep, options, on_done);
  return run_sweep_mpi(sweep, options, MPI_COMM_WORLD);
}

}  // namespace spp::cli
