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
/// A window edge within this fraction of the fastest quarter period of a pole line is widened past it (the line
/// becomes interior and its strip is paired; an edge is never snapped onto a pole line).
inline constexpr double kEdgePole = 1e-4;

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

}  // namespace spp::search
