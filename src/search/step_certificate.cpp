#include "search/step_certificate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "spp/detail/dense_products.hpp"

namespace spp::search {

namespace {

// Positive root of G + c1 x - L2 x^2 / 2 (the Taylor lower bound of |g| reaches 0 there); 0 when G <= 0.
double zero_free_radius(double G, double c1, double L2) {
  if (!(G > 0)) return 0.0;
  if (!(L2 > 0)) return c1 >= 0 ? std::numeric_limits<double>::infinity() : G / -c1;
  return (c1 + std::sqrt(c1 * c1 + 2.0 * L2 * G)) / L2;
}

double weighted_norm(const Eigen::VectorXd& weights, const Eigen::VectorXd& v) {
  return weights.cwiseProduct(v).norm();
}

}  // namespace

const detail::SymmetricEigen& EigenCache::at(const BorderedForm& bf, double t1, double t2, bool& computed) {
  const std::vector<int> key = bf.key();
  for (int i = 0; i < 3; ++i) {
    Entry& e = entries_[i];
    if (e.used && e.t1 == t1 && e.t2 == t2 && e.key == key) {
      computed = false;
      last_ = i;
      return e.es;
    }
  }
  last_ = next_;
  Entry& e = entries_[next_];
  next_ = (next_ + 1) % 3;
  e.t1 = t1;
  e.t2 = t2;
  e.key = key;
  e.es = detail::symmetric_eigen(bf.matrix(t1, t2));
  e.products.ready = false;
  e.products.box_ready = false;
  e.used = true;
  computed = true;
  return e.es;
}

namespace {
// Error bound of a symmetric eigendecomposition with eigenvalues lam: |B - U diag(lam) U^T| (backward stable solver).
double decomposition_error(const Eigen::VectorXd& lam) {
  return 16.0 * static_cast<double>(lam.size()) * std::numeric_limits<double>::epsilon() * lam.cwiseAbs().maxCoeff();
}

// Bootstrap of AlongCurve's angle where the unsigned bound fails: the first assumed angle (sin), and the rounds.
constexpr double kBootstrapAngle = 0.25;
constexpr int kBootstrapRounds = 3;
}  // namespace

// The derivation is in the header (spectral_bounds).
SpectralBounds spectral_bounds(const BorderedForm& bf, const StepEnd& x, double lo_s, double hi_s, double lo1,
                               double hi1, double lo2, double hi2, EigenCache* cache) {
  using Vec = Eigen::VectorXd;
  using Mat = Eigen::MatrixXd;
  SpectralBounds sb;
  detail::SymmetricEigen own;
  bool computed = true;
  if (!cache) own = detail::symmetric_eigen(bf.matrix(x.t1, x.t2));
  const detail::SymmetricEigen& es = cache ? cache->at(bf, x.t1, x.t2, computed) : own;
  sb.evaluations = computed ? 1 : 0;
  if (!es.ok) return sb;
  const Vec& lam = es.values;
  const Mat& U = es.vectors;
  const Eigen::Index m = lam.size();
  Eigen::Index k = 0;
  lam.cwiseAbs().minCoeff(&k);
  Vec bx = U.col(k);
  if (bx.dot(bf.extend(*x.b, x.t1, x.t2)) < 0) bx = -bx;
  const double eps = std::numeric_limits<double>::epsilon();
  const double err = decomposition_error(lam);  // |H_x - U lam U^T|
  double gap = std::numeric_limits<double>::infinity();
  Vec inv = Vec::Zero(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    if (j == k) continue;
    gap = std::min(gap, std::abs(lam(j)));
    inv(j) = 1.0 / lam(j);
  }
  if (!(gap > 0) || !std::isfinite(gap)) return sb;
  const Mat& G = bf.Gx();
  // The three m^3 products depend on the point and the bordered modes only: kept in the cache beside the eigenpairs
  // (a step refused is retried from the same start, and a step's end is the next step's start).
  SpectralProducts own_products;
  SpectralProducts& products = cache ? cache->last_products() : own_products;
  if (!products.ready) {
    products.Hp = detail::congruence(U, inv);
    products.HpG = detail::product(products.Hp, false, G, false);
    products.GHpG = detail::product(G, true, products.HpG, false);
    products.aHp = products.Hp.cwiseAbs();
    products.aHpG = products.HpG.cwiseAbs();
    products.aGHpG = products.GHpG.cwiseAbs();
    products.ready = true;
  }
  const Mat& Hp = products.Hp;
  const Mat& HpG = products.HpG;
  const Mat& GHpG = products.GHpG;
  const Mat &aHp = products.aHp, &aHpG = products.aHpG, &aGHpG = products.aGHpG;
  const PhaseBounds F = phase_bounds(bf.flight(), lo1, hi1);
  const PhaseBounds C = phase_bounds(bf.contact(), lo2, hi2);
  const Vec& dF = F.increment;
  const Vec& dC = C.increment;
  const Vec yb = G.transpose() * bx;
  const Vec abx = bx.cwiseAbs(), ayb = yb.cwiseAbs();

  // angle of b(s) to b_x, and the reach of g = c^T b, over a box with increments (iF, iC)
  const double e_gap = err / gap;
  const Vec& c = bf.onset();
  const Vec vx = Hp * c, yv = G.transpose() * vx;
  const Vec avx = vx.cwiseAbs(), ayv = yv.cwiseAbs();
  const double gx = c.dot(bx);
  struct Reach {
    double k1, k2, sin, cos, g;
  };
  auto reach_over = [&](const Vec& iF, const Vec& iC) {
    Reach r;
    r.k1 = (aHp * iF.cwiseProduct(abx) + aHpG * iC.cwiseProduct(ayb)).norm() + e_gap;
    r.k2 = (Hp * iF.asDiagonal()).norm() + (HpG * iC.asDiagonal()).norm() + e_gap;
    const double t = r.k1 / (1.0 - r.k2);
    r.sin = t / std::sqrt(1.0 + t * t);
    r.cos = 1.0 / std::sqrt(1.0 + t * t);
    r.g = iF.cwiseProduct(avx).dot(abx) + iF.cwiseProduct(vx).norm() * r.sin + iC.cwiseProduct(ayv).dot(ayb) +
          iC.cwiseProduct(yv).norm() * r.sin + err * vx.norm();
    return r;
  };
  Reach R = reach_over(dF, dC);
  // First-order terms sup |Hp E b_x| (flight and contact bases) and sup |v_x^T E b_x| from the unsigned increments;
  // the signed form below may tighten them.
  Vec firstF = aHp * dF.cwiseProduct(abx) + aHpG * dC.cwiseProduct(ayb);
  Vec firstC = aHpG.transpose() * dF.cwiseProduct(abx) + aGHpG * dC.cwiseProduct(ayb);
  Vec firstvF = aHp * dF.cwiseProduct(avx) + aHpG * dC.cwiseProduct(ayv);
  Vec firstvC = aHpG.transpose() * dF.cwiseProduct(avx) + aGHpG * dC.cwiseProduct(ayv);
  double first_g = dF.cwiseProduct(avx).dot(abx) + dC.cwiseProduct(ayv).dot(ayb);
  double k2 = R.k2;
  {
    // Along the curve (header): E(s) = u E_box + remainders, E_box the exact difference of the box's two corners.
    const double ex1 = 2.0 * x.pos_err + 4.0 * eps * std::abs(x.t1), ex2 = 2.0 * x.pos_err + 4.0 * eps * std::abs(x.t2);
    const AlongCurve along(bf, F, C, hi_s - lo_s, hi1 - lo1, hi2 - lo2,
                           phase_bounds(bf.flight(), std::max(lo1, x.t1 - ex1), std::min(hi1, x.t1 + ex1)).increment,
                           phase_bounds(bf.contact(), std::max(lo2, x.t2 - ex2), std::min(hi2, x.t2 + ex2)).increment);
    if (along.valid()) {
      // Bootstrap on the angle S of b(s) to b_x: from an assumed S (the unsigned bound where it holds) the signed
      // bounds give S'; S' < S proves S' (by continuity from the true curve point at x, where u = v = 0), and a bound
      // computed under a proved S is proved.
      bool proved = R.k2 < 0.5;
      double S = proved ? R.sin : kBootstrapAngle, kappa = 1.0;
      for (int it = 0; it < kBootstrapRounds; ++it) {
        const double kap = along.kappa(abx, ayb, S);
        const AlongCurve::FirstOrder t = along.first_order(bx, yb, kap, Hp, HpG, aHp, aHpG, aGHpG);
        const double k1s = t.F.norm() + e_gap, k2s = along.k2(kap, Hp, HpG, &products) + e_gap;
        if (!(k2s < 0.5)) break;
        const double tt = k1s / (1.0 - k2s), Sn = tt / std::sqrt(1.0 + tt * tt);
        if (!proved && !(Sn < S)) break;
        proved = true;
        kappa = std::min(kappa, kap);
        k2 = std::min(k2, k2s);
        firstF = firstF.cwiseMin(t.F);
        firstC = firstC.cwiseMin(t.C);
        if (!(R.k2 < 0.5) || Sn < R.sin) {
          R.sin = Sn;
          R.cos = 1.0 / std::sqrt(1.0 + tt * tt);
        }
        S = R.sin;
      }
      if (proved) {
        const AlongCurve::FirstOrder tv = along.first_order(vx, yv, kappa, Hp, HpG, aHp, aHpG, aGHpG);
        firstvF = firstvF.cwiseMin(tv.F);
        firstvC = firstvC.cwiseMin(tv.C);
        first_g = std::min(first_g, along.bilinear(vx, yv, bx, yb, kappa));
      }
    }
  }
  R.g = first_g + (dF.cwiseProduct(vx).norm() + dC.cwiseProduct(yv).norm()) * R.sin + err * vx.norm();
  const double sin = R.sin, cos = R.cos;
  if (!(k2 < 0.5)) return sb;
  // g of the true curve point at s_x (within pos_err of x in t1 and t2; tan evaluated at a rounded t): the mean value
  // range below starts from it, not from g_x
  const double ex = 2.0 * x.pos_err + 4.0 * eps * std::max(std::abs(x.t1), std::abs(x.t2));
  const double xlo1 = std::max(lo1, x.t1 - ex), xhi1 = std::min(hi1, x.t1 + ex);
  const double xlo2 = std::max(lo2, x.t2 - ex), xhi2 = std::min(hi2, x.t2 + ex);
  const Reach Rx =
      reach_over(phase_bounds(bf.flight(), xlo1, xhi1).increment, phase_bounds(bf.contact(), xlo2, xhi2).increment);
  if (!(Rx.k2 < 0.5)) return sb;
  sb.g_err = Rx.g + (1.0 - Rx.cos) * std::abs(gx) + e_gap + 4.0 * eps;
  sb.g_x = gx;
  const double db_norm = std::sqrt(2.0 * (1.0 - cos));
  // componentwise |b(s) - b_x| (flight basis dbF, contact basis dbC)
  // (first order: E b_x; second: E (b(s) - b_x), |b(s) - b_x| <= sin per component)
  const Vec dbF =
      (firstF + sin * (aHp * dF + aHpG * dC) + ((1.0 - cos) * abx.array() + e_gap).matrix()).cwiseMin(db_norm);
  const Vec dbC = (firstC + sin * (aHpG.transpose() * dF + aGHpG * dC) + ((1.0 - cos) * ayb.array() + e_gap).matrix())
                      .cwiseMin(db_norm);

  // g over the step (g = alpha g_x - v_x^T E b(s) from the computed x itself: no end error)
  sb.g_lo = std::min(cos * gx, gx) - R.g;
  sb.g_hi = std::max(cos * gx, gx) + R.g;
  const double gmax = std::max(std::abs(sb.g_lo), std::abs(sb.g_hi));

  // v(s) = H(s)^+ c over the step
  const double den = 1.0 - k2 - sin / cos;
  if (!(den > 0.1)) return sb;
  const double vmax = (vx.norm() + gmax * sin / gap) / den;
  const double dv_norm = k2 * vmax + gmax * sin / gap + sin * vmax / cos;
  const double dv_iso = err * vmax / gap + gmax * sin / gap;
  const Vec dvF = (firstvF + dv_norm * (aHp * dF + aHpG * dC) + (dv_iso + abx.array() * (sin * vmax / cos)).matrix())
                      .cwiseMin(dv_norm);
  const Vec dvC =
      (firstvC + dv_norm * (aHpG.transpose() * dF + aGHpG * dC) + (dv_iso + ayb.array() * (sin * vmax / cos)).matrix())
          .cwiseMin(dv_norm);

  // P = -v^T F' b (flight basis), Q = -v^T C' b (contact basis): value at x and the variation over the step
  auto part = [](const Vec& d1x, const PhaseBounds& B, const Vec& v, const Vec& b, const Vec& dv, const Vec& db,
                 double& val, double& var) {
    const Vec dd = (B.d1 - d1x).cwiseMax(d1x - B.d1_min);
    val = -(v.cwiseProduct(d1x)).dot(b);
    var = v.cwiseAbs().cwiseProduct(b.cwiseAbs()).dot(dd) +
          B.d1.dot((dv.cwiseProduct(b.cwiseAbs() + db) + v.cwiseAbs().cwiseProduct(db)));
  };
  double P = 0, dP = 0, Q = 0, dQ = 0;
  const Vec d1x = bf.flight().d1(x.t1), d2x = bf.contact().d1(x.t2);
  part(d1x, F, vx, bx, dvF, dbF, P, dP);
  part(d2x, C, yv, yb, dvC, dbC, Q, dQ);
  // g' = (l1 Q - l2 P) / (l1 + l2) with l1 = b^T F' b, l2 = b^T C' b > 0 (tau' = -l2 / (l1 + l2)): the sign of g' is
  // that of N = l1 Q - l2 P, bounded by its value at x and the variations (keeping the cancellation between the
  // two terms exact at x, which bounding tau', P and Q separately would lose).
  auto form = [](const Vec& w, const Vec& ab, const Vec& db, bool upper) {
    const Vec r = upper ? Vec(ab + db) : Vec((ab - db).cwiseMax(0.0));
    return w.dot(r.cwiseProduct(r));
  };
  const double l1x = d1x.dot(bx.cwiseProduct(bx));
  const double l2x = d2x.dot(yb.cwiseProduct(yb));
  const double l1lo = form(F.d1_min, abx, dbF, false), l1hi = form(F.d1, abx, dbF, true);
  const double l2lo = form(C.d1_min, ayb, dbC, false), l2hi = form(C.d1, ayb, dbC, true);
  const double dl1 = std::max(l1hi - l1x, l1x - l1lo), dl2 = std::max(l2hi - l2x, l2x - l2lo);
  const double N = l1x * Q - l2x * P;
  const double dN =
      dl1 * (std::abs(Q) + dQ) + std::max(l1hi, l1x) * dQ + dl2 * (std::abs(P) + dP) + std::max(l2hi, l2x) * dP;
  // and through the range of tau' = -l2 / (l1 + l2) in [-1, 0], g' = tau' P + (1 + tau') Q being bilinear: both
  // bounds hold, so the tighter one is kept (neither is always better).
  double tlo = -1.0, thi = 0.0;
  if (l1lo + l2hi > 0) tlo = -l2hi / (l1lo + l2hi);
  if (l1hi + l2lo > 0) thi = -l2lo / (l1hi + l2lo);
  auto lower = [&](double tp) { return tp * (P + dP) + (1.0 + tp) * (Q - dQ); };
  auto upper = [&](double tp) { return tp * (P - dP) + (1.0 + tp) * (Q + dQ); };
  sb.dg_lo = std::min(lower(tlo), lower(thi));
  sb.dg_hi = std::max(upper(tlo), upper(thi));
  const double Dlo = l1lo + l2lo, Dhi = l1hi + l2hi;
  if (Dlo > 0) {
    const double nlo = N - dN, nhi = N + dN;
    sb.dg_lo = std::max(sb.dg_lo, std::min(nlo / Dlo, nlo / Dhi));
    sb.dg_hi = std::min(sb.dg_hi, std::max(nhi / Dlo, nhi / Dhi));
  }
  constexpr double kBoundSlack = 1e-9;  // rounding in the bounds themselves: ~5e6 eps of sums of O(m) terms
  const double slack = kBoundSlack * (std::abs(sb.dg_lo) + std::abs(sb.dg_hi));
  sb.dg_lo -= slack;
  sb.dg_hi += slack;
  // Mean value theorem: g(s) = g_x + g'(xi) (s - s_x) on the step of length h from x (forward from a, backward
  // from b), which keeps the exact cancellation of g' at x; tighter than the direct range where g itself is small
  // (curves along which c^T b stays near 0).
  const double h = hi_s - lo_s;
  double mlo, mhi;
  if (x.s <= 0.5 * (lo_s + hi_s)) {
    mlo = gx + std::min(0.0, h * sb.dg_lo);
    mhi = gx + std::max(0.0, h * sb.dg_hi);
  } else {
    mlo = gx - std::max(0.0, h * sb.dg_hi);
    mhi = gx - std::min(0.0, h * sb.dg_lo);
  }
  sb.g_lo = std::max(sb.g_lo, mlo - sb.g_err);
  sb.g_hi = std::min(sb.g_hi, mhi + sb.g_err);
  sb.valid = std::isfinite(sb.g_lo) && std::isfinite(sb.g_hi) && std::isfinite(sb.dg_lo) && std::isfinite(sb.dg_hi);
  return sb;
}

AlongCurve::AlongCurve(const BorderedForm& bf, const PhaseBounds& F, const PhaseBounds& C, double length, double w1,
                       double w2, Vec offset_F, Vec offset_C)
    : G_(bf.Gx()), F_(F), C_(C), h_(length), w1_(w1), w2_(w2), iFx_(std::move(offset_F)), iCx_(std::move(offset_C)) {
  rhoF_ = ratio_minus_one(F);
  rhoC_ = ratio_minus_one(C);
}

bool AlongCurve::valid() const {
  return w1_ > 0 && w2_ > 0 && h_ > 0 && rhoF_.allFinite() && rhoC_.allFinite();
}

double AlongCurve::kappa(const Vec& abx, const Vec& ayb, double S) const {
  const double db = std::sqrt(2.0 * (1.0 - std::sqrt(std::max(0.0, 1.0 - S * S))));
  auto form = [db](const Vec& w, const Vec& ab, bool upper) {
    const Vec r = upper ? Vec(ab.array() + db) : Vec((ab.array() - db).cwiseMax(0.0));
    return w.dot(r.cwiseProduct(r));
  };
  const double l1lo = form(F_.d1_min, abx, false), l1hi = form(F_.d1, abx, true);
  const double l2lo = form(C_.d1_min, ayb, false), l2hi = form(C_.d1, ayb, true);
  if (!(l1lo + l2hi > 0 && l1hi + l2lo > 0)) return 1.0;
  const double p = l2lo / (l1hi + l2lo), q = l2hi / (l1lo + l2hi);  // |tau'| in [p, q]
  return std::min(1.0, h_ * std::max({q / w1_ - (1.0 - q) / w2_, (1.0 - p) / w2_ - p / w1_, 0.0}));
}

AlongCurve::FirstOrder AlongCurve::first_order(const Vec& a, const Vec& ya, double kappa, const Mat& Hp, const Mat& HpG,
                                               const Mat& aHp, const Mat& aHpG, const Mat& aGHpG) const {
  const Vec w = Hp * (-F_.increment.cwiseProduct(a)) + HpG * C_.increment.cwiseProduct(ya);  // Hp E_box a
  const Vec ra = weight_F().cwiseProduct(a.cwiseAbs()), rya = weight_C(kappa).cwiseProduct(ya.cwiseAbs());
  return {w.cwiseAbs() + aHp * ra + aHpG * rya, (G_.transpose() * w).cwiseAbs() + aHpG.transpose() * ra + aGHpG * rya};
}

namespace {
// Where the expansion of structured_box_norm may stand in for the dense product: its rounding slack at most this part
// of the squared norm (the bound then exceeds the exact norm by at most ~5e-7 of it, far below what moves a verdict;
// with ~3e-11 m-relative slack at m = 1000, that holds unless the flight and contact parts of Hp E_box cancel to below
// ~5e-3 of their size).
constexpr double kStructuredBoxSlack = 1e-6;
// |Gx^T Gx - I|_2 in units of m eps: Gx's columns are eigenvectors from a backward stable solver (or exact unit
// vectors where bordered), orthonormal to O(m eps).
constexpr double kGramSlack = 4.0;
}  // namespace

void prepare_box_products(SpectralProducts& p, const Eigen::MatrixXd& G) {
  const Eigen::MatrixXd W = detail::product(p.Hp, false, p.HpG, false);  // Hp Hp G
  p.GW = G.cwiseProduct(W);
  p.aGW = p.GW.cwiseAbs();
  p.hp_col2 = p.Hp.colwise().squaredNorm().transpose();
  p.hpg_col2 = p.HpG.colwise().squaredNorm().transpose();
  p.box_ready = true;
}

BoxNorm structured_box_norm(const SpectralProducts& p, const Eigen::VectorXd& dF, const Eigen::VectorXd& dC) {
  const double eps = std::numeric_limits<double>::epsilon();
  const auto n = static_cast<double>(p.GW.rows()), mG = static_cast<double>(p.GW.cols());
  const double a = dF.cwiseProduct(dF).dot(p.hp_col2);   // |Hp diag(dF)|_F^2
  const double c = dC.cwiseProduct(dC).dot(p.hpg_col2);  // |Hp G diag(dC)|_F^2
  const Eigen::VectorXd GWdC = p.GW * dC;
  const double T = dF.dot(GWdC);  // <Hp diag(dF), Hp G diag(dC) G^T>_F
  const double Tabs = dF.dot(p.aGW * dC);
  // Rounding: each sum (of at most n + mG terms) within u of its absolute sum; Hp Hp G within u |Hp| |Hp G|
  // entrywise, and (|Hp| |Hp G|)_li <= |Hp e_l| |Hp G e_i| (Cauchy-Schwarz), so its part of T is within
  // u sum_li dF_l |G_li| dC_i |Hp e_l| |Hp G e_i| <= u |G|_F sqrt(a c) <= u sqrt(mG) (a + c) / 2.
  const double u = 2.0 * (n + mG + 4.0) * eps;
  const double delta = kGramSlack * n * eps;
  BoxNorm r;
  const double sq = a - 2.0 * T + c;
  r.slack = u * (1.0 + std::sqrt(mG)) * (a + c) + 2.0 * u * Tabs + delta * c;
  r.value = std::sqrt(std::max(0.0, sq + r.slack));
  r.usable = std::isfinite(r.value) && sq > 0.0 && r.slack <= kStructuredBoxSlack * sq;
  return r;
}

double dense_box_norm(const Eigen::MatrixXd& Hp, const Eigen::MatrixXd& HpG, const Eigen::MatrixXd& G,
                      const Eigen::VectorXd& dF, const Eigen::VectorXd& dC) {
  const Eigen::MatrixXd HpE = -Hp * dF.asDiagonal() + detail::product(HpG * dC.asDiagonal(), false, G, true);
  return HpE.norm();
}

double AlongCurve::k2(double kappa, const Mat& Hp, const Mat& HpG, SpectralProducts* products) const {
  if (box_norm_ < 0.0 && products && Hp.rows() >= detail::kLapackFrom) {
    if (!products->box_ready) prepare_box_products(*products, G_);
    const BoxNorm s = structured_box_norm(*products, F_.increment, C_.increment);
    if (s.usable) box_norm_ = s.value;
  }
  if (box_norm_ < 0.0) box_norm_ = dense_box_norm(Hp, HpG, G_, F_.increment, C_.increment);
  return box_norm_ + (Hp * weight_F().asDiagonal()).norm() + (HpG * weight_C(kappa).asDiagonal()).norm();
}

double AlongCurve::bilinear(const Vec& v, const Vec& yv, const Vec& b, const Vec& yb, double kappa) const {
  const double box = -v.dot(F_.increment.cwiseProduct(b)) + yv.dot(C_.increment.cwiseProduct(yb));
  return std::abs(box) + weight_F().cwiseProduct(v.cwiseAbs()).dot(b.cwiseAbs()) +
         weight_C(kappa).cwiseProduct(yv.cwiseAbs()).dot(yb.cwiseAbs());
}

Eigen::VectorXd AlongCurve::ratio_minus_one(const PhaseBounds& P) {
  Vec r(P.d1.size());
  for (Eigen::Index i = 0; i < r.size(); ++i) r(i) = P.d1_min(i) > 0 ? std::min(1.0, P.d1(i) / P.d1_min(i) - 1.0) : 1.0;
  return r;
}

Eigen::VectorXd AlongCurve::weight_F() const {
  return rhoF_.cwiseProduct(F_.increment) + iFx_;
}

Eigen::VectorXd AlongCurve::weight_C(double kappa) const {
  return (rhoC_.array() + kappa).min(1.0).matrix().cwiseProduct(C_.increment) + iCx_;
}

PhaseBounds phase_bounds(const PhaseFamily& f, double lo, double hi) {
  const Eigen::Index m = f.size();
  PhaseBounds pb{Eigen::VectorXd(m), Eigen::VectorXd(m), Eigen::VectorXd(m), Eigen::VectorXd(m), Eigen::VectorXd(m)};
  for (Eigen::Index i = 0; i < m; ++i) {
    const PhaseFamily::Point a = f.at(i, lo), b = f.at(i, hi);
    // a tan is increasing, its derivative convex and its second derivative increasing between poles: their extremes
    // are at the ends.
    pb.increment(i) = std::abs(b.v - a.v);
    pb.d1(i) = std::max(a.d1, b.d1);
    pb.d2(i) = std::max(std::abs(a.d2), std::abs(b.d2));
    pb.value(i) = std::max(std::abs(a.v), std::abs(b.v));
    // the derivative a w sec^2 is smallest (a w) where tan = 0, if the interval holds such a point
    if (f.linear(i) || f.amp(i) == 0.0)
      pb.d1_min(i) = a.d1;
    else
      pb.d1_min(i) = (a.v <= 0.0 && b.v >= 0.0) ? f.amp(i) * f.freq(i) : std::min(a.d1, b.d1);
  }
  return pb;
}

PhaseBounds phase_bounds(const Eigen::VectorXd& freqs, PhaseShape shape, double lo, double hi) {
  // The family of H's own phases depends only on (freqs, shape): kept for the last two (the flight and the contact
  // frequencies alternate), per thread. It was built anew (five vectors) on every call: 265 254 times on the 5-dof
  // chain's certified box (`spp solve c5.json --box --threads 1` under callgrind; with this and SpectralProducts' kept
  // absolute values, 2.645G -> 2.563G instructions, same evaluations and SPPs).
  struct Slot {
    Eigen::VectorXd freqs;
    PhaseShape shape = PhaseShape::FTan;
    PhaseFamily family;
  };
  thread_local Slot slots[2];
  thread_local int next = 0;
  for (const Slot& slot : slots)
    if (slot.shape == shape && slot.freqs.size() == freqs.size() && slot.freqs.size() > 0 && slot.freqs == freqs)
      return phase_bounds(slot.family, lo, hi);
  Slot& slot = slots[next];
  next = 1 - next;
  slot.freqs = freqs;
  slot.shape = shape;
  slot.family = PhaseFamily::of_modes(freqs, shape);
  return phase_bounds(slot.family, lo, hi);
}

namespace {
StepCertificate certify_step_weyl(const EquationSet& eq, const StepEnd& a, const StepEnd& b) {
  const ModalForm& md = eq.modal();
  const PhaseShape shape = eq.phase_shape();
  StepCertificate cert;
  // the s-interval between the true curve points of the ends (each within pos_err of its end in t1 and t2)
  const double h = b.s - a.s + 2.0 * (a.pos_err + b.pos_err);
  const PhaseBounds F = phase_bounds(md.omega(), shape, std::min(a.t1, b.t1), std::max(a.t1, b.t1));
  const PhaseBounds C = phase_bounds(md.d(), shape, std::min(a.t2, b.t2), std::max(a.t2, b.t2));
  const double dF = F.increment.maxCoeff(), dC = C.increment.maxCoeff();
  const double eig_err = std::max(a.eig_error, b.eig_error);
  const double gap_err = eig_err + std::max(a.offset_norm, b.offset_norm);  // eigenvalues at the true curve points

  // Gap: Loewner bounds of the neighbouring eigenvalues over the step's box (Weyl).
  const double above = std::max(a.lam_above - dF, b.lam_above - dC) - gap_err;
  const double below = std::min(a.lam_below + dC, b.lam_below + dF) + gap_err;
  const double gamma = std::min(above, -below);
  cert.gap = gamma;
  if (!(gamma > 0) || !std::isfinite(gamma)) return cert;

  // Bounds of |W b(s)| and b(s)^T W b(s) for a diagonal weight W (flight basis, or contact basis through
  // y = G^T b) over the step, from one end x: b(s) stays within |b(s) - b_x| <= drift_x of b_x (Davis-Kahan:
  // sin angle <= |H(s) b_x| / gamma, |H(s) b_x| <= |H_x b_x| + |dF o b_x| + |dC o G^T b_x|). The better end wins.
  struct End {
    Eigen::VectorXd b, y;
    double drift = 2.0, sin = 1.0;
  };
  auto make_end = [&](const StepEnd& x) {
    End e{*x.b, md.G().transpose() * *x.b};
    const double rho = x.residual + weighted_norm(F.increment, e.b) + weighted_norm(C.increment, e.y);
    e.sin = std::min(1.0, rho / gamma);
    if (e.sin < 1.0) e.drift = std::sqrt(2.0) * e.sin;
    return e;
  };
  const End ea_ = make_end(a), eb_ = make_end(b);
  // Zeroth order: |g(s) - g_x| <= |c(s) - c_x| + |c_x| |b(s) - b_x| <= dc + |c_x| drift_x on the whole step (c = z /
  // |z| constant for axial symmetry, dc = 0; c(t2) = -G tan(D t2) D^-1 G^T z for point symmetry, dc from the increments
  // of tan(d t2) / d weighted by |G^T z|), so |g_x| beyond that and its error keeps the sign. Linear in |g|, and no
  // derivative of H enters: this holds next to pole lines too. Its safe length from b: as long as the bound (linear
  // in the step, to first order) stays below |g_b|.
  double zeroth_length = 0.0;
  if ((a.g > 0) == (b.g > 0)) {
    double dc = 0.0, ca = 1.0, cb = 1.0;
    if (!eq.onset_direction_fixed()) {  // c(t2) = -contact_part(t2) z moves, and is not normalised
      dc = weighted_norm(C.increment, md.G().transpose() * md.z());
      ca = eq.onset_direction(a.t2).norm();
      cb = eq.onset_direction(b.t2).norm();
    }
    const double ga = std::abs(a.g) - ca * (a.residual + eig_err) / gamma;
    const double gb = std::abs(b.g) - cb * (b.residual + eig_err) / gamma;
    const double reach_a = dc + ca * ea_.drift, reach_b = dc + cb * eb_.drift;
    if ((ea_.sin < 1.0 && ga > reach_a) || (eb_.sin < 1.0 && gb > reach_b)) {
      cert.verdict = StepVerdict::NoRoot;
      cert.rotation = std::min(ea_.drift, eb_.drift);
      zeroth_length = reach_b > 0 ? h * std::max(0.0, gb) / reach_b : 4.0 * h;
      cert.safe_length = zeroth_length;
    }
  }
  if (!(std::min(ea_.sin, eb_.sin) < 0.9)) return cert;
  auto norm_bound = [&](const Eigen::VectorXd& w, bool contact) {  // |W b(s)|
    auto one = [&](const End& e) { return weighted_norm(w, contact ? e.y : e.b) + w.cwiseAbs().maxCoeff() * e.drift; };
    return std::min(one(ea_), one(eb_));
  };
  auto form_bound = [&](const Eigen::VectorXd& w, bool contact) {  // |b(s)^T W b(s)|
    const Eigen::VectorXd r = w.cwiseAbs().cwiseSqrt();
    auto one = [&](const End& e) {
      const double v = weighted_norm(r, contact ? e.y : e.b) + r.maxCoeff() * e.drift;
      return v * v;
    };
    return std::min(one(ea_), one(eb_));
  };
  const double P1 = F.d1.maxCoeff(), P2 = C.d1.maxCoeff(), P = std::max(P1, P2);
  // Rotation rate: |b'| <= |H' b| / gamma, H' = tau' F' + (1 + tau') C' a convex combination (tau' in [-1, 0]).
  const double A1 = norm_bound(F.d1, false), A2 = norm_bound(C.d1, true);
  const double L1 = std::max(A1, A2) / gamma;
  const double rotation = L1 * h;
  if (cert.verdict == StepVerdict::Uncertified) cert.rotation = rotation;

  // Curvature: tau'' = (-l2' - tau' (l1' + l2')) / (l1 + l2), l1 + l2 bounded below from its end values and
  // its rate (and by min f' >= w^2), then b'' = -H^+ (H'' b + 2 H' b') - |b'|^2 b, then g''.
  const double dl1 = 2.0 * A1 * L1 + form_bound(F.d2, false), dl2 = 2.0 * A2 * L1 + form_bound(C.d2, true);
  const double lcrude = eq.min_flight_slope();
  const double lsum = std::max(lcrude, 0.5 * (a.slope_sum + b.slope_sum - (dl1 + dl2) * h));
  const double tau2 = (dl1 + 2.0 * dl2) / lsum;
  const double Hppb = tau2 * (A1 + A2) + std::max(norm_bound(F.d2, false), norm_bound(C.d2, true));
  const double bpp = (Hppb + 2.0 * P * L1) / gamma + L1 * L1;
  double L2 = bpp;
  double cnorm = 1.0;
  if (!eq.onset_direction_fixed()) {  // g = c(t2)^T b, c = -contact_part(t2) z (point: -G tan(D t2) D^-1 G^T z)
    const double zn = md.z().norm();
    cnorm = C.value.maxCoeff() * zn;
    const double c1 = P2 * zn, c2 = (C.d2.cwiseAbs().maxCoeff() + P2 * tau2) * zn;
    L2 = c2 + 2.0 * c1 * L1 + cnorm * bpp;
  }
  constexpr double kCurvatureSlack = 1e-6;  // rounding in the bound itself: products of O(m)-term sums
  L2 *= 1.0 + kCurvatureSlack;
  cert.curvature = L2;

  // Errors of the computed g at the ends: the computed b is within residual / gamma of the true one.
  const double ea = cnorm * (a.residual + eig_err) / gamma, eb = cnorm * (b.residual + eig_err) / gamma;
  const bool same_sign = (a.g > 0) == (b.g > 0);
  if (same_sign) {
    const double sigma = a.g > 0 ? 1.0 : -1.0;
    const double xa = zero_free_radius(std::abs(a.g) - ea, sigma * a.dg, L2);
    const double yb = zero_free_radius(std::abs(b.g) - eb, -sigma * b.dg, L2);
    if (xa + yb > h && rotation < 1.0) cert.verdict = StepVerdict::NoRoot;
  } else if (std::abs(a.g) > ea && std::abs(b.g) > eb) {
    const double sigma = b.g > 0 ? 1.0 : -1.0;  // direction of the crossing
    const double xa = std::max(0.0, sigma * a.dg) / L2, yb = std::max(0.0, sigma * b.dg) / L2;
    if (xa + yb > h && rotation < 1.0) cert.verdict = StepVerdict::OneRoot;
  }
  // A step from b that the same bounds would certify: past a zero-free stretch, or across one simple root.
  const double sb = b.g > 0 ? 1.0 : -1.0;
  const double free_b = zero_free_radius(std::abs(b.g) - eb, sb * b.dg, L2);
  const double cross_b = 0.9 * std::abs(b.dg) / L2;
  cert.safe_length = std::max(zeroth_length, std::min(std::max(free_b, cross_b), 0.5 / std::max(L1, 1e-300)));
  return cert;
}

}  // namespace

Offset offset_bound(const EquationSet& eq, double t1, double t2, double e1, double e2, const Eigen::VectorXd& b) {
  const ModalForm& md = eq.modal();
  const double inf = std::numeric_limits<double>::infinity();
  if (count_tangent_poles(md.omega(), t1 - e1, t1 + e1) > 0 || count_tangent_poles(md.d(), t2 - e2, t2 + e2) > 0)
    return {inf, inf};
  const PhaseBounds F = phase_bounds(md.omega(), eq.phase_shape(), t1 - e1, t1 + e1),
                    C = phase_bounds(md.d(), eq.phase_shape(), t2 - e2, t2 + e2);
  return {weighted_norm(F.increment, b) + weighted_norm(C.increment, md.G().transpose() * b),
          F.increment.maxCoeff() + C.increment.maxCoeff()};
}

BorderedOffset bordered_offset(const EquationSet& eq, double t1, double t2, EigenCache* cache) {
  BorderedOffset o;
  const BorderedForm bf(eq, t1, t1, t2, t2);
  if (!bf.valid() || bf.bordered() == 0) return o;
  detail::SymmetricEigen own;
  bool computed = true;
  if (!cache) own = detail::symmetric_eigen(bf.matrix(t1, t2));
  const detail::SymmetricEigen& es = cache ? cache->at(bf, t1, t2, computed) : own;
  if (!es.ok) return o;
  const Eigen::VectorXd& lam = es.values;
  Eigen::Index k = 0;
  lam.cwiseAbs().minCoeff(&k);
  const Eigen::VectorXd x = es.vectors.col(k);
  const double err = decomposition_error(lam);
  const Eigen::VectorXd y = bf.Gx().transpose() * x;
  o.lam_err = std::abs(lam(k)) + err;
  o.l1 = bf.flight().d1(t1).dot(x.cwiseProduct(x));
  o.l2 = bf.contact().d1(t2).dot(y.cwiseProduct(y));
  o.valid = o.l1 >= 0 && o.l2 >= 0 && o.l1 + o.l2 > 0;
  return o;
}

StepCertificate certify_step(const EquationSet& eq, const StepEnd& a, const StepEnd& b, const StepBox& cell,
                             EigenCache* cache) {
  StepCertificate cert = certify_step_weyl(eq, a, b);
  if (cert.verdict != StepVerdict::Uncertified) {  // each of its proofs needs |g_b| beyond its error
    cert.end_sign = b.g > 0 ? 1 : -1;
    return cert;
  }
  // The true curve points of the step: within pos_err (twice, for safety) of the computed ends in t1 and t2, t1
  // non-increasing and t2 non-decreasing in s, and inside the cell (which keeps every phase function monotone).
  const double e = 2.0 * std::max(a.pos_err, b.pos_err);
  const double lo1 = std::max(cell.lo1, std::min(a.t1, b.t1) - e), hi1 = std::min(cell.hi1, std::max(a.t1, b.t1) + e);
  const double lo2 = std::max(cell.lo2, std::min(a.t2, b.t2) - e), hi2 = std::min(cell.hi2, std::max(a.t2, b.t2) + e);
  if (!(lo1 <= hi1 && lo2 <= hi2)) return cert;
  // The sign of the true g at an end, from its computed value and Davis-Kahan at that point (0: not certain).
  auto sign_at = [](const StepEnd& y) {
    const double gap = std::min(y.lam_above, -y.lam_below) - y.eig_error - y.offset_norm;
    if (!(gap > 0)) return 0;
    const double err = (y.residual + y.eig_error) / gap + 4.0 * std::numeric_limits<double>::epsilon();
    return std::abs(y.g) > err ? (y.g > 0 ? 1 : -1) : 0;
  };
  // The bounds from each end in turn (a first: its eigenpairs are usually cached), in the bordered form of the step's
  // box. Each range holds on the whole step, so what one end proves (monotone g) combines with what the other adds (its
  // own end sign).
  const BorderedForm bf(eq, lo1, hi1, lo2, hi2);
  if (!bf.valid()) return cert;
  int sign_a = a.proved_sign != 0 ? a.proved_sign : sign_at(a), sign_b = sign_at(b);
  bool monotone = false;
  for (const StepEnd* x : {&a, &b}) {
    // s-range between the true curve points of the ends (each within pos_err of its end in t1 and t2)
    const SpectralBounds sb =
        spectral_bounds(bf, *x, a.s - 2.0 * a.pos_err, b.s + 2.0 * b.pos_err, lo1, hi1, lo2, hi2, cache);
    cert.evaluations += sb.evaluations;
    if (!sb.valid) continue;
    cert.spectral_valid = true;
    // the sign of the true g at x, from the bordered form's own error bound there (tighter next to pole lines)
    if (std::abs(sb.g_x) > sb.g_err) {
      int& sx = x == &a ? sign_a : sign_b;
      if (sx == 0) sx = sb.g_x > 0 ? 1 : -1;
    }
    const bool same_sign = (a.g > 0) == (b.g > 0);
    if (cert.monotone_dir == 0 && sb.dg_lo > 0) cert.monotone_dir = 1;
    if (cert.monotone_dir == 0 && sb.dg_hi < 0) cert.monotone_dir = -1;
    monotone = cert.monotone_dir != 0;
    if ((sb.g_lo > 0 || sb.g_hi < 0) && same_sign && (sb.g_lo > 0) == (a.g > 0)) {
      cert.verdict = StepVerdict::NoRoot;  // g keeps the sign the computed ends show
      cert.end_sign = sb.g_lo > 0 ? 1 : -1;
    } else if (monotone) {  // the true end signs decide
      if (sign_a != 0 && sign_b != 0 && (sign_a > 0) == (a.g > 0) && (sign_b > 0) == (b.g > 0)) {
        cert.verdict = sign_a == sign_b ? StepVerdict::NoRoot : StepVerdict::OneRoot;
        cert.end_sign = sign_b;
      }
    }
    if (cert.verdict != StepVerdict::Uncertified) {
      cert.spectral = true;
      return cert;
    }
  }
  cert.sign_a = sign_a != 0 && (sign_a > 0) == (a.g > 0) ? sign_a : 0;
  cert.sign_b = sign_b != 0 && (sign_b > 0) == (b.g > 0) ? sign_b : 0;
  return cert;
}

}  // namespace spp::search
