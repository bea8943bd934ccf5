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
// Where these fail (stiff systems: the gap gamma is small next to the derivative of the stiff modes' entries), the
// spectrally weighted bounds of spectral_bounds (below) divide each mode's part by its own eigenvalue instead.
// A third proof, of root-free boxes, is the onset inertia (Evaluator::onset_inertia, used by cell_trace).
// Written here because no library bounds eigenvector curvature of a structured matrix family.

#include <Eigen/Dense>

#include "search/bordered_form.hpp"
#include "spp/detail/symmetric_eigen.hpp"
#include "spp/modal/equation_set.hpp"

namespace spp::search {

/// One end of a step: a traced point of curve k.
struct StepEnd {
  double s = 0, t1 = 0, t2 = 0;
  double g = 0, dg = 0;    ///< onset function and its derivative in s (oriented)
  double lam_below = 0;    ///< lambda_{k-1} (-inf when k = 0)
  double lam_above = 0;    ///< lambda_{k+1} (+inf when k = m - 1)
  double residual = 0;     ///< bound of |H b| at the true curve point of the same s (offset_bound)
  double eig_error = 0;    ///< error bound of the computed eigenvalues (of H at the point)
  double offset_norm = 0;  ///< bound of |H(true curve point) - H(point)| (offset_bound)
  double slope_sum = 0;    ///< l1 + l2 = b^T (dH/dt1 + dH/dt2) b at the point
  double pos_err = 0;      ///< bound of |t1 - t1*| and |t2 - t2*| for the true curve point (t1*, t2*) of this end
  int proved_sign = 0;     ///< sign of the true g here, proved by the step that reached this point (0: not proved)
  const Eigen::VectorXd* b = nullptr;  ///< unit null vector (oriented)
};

enum class StepVerdict {
  NoRoot,      ///< certified: g keeps its sign on the step
  OneRoot,     ///< certified: g changes sign exactly once on the step
  Uncertified  ///< the bounds are too weak at this step length: shorten it
};

struct StepCertificate {
  StepVerdict verdict = StepVerdict::Uncertified;
  double gap = 0;          ///< lower bound of min_{j != k} |lambda_j| over the step (<= 0: no separation)
  double rotation = 0;     ///< bound of the total turn of b over the step (rad)
  double curvature = 0;    ///< L2, bound of |g''| over the step
  double safe_length = 0;  ///< a step length that the same bounds would certify from a (for the next step)
  int evaluations = 0;     ///< evaluations of H (with its full eigenpairs) the certificate made
  int end_sign = 0;        ///< certified: the sign of the true g at b (0: not proved)
  /// What the bounds proved even where they decide nothing alone (a step whose ends lie within g's error bound of
  /// zero): the sign of g' over the whole step (+1, -1; 0: not proved) and the signs of the true g at a and b (0: not
  /// proved). Chained over consecutive steps (cell_trace's monotone run) they prove none or one root over the chain.
  int monotone_dir = 0;
  int sign_a = 0, sign_b = 0;
  /// Proved by the spectral bounds (safe_length is then the Weyl bounds' alone, often 0: the spectral bounds give no
  /// length of their own).
  bool spectral = false;
  /// The spectral bounds held (SpectralBounds::valid) at one end at least, whether they proved the step or not.
  bool spectral_valid = false;
};

/// The cell the step lies in (no pole line inside): the true curve points of the step stay in it.
struct StepBox {
  double lo1, hi1, lo2, hi2;
};

/// The m^3 products spectral_bounds forms from the eigenpairs at one point: the pseudo-inverse Hp = U diag(1 / lam_j,
/// j != k) U^T and its products with the contact basis, Hp Gx and Gx^T Hp Gx. They depend only on the point and on the
/// bordered modes (which fix Gx), not on the step, so they are kept beside the eigenpairs (`ready` once formed).
struct SpectralProducts {
  Eigen::MatrixXd Hp, HpG, GHpG;
  /// Their entrywise absolute values, formed with them (every step from this point reads them).
  Eigen::MatrixXd aHp, aHpG, aGHpG;
  bool ready = false;
  /// What |Hp E_box|_F needs at O(m^2) per step (structured_box_norm): the squared column norms of Hp and of Hp Gx,
  /// and Gx o (Hp Hp Gx) (entrywise product) with its absolute value. One m^3 product, formed by the first
  /// AlongCurve::k2 at this point (`box_ready`), then shared by every step from it.
  Eigen::VectorXd hp_col2, hpg_col2;
  Eigen::MatrixXd GW, aGW;
  bool box_ready = false;
};

/// Forms the box_ready part of p (p.Hp, p.HpG formed) for the contact basis G.
void prepare_box_products(SpectralProducts& p, const Eigen::MatrixXd& G);

/// |Hp E|_F for E = -diag(dF) + G diag(dC) G^T (dF, dC >= 0), from the pieces prepare_box_products kept, in O(m^2):
///   |Hp E|_F^2 = sum_l dF_l^2 |Hp e_l|^2 - 2 dF^T (G o Hp Hp G) dC + |Hp G diag(dC) G^T|_F^2,
/// the last term at most sum_i dC_i^2 |Hp G e_i|^2 (1 + delta), delta a bound of |G^T G - I|_2 (rounding of G's
/// orthonormal columns). `value` is an upper bound of the exact norm for the given Hp, Hp G and G, rounding of the
/// sums and of Hp Hp G included (`slack`, in squared units); `usable` false where that slack exceeds
/// kStructuredBoxSlack of the squared norm (cancellation between the flight and contact parts, where the
/// expansion loses the digits the dense product keeps): take dense_box_norm there.
struct BoxNorm {
  double value = 0, slack = 0;
  bool usable = false;
};
BoxNorm structured_box_norm(const SpectralProducts& p, const Eigen::VectorXd& dF, const Eigen::VectorXd& dC);
/// The same norm from the dense product -Hp diag(dF) + (Hp G diag(dC)) G^T (an m^3 product per call).
double dense_box_norm(const Eigen::MatrixXd& Hp, const Eigen::MatrixXd& HpG, const Eigen::MatrixXd& G,
                      const Eigen::VectorXd& dF, const Eigen::VectorXd& dC);

/// Full eigenpairs of bordered forms at the last few points: a step's start is the previous step's end, and a step
/// the bounds refuse is retried, shorter, from the same start. Keyed by the point and the bordered modes.
class EigenCache {
 public:
  /// The eigenpairs of bf at (t1, t2); `computed` is set when they were not cached (one evaluation).
  const detail::SymmetricEigen& at(const BorderedForm& bf, double t1, double t2, bool& computed);
  /// The products kept beside the eigenpairs the last call of at() returned (formed by the caller when not ready).
  SpectralProducts& last_products() { return entries_[last_].products; }

