#pragma once
// Every SPP in a window (t1, t2) in (t1_min, t1_max] x (t2_min, t2_max]: the paper's algorithm (§5.1) done
// completely with the modal form's counting (shared design note §3, §3b):
//  - pole lines of tan(W t1) and tan(D t2) cut the window into rectangles; inside one, every eigenvalue of H
//    is non-decreasing in t1 and t2 (strictly along (1,1)), so the zero curves of det H crossing it are
//    exactly the indices k with lambda_k(bottom-left) < 0 < lambda_k(top-right) (Sylvester inertia);
//  - each such curve is traced by its index k, one 1-D solve per anti-diagonal t2 - t1 = s, never by
//    following a numerical branch; the signed g = z^T b / |z| (b the null vector, orientation kept
//    continuous) changes sign exactly at the SPPs; each step carries a proof that g changes sign there at most
//    as seen (SolveOptions::certify_steps, on by default); a step no bound proves is taken by the midpoint check
//    (turn of b, Hermite model of g: a careful heuristic), counted, and the window ends Incomplete;
//  - the thin strips left around pole lines are checked by pairing the curves across each line;
//  - each root is polished by Newton on the pole-free bordered system N(t1,t2) a = 0, z^T cos(W t1) a = 0.
// The steps, one file each: src/search/window_plan, evaluator, cell_trace, pole_pairing, polish (and
// step_certificate); solve() in src/search/solver.cpp calls them in order.

#include <Eigen/Dense>
#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "spp/core/system.hpp"
#include "spp/orbit/orbit.hpp"
#include "spp/orbit/solution.hpp"

namespace spp {

/// What a running solve reports to SolveOptions::progress: the window's cells traced so far (of all of them), the
/// sign changes of g found so far (candidate roots, before polishing) and the time since the start.
struct SolveProgress {
  long cells_done = 0, cells_total = 0;
  long candidates = 0;
  double seconds = 0.0;
  /// "cells 120 / 460 (26%), 17 sign changes of g, 1.2 s elapsed, ~3 s left": the line the CLI and Python show. The
  /// time left assumes the cells left cost what the cells done did; it is left out before the first cell is done,
  /// and once every cell has started the line ends "finishing the last cells" instead.
  std::string line() const;
};

/// The window is half-open, (t1_min, t1_max] x (t2_min, t2_max]: a root on a shared edge of two tiles belongs to one
/// tile only, so the union of the results of a tiling equals the result of the whole window.
struct SolveOptions {
  double t1_max = 0.0;  ///< upper end of the flight half-duration window (required, > 0)
  double t2_max = 0.0;  ///< upper end of the contact half-duration window (required, > 0)
  /// Lower ends. t1 -> 0 and t2 -> 0 are limits (pure contact or pure flight oscillations), not SPPs: 0 means
  /// "from the axis" and selects default_lower_ends(); a positive value is taken as written. Whatever the window,
  /// roots within axis_band() of an axis are not reported (not resolvable in double precision).
  double t1_min = 0.0;
  double t2_min = 0.0;
  /// Largest number of cells (rectangles between pole lines) a window may hold; larger windows are refused before
  /// any evaluation, with their count.
  long max_cells = 10'000'000;
  /// Prove every trace step outside the axis bands (search/step_certificate.hpp: zeroth-order drift of the null
  /// vector, the curvature bound, the spectral bounds in the bordered form, or the onset inertia of the step's box).
  /// On by default: `success` means every step was proved. Where no bound proves a step within the step budget (two
  /// zero curves of det H side by side, g small and flat, curves packed against clustered pole lines) the midpoint
  /// check takes it, the step is counted in stats.uncertified_steps and the window ends Incomplete. Off: the midpoint
  /// check takes every step (3-25x faster on the benchmarks; a careful heuristic, not a proof), so the status is
  /// Incomplete whenever a step lies outside the axis bands.
  bool certify_steps = true;
  double pole_margin =
      1e-6;  ///< distance kept from pole lines, relative to the wider neighbouring cell (at most 1/4 of the narrower)
  double max_turn = 0.2;             ///< largest angle (rad) of the null vector b between two trace points
  double min_step = 1e-13;           ///< smallest trace step in s = t2 - t1, relative to t1_max + t2_max
  double admissibility_tol = 1e-9;   ///< relative tolerance of ineqs. (5.3) on each cosine sum's amplitude
  bool admissible_only = false;      ///< keep only admissible SPPs in the result
  bool compute_return_error = true;  ///< propagate each SPP over one period with the physical flows
  /// Floquet multipliers of each axially symmetric SPP under Newton's impact law, e < 1 (stability/floquet.hpp):
  /// O(m^3) per SPP (a nonsymmetric eigenproblem of size 2m - 2).
  bool compute_stability = true;
  int threads = 0;  ///< worker threads over t2-strips; 0 = every hardware thread
  /// Axial: the SPPs (eqs. 5.1). Point: the point-symmetric potential SPPs of det T2 = 0 (paper §6.2), same
  /// search on H_T (see Symmetry); never admissible, and with g0 != 0 they need a moving obstacle.
  Symmetry symmetry = Symmetry::Axial;
  /// Called about every 0.2 s while the cells are traced, always from the thread that called solve() (so a Python
  /// callback may take the GIL), and once when the trace ends. Returning false stops the search: the cells not
  /// traced yet are skipped, what was found is polished and returned, and the status is Incomplete with
  /// stats.unsearched_cells > 0 and the skipped cells listed in `uncertified` (cause "interrupted"). Empty: no reports.
  std::function<bool(const SolveProgress&)> progress;

