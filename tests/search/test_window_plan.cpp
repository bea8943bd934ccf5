// The search region of a window (src/search/window_plan.hpp): where its edges go next to pole lines, and that the
// plan keeps the pole lines the window asks for where the poles cluster (issue 12).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "search/tolerances.hpp"
#include "search/window_plan.hpp"
#include "spp/core/generators.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"

using namespace spp;

namespace {

// Flight frequencies of the unit fixed-free chain of n masses: omega_k = 2 sin((2k - 1) pi / (2 (2n + 1))), k = 1..n
// (the eigenvalues of its tridiagonal K, closed form); the top ones cluster ~1/n^2 apart.
Eigen::VectorXd fixed_free_chain_frequencies(int n) {
  Eigen::VectorXd f(n);
  for (int k = 1; k <= n; ++k) f(k - 1) = 2.0 * std::sin((2.0 * k - 1.0) * std::numbers::pi / (2.0 * (2.0 * n + 1.0)));
  return f;
}

// The rule the plan's edges obey (tolerances.hpp kEdgePole): from each line next to the edge, at least kEdgePole
// times the smaller of the fastest quarter period and the wider of the two gaps beside that line. Listed
// independently of plan_axis: all lines within two periods of the fastest mode, then the ones around the edge.
void expect_edge_clear(const Eigen::VectorXd& freqs, double edge, const std::string& what) {
  const double quarter = std::numbers::pi / (2.0 * freqs.maxCoeff());
  std::vector<double> lines{0.0};  // the axis
  for (double p : tangent_poles(freqs, std::max(0.0, edge - 8.0 * quarter), edge + 8.0 * quarter)) lines.push_back(p);
  const size_t above = static_cast<size_t>(std::upper_bound(lines.begin(), lines.end(), edge) - lines.begin());
  ASSERT_TRUE(above >= 1 && above + 1 < lines.size()) << what;
  auto clear = [&](size_t i) {
    const double left = i > 0 ? lines[i] - lines[i - 1] : lines[i];
    return search::kEdgePole * std::min(quarter, std::max(left, lines[i + 1] - lines[i]));
  };
  const double ulps = 8.0 * std::numeric_limits<double>::epsilon() * edge;  // the sum edge = line + clearance
  EXPECT_GE(lines[above] - edge, clear(above) - ulps)
      << what << ": edge " << edge << " next to the line " << lines[above];
  if (above >= 2) {
    EXPECT_GE(edge - lines[above - 1], clear(above - 1) - ulps)
        << what << ": edge " << edge << " next to the line " << lines[above - 1];
  }
}

}  // namespace

TEST(WindowPlan, EdgesBetweenClusteredPoleLinesKeepTheWindowsPoleLines) {
  // Regression (issue 12): an edge within 1e-4 of the fastest quarter period of a pole line was widened past it, and
  // again past the next, as long as one lay that close: where the top frequencies of a chain cluster (lines 3e-6 to
  // 5e-5 apart near pi / (2 omega_max)) the window (0, 0.78545]^2 of the 300-dof chain (2 x 2 pole lines, its
  // edges 0.17 of the gap above a line) was planned over 7 x 7 lines, (0, 0.785403]^2 of the 1000-dof chain (2 x 2,
  // edges 0.2 of the gap above a line) over 33 x 33. The edge rule is now relative to the local pole spacing.
  const System s = chain(300, {1.0}, {1.0}, 299, ContactSide::Upper, 1.0);
  const ModalForm md(s);
  SolveOptions o;
  o.t1_max = o.t2_max = 0.78545;
  const search::WindowPlan plan = search::plan_window(md, o);
  EXPECT_EQ(static_cast<size_t>(plan.t1.poles()), md.flight_poles(plan.options.t1_min, o.t1_max).size());
  EXPECT_EQ(static_cast<size_t>(plan.t2.poles()), md.contact_poles(plan.options.t2_min, o.t2_max).size());
  EXPECT_EQ(plan.t1.poles(), 2);
  EXPECT_EQ(plan.t2.poles(), 2);
  EXPECT_NEAR(plan.t1.bp.back(), 0.78545, 1e-8);
  EXPECT_NEAR(plan.t2.bp.back(), 0.78545, 1e-8);

  const Eigen::VectorXd f1000 = fixed_free_chain_frequencies(1000);
  const search::AxisPlan a = search::plan_axis(f1000, 1e-6, 0.785403, false, 1e-6, 1e8);
  EXPECT_EQ(a.poles(), 2);
  EXPECT_EQ(a.poles(), static_cast<int>(tangent_poles(f1000, 1e-6, 0.785403).size()));
  expect_edge_clear(f1000, a.bp.back(), "n = 1000");
}

