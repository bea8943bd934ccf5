#include "search/window_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "search/tolerances.hpp"
#include "spp/detail/invalid.hpp"

namespace spp::search {

namespace {

// The pole lines around x: the two last at or below x (0, the axis, where there are fewer) and the two first above.
struct PolesAround {
  double below2 = 0.0, below = 0.0, above = 0.0, above2 = 0.0;
};

PolesAround poles_around(const Eigen::VectorXd& freqs, double fmax, double x) {
  // the fastest mode alone has a pole line every pi / fmax: two on each side lie within this reach
  const double reach = 2.25 * std::numbers::pi / fmax;
  PolesAround p;
  for (double t : tangent_poles(freqs, std::max(0.0, x - reach), x + reach)) {  // O(m) lines listed
    if (t <= x) {
      p.below2 = p.below;
      p.below = t;
    } else if (p.above == 0.0) {
      p.above = t;
    } else if (p.above2 == 0.0) {
      p.above2 = t;
    }
  }
  return p;
}

}  // namespace

// The region searched for the window (lo, hi] of one phase: the window widened by a hair (roots found outside the
// window are dropped by the half-open membership rule, so a root on a tile edge is found by both tiles and kept by
// one), and each edge kept clear of the pole lines around it (kEdgePole: a line's clearance follows the spacing of
// the lines next to it, at most the fastest quarter period): an edge too close to the line beyond it is moved past
// that line (the line becomes interior and its thin strip is covered by pairing), one too close to the line inside
// it is moved away from that line (the cell between them is no sliver), and a gap too narrow to hold an edge clear
// of both its lines is passed. An edge only ever moves outwards, so the region holds the window, and never onto a
// pole line.
AxisPlan plan_axis(const Eigen::VectorXd& freqs, double lo, double hi, bool widen_lo, double pole_margin,
                   double max_count) {
  const double fmax = freqs.size() ? freqs.maxCoeff() : 0.0;
  const double quarter = fmax > 0 ? std::numbers::pi / (2.0 * fmax) : 0.0;
  double rlo = widen_lo ? lo - kEdgeSlack * (hi - lo) : lo, rhi = hi + kEdgeSlack * (hi - lo);
  // The distance an edge keeps from the line p whose neighbours are `left` and `right` (0: the axis): kEdgePole of
  // the wider gap next to p (as p's pole margin), at most of the quarter period; at least ~7 ulps of p (far windows).
  auto clearance = [&](double left, double p, double right) {
    return std::max(kEdgePole * std::min(quarter, std::max(p - left, right - p)), 4.0 * kMinPoleMargin * p);
  };
  // Where an edge goes from a line into the gap of width `gap` beyond it (kEdgeIntoGap): clear of both lines of the
  // gap when the gap can hold an edge at all.
  auto into = [&](double gap, double p) {
    return std::max(std::min(kEdgePole * quarter, kEdgeIntoGap * gap), 8.0 * kMinPoleMargin * p);
  };
  // An edge put into() a gap is clearance() from its line up to the rounding of the sum (eps p): that is clear. (The
  // clearance's floor exceeds this allowance: an edge on a line is never clear.)
  auto clear_of = [](double distance, double clear, double p) {
    return distance >= clear - 2.0 * std::numeric_limits<double>::epsilon() * p;
  };
  // Each pass settles the edge in its gap or moves it past one more line (outwards): it ends.
  for (long pass = 0; fmax > 0 && widen_lo && pass <= static_cast<long>(freqs.size()) * 8 + 16; ++pass) {
    const PolesAround p = poles_around(freqs, fmax, rlo);
    const double gap = p.above - p.below;
    const double cb = p.below > 0.0 ? clearance(p.below2, p.below, p.above) : 0.0;
    const double ca = clearance(p.below, p.above, p.above2);
    const bool clear_below = p.below == 0.0 || clear_of(rlo - p.below, cb, p.below),
               clear_above = clear_of(p.above - rlo, ca, p.above);
    if (clear_below && clear_above) break;
    if ((clear_below && std::max(cb, ca) <= kEdgeIntoGap * gap) || p.below == 0.0)
      rlo = std::min(rlo, p.above - into(gap, p.above));  // away from the line above, clear of both lines of the gap
    else
      rlo = p.below - into(p.below - p.below2, p.below);  // past the line below (at most half-way to the axis)
  }
  for (long pass = 0; fmax > 0 && pass <= static_cast<long>(freqs.size()) * 8 + 16; ++pass) {
    const PolesAround p = poles_around(freqs, fmax, rhi);
    const double gap = p.above - p.below;
    const double cb = p.below > 0.0 ? clearance(p.below2, p.below, p.above) : 0.0;
    const double ca = clearance(p.below, p.above, p.above2);
    const bool clear_below = clear_of(rhi - p.below, cb, p.below), clear_above = clear_of(p.above - rhi, ca, p.above);
    if (clear_below && clear_above) break;
    if (clear_above && std::max(cb, ca) <= kEdgeIntoGap * gap)
      rhi = std::max(rhi, p.below + into(gap, p.below));  // away from the line below, clear of both lines of the gap
    else
      rhi = p.above + into(p.above2 - p.above, p.above);  // past the line above
  }
  AxisPlan a;
  a.bp.push_back(rlo);
  a.pole.push_back(false);
  for (double p : tangent_poles(freqs, rlo, rhi, max_count)) {
    a.bp.push_back(p);
    a.pole.push_back(true);
  }
  a.bp.push_back(rhi);
  a.pole.push_back(false);
  a.margin.assign(a.bp.size(), 0.0);
  for (size_t i = 1; i + 1 < a.bp.size(); ++i) {
    const double left = a.bp[i] - a.bp[i - 1], right = a.bp[i + 1] - a.bp[i];
    a.margin[i] =
        std::max(std::min(pole_margin * std::max(left, right), 0.25 * std::min(left, right)), kMinPoleMargin * a.bp[i]);
  }
  return a;
}

// Counts the cells before anything is listed: windows beyond max_cells are refused with their count.
void check_window_size(const ModalForm& md, const SolveOptions& opt, const std::string& where,
                       const std::string& remedy) {
  const double c1 = count_tangent_poles(md.omega(), opt.t1_min, opt.t1_max) + 1.0;
  const double c2 = count_tangent_poles(md.d(), opt.t2_min, opt.t2_max) + 1.0;
  if (c1 * c2 > static_cast<double>(opt.max_cells)) {
    std::ostringstream os;
    os << where << ": the window searched (" << opt.t1_min << ", " << opt.t1_max << "] x (" << opt.t2_min << ", "
       << opt.t2_max << "] holds about " << c1 * c2 << " cells (" << c1 - 1 << " x " << c2 - 1
       << " pole lines), more than max_cells = " << opt.max_cells << ": " << remedy;
    detail::invalid(os.str());
  }
}

SolveOptions planned_window(const ModalForm& md, const SolveOptions& options) {
  SolveOptions planned = options;
  const auto [t1_auto, t2_auto] = default_lower_ends(md, options.t1_max, options.t2_max);
  if (options.t1_min == 0.0) planned.t1_min = t1_auto;
  if (options.t2_min == 0.0) planned.t2_min = t2_auto;
  // Nothing within axis_band() of an axis is reported: a window reaching into the band is searched from half of it
  // (the max_cells refusal printed the default lower ends, 1e-4 quarter periods, while the plan starts at 0.5
  // axis_band; found by an independent attack)
  const auto [band1, band2] = axis_band(md);
  if (planned.t1_min < 0.5 * band1 && 0.5 * band1 < planned.t1_max) planned.t1_min = 0.5 * band1;
  if (planned.t2_min < 0.5 * band2 && 0.5 * band2 < planned.t2_max) planned.t2_min = 0.5 * band2;
  return planned;
}

WindowPlan plan_window(const ModalForm& md, const SolveOptions& options) {
  // the lower ends as planned_window sets them (it alone holds the rules: automatic ends, the axis band); a lower end
  // the caller gave and the plan kept is widened by a hair like an upper end, an automatic or raised one is not
  WindowPlan w;
  w.options = planned_window(md, options);
  const SolveOptions& opt = w.options;
  w.axis1 = options.t1_min == 0.0;
  w.axis2 = options.t2_min == 0.0;
  const bool own1 = opt.t1_min == options.t1_min, own2 = opt.t2_min == options.t2_min;
  const double max_lines = static_cast<double>(opt.max_cells) + 16.0;
  w.t1 = plan_axis(md.omega(), opt.t1_min, opt.t1_max, own1, opt.pole_margin, max_lines);
  w.t2 = plan_axis(md.d(), opt.t2_min, opt.t2_max, own2, opt.pole_margin, max_lines);
  return w;
}

}  // namespace spp::search
