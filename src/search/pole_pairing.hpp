#pragma once
// Step "pair across pole lines": cells keep a thin margin from pole lines (H is unbounded there); each curve leaving a
// cell through an edge next to a pole line is matched with the curve entering the neighbouring cell, and a sign
// change of the oriented g across the thin strip is a root there (a candidate flagged near_pole_line).

#include <vector>

#include "search/cell_trace.hpp"
#include "search/window_plan.hpp"

namespace spp::search {

// Hits of the curves on the pole lines, per cell: v_from[i][j] exits of cell (i, j) through its left edge (line
// i), v_to[i][j] entries of cell (i - 1, j) through its right edge; h_from[j][i] exits of cell (i, j - 1) through its
// top edge (line j), h_to[j][i] entries of cell (i, j) through its bottom edge.
struct PoleHits {
  std::vector<std::vector<std::vector<EdgeHit>>> v_from, v_to, h_from, h_to;
};

/// Pairs every segment of every pole line (and the diagonal passes through their crossings); unpaired hits are
/// counted in stats.unpaired_crossings and located in uncertified; sign changes go to candidates.
void pair_across_pole_lines(PoleHits& hits, const AxisPlan& a1, const AxisPlan& a2, SolveStats& stats,
                            std::vector<UncertifiedRegion>& uncertified, std::vector<Candidate>& candidates);

}  // namespace spp::search