TEST(WindowPlan, EdgesNextToAPoleLineMoveOutwardsAndNeverOntoIt) {
  // Edges placed at fractions 0.3 down to 1e-13 of the local gap from a pole line, on either side of it, at both ends
  // of the window, on clustered lines (1000-dof chain near pi / (2 omega_max), gaps 3e-6 to 1e-5) and on a pair 1.6e-6
  // apart amid lines 1e-2 apart (tests/data/near_coincident7.json): the planned region holds the window, its edges are
  // no pole lines and keep the rule's distance from the lines around them, and an edge moves past one line at most,
  // or two where the gap beyond the first cannot hold an edge (the chain's lowest line, its fastest quarter period,
  // has the axis beside it and asks 1e-4 of that, more than half the 2.9e-6 gap above it).
  const ModalForm nc(load_system(std::string(SPP_SOURCE_DIR) + "/tests/data/near_coincident7.json"));
  struct Case {
    Eigen::VectorXd freqs;
    double near, span;  // the lines within span of near are tried
    const char* name;
  };
  const std::vector<Case> cases = {{fixed_free_chain_frequencies(1000), 0.785405, 2e-5, "chain1000"},
                                   {nc.omega(), 0.1570785, 5e-6, "near_coincident7 flight"},
                                   {nc.d(), 0.1570785, 5e-6, "near_coincident7 contact"}};
  int tried = 0, kept = 0;
  for (const Case& c : cases) {
    const double reach = 2.25 * std::numbers::pi / c.freqs.maxCoeff();
    const std::vector<double> lines = tangent_poles(c.freqs, std::max(0.0, c.near - reach), c.near + reach);
    const double lo = 0.5 * c.near, hi = 1.5 * c.near;  // the window's other ends
    for (size_t i = 1; i + 1 < lines.size(); ++i) {
      if (std::abs(lines[i] - c.near) > c.span) continue;
      const double p = lines[i], gap_lo = p - lines[i - 1], gap_hi = lines[i + 1] - p;
      for (const double frac : {0.3, 1e-2, 1e-3, 1e-4, 1e-5, 1e-7, 1e-9, 1e-12, 1e-13})
        for (const double edge : {p - frac * gap_lo, p + frac * gap_hi}) {
          const std::string what = std::string(c.name) + " line " + std::to_string(p) + " frac " +
                                   std::to_string(frac) + (edge < p ? " below" : " above");
          // upper edge: window (lo, edge]; the line at the edge (edge == p after rounding) is in the window
          const search::AxisPlan up = search::plan_axis(c.freqs, lo, edge, true, 1e-6, 1e8);
          const int inside = static_cast<int>(tangent_poles(c.freqs, lo, edge).size()) + (edge == p);
          EXPECT_GE(up.bp.back(), edge) << what;
          EXPECT_LE(up.poles(), inside + 1) << what;
          expect_edge_clear(c.freqs, up.bp.back(), what + " (upper)");
          for (size_t k = 0; k < up.bp.size(); ++k) EXPECT_EQ(up.pole[k], k > 0 && k + 1 < up.bp.size()) << what;
          // lower edge: window (edge, hi]
          const search::AxisPlan down = search::plan_axis(c.freqs, edge, hi, true, 1e-6, 1e8);
          EXPECT_LE(down.bp.front(), edge) << what;
          EXPECT_LE(down.poles(), static_cast<int>(tangent_poles(c.freqs, edge, hi).size()) + 2) << what;
          expect_edge_clear(c.freqs, down.bp.front(), what + " (lower)");
          ++tried;
          kept += up.poles() == inside;
        }
    }
  }
  EXPECT_GT(tried, 100) << "lines tried: " << tried / 18;
  EXPECT_GT(kept, 0);  // edges a safe fraction of their gap from the lines stay where they are
}

