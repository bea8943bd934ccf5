#pragma once
// The one type that describes an SPP: its orbit (half-durations, initial state, modal coordinates, energy), the
// verdict on admissibility, its Floquet multipliers, and how well it solves the equations. Everything else that
// speaks of an SPP is a view of it: spp solve's JSON/CSV/table rows (io/), verify's checks (which point back to a
// Solution by index), Python's Solution. A branch point of continuation is the one exception: a parameter value and
// a summary (continuation/continuation.hpp), from which solution_at rebuilds the Solution when one is wanted.

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "spp/orbit/orbit.hpp"
#include "spp/stability/floquet.hpp"

namespace spp {

/// Every flag a Solution can carry (see Solution::flags); a result file with another is refused.
inline constexpr std::array<const char*, 5> kSolutionFlags = {"point_symmetric", "uncertified_step", "near_pole_line",
                                                              "decoupled_mode_resonant", "gap_closure_degenerate"};

struct Solution {
  Orbit orbit;                  ///< t1, t2, the state at contact onset, modal coordinates, energy
  Admissibility admissibility;  ///< ineqs. (5.3): the verdict and the minima of gap and force
  /// Multipliers, spectral radius, margin (stability/floquet.hpp); spectral_radius NaN when not computed (point
  /// symmetry, compute_stability off). Physical only for an admissible SPP: see stable().
  Floquet floquet;
  double residual = 0.0;       ///< relative residual of N a = 0 and z^T p0 = 0 (eqs. 5.1a-b)
  double return_error = -1.0;  ///< relative periodicity error after one period (-1: not computed)
  /// "point_symmetric" (Symmetry::Point),
  /// "uncertified_step" (found in a step whose bound could not be proved), "near_pole_line" (found in a thin strip),
  /// "decoupled_mode_resonant" (a mode that never sees the contact has the same period: any amount of it can be added),
  /// "gap_closure_degenerate": the list kSolutionFlags.
  std::vector<std::string> flags;

  // Views of the parts above (one place holds each number).
  double t1() const { return orbit.t1; }          ///< flight half-duration (system's time unit)
  double t2() const { return orbit.t2; }          ///< contact half-duration
  double period() const { return orbit.period(); }  ///< 2 (t1 + t2)
  double energy() const { return orbit.energy; }  ///< 1/2 v^T M v + 1/2 x^T K x
  const Eigen::VectorXd& x0() const { return orbit.x0; }  ///< (n) position at contact onset
  const Eigen::VectorXd& v0() const { return orbit.v0; }  ///< (n) velocity at contact onset
  bool admissible() const { return admissibility.admissible; }
  double min_gap() const { return admissibility.min_gap; }      ///< smallest gap over the flight
  double min_force() const { return admissibility.min_force; }  ///< smallest force over the contact phase
  /// Admissible and every multiplier but the two structural 1s inside the unit circle, proved up to the rounding
  /// bound (floquet.verdict == Stable; not when Undecided or Neutral).
  bool stable() const { return admissible() && floquet.stable; }
};

}  // namespace spp
