#pragma once
// The steps of solve() (solver.hpp) as separate calls, for callers that run the window's work units themselves
// (spp/distributed/window_work.hpp: the t2-strips on other processes): plan, trace one strip, merge the strips in
// strip order, then pair, polish and finalize. solve() is these calls in order, with threads over the strips.

#include <atomic>
#include <vector>

#include "search/cell_trace.hpp"
#include "search/pole_pairing.hpp"
#include "search/window_plan.hpp"
#include "spp/core/system.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/search/solver.hpp"

namespace spp::search {

/// The time unit of the search. The system's frequencies are in rad per the user's time unit, anything from 1e-50 to
/// 1e50; the search's tolerances were written and tested on systems with frequencies near 1, and several of its
/// decisions mix a time with a number of another unit (eigenvalues of H in rad per time unit, g, the steps' bounds):
/// chain5 with K x 1e12 on the window (0, 12e-6]^2 ended incomplete with 58 unproved steps and 1 647 584
/// evaluations, where the unit system on (0, 12]^2 ends success with 180 329 (K x 1e-12: 15 unproved, 1 283 735;
/// M x 1e8: 15 unproved, 1 072 317; issue 11 finding). Among those numbers: the onset root's tolerance
/// kOnsetRootXtol (|s_A| + |s_B| + 1), an absolute time. Rather than chase each such number, time is
/// nondimensionalised once, here: the search runs in tau = rate t, rate the system's reference frequency (the
/// geometric mean of its slowest and fastest coupled frequency, so that the scaled spectrum straddles 1), on the
/// modal form in tau (ModalForm::in_time_unit) and the window in tau; the roots, the window and the uncertified
/// regions go back to the user's unit in finish_search, and each SPP's orbit, admissibility, return error and
/// stability are built on the user's own modal form, at the user's times. The same system in any time unit then
/// sees the same search, up to the rounding of the frequencies.
struct SearchTime {
  SearchTime(const ModalForm& user, const SolveOptions& user_options);
  double rate = 1.0;      ///< the reference frequency, rad per user time unit: tau = rate t
  ModalForm modal;        ///< the modal form in tau (frequencies / rate)
  SolveOptions options;   ///< the window in tau (lower ends 0, "from the axis", stay 0)
  double to_user(double tau) const { return tau / rate; }
};

/// The reference frequency of SearchTime: sqrt(omega_min omega_max) over the coupled modes (1 when there are none).
double reference_frequency(const ModalForm& md);

/// Throws std::invalid_argument as solve() does for g0 = 0 or a modal form that is not the system's (`where` names
/// the caller).
void check_solve_inputs(const System& system, const ModalForm& md, const char* where);

/// Step 1: the window outside the axis bands, planned in the search's time (throws for a window inside a band, or too
/// large, naming the user's window: md and options are the user's).
WindowPlan plan_search(const ModalForm& md, const SolveOptions& options, const SearchTime& time);

/// A result before the search: the window searched (in the user's time), pole lines, decoupled modes, symmetry.
SolveResult start_result(const ModalForm& md, const WindowPlan& plan, const SolveOptions& options,
                         const SearchTime& time);

/// What tracing the cells of one t2-strip j gives: its candidates, uncertified cells, counts, and the hits of its
/// cells' curves on pole lines (index i = the cell's column): left[i] exits of cell (i, j) through its left edge,
/// top[i] through its top edge, right[i] entries through its right edge, bottom[i] through its bottom edge.
/// A strip is traced with its own evaluator (own cache and counters): its output depends on nothing else, so it is the
/// same whichever thread or process traces it.
struct StripOut {
  std::vector<Candidate> candidates;
  std::vector<UncertifiedRegion> uncertified;
  SolveStats stats;
  std::vector<std::vector<EdgeHit>> left, top, right, bottom;
};

/// Counters a running trace updates for SolveOptions::progress (shared by the threads).
struct TraceCounters {
  std::atomic<long> cells_done{0}, candidates_found{0};
};

/// Traces strip j (0 <= j < plan.t2.cells()). stop: raised by another thread to end the trace early (the rest of the
/// strip is then counted as not searched); nullptr: never stopped. counters: nullptr for none.
StripOut trace_strip(const EquationSet& eq, const WindowPlan& plan, size_t j, const std::atomic<bool>* stop = nullptr,
                     TraceCounters* counters = nullptr);

/// The candidates and pole-line hits of the whole window.
struct TracedWindow {
  std::vector<Candidate> candidates;
  PoleHits hits;
};

/// Merges every strip's output (strips[j] of strip j, moved from) in strip order into res's counts and uncertified
/// list: the result does not depend on who traced which strip, or when.
TracedWindow merge_strips(const WindowPlan& plan, std::vector<StripOut>& strips, SolveResult& res);

/// Steps 4-6: pair across pole lines (unless cells were left unsearched), polish the candidates into roots of the
/// window, sort, filter and set the status. The trace, plan and eq are in the search's time (eq on time.modal),
/// user_eq on the user's modal form builds the SPPs; the result leaves in the user's time. res.stats.seconds is left
/// to the caller.
void finish_search(const System& system, const EquationSet& user_eq, const EquationSet& eq, const SearchTime& time,
                   const WindowPlan& plan, TracedWindow& traced, const SolveOptions& options, SolveResult& res);

}  // namespace spp::search
