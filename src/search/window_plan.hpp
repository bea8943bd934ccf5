#pragma once
// Step "plan the window": the search region of a window (t1_min, t1_max] x (t2_min, t2_max], its pole lines and cells,
// counted (and refused beyond SolveOptions::max_cells) before any evaluation.

#include <Eigen/Dense>
#include <algorithm>
#include <vector>

#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"

namespace spp::search {

// One axis of the search region: breakpoints (region edges and pole lines), which are poles, and the margin kept on
// each side of a pole line (0 at region edges).
struct AxisPlan {
  std::vector<double> bp;
  std::vector<bool> pole;
  std::vector<double> margin;
  size_t cells() const { return bp.size() - 1; }
  int poles() const { return static_cast<int>(std::count(pole.begin(), pole.end(), true)); }  ///< pole lines
};

// The region searched for the window (lo, hi] of one phase: the window widened by a hair (roots found outside the
// window are dropped by the half-open membership rule, so a root on a tile edge is found by both tiles and kept by
// one), and, where an edge falls closer to a pole line than kEdgePole of the local pole spacing (at most of the
// fastest quarter period), moved outwards past that line or away from it (never onto it; see tolerances.hpp).
/// The region searched for the window (lo, hi] of one phase (see plan_window).
AxisPlan plan_axis(const Eigen::VectorXd& freqs, double lo, double hi, bool widen_lo, double pole_margin,
                   double max_count);

/// Throws std::invalid_argument with the count when the window holds more than max_cells cells, the message starting
/// with `where` and ending with `remedy` (what the caller can change: solve's window and --max-cells, nearest_spp's
/// guess and radius). O(m).
void check_window_size(
    const ModalForm& md, const SolveOptions& opt, const std::string& where = "options",
    const std::string& remedy = "narrow the window, or raise max_cells (--max-cells) if the work is intended");

/// The window as planned: lower ends 0 ("from the axis") replaced by default_lower_ends, and a lower end inside
/// axis_band() raised to half the band (nothing within the band is reported). In md's time unit. O(m).
SolveOptions planned_window(const ModalForm& md, const SolveOptions& options);

struct WindowPlan {
  SolveOptions options;               ///< planned_window(caller's options): the lower ends as searched
  bool axis1 = false, axis2 = false;  ///< lower ends automatic ("from the axis")
  AxisPlan t1, t2;
};

/// The whole plan: the lower ends of planned_window, both axes. The size is not checked here: the caller checks it
/// once, before (check_window_size on the window in the user's time, whose message names it; plan_search). Each
/// axis lists at most max_cells + 16 pole lines whatever the window.
WindowPlan plan_window(const ModalForm& md, const SolveOptions& options);

}  // namespace spp::search
