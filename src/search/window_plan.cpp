#include "search/window_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "search/tolerances.hpp"
#include "spp/detail/invalid.hpp"

namespace spp::search {

// The region searched for the window (lo, hi] of one phase: the window widened by a hair (roots found outside the
// window are dropped by the half-open membership rule, so a root on a tile edge is found by both tiles and kept by
// one), and, where an edge falls within kEdgePole of a pole line, widened past that line so that the line is
// interior and its thin strip is covered by pairing (a window edge is never snapped onto a pole line).
AxisPlan plan_axis(const Eigen::VectorXd& freqs, double lo, double hi, bool widen_lo, double pole_margin,
                   double max_count) {
  const double fmax = freqs.size() ? freqs.maxCoeff() : 0.0;
  const double kappa = fmax > 0 ? kEdgePole * std::numbers::pi / (2.0 * fmax) : 0.0;
  double rlo = widen_lo ? lo - kEdgeSlack * (hi - lo) : lo, rhi = hi + kEdgeSlack * (hi - lo);
  for (int pass = 0; pass < 8 && kappa > 0; ++pass) {  // poles may cluster: widen until no pole is near an edge
    bool moved = false;
    if (widen_lo) {
      const auto near = tangent_poles(freqs, std::max(0.0, rlo - kappa), rlo + kappa, max_count);
      if (!near.empty()) {
        rlo = std::max(0.5 * near.front(), near.front() - kappa);
        moved = true;
      }
    }
    const auto near = tangent_poles(freqs, rhi - kappa, rhi + kappa, max_count);
    if (!near.empty()) {
      rhi = near.back() + kappa;
      moved = true;
    }
    if (!moved) break;
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
    os << where << ": the window (" << opt.t1_min << ", " << opt.t1_max << "] x (" << opt.t2_min << ", " << opt.t2_max
       << "] holds about " << c1 * c2 << " cells (" << c1 - 1 << " x " << c2 - 1
       << " pole lines), more than max_cells = " << opt.max_cells << ": " << remedy;
    detail::invalid(os.str());
  }
}

WindowPlan plan_window(const ModalForm& md, const SolveOptions& options) {
  WindowPlan w;
  w.options = options;
  SolveOptions& opt = w.options;
  const auto [t1_auto, t2_auto] = default_lower_ends(md, opt.t1_max, opt.t2_max);
  w.axis1 = opt.t1_min == 0.0;
  w.axis2 = opt.t2_min == 0.0;
  if (w.axis1) opt.t1_min = t1_auto;
  if (w.axis2) opt.t2_min = t2_auto;
  check_window_size(md, opt);
  const double max_lines = static_cast<double>(opt.max_cells) + 16.0;
  // Nothing within axis_band() of an axis is reported: a window reaching into the band is searched from half of it.
  const auto [band1, band2] = axis_band(md);
  const bool cut1 = opt.t1_min < 0.5 * band1 && 0.5 * band1 < opt.t1_max;
  const bool cut2 = opt.t2_min < 0.5 * band2 && 0.5 * band2 < opt.t2_max;
  w.t1 = plan_axis(md.omega(), cut1 ? 0.5 * band1 : opt.t1_min, opt.t1_max, !(w.axis1 || cut1), opt.pole_margin,
                   max_lines);
  w.t2 = plan_axis(md.d(), cut2 ? 0.5 * band2 : opt.t2_min, opt.t2_max, !(w.axis2 || cut2), opt.pole_margin, max_lines);
  return w;
}

}  // namespace spp::search
