#pragma once
// f(t) = c0 + sum_k a_k cos(f_k t + phi_k): the gap in flight and the contact force are such sums (measured
// from the phase's symmetry axis, Theorem 3.1, the phases vanish). Their minimum and their first crossing of
// zero are bounded rigorously through |f^(p)| <= sum |a_k| f_k^p, so that a short negative excursion cannot
// hide between samples.

#include <Eigen/Dense>

namespace spp::detail {

struct CosineSum {
  double c0 = 0.0;
  Eigen::VectorXd amp, freq;
  Eigen::VectorXd phase;  ///< phi_k; empty means all zero

  /// c0 + sum_k (a_k cos(f_k t) + b_k sin(f_k t)) in the amplitude-phase form.
  static CosineSum from_cos_sin(double c0, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                                const Eigen::VectorXd& freq);

  double value(double t) const;
  /// k-th derivative (k >= 0).
  double derivative(double t, int k) const;
  /// sum |a_k| f_k^p: bound on |f^(p)|.
  double bound(int p) const;
};

struct CosineMinimum {
  double t = 0.0;
  double value = 0.0;
  double lower_bound = 0.0;  ///< certified: f >= lower_bound on the interval
  bool certified = false;    ///< false when the evaluation budget ran out before value - lower_bound <= tol
};

/// Global minimum of f on [lo, hi] to absolute tolerance abs_tol.
CosineMinimum minimize(const CosineSum& f, double lo, double hi, double abs_tol, int max_evaluations = 400000);

/// First time t in [lo, hi] where f crosses below zero; found = false if f >= -abs_tol on all of [lo, hi],
/// certified by Taylor bounds, so that no excursion deeper than abs_tol is missed. The crossing is located to
/// rounding between the last point seen with f >= 0 and the first with f < -abs_tol; dips into [-abs_tol, 0)
/// that come back are not crossings. abs_tol is raised to 64 eps times the amplitude if below it.
struct Crossing {
  bool found = false;
  double t = 0.0;
  int evaluations = 0;
};
Crossing first_crossing_below_zero(const CosineSum& f, double lo, double hi, double abs_tol);

}  // namespace spp::detail
