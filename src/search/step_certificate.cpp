#include "search/step_certificate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spp::search {

namespace {

// Phase function of one frequency f at t (inside a pole interval): value, first and second derivative.
struct Phase {
  double v, d1, d2;
};
Phase phase(double f, Symmetry sym, double t) {
  if (f == 0.0) return sym == Symmetry::Point ? Phase{t, 1.0, 0.0} : Phase{0.0, 0.0, 0.0};
  const double tn = std::tan(f * t), sec2 = 1.0 + tn * tn;
  if (sym == Symmetry::Point) return {tn / f, sec2, 2.0 * f * sec2 * tn};
  return {f * tn, f * f * sec2, 2.0 * f * f * f * sec2 * tn};
}

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

PhaseBounds phase_bounds(const Eigen::VectorXd& freqs, Symmetry sym, double lo, double hi) {
  const Eigen::Index m = freqs.size();
  PhaseBounds pb{Eigen::VectorXd(m), Eigen::VectorXd(m), Eigen::VectorXd(m), Eigen::VectorXd(m)};
  for (Eigen::Index i = 0; i < m; ++i) {
    const Phase a = phase(freqs(i), sym, lo), b = phase(freqs(i), sym, hi);
    // f is increasing, f' convex and f'' increasing between poles: their extremes are at the ends.
    pb.increment(i) = std::abs(b.v - a.v);
    pb.d1(i) = std::max(a.d1, b.d1);
    pb.d2(i) = std::max(std::abs(a.d2), std::abs(b.d2));
    pb.value(i) = std::max(std::abs(a.v), std::abs(b.v));
  }
  return pb;
}

StepCertificate certify_step(const ModalForm& md, Symmetry sym, const StepEnd& a, const StepEnd& b) {
  StepCertificate cert;
  const double h = b.s - a.s;
  const PhaseBounds F = phase_bounds(md.omega(), sym, std::min(a.t1, b.t1), std::max(a.t1, b.t1));
  const PhaseBounds C = phase_bounds(md.d(), sym, std::min(a.t2, b.t2), std::max(a.t2, b.t2));
  const double dF = F.increment.maxCoeff(), dC = C.increment.maxCoeff();
  const double eig_err = std::max(a.eig_error, b.eig_error);

  // Gap: Loewner bounds of the neighbouring eigenvalues over the step's box (Weyl).
  const double above = std::max(a.lam_above - dF, b.lam_above - dC) - eig_err;
  const double below = std::min(a.lam_below + dC, b.lam_below + dF) + eig_err;
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
  // Zeroth order: |g(s) - g_x| <= |c(s) - c_x| + |c_x| |b(s) - b_x| <= dc + |c_x| drift_x on the whole step (c = z / |z|
  // constant for axial symmetry, dc = 0; c(t2) = -G tan(D t2) D^-1 G^T z for point symmetry, dc from the increments
  // of tan(d t2) / d weighted by |G^T z|), so |g_x| beyond that and its error keeps the sign. Linear in |g|, and no
  // derivative of H enters: this holds next to pole lines too. Its safe length from b: as long as the bound (linear
  // in the step, to first order) stays below |g_b|.
  double zeroth_length = 0.0;
  if ((a.g > 0) == (b.g > 0)) {
    double dc = 0.0, ca = 1.0, cb = 1.0;
    if (sym == Symmetry::Point) {
      dc = weighted_norm(C.increment, md.G().transpose() * md.z());
      ca = md.onset_direction(a.t2, sym).norm();
      cb = md.onset_direction(b.t2, sym).norm();
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
  const double lcrude = sym == Symmetry::Point ? 1.0 : md.omega().cwiseProduct(md.omega()).minCoeff();
  const double lsum = std::max(lcrude, 0.5 * (a.slope_sum + b.slope_sum - (dl1 + dl2) * h));
  const double tau2 = (dl1 + 2.0 * dl2) / lsum;
  const double Hppb = tau2 * (A1 + A2) + std::max(norm_bound(F.d2, false), norm_bound(C.d2, true));
  const double bpp = (Hppb + 2.0 * P * L1) / gamma + L1 * L1;
  double L2 = bpp;
  double cnorm = 1.0;
  if (sym == Symmetry::Point) {  // g = c(t2)^T b, c = -G tan(D t2) D^-1 G^T z
    const double zn = md.z().norm();
    cnorm = C.value.maxCoeff() * zn;
    const double c1 = P2 * zn, c2 = (C.d2.cwiseAbs().maxCoeff() + P2 * tau2) * zn;
    L2 = c2 + 2.0 * c1 * L1 + cnorm * bpp;
  }
  L2 *= 1.0 + 1e-6;  // rounding in the bound itself
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

}  // namespace spp::search
