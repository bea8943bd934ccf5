#include "spp/detail/cosine_sum.hpp"

#include <algorithm>
#include <cmath>
#include <queue>

namespace spp::detail {

double CosineSum::value(double t) const {
  return c0 + (amp.array() * (freq.array() * t).cos()).sum();
}

double CosineSum::derivative(double t, int k) const {
  if (k == 0) return value(t);
  // d^k/dt^k cos(w t) = w^k cos(w t + k pi/2)
  const double shift = k * std::acos(-1.0) / 2.0;
  return (amp.array() * freq.array().pow(k) * (freq.array() * t + shift).cos()).sum();
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

}  // namespace spp::detail
