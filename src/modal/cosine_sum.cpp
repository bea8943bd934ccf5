#include "spp/detail/cosine_sum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "spp/detail/brent.hpp"

namespace spp::detail {

CosineSum CosineSum::from_cos_sin(double c0, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                                  const Eigen::VectorXd& freq) {
  CosineSum f;
  f.c0 = c0;
  f.freq = freq;
  f.amp.resize(a.size());
  f.phase.resize(a.size());
  for (Eigen::Index k = 0; k < a.size(); ++k) {  // a cos + b sin = A cos(w t - atan2(b, a))
    f.amp(k) = std::hypot(a(k), b(k));
    f.phase(k) = -std::atan2(b(k), a(k));
  }
  return f;
}

double CosineSum::value(double t) const {
  return derivative(t, 0);
}

double CosineSum::derivative(double t, int k) const {
  // d^k/dt^k cos(w t + phi) = w^k cos(w t + phi + k pi/2)
  const double shift = k * std::acos(-1.0) / 2.0;
  Eigen::ArrayXd arg = freq.array() * t + shift;
  if (phase.size() == freq.size()) arg += phase.array();
  const double s = k == 0 ? (amp.array() * arg.cos()).sum() : (amp.array() * freq.array().pow(k) * arg.cos()).sum();
  return k == 0 ? c0 + s : s;
}

double CosineSum::bound(int p) const {
  return (amp.array().abs() * freq.array().pow(p)).sum();
}

namespace {
struct Interval {
  double a, b, fa, fb, da, db, lb;
  bool operator<(const Interval& o) const { return lb > o.lb; }  // min-heap on the lower bound
};
}  // namespace

CosineMinimum minimize(const CosineSum& f, double lo, double hi, double abs_tol, int max_evaluations) {
  const double M2 = f.bound(2);
  auto make = [&](double a, double b, double fa, double fb, double da, double db) {
    const double h = b - a;
    double lb = std::min(fa, fb) - M2 * h * h / 8.0;                  // interpolation error bound
    lb = std::max(lb, std::min(fa, fa + da * h - 0.5 * M2 * h * h));  // Taylor from a (concave bound)
    lb = std::max(lb, std::min(fb, fb - db * h - 0.5 * M2 * h * h));  // Taylor from b
    return Interval{a, b, fa, fb, da, db, lb};
  };
  CosineMinimum best;
  const double flo = f.value(lo), fhi = f.value(hi);
  best.t = flo <= fhi ? lo : hi;
  best.value = std::min(flo, fhi);
  std::priority_queue<Interval> q;
  q.push(make(lo, hi, flo, fhi, f.derivative(lo, 1), f.derivative(hi, 1)));
  int evals = 2;
  while (!q.empty()) {
    Interval iv = q.top();
    if (iv.lb >= best.value - abs_tol) {
      best.lower_bound = iv.lb;
      best.certified = true;
      return best;
    }
    if (evals >= max_evaluations) break;
    q.pop();
    const double c = 0.5 * (iv.a + iv.b);
    const double fc = f.value(c), dc = f.derivative(c, 1);
    evals += 1;
    if (fc < best.value) {
      best.value = fc;
      best.t = c;
    }
    q.push(make(iv.a, c, iv.fa, fc, iv.da, dc));
    q.push(make(c, iv.b, fc, iv.fb, dc, iv.db));
  }
  best.lower_bound = q.empty() ? best.value : q.top().lb;
  best.certified = q.empty();
  return best;
}

Crossing first_crossing_below_zero(const CosineSum& f, double lo, double hi, double abs_tol) {
  const double eps = std::numeric_limits<double>::epsilon();
  const double tol = std::max(abs_tol, 64.0 * eps * (std::abs(f.c0) + f.bound(0)));
  const double M3 = f.bound(3);
  const double h_min = 8.0 * eps * std::max({1.0, std::abs(lo), std::abs(hi)});
  Crossing out;
  auto eval = [&](double t) {
    ++out.evaluations;
    return f.value(t);
  };
  const double f_lo = eval(lo);
  double last_nonneg = lo, f_last = f_lo;
  double t_neg = f_lo < -tol ? lo : std::numeric_limits<double>::infinity();
  double f_neg = f_lo;
  double a = lo, h = hi - lo;
  // Sweep left to right: [a, b] is accepted when a third-order Taylor bound about its middle keeps f >= -tol;
  // otherwise it is halved. The first point seen with f < -tol ends the sweep once everything left of it is
  // accepted (or irreducible).
  while (a < std::min(hi, t_neg)) {
    const double b = std::min({a + h, hi, t_neg});
    const double m = 0.5 * (a + b), r = 0.5 * (b - a);
    const double fm = eval(m), fb = b == t_neg ? f_neg : eval(b);
    const double lb =
        fm - std::abs(f.derivative(m, 1)) * r - 0.5 * std::abs(f.derivative(m, 2)) * r * r - M3 * r * r * r / 6.0;
    const bool irreducible = b - a <= h_min;
    if (fm < -tol && m < t_neg) {
      t_neg = m;
      f_neg = fm;
    } else if (fb < -tol && b < t_neg) {
      t_neg = b;
      f_neg = fb;
    }
    if (lb >= -tol || irreducible) {
      if (fm >= 0.0 && m < t_neg) last_nonneg = m, f_last = fm;
      if (fb >= 0.0 && b < t_neg) last_nonneg = b, f_last = fb;
      if (irreducible && t_neg <= b) break;
      a = b;
      h = 4.0 * r;  // grow after an accepted interval
    } else {
      h = r;
    }
  }
  if (!std::isfinite(t_neg)) return out;
  out.found = true;
  if (f_last < 0.0) {
    out.t = last_nonneg;
    return out;
  }
  out.t = brent([&](double t) { return eval(t); }, last_nonneg, t_neg, f_last, f_neg, 0.0);
  return out;
}

}  // namespace spp::detail
