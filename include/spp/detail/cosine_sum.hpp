#pragma once
// f(t) = c0 + sum_k a_k cos(f_k t): the gap in flight and the contact force, measured from the phase's
// symmetry axis (Theorem 3.1), are such sums. Their minimum is bounded rigorously by a branch and bound on
// |f''| <= sum |a_k| f_k^2, so that a short negative excursion cannot hide between samples.

#include <Eigen/Dense>

namespace spp::detail {

struct CosineSum {
  double c0 = 0.0;
  Eigen::VectorXd amp, freq;

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

}  // namespace spp::detail
