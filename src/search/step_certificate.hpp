#pragma once
// Certified trace steps (issue "completeness you can trust", item 2).
//
// On one zero curve lambda_k(H(t1, t2)) = 0 inside a cell (no pole line), parametrised by s = t2 - t1
// (t1 = tau(s), t2 = s + tau(s), tau' = -l2 / (l1 + l2) in [-1, 0], l1 = b^T dH/dt1 b, l2 = b^T dH/dt2 b), the
// onset function g(s) = c(t2)^T b(s) (b the unit null vector, orientation continuous; c = z/|z| for axial
// symmetry, c = -G tan(D t2) D^-1 G^T z for point symmetry) changes sign exactly at the SPPs.
// A step [s_a, s_b] between two traced points spans the box t1 in [t1_b, t1_a], t2 in [t2_a, t2_b]; since
// H = F(t1) + C(t2) grows in both variables (Loewner order), every H on the step lies between
// H(t1_b, t2_a) and H(t1_a, t2_b). From that alone:
//  - gap: every other eigenvalue stays at least gamma from 0, with
//      lambda_{k+1}(s) >= max(lambda_{k+1}(a) - max_i dF_i, lambda_{k+1}(b) - max_j dC_j),
//      lambda_{k-1}(s) <= min(lambda_{k-1}(a) + max_j dC_j, lambda_{k-1}(b) + max_i dF_i)   (Weyl),
//    dF_i, dC_j the increments of the diagonal flight part and of the contact-part eigenvalues over the box;
//  - rotation: |b'| <= |H' b| / gamma (first-order perturbation, H' = tau' F' + (1 + tau') C'), with
//    |H' b| bounded through the Davis-Kahan sin-theta bound sin angle(b(s), b_a) <= |H(s) b_a| / gamma and
//    |H(s) b_a| <= |H_a b_a| + |dF o b_a| + |dC o G^T b_a| (componentwise, so small components on stiff modes
//    cost little);
//  - curvature: b'' = -H^+ (H'' b + 2 H' b') - |b'|^2 b, so |g''| <= L2 with L2 from bounds of F', F'', C', C''
//    over the box (each a monotone or convex function of t between poles: its extreme is at a box end).
// Zeroth order (axial symmetry, c constant): |g(s) - g_x| <= |b(s) - b_x| <= sqrt(2) sin angle, so |g_x| above that
// drift (plus the error of the computed g) proves the sign on the whole step from one end x; no derivative of H enters,
// so it holds next to pole lines, where the curvature bound below explodes.
// With the end values g, g' and L2:
//  - no sign change: the Taylor lower bounds |g_a| + sigma g'_a x - L2 x^2 / 2 (from a) and the same from b
//    cover [s_a, s_b] between them;
//  - exactly one sign change: sigma g' >= sigma g'_a - L2 x > 0 or sigma g'_b - L2 (h - x) > 0 on the step.
// A third proof, of root-free boxes, is the onset inertia (Evaluator::onset_inertia, used by cell_trace).
// Written here because no library bounds eigenvector curvature of a structured matrix family.

#include <Eigen/Dense>

#include "spp/modal.hpp"

namespace spp::search {

/// One end of a step: a traced point of curve k.
struct StepEnd {
  double s = 0, t1 = 0, t2 = 0;
  double g = 0, dg = 0;        ///< onset function and its derivative in s (oriented)
  double lam_below = 0;        ///< lambda_{k-1} (-inf when k = 0)
  double lam_above = 0;        ///< lambda_{k+1} (+inf when k = m - 1)
  double residual = 0;         ///< |H b| at the point (includes the computed eigenvalue and rounding)
  double eig_error = 0;        ///< absolute error bound of the computed eigenvalues
  double slope_sum = 0;        ///< l1 + l2 = b^T (dH/dt1 + dH/dt2) b at the point
  const Eigen::VectorXd* b = nullptr;  ///< unit null vector (oriented)
};

enum class StepVerdict {
  NoRoot,      ///< certified: g keeps its sign on the step
  OneRoot,     ///< certified: g changes sign exactly once on the step
  Uncertified  ///< the bounds are too weak at this step length: shorten it
};

struct StepCertificate {
  StepVerdict verdict = StepVerdict::Uncertified;
  double gap = 0;         ///< lower bound of min_{j != k} |lambda_j| over the step (<= 0: no separation)
  double rotation = 0;    ///< bound of the total turn of b over the step (rad)
  double curvature = 0;   ///< L2, bound of |g''| over the step
  double safe_length = 0; ///< a step length that the same bounds would certify from a (for the next step)
};

/// The bound of the header comment, for the step a -> b of curve k (s_b > s_a).
StepCertificate certify_step(const ModalForm& md, Symmetry sym, const StepEnd& a, const StepEnd& b);

/// Extreme values over t in [lo, hi] (inside one pole interval) of the phase functions of the flight (omega) or
/// contact (d) frequencies: f = w tan(w t) (axial) or tan(w t)/w (point); increments |f(hi) - f(lo)| per mode,
/// max f', max |f''| per mode, and max |f| per mode.
struct PhaseBounds {
  Eigen::VectorXd increment, d1, d2, value;
};
PhaseBounds phase_bounds(const Eigen::VectorXd& freqs, Symmetry sym, double lo, double hi);

}  // namespace spp::search