  /// Throws std::invalid_argument naming the field, its value and the rule.
  void validate() const;
  /// validate() without the window (t1_min .. t2_max): for solution_at, which uses no window.
  void validate_fields_but_window() const;
};

enum class SolveStatus {
  NotRun,      ///< default: solve() has not filled this result
  Success,     ///< every check of completeness passed
  Incomplete,  ///< a part of the window could not be certified: SolveResult::uncertified and the counted causes
};
const char* to_string(SolveStatus s);
/// Its values: 0 .. 2 (Incomplete last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(SolveStatus) {
  return 3;
}

struct SolveStats {
  int flight_pole_lines = 0, contact_pole_lines = 0;
  long rectangles = 0, curve_pieces = 0, roots = 0;
  long evaluations = 0;      ///< symmetric eigen-decompositions of H
  long strip_pairs = 0;      ///< curves paired across pole lines (diagonal passes through a pole-line crossing too)
  long certified_steps = 0;  ///< trace steps with a proof that g keeps its sign, or changes it once (step_certificate)
  /// Steps accepted by the midpoint turn check (all of them without certify_steps; with it, those inside the axis
  /// bands and those no bound proved within the step budget): not a proof.
  long heuristic_steps = 0;
  /// Sign changes whose Newton stalled (residual between 1e-10 and 1e-6) within 1e-6 (relative) of a pole line: the
  /// pole-free form N is singular on every pole line (det N = det H times the cosines), and there its near-roots
  /// are not SPPs (an independent brute force finds none; an SPP on a pole line needs a vanishing modal component).
  /// Dismissed, not reported.
  long pole_line_artifacts = 0;
  // Causes of an Incomplete status, counted:
  long uncertified_steps = 0;    ///< steps not proved: those the midpoint check took outside the axis bands, the
                                 ///< steps of monotone runs no point of proved sign closed, and steps at the minimum
                                 ///< length where g touches zero (near-double roots)
  long uncertified_corners = 0;  ///< cell corners with an eigenvalue within its error bound of 0 after nudging
  long unpaired_crossings = 0;   ///< curve crossings of a pole line that could not be paired
  long unresolved_pieces = 0;    ///< curve pieces whose null vector could not be followed (budget, or turn at min step)
  long unpolished_roots = 0;     ///< sign changes of g that Newton could not polish to a root (residual above 1e-10
                                 ///< away from pole lines: not reported as SPPs)
  long unsearched_cells = 0;     ///< cells skipped because SolveOptions::progress stopped the search
  double seconds = 0.0;
};

/// The causes of an UncertifiedRegion (the result file's reader accepts these and no other).
inline constexpr std::array<const char*, 6> kUncertifiedCauses = {"step",    "corner", "budget",
                                                                  "pairing", "polish", "interrupted"};

/// A part of the window that could not be certified, and why.
struct UncertifiedRegion {
  double t1_lo = 0, t1_hi = 0, t2_lo = 0, t2_hi = 0;
  std::string cause;  ///< one of kUncertifiedCauses
};

struct SolveResult {
  SolveStatus status = SolveStatus::NotRun;
  std::vector<Solution> solutions;  ///< sorted by period
  SolveStats stats;
  /// The window whose roots are reported: the lower ends raised to axis_band() where the window reaches into it.
  double t1_min = 0.0, t2_min = 0.0, t1_max = 0.0, t2_max = 0.0;
  int decoupled_modes = 0, repeated_groups = 0;
  Symmetry symmetry = Symmetry::Axial;
  std::vector<std::string> warnings;
  std::vector<UncertifiedRegion> uncertified;  ///< empty exactly when status is Success
  /// One line: status, counts, time.
  std::string brief_report() const;
};

/// The lower window ends solve() takes when t1_min / t2_min are 0: 1e-4 of the fastest quarter period of each
/// phase (flight: pi / (2 omega_max), contact: pi / (2 d_max)), at most 1e-3 of t1_max / t2_max.
std::pair<double, double> default_lower_ends(const ModalForm& modal, double t1_max, double t2_max);

/// The fundamental box: t1 <= pi / omega_1 (half the period of the slowest free-flight mode that sees the contact)
/// and t2 <= pi / d_1 (half the period of the slowest contact-phase oscillation, d_1 the smallest positive contact
/// frequency). It holds the SPPs whose two phases are each at most one half-oscillation long: the paper's Fig. 4
/// window and the benchmarks' "chain box". Throws std::invalid_argument when there is no contact oscillation.
std::pair<double, double> fundamental_box(const ModalForm& modal);