TEST(WindowPlan, AGapTooNarrowToHoldAnEdgeIsPassed) {
  // Two lines 1.6e-7 apart, the only ones within a quarter period (frequencies 1 and 1 + 1e-7): each keeps 1e-4 of a
  // quarter period (1.6e-4) of clearance, since its wider neighbouring gap is that wide, so no edge fits between them.
  // An edge in the middle moves past both (upper edge: past the second; lower edge: past the first).
  Eigen::VectorXd f(2);
  f << 1.0, 1.0 + 1e-7;
  const std::vector<double> pair = tangent_poles(f, 1.0, 2.0);
  ASSERT_EQ(pair.size(), 2u);
  const double mid = 0.5 * (pair[0] + pair[1]);
  const search::AxisPlan up = search::plan_axis(f, 1.0, mid, true, 1e-6, 1e8);
  EXPECT_EQ(up.poles(), 2);
  EXPECT_GT(up.bp.back(), pair[1]);
  expect_edge_clear(f, up.bp.back(), "upper");
  const search::AxisPlan down = search::plan_axis(f, mid, 2.0, true, 1e-6, 1e8);
  EXPECT_EQ(down.poles(), 2);
  EXPECT_LT(down.bp.front(), pair[0]);
  expect_edge_clear(f, down.bp.front(), "lower");
}

TEST(WindowPlan, AnEdgeOnAPoleLineFarOutMovesPastIt) {
  // Far out (t ~ 1e12 quarter periods) 1e-4 of a quarter period is below an ulp of t: the clearance's floor (a few
  // ulps) keeps an edge placed exactly on a line, or an ulp from it, off that line.
  Eigen::VectorXd f(2);
  f << 1.0, std::sqrt(2.0);
  const double p = (1e12 + 0.5) * std::numbers::pi;  // a pole line of frequency 1
  for (const double edge : {p, std::nextafter(p, 0.0), std::nextafter(p, 1e300)}) {
    const search::AxisPlan up = search::plan_axis(f, p - 10.0, edge, true, 1e-6, 1e8);
    const search::AxisPlan down = search::plan_axis(f, edge, p + 10.0, true, 1e-6, 1e8);
    for (const double e : {up.bp.back(), down.bp.front()}) {
      const std::vector<double> near = tangent_poles(f, e - 1.0, e + 1.0);
      for (double q : near) EXPECT_GT(std::abs(e - q), 4.0 * std::numeric_limits<double>::epsilon() * q) << edge;
    }
    EXPECT_GT(up.bp.back(), p);
    EXPECT_LT(down.bp.front(), p);
  }
}

TEST(WindowPlan, PlanStartsWherePlannedWindowSaysForEveryKindOfLowerEnd) {
  // Review (issue 11): plan_window held its own copy of planned_window's lower-end rules (automatic ends, the axis
  // band), and its options kept the automatic end where the plan started at half the band. Now derived from it: the
  // plan starts at planned_window's ends, the caller's own lower end widened by a hair like an upper end.
  const ModalForm md(two_dof(1.0, 1.0, 1.0, 1.0, 1.0));
  const auto [band1, band2] = axis_band(md);
  for (const double lo : {0.0, 0.1 * band1, 10.0 * band1}) {  // from the axis, inside the band, the caller's own
    SolveOptions o;
    o.t1_max = o.t2_max = 3.0;
    o.t1_min = o.t2_min = lo;
    const SolveOptions planned = search::planned_window(md, o);
    const search::WindowPlan plan = search::plan_window(md, o);
    EXPECT_EQ(plan.options.t1_min, planned.t1_min) << lo;
    EXPECT_EQ(plan.options.t2_min, planned.t2_min) << lo;
    EXPECT_EQ(plan.axis1, lo == 0.0);
    if (lo > band1) {
      EXPECT_LT(plan.t1.bp.front(), lo);
      EXPECT_LT(plan.t2.bp.front(), lo);
    } else {
      EXPECT_EQ(plan.t1.bp.front(), std::max(0.5 * band1, planned.t1_min)) << lo;
      EXPECT_EQ(plan.t2.bp.front(), std::max(0.5 * band2, planned.t2_min)) << lo;
    }
  }
}
