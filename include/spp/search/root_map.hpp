#pragma once
// The two conditions of the SPP equations sampled over a window, for root maps like the paper's Fig. 4.
//   (5.1a)  det H(t1, t2) = 0          an orbit that is symmetric about -t1 and t2 exists;
//   (5.1b)  det P^T H P (t1, t2) = 0   it also starts contact with zero normal acceleration (P: basis of z-perp).
// An SPP is a point on both curves; there a curve of (5.1b) touches one of (5.1a) (Cauchy interlacing: a
// tangency, modal form §3b), so in a root map the SPPs are where solid and dashed curves meet.
// Each condition is sampled as sign(det A) * min_k |lambda_k(A)|: continuous inside a pole-line cell, linear
// through its simple zeros, so a zero-level contour per cell draws its curves without pole artefacts.

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "spp/core/system.hpp"
#include "spp/modal/modal.hpp"

namespace spp {

/// What a running root map reports to RootMapOptions::progress: cells sampled so far (of all of them), grid points
/// evaluated and the time since the start.
struct RootMapProgress {
  long cells_done = 0, cells_total = 0;
  long evaluations = 0;
  double seconds = 0.0;
  /// "cells 120 / 460 (26%), 9600 points, 1.2 s, ~3 s left" (time left at the rate so far).
  std::string line() const;
};

struct RootMapOptions {
  double t1_min = 0.0, t1_max = 0.0;  ///< window (t1_max > t1_min >= 0 required)
  double t2_min = 0.0, t2_max = 0.0;  ///< window (t2_max > t2_min >= 0 required)
  /// Grid points across the whole window along t1 (>= 16), spread over the cells in proportion to their width (so the
  /// map has about t1_points x t2_points in all, each cell in proportion to its area), each cell at least
  /// min_cell_points: a window of more cells than t1_points / min_cell_points along an axis has more.
  int t1_points = 400;
  int t2_points = 400;  ///< the same along t2 (>= 16)
  /// At least this many points per cell and axis (>= 2; 2 by default: the fewest a zero contour is drawn from, a
  /// straight piece across the cell; a narrow cell's curves are short).
  int min_cell_points = 2;
  double pole_margin = 2e-3;          ///< distance kept from pole lines, relative to the cell width (in [0, 0.25))
  /// Called about every 0.2 s while the cells are sampled (between two rows of a cell), always from the thread that
  /// called root_map(), and once at the end. Returning false stops the map: the cells sampled so far are returned and
  /// RootMap::unsampled_cells counts the others. Empty: no reports.
  std::function<bool(const RootMapProgress&)> progress;

  /// Throws std::invalid_argument naming the field, its value and the rule.
  void validate() const;
};

/// One rectangle between consecutive pole lines, sampled on its own grid.
struct RootMapCell {
  Eigen::VectorXd t1, t2;     ///< grid, ascending, strictly inside the cell
  Eigen::MatrixXd symmetric;  ///< (5.1a) at (t2(i), t1(j)): rows follow t2, columns t1 (matplotlib's layout)
  Eigen::MatrixXd onset;      ///< (5.1b), same layout
};

struct RootMap {
  std::vector<double> flight_poles;   ///< pole lines t1 = (k + 1/2) pi / omega_i in the window
  std::vector<double> contact_poles;  ///< pole lines t2 = (k + 1/2) pi / d_j in the window
  std::vector<RootMapCell> cells;
  long evaluations = 0;  ///< grid points evaluated
  /// Cells left out because RootMapOptions::progress stopped the map (0: every cell of the window is in `cells`).
  long unsampled_cells = 0;
};

/// Samples both conditions over the window, cell by cell: two symmetric eigenproblems (m x m, m - 1 x m - 1) per
/// grid point, O(m^3) each, about t1_points x t2_points of them (more when the cells' minimum needs more). Throws
/// std::invalid_argument for invalid options.
RootMap root_map(const ModalForm& modal, const RootMapOptions& options);
/// The same building the modal form of `system` (O(n^3)) first: for one map of a system.
RootMap root_map(const System& system, const RootMapOptions& options);

}  // namespace spp