 private:
  struct Entry {
    double t1 = 0, t2 = 0;
    std::vector<int> key;
    detail::SymmetricEigen es;
    SpectralProducts products;
    bool used = false;
  };
  int last_ = 0;
  Entry entries_[3];
  int next_ = 0;
};

/// The bounds of the header comment, for the step a -> b of curve k (s_b > s_a) inside `cell`: the Weyl /
/// Davis-Kahan bounds first (no evaluation of H), then, where they fail (axial symmetry), the spectral bounds from the
/// full eigenpairs at b, then at a.
StepCertificate certify_step(const EquationSet& eq, const StepEnd& a, const StepEnd& b, const StepBox& cell,
                             EigenCache* cache = nullptr);

// Spectrally weighted bounds of g and g' over a step, from the full eigenpairs at one end x (axial symmetry,
// c = z / |z|). Notation: H_x = U diag(lam) U^T (lam_k ~ 0, b_x = u_k), Hp = U diag(1 / lam_j, j != k) U^T its
// pseudo-inverse, E = H(s) - H_x on the step, bounded entrywise in the flight basis (|dF_i|, diagonal) and in the
// contact basis (|dPhi_j|, G diagonal G^T). For the null vector b(s) = alpha b_x + U_perp beta of the curve point:
//   beta = -diag(1/lam) U_perp^T E b(s)    (rows j != k of U^T H(s) b(s) = 0),
//   tan angle(b(s), b_x) <= kappa1 / (1 - kappa2), kappa1 = sup |Hp E b_x|, kappa2 = sup |Hp E|;
//   g(s) = c^T b(s) = alpha g_x - v_x^T E b(s),  v_x = Hp c;
//   g'(s) = -v(s)^T H'(s) b(s) = tau' P + (1 + tau') Q,  P = -v^T F' b,  Q = -v^T C' b,  v(s) = H(s)^+ c,
// with v(s) = v_x - Hp E v - g U_perp diag(1/lam) beta - b_x (beta^T U_perp^T v) / alpha (from H(s) v = c - g b,
// v orthogonal to b), and componentwise bounds of b - b_x and v - v_x through |Hp| and |Hp G|. Each stiff mode's part
// of E is divided by its own eigenvalue, not by the gap to the nearest eigenvalue (Davis-Kahan, certify_step_weyl),
// which is what lets stiff systems (frequency spread ~300) be certified in steps of ~1 / omega_max instead of ~gap.
// The range of g' is also bounded through g' = (l1 Q - l2 P) / (l1 + l2) (l1 = b^T F' b, l2 = b^T C' b), which keeps
// the cancellation between P and Q exact at x, and the range of g through the mean value theorem with that range
// (tighter where g stays small along a whole curve). No root on the step when the range of g excludes 0, or when g
// is monotone and the ends' true signs agree; exactly one when g is monotone and they differ.
// Along the curve: the bounds above take |E| entrywise, as if t1 and t2 could move independently over the box; on the
// curve t1 falls while t2 rises, and the stiff modes' parts of E cancel on b (AlongCurve): the first-order terms are
// also bounded through the exact corner difference E_box, with the smaller bound kept.
// Written here because no library bounds eigenvector derivatives of a structured matrix family.
struct SpectralBounds {
  bool valid = false;           ///< false when the perturbation is too large for the bounds (shorten the step)
  double g_lo = 0, g_hi = 0;    ///< range of g over the step
  double dg_lo = 0, dg_hi = 0;  ///< range of g' = dg/ds over the step
  double g_err = 0;             ///< error bound of g at x (computed b_x against the true null vector there)
  double g_x = 0;               ///< g at x (of the bordered form's null vector: the sign of the traced g's)
  int evaluations = 0;          ///< full eigenpairs computed (0 when the cache had them)
};
/// The bounds above from end x of the step [lo_s, hi_s] of a curve whose true points lie in the box
/// [lo1, hi1] x [lo2, hi2] (inside one cell), taken in the bordered form bf of that box (bordered_form.hpp; the modal
/// form's H when nothing is bordered): next to a pole line its phases' derivatives stay O(1) where H's grow like
/// 1 / distance^2, which is what keeps the bounds tight there. g, g' and their ranges are those of
/// c^T [b; nu] / |[b; nu]| (same sign as the traced g). Costs the full eigenpairs of bf at x (O(m^3)), unless cached.
/// Axial symmetry only.
SpectralBounds spectral_bounds(const BorderedForm& bf, const StepEnd& x, double lo_s, double hi_s, double lo1,
                               double hi1, double lo2, double hi2, EigenCache* cache = nullptr);

/// Bounds of |(H(t1', t2') - H(t1, t2)) b| and of |H(t1', t2') - H(t1, t2)|_2 over |t1' - t1| <= e1,
/// |t2' - t2| <= e2 (+inf when a pole line lies that close): added to a traced point's residual and eigenvalue error
/// so that they hold at a true curve point (within e1, e2; tan evaluated at a rounded t), not only at the computed one.
struct Offset {
  double residual, norm;
};
Offset offset_bound(const EquationSet& eq, double t1, double t2, double e1, double e2, const Eigen::VectorXd& b);

/// The eigenvalue of the bordered form at (t1, t2) nearest 0 with its error bound (lam_err = |lambda| + error) and its
/// derivatives along t1 and t2 (l1, l2 >= 0): the distance to the zero curve of det H the point stands for, estimated
/// where H's own estimate fails. Next to a pole line the error of H's eigenvalues grows like 1 / distance (a traced
/// point 5e-9 from a contact pole line of a 30-dof chain had a position error of 7.6e-4 from H, and its step could
/// not be proved), while B's entries stay bounded. valid = false where nothing is bordered (axial symmetry only).
struct BorderedOffset {
  bool valid = false;
  double lam_err = 0, l1 = 0, l2 = 0;
};
/// With `cache`, the eigenpairs come from (and stay in) it: the step certificate at the same point, in a bordered form
/// with the same bordered modes, then takes them without a second decomposition.
BorderedOffset bordered_offset(const EquationSet& eq, double t1, double t2, EigenCache* cache = nullptr);

/// Extreme values over t in [lo, hi] (inside one pole interval) of the phase functions of the flight (omega) or
/// contact (d) frequencies: f = w tan(w t) (PhaseShape::FTan) or tan(w t)/w (TanOverF); increments |f(hi) - f(lo)| per
/// mode, max f', max |f''| per mode, max |f| per mode and min f' per mode.
struct PhaseBounds {
  Eigen::VectorXd increment, d1, d2, value;
  Eigen::VectorXd d1_min;  ///< min f' per mode over [lo, hi]
};
PhaseBounds phase_bounds(const Eigen::VectorXd& freqs, PhaseShape shape, double lo, double hi);
/// The same for any family of phases a tan(w t + shift) (bordered_form.hpp).
PhaseBounds phase_bounds(const PhaseFamily& phases, double lo, double hi);

// The signed form of spectral_bounds' perturbation terms ("Along the curve" in the header). On the step the true curve
// moves t1 down and t2 up, so with u = (t1(s_x) - t1(s)) / W1 and v = (t2(s) - t2(s_x)) / W2 (W1, W2 the box's
// widths, u and v in [-1, 1] with the same sign)
//     H(s) - H(s_x) = u E_box + (v - u) Gx diag(DC) Gx^T + R(s),   E_box = -diag(DF) + Gx diag(DC) Gx^T,
// DF, DC the phases' increments over the box (E_box is the exact difference of its two corners along the step), and
// R(s) diagonal in each basis with |R_i| <= rho_i DF_i, rho_i = max f_i' / min f_i' - 1 (mean value theorem), capped
// at 1. Where b(s) stays within angle S of b_x, |tau'| = l2 / (l1 + l2) lies in [p, q] (l1, l2 bounded as in
// spectral_bounds), so |v - u| <= kappa = h max(q / W1 - (1 - q) / W2, (1 - p) / W2 - p / W1, 0) for the step's
// length h. Where a stiff flight mode and a stiff contact mode move together (a curve along which their entries cancel,
// next to the axis limit points of a stiff system), E_box b_x is small while each increment alone is not: the
// unsigned bounds add the two and shrink the provable step by the stiff frequency squared over the gap.
class AlongCurve {
 public:
  using Vec = Eigen::VectorXd;
  using Mat = Eigen::MatrixXd;
  struct FirstOrder {
    Vec F, C;  ///< componentwise bounds of |Hp E(s) a| in the flight basis and of |Gx^T Hp E(s) a|
  };
  /// F, C: the phases' bounds over the box [lo1, hi1] x [lo2, hi2] (kept by reference); length: the step's length in
  /// s; w1, w2: the box's widths; offset_F, offset_C: the phases' increments between the computed x and the true
  /// curve point it stands for (added unsigned).
  AlongCurve(const BorderedForm& bf, const PhaseBounds& F, const PhaseBounds& C, double length, double w1, double w2,
             Vec offset_F, Vec offset_C);
  bool valid() const;
  /// Bound of |v - u| over the step where b(s) stays within angle S (its sine) of b_x (|b_x|, |Gx^T b_x| given).
  double kappa(const Vec& abx, const Vec& ayb, double S) const;
  /// sup over the step of |Hp E(s) a|, componentwise in both bases (ya = Gx^T a; aHp = |Hp|, aHpG = |Hp Gx|, aGHpG =
  /// |Gx^T Hp Gx| entrywise). E(s) = H(s) - H_x.
  FirstOrder first_order(const Vec& a, const Vec& ya, double kappa, const Mat& Hp, const Mat& HpG, const Mat& aHp,
                         const Mat& aHpG, const Mat& aGHpG) const;
  /// sup over the step of |Hp E(s)| (Frobenius). Its first term, |Hp E_box|, does not depend on kappa: formed on the
  /// first call only, for the Hp, HpG of that call (one AlongCurve serves one end's eigenpairs). With `products` (the
  /// point's, holding Hp and HpG) and m >= kLapackFrom, in O(m^2) from its box part (structured_box_norm, formed once
  /// per point); else, or where that bound is not usable, by an m^3 product (dense_box_norm).
  double k2(double kappa, const Mat& Hp, const Mat& HpG, SpectralProducts* products = nullptr) const;
  /// sup over the step of |v^T E(s) b|.
  double bilinear(const Vec& v, const Vec& yv, const Vec& b, const Vec& yb, double kappa) const;

 private:
  static Vec ratio_minus_one(const PhaseBounds& P);
  Vec weight_F() const;              // per unit |a_i|: the remainder R and the offset of x (flight basis)
  Vec weight_C(double kappa) const;  // the same, contact basis, with the progress mismatch kappa
  const Mat& G_;
  const PhaseBounds &F_, &C_;
  double h_, w1_, w2_;
  Vec iFx_, iCx_, rhoF_, rhoC_;
  mutable double box_norm_ = -1.0;  // |Hp E_box|_F once formed (k2)
};

}  // namespace spp::search