/// The bands next to the axes where roots are not reported: t1 <= 0.05 * pi / (2 omega_max) and
/// t2 <= 0.05 * pi / (2 d_max) (5% of the fastest quarter period of each phase). There g vanishes like the square of
/// the distance to the axis while its rounding error grows like its inverse: sign changes found there were rounding
/// noise (an independent brute force checked at 50 digits; up to 1.7% of that quarter period on a 30-dof chain) and
/// the real SPPs of every system tried lie beyond one quarter period. The band depends on the system only, so that a
/// tiling gives the whole window's roots; SolveResult's window shows the effective lower ends.
std::pair<double, double> axis_band(const ModalForm& modal);

/// Finds every potential SPP in the window, builds its initial conditions and checks admissibility.
/// Cost: the modal form (O(n^3)), then about 120 (midpoint trace) to 480 (certify_steps) symmetric eigenproblems of
/// H (m x m, O(m^3)) per cell, cells = (flight pole lines + 1) x (contact pole lines + 1); estimate_window gives the
/// number before the search. Throws std::invalid_argument for invalid options or g0 = 0 (the zero-gap case needs a
/// parameter).
SolveResult solve(const System& system, const SolveOptions& options);
// (SolveResult::symmetry records which equations were solved.)
/// The same with the modal form of `system` given by the caller, who computes it once (O(n^3): ~1 s at n = 1000) for
/// several calls. Throws std::invalid_argument when `modal` is not that of `system` (dofs or gap differ).
SolveResult solve(const System& system, const ModalForm& modal, const SolveOptions& options);

/// Result of solution_at. Whether Newton reaches a root near the point is a numerical outcome, not a mistake: found
/// or not, with where Newton ended and its residual.
struct SolutionAt {
  bool found = false;
  Solution solution;            ///< the polished SPP (when found)
  double t1 = 0.0, t2 = 0.0;    ///< where Newton ended
  double residual = 0.0;        ///< its residual there
  double start_t1 = 0.0, start_t2 = 0.0;  ///< the point asked for
  /// "SPP at (t1, t2) ..." or "no SPP near (t1, t2): Newton reached residual r at (t1', t2')".
  std::string brief_report() const;
};

/// The SPP nearest to (t1, t2) (half-durations of flight and contact, in the system's time unit): Newton on the
/// bordered pole-free system from that point (at most 12 steps, O(m^3) each), then initial conditions and
/// admissibility. Not found when Newton does not converge to a root within 1e-3 (t1 + t2) of the given point, or the
/// root's gap cannot close (eq. 5.2). Throws std::invalid_argument for t1 or t2 not positive and finite, g0 = 0, or
/// a modal form of another system.
SolutionAt solution_at(const System& system, double t1, double t2, const SolveOptions& options = {});
SolutionAt solution_at(const System& system, const ModalForm& modal, double t1, double t2,
                       const SolveOptions& options = {});

/// Result of nearest_spp.
struct NearestSpp {
  bool found = false;
  Solution solution;                                  ///< the nearest SPP of the searched window (when found)
  SolveStatus search_status = SolveStatus::NotRun;    ///< status of the complete search around the guess
  double t1_lo = 0, t1_hi = 0, t2_lo = 0, t2_hi = 0;  ///< the window searched
  long candidates = 0;                                ///< SPPs in that window
};

/// The work of a window, known before the search (spp solve --dry-run): its pole lines and cells (as solve() plans
/// them), the measured cost of one evaluation of H here, and a rough time: cells x evaluations per cell (about 120 on
/// the benchmarks' chains and random systems with the midpoint trace, about 4x that with certify_steps) x that cost,
/// divided by the threads. An order of magnitude: curves per cell and step counts vary several-fold between systems.
struct WindowEstimate {
  double t1_min = 0, t1_max = 0, t2_min = 0, t2_max = 0;  ///< the window searched (lower ends filled in)
  int flight_pole_lines = 0, contact_pole_lines = 0;
  long cells = 0;
  double seconds_per_evaluation = 0;  ///< measured: mean of a few evaluations (eigenpairs) of H in the window
  double evaluations_per_cell = 0;    ///< the model's constant (above)
  int threads = 1;
  double seconds = 0;  ///< the estimate
};
/// Throws std::invalid_argument like solve() for an invalid window, or one beyond options.max_cells.
WindowEstimate estimate_window(const System& system, const ModalForm& modal, const SolveOptions& options);

/// Refines a guess read off the root map (within a few percent): the complete solver on the window
/// (t1 (1 - radius), t1 (1 + radius)] x (t2 (1 - radius), t2 (1 + radius)], then the SPP nearest to the guess
/// (relative distance). found = false when the window holds none: a status, not an exception. Throws
/// std::invalid_argument for a non-positive guess or radius outside (0, 1), and as solve() does. Cost: solve() on
/// that small window.
NearestSpp nearest_spp(const System& system, double t1, double t2, double radius = 0.05,
                       const SolveOptions& options = {});
NearestSpp nearest_spp(const System& system, const ModalForm& modal, double t1, double t2, double radius = 0.05,
                       const SolveOptions& options = {});

}  // namespace spp
