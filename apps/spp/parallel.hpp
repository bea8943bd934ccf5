#pragma once
// The processes of one run of the command line: this process alone (build/spp, parallel_serial.cpp), or the ranks of
// MPI_COMM_WORLD (build/spp-mpi under mpirun, parallel_mpi.cpp: solve and sweep spread their work over the ranks;
// rank 0 prints and writes the files).

#include <functional>
#include <string>
#include <vector>

#include "spp/distributed/sweep.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"

namespace spp::cli {

/// Starts and ends the run's parallel runtime (MPI_Init_thread / MPI_Finalize in spp-mpi; nothing in spp).
class Runtime {
 public:
  Runtime(int& argc, char**& argv);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;
};

/// Before a subcommand that runs dense linear algebra: where OpenBLAS fell back to its generic kernels, spp
/// re-executes itself (argv: main's, unchanged) with OPENBLAS_CORETYPE set to the kernels of this CPU
/// (detail::blas_core_advice: never when the user set the variable); nothing in spp-mpi (no exec after MPI_Init).
/// Not called for --help, --version, usage errors and generate, which start at once.
void prefer_fast_blas(char** argv);

/// Processes of the run (1 in spp).
int ranks();
/// This process's rank (0 in spp).
int rank();
/// This process prints the results and writes the output files (rank 0).
bool is_root();
/// Subcommands that spread their work over the ranks (the others refuse to run on more than one rank).
bool distributed(const std::string& subcommand);
/// Ends the run after an error on this process (message already printed): with more than one rank, every rank ends
/// (MPI_Abort with `code`), otherwise returns `code`.
int end_on_error(int code);
/// After an input error on this process: whether every rank reached one too within `seconds` (true in spp). Under MPI
/// every rank validates the input alike, so a mistake is found by all: they then end together through MPI_Finalize
/// with exit code 1 (one message, by rank 0), instead of several ranks racing to MPI_Abort (which printed Open MPI's
/// "ORTE_ERROR_LOG: Data unpack had inadequate space" in about 1 run in 3; found by an independent attack). False:
/// an error of this rank alone, which ends the run with end_on_error.
bool every_rank_failed(double seconds);

/// solve() on this process, or over the ranks (solve_mpi: the result on rank 0, NotRun elsewhere; progress only on
/// one rank).
SolveResult solve_window(const System& system, const ModalForm& modal, const SolveOptions& options);
/// run_sweep() on this process (on_done after each item), or over the ranks (run_sweep_mpi: outcomes on rank 0).
std::vector<SweepItemOutcome> sweep_items(const Sweep& sweep, const SolveOptions& options,
                                          const std::function<void(size_t, const SweepItemOutcome&)>& on_done);

}  // namespace spp::cli
