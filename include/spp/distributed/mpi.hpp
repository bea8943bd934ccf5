#pragma once
// spp on MPI (built when CMake finds MPI: the library spp_mpi and the executable spp-mpi). Every function here is
// collective: all ranks of `comm` call it with the same arguments. Rank 0 hands the work units out one at a time, to
// whichever worker asks (a rank that finishes early takes more), traces its own share with its worker threads, and
// gets every unit's output; the merge is in unit order, so the result does not depend on the ranks or threads.
// MPI must be initialised with at least MPI_THREAD_FUNNELED (MPI_THREAD_SERIALIZED for more than one thread per rank:
// workers of ranks other than 0 call MPI one at a time, under a lock). Results are bit for bit those of one process
// when the ranks run the same binary on the same kind of CPU (OpenBLAS picks its kernels by CPU: on a mixed cluster,
// pin them with OPENBLAS_CORETYPE).

#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "spp/distributed/sweep.hpp"
#include "spp/search/solver.hpp"

namespace spp {

/// Worker threads per rank: `requested` when > 0, else the hardware threads of this node divided by the ranks of
/// `comm` on it (at least 1), so that ranks x threads does not oversubscribe the cores. Collective.
int threads_per_rank(MPI_Comm comm, int requested);

/// Runs work(j) for every unit j in [0, units) over the ranks of `comm`, `threads` worker threads on each (rank 0's
/// main thread hands the units out, in the order `order` lists them: the costliest first). Returns on rank 0 the
/// outputs by unit index, elsewhere an empty vector. When work throws on any rank, no further unit is handed out and
/// every rank throws: rank 0 the original exception when it was its own, else std::runtime_error naming the rank and
/// its message. Throws std::invalid_argument (on every rank) when `order` is not a permutation of [0, units).
std::vector<std::string> distribute_units(MPI_Comm comm, size_t units, const std::vector<size_t>& order, int threads,
                                          const std::function<std::string(size_t)>& work);

/// solve() over the ranks of `comm`: the window's t2-strips (WindowWork's units) spread over them, options.threads
/// worker threads per rank (0: threads_per_rank). Returns on rank 0 the result solve(system, modal, options) gives
/// (same roots bit for bit, same stats but the time); on the other ranks a result with status NotRun. Throws as
/// solve() does (on every rank: each plans the window). options.progress is not called.
SolveResult solve_mpi(const System& system, const ModalForm& modal, const SolveOptions& options,
                      MPI_Comm comm = MPI_COMM_WORLD);

/// run_sweep() over the ranks of `comm`: one item at a time per rank (each solve with options.threads threads; 0:
/// threads_per_rank), handed out dynamically. Returns every item's outcome on rank 0, an empty vector elsewhere.
std::vector<SweepItemOutcome> run_sweep_mpi(const Sweep& sweep, const SolveOptions& options,
                                            MPI_Comm comm = MPI_COMM_WORLD);

}  // namespace spp
