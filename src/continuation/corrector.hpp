#pragma once
// A generic pseudo-arclength corrector for F: R^(k+1) -> R^k (issue 11: one Newton corrector for every branch; the
// SPP branches of continuation.cpp are its first user, k = 2). The caller linearizes F at y, with the analytic
// Jacobian where its equations give one (continuation.cpp: N's derivatives in t1, t2; differences in mu only).

#include <Eigen/Dense>
#include <limits>

namespace spp::continuation {

struct CorrectorOptions {
  int max_iterations = 12;  ///< Newton iterations; a converging corrector needs 3 to 5 (more: the predictor was off)
  double max_step = 0.2;    ///< a Newton step longer than this left the branch: not converged
  double step_tol = 1e-14;  ///< converged when a Newton step is this short (the rounding level of y ~ 1)
  /// Also converged when a step is no shorter than the one before and below this: Newton has reached the rounding
  /// floor of F over an ill-conditioned J, where steps jitter and never fall below step_tol. 0: off.
  double stagnation_tol = 0.0;
  /// LU with full pivoting (the default, k = 2 for the SPP branches: cost nil) or partial pivoting, blocked, several
  /// times faster for large k (the k-IPP families of a 200-dof chain: k ~ 200, where the full-pivoting LU was ~40% of
  /// the run). The bordered matrix [J; tau^T] is regular at a regular point of the curve, where either is accurate.
  bool full_pivoting = true;
};

struct CorrectorResult {
  bool converged = false;
  int iterations = 0;
};

/// Newton on F(y) = 0, tau^T (y - y_pred) = 0 from y = y_pred (tau: unit, k + 1). `linearize(y, F, J)` fills F (k)
/// and J (k x (k + 1)) at y. y holds the last iterate; not converged when a step is not finite, longer than
/// max_step, or, after max_iterations, still above step_tol without having stagnated below stagnation_tol. Cost: one
/// linearization and one (k + 1)^2 LU per iteration.
template <class Linearize>
CorrectorResult correct_pseudo_arclength(Linearize&& linearize, const Eigen::VectorXd& y_pred,
                                         const Eigen::VectorXd& tau, Eigen::VectorXd& y,
                                         const CorrectorOptions& options = {}) {
  const Eigen::Index k = tau.size() - 1;
  CorrectorResult out;
  y = y_pred;
  Eigen::VectorXd F(k), r(k + 1);
  Eigen::MatrixXd J(k, k + 1), A(k + 1, k + 1);
  double previous = std::numeric_limits<double>::infinity();
  for (out.iterations = 1; out.iterations <= options.max_iterations; ++out.iterations) {
    linearize(y, F, J);
    A.topRows(k) = J;
    A.row(k) = tau.transpose();
    r << F, tau.dot(y - y_pred);
    const Eigen::VectorXd dy =
        options.full_pivoting ? Eigen::VectorXd(A.fullPivLu().solve(-r)) : Eigen::VectorXd(A.partialPivLu().solve(-r));
    if (!dy.allFinite() || dy.norm() > options.max_step) return out;
    y += dy;
    const double step = dy.norm();
    if (step <= options.step_tol || (step >= previous && step <= options.stagnation_tol)) break;
    previous = step;
  }
  out.converged = out.iterations <= options.max_iterations && y.allFinite();
  return out;
}

/// Unit tangent of the curve F = 0 at a regular point: the kernel of J (k x (k + 1), rank k), oriented so that
/// tangent^T orient >= 0. NaN when J is not finite. Cost: one QR of J^T.
inline Eigen::VectorXd curve_tangent(const Eigen::MatrixXd& J, const Eigen::VectorXd& orient) {
  const Eigen::Index k = J.rows();
  if (!J.allFinite()) return Eigen::VectorXd::Constant(k + 1, std::numeric_limits<double>::quiet_NaN());
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(J.transpose());
  Eigen::VectorXd t = qr.householderQ() * Eigen::VectorXd::Unit(k + 1, k);  // orthogonal to J's k rows
  t.normalize();
  return t.dot(orient) < 0 ? Eigen::VectorXd(-t) : t;
}

}  // namespace spp::continuation
