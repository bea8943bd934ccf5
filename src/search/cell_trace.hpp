#pragma once
// Steps "count at the corners" and "trace the pieces" of the search (solver.hpp), for one cell between pole lines.
// Inside a cell every eigenvalue of H is non-decreasing in t1 and t2 (strictly along (1, 1)), so the zero curves of
// det H crossing it are exactly the k with lambda_k(bottom-left) < 0 < lambda_k(top-right) (Sylvester inertia at
// the corners). Curve k enters through the bottom or right edge and leaves through the left or top edge; it is
// traced by one 1-D root of lambda_k per anti-diagonal t2 - t1 = s (never by following a branch), and the signed
// g = c^T b (b the null vector, orientation kept continuous; c = z / |z|) changes sign exactly at the SPPs. Steps are
// accepted by the midpoint check (the turn of b over both halves, a Hermite model of g on each), or, with
// SolveOptions::certify_steps, by the proof of step_certificate.hpp where it holds.

#include <Eigen/Dense>
#include <atomic>
#include <memory>
#include <vector>

#include "search/evaluator.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/search/solver.hpp"

namespace spp::search {

/// Where a curve meets a pole line (the edge of a cell next to it), with its oriented null vector and g.
struct EdgeHit {
  double pos = 0;  // coordinate along the pole line (t2 on a vertical line, t1 on a horizontal one)
  double t1 = 0, t2 = 0, g = 0;
  Eigen::VectorXd b;
  size_t cell = 0;  // column of the cell (hits on horizontal lines)
};

/// A sign change of g found by the trace or by pairing: polished into a root by polish().
struct Candidate {
  double t1, t2;
  bool uncertified = false, near_pole = false;
  Eigen::VectorXd b;  // null vector of H from the trace (empty: take the SVD of N)
};

/// One cell: its bounds (kept off the pole lines by their margins) and which of its edges lie next to a pole line.
struct Cell {
  double a1, b1, A, B;  ///< t1 in [a1, b1], t2 in [A, B]
  bool left_pole, right_pole, bottom_pole, top_pole;
};

/// Traces the cells of one strip (one thread): candidates and the hits on pole lines for pairing.
class CellTracer {
 public:
  /// stop: raised by another thread (Ctrl-C, a progress callback) to end the trace promptly: each curve piece ends
  /// at its next step, unproved (trace_cell then returns false), instead of at the end of the cell, which can take
  /// tens of seconds (a certified cell of a 20-dof chain). nullptr: never stopped.
  CellTracer(const EquationSet& equations, const SolveOptions& options, SolveStats& stats, Evaluator& evaluator,
             const std::atomic<bool>* stop = nullptr);
  ~CellTracer();
  CellTracer(const CellTracer&) = delete;
  CellTracer& operator=(const CellTracer&) = delete;

  /// Counts the curves of one cell at its corners, finds each curve's entry and exit and traces it; curves
  /// entering or leaving through an edge next to a pole line are appended to the matching list (column = the cell's
  /// column, for pairing). Returns false when a part of the cell could not be certified.
  bool trace_cell(const Cell& cell, size_t column, std::vector<EdgeHit>& left_exits, std::vector<EdgeHit>& top_exits,
                  std::vector<EdgeHit>& right_entries, std::vector<EdgeHit>& bottom_entries);
  /// The sign changes of g found so far.
  std::vector<Candidate>& candidates();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace spp::search
