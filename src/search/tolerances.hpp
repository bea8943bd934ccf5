#pragma once
// The tolerances that decide what the search reports, each with its reason (issue: one layout, named tolerances).
// Relative quantities say relative to what. Changing one changes which roots are reported: re-run the cross-checks
// (tests/crosscheck) and the benchmarks.

namespace spp::search {

// ---- polish (step 5) ----
/// A root is converged when the relative residual of N a = 0 and z^T p0 = 0 (polish.cpp residual_of) falls below
/// this: ~1e6 eps, the level Newton reaches on well-conditioned roots with a margin for m ~ 1000.
inline constexpr double kConvergedResidual = 1e-10;
/// Newton that stalls below this residual within kOnPoleLine of a pole line stalled on the pole line's artifact of
/// the pole-free form (dismissed); any other unconverged root is a gap of the search (never reported as an SPP).
inline constexpr double kStalledResidual = 1e-6;
/// A stalled root this close (relative) to a pole line is an artifact of the pole-free form there (solver.cpp).
inline constexpr double kOnPoleLine = 1e-6;
/// Newton steps stay within this fraction of t1 + t2 from the candidate (the limit points on the axes attract it).
inline constexpr double kPolishReach = 1e-3;
/// Newton stops when its step in (t1, t2) falls below this fraction of t1 + t2: a few ulps, where rounding of N
/// decides the step.
inline constexpr double kPolishStep = 1e-15;
/// Newton iterations of polish: quadratic convergence needs 3 to 5 from a traced root; the best iterate is kept.
inline constexpr int kPolishIterations = 12;
/// The trust region halves a step at most down to this fraction (20 halvings): a smaller step cannot move the root.
inline constexpr double kPolishMinAlpha = 1e-6;
/// The start a = p0 ./ cos(W t1) is used only while every |cos(omega_k t1)| exceeds this: below it the division
/// amplifies the traced vector's rounding by more than 1e3 and the SVD start is safer.
inline constexpr double kPolishCosFloor = 1e-3;
/// Two roots closer than this fraction of the window size (t1_max + t2_max) are one root (found from two cells or
/// two tiles); also the distance at which one unpolished sign change reached twice counts once.
inline constexpr double kSameRoot = 1e-9;

// ---- orbit flags ----
/// closure_ratio |u^T W^-1 p0| / |W^-1 p0| below this: the gap can hardly close at g0 != 0 ("gap_closure_degenerate").
inline constexpr double kClosureDegenerate = 1e-10;
/// A decoupled mode whose period divides 2 (t1 + t2) to this relative precision resonates with the orbit.
inline constexpr double kResonance = 1e-9;

// ---- window ----
/// A polished root within this many units of rounding (relative, of the edge) of a window edge is taken as on that
/// edge, and the half-open rule decides: each tile's Newton lands a root that lies on a cut within an ulp or two of
/// it, on either side, so without this a root on a shared edge was reported by both tiles or by neither.
inline constexpr double kOnEdgeUlps = 8.0;
/// Roots within this fraction of the fastest quarter period of each phase from the axes are not reported (axis_band:
/// g = O(t^2) there while its rounding error grows like 1 / t; an independent brute force at 50 digits saw only
/// rounding noise, up to 1.7% of that quarter period on a 30-dof chain).
inline constexpr double kAxisBand = 5e-2;
/// Default lower window ends: this fraction of the fastest quarter period (at most kDefaultLowerCap of the window).
inline constexpr double kDefaultLower = 1e-4;
inline constexpr double kDefaultLowerCap = 1e-3;
/// A window edge keeps from each pole line next to it kEdgePole times the smaller of the fastest quarter period and
/// the local pole spacing, the wider of the two gaps beside that line (window_plan.cpp plan_axis). Closer, it is
/// moved outwards: past the line if it lies outside the window (the line becomes interior and its strip is paired),
/// away from it if it lies inside (no sliver cell); a gap too narrow to hold an edge clear of both its lines is
/// passed; an edge is never moved onto a pole line. Why relative to that gap: a line's pole margin (pole_margin, 1e-6
/// by default) is taken of the wider neighbouring cell, so the corners of interior cells come that close to it and no
/// closer; an edge kept kEdgePole = 100 pole margins away has its corners 100 times farther from the line than those.
/// An edge 1e-3 of a 1.6e-6 gap from a line whose other gap is 1e-2 wide (tests/data/near_coincident7.json) is
/// inside that line's margin: there a crossing went unpaired (incomplete). With the quarter period alone (the rule
/// until 2026-11-24) an edge between clustered lines (3e-6 apart at n = 1000, 1e-4 of the quarter period = 7.9e-5)
/// was widened over 33 x 33 lines where the window held 2 x 2. Where a line has a gap of a quarter period or more
/// beside it the rule is the old one.
inline constexpr double kEdgePole = 1e-4;
/// An edge moved into a gap goes this fraction of it from the line it passed or left, or kEdgePole times the quarter
/// period if that is less (the old rule's distance): clear of both lines of the gap whenever the gap can hold an edge.
inline constexpr double kEdgeIntoGap = 0.5;
/// The searched region is the window widened by this fraction of its size at each edge: wider than the rounding of
/// a root computed on a tile edge, so a root on a shared edge is found by both tiles (the half-open rule keeps one).
inline constexpr double kEdgeSlack = 1e-9;
/// Smallest pole margin, relative to the pole time: two ulps, so that the margin never rounds to zero at large t.
inline constexpr double kMinPoleMargin = 4e-16;

// ---- trace (steps 2-3) ----
/// 1-D solves for lambda_k = 0 stop when |lambda_k| falls below this times |H| (edge roots; diagonal roots of the
/// trace use kDiagonalRootTol): a few ulps of the largest eigenvalue.
inline constexpr double kEdgeRootTol = 1e-14;
inline constexpr double kDiagonalRootTol = 1e-13;
/// A located sign change whose |g| stays above max(kJump |g_ends|, kJumpFloor) where the bracket closed is a jump of
/// g (b swung past 90 degrees inside the step), not a zero: the step is traced again (retrace).
inline constexpr double kJump = 1e-3;
inline constexpr double kJumpFloor = 1e-9;
/// g values below this at both ends of a step at the minimum length: g touches zero (a near-double root); the step
/// is reported as not proved.
inline constexpr double kTouchesZero = 1e-8;
/// 1-D root solves along a segment stop when the bracket is this fraction of |lo| + |hi| wide: two ulps, the
/// resolution of the parameter itself.
inline constexpr double kSegmentRootXtol = 4e-16;
/// Brent on g between two trace points stops at this fraction of |s_A| + |s_B| + 1: rounding level of s.
inline constexpr double kOnsetRootXtol = 1e-15;
/// A corner whose count neither H nor the bordered form proves is moved outwards by this fraction of the cell side
/// (up to 4 times): far beyond the eigenvalue rounding that made the count uncertain, far inside the pole margin.
inline constexpr double kCornerMove = 1e-9;
/// A trace point's relative position error (of max(t1, t2)) beyond which the bordered form estimates it instead of
/// H's eigenvalue bound (next to a pole line H's bound overestimates by |H|, see cell_trace.cpp); with certify_steps,
/// also the error at a 1-D root's first point beyond which the root is solved in the bordered form
/// (cell_trace.cpp segment_root): there H cannot place it closer than this, B can.
inline constexpr double kPosErrBordered = 1e-8;
/// When a piece's proof budget runs out, the midpoint trace restarts from at least this fraction of the piece.
inline constexpr double kFallbackStep = 1e-3;
/// Lower grid ends at 0 (the trivial line t1 = 0, or pure flight) are moved this fraction of the first grid step
/// off it (root_map.cpp): off the singular line, well inside the first grid interval.
inline constexpr double kOffAxis = 1e-3;

}  // namespace spp::search
