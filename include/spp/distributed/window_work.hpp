#pragma once
// A window's search (solve(), search/solver.hpp) cut into its independent work units, for a scheduler outside this
// process (MPI: distributed/mpi_solve.hpp). The units are the t2-strips the threads of solve() take: each is traced
// with its own evaluator, so its output depends only on (system, modal form, options, unit) and is the same bytes
// on whichever process traces it; finish() merges the outputs in unit order and then pairs, polishes and finalizes
// exactly as solve() does, so the result equals solve()'s (same roots bit for bit, same stats but the time).
// Cost: units() = contact pole lines in the window + 1; trace_unit(j) = the cells of strip j (flight pole lines + 1),
// each ~120-480 evaluations of H (O(m^3)); finish() = pairing and polishing, as in solve(), on one process.

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "spp/core/system.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"

namespace spp {

class WindowWork {
 public:
  /// Plans the window as solve() does (the system is copied; `modal` must outlive this object); throws
  /// std::invalid_argument as solve() does (options, g0 = 0, a modal form not of the system, a window beyond
  /// max_cells). options.threads and options.progress are not used.
  WindowWork(const System& system, const ModalForm& modal, const SolveOptions& options);
  ~WindowWork();
  WindowWork(const WindowWork&) = delete;
  WindowWork& operator=(const WindowWork&) = delete;

  /// Number of work units (t2-strips).
  size_t units() const;
  /// Cells of unit j (its cost estimate: each cell costs ~120-480 evaluations of H). Throws std::invalid_argument for
  /// j >= units().
  long unit_cells(size_t j) const;
  /// The relative cost estimate of unit j, for handing out the costliest first: its cells times its t2-width. The
  /// strips hold the same cells, but their times differ up to 40-fold (the 8-mass chain's fundamental box: 0.02 to
  /// 0.82 s) and follow the width (correlation 0.92 there): a wider strip holds longer curves. Throws
  /// std::invalid_argument for j >= units().
  double unit_cost(size_t j) const;
  /// Traces unit j: its output as bytes (exact doubles, this machine's byte order) that finish() reads. Thread safe
  /// (several units at once). Throws std::invalid_argument for j >= units().
  std::string trace_unit(size_t j) const;
  /// The result of the window from the outputs of every unit (outputs[j] from trace_unit(j), on any process with the
  /// same system and options): merged in unit order, paired, polished, finalized. stats.seconds counts from this
  /// object's construction. Throws std::invalid_argument when an output is missing, of another unit, or not read whole.
  SolveResult finish(const std::vector<std::string>& outputs) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace spp
