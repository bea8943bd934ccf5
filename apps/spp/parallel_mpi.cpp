// build/spp-mpi: the ranks of MPI_COMM_WORLD (mpirun -n P build/spp-mpi solve|sweep ...).
#include <mpi.h>

#include <chrono>
#include <iostream>
#include <thread>

#include "parallel.hpp"
#include "spp/distributed/mpi.hpp"

namespace spp::cli {

namespace {
// A communicator of its own for every_rank_failed's barrier: it never meets the collectives of the work on
// MPI_COMM_WORLD that ranks without an error may be in.
MPI_Comm error_comm = MPI_COMM_NULL;
}  // namespace

Runtime::Runtime(int& argc, char**& argv) {
  int provided = 0;
  // SERIALIZED: the worker threads of a rank call MPI one at a time (distributed/mpi.hpp)
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  MPI_Comm_dup(MPI_COMM_WORLD, &error_comm);
}
Runtime::~Runtime() {
  MPI_Comm_free(&error_comm);
  MPI_Finalize();
}
void prefer_fast_blas(char**) {}
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

bool every_rank_failed(double seconds) {
  if (ranks() == 1) return true;
  MPI_Request request;
  MPI_Ibarrier(error_comm, &request);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return true;
    if (std::chrono::steady_clock::now() > end) return false;  // the request is left: the run is aborted next
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
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
