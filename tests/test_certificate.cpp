// The proofs behind certified trace steps (issue: completeness you can trust, item 2): the onset inertia (an SPP
// makes H compressed to z^perp singular; Hc grows with t1 and t2 between pole lines) and the certified search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "search/evaluator.hpp"
#include "spp/io.hpp"
#include "spp/modal.hpp"
#include "spp/solver.hpp"

using namespace spp;

namespace {

System chain5() { return load_system(std::string(SPP_SOURCE_DIR) + "/examples/chain5.json"); }

// The pole-free interval of sorted poles holding x.
std::pair<double, double> interval(const std::vector<double>& poles, double x) {
  double lo = 0.0, hi = 1e300;
  for (double p : poles) {
    if (p <= x) lo = std::max(lo, p);
    if (p > x) hi = std::min(hi, p);
  }
  return {lo, hi};
}

}  // namespace

TEST(OnsetInertia, SingularAtAnSppAndCountsItsCrossing) {
  // Hc is singular at the paper's SPP: the count is uncertain there, and a small box around it has different counts
  // at its two Loewner corners.
  const ModalForm md(chain5());
  search::DenseEvaluator ev(md, Symmetry::Axial);
  const double t1 = 3.2160302, t2 = 0.52773599;
  const int lo = ev.onset_inertia(t1 - 1e-3, t2 - 1e-3), hi = ev.onset_inertia(t1 + 1e-3, t2 + 1e-3);
  ASSERT_GE(lo, 0);
  ASSERT_GE(hi, 0);
  EXPECT_GT(lo, hi);  // Hc grows: fewer negative eigenvalues at the upper corner
}

TEST(OnsetInertia, BoxesProvedFreeHoldNoSpp) {
  // Property: any box inside one cell whose two Loewner corners have equal certain counts holds none of the 64 SPPs
  // of (0, 12]^2, and boxes around each SPP are never proved free.
  const System s = chain5();
  const ModalForm md(s);
  SolveOptions o;
  o.t1_max = 12;
  o.t2_max = 12;
  const SolveResult ref = solve(s, o);
  ASSERT_EQ(ref.solutions.size(), 64u);
  const std::vector<double> p1 = md.flight_poles(0.0, 13.0), p2 = md.contact_poles(0.0, 13.0);
  search::DenseEvaluator ev(md, Symmetry::Axial);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int free_boxes = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double x = 0.05 + 11.9 * u(rng), y = 0.05 + 11.9 * u(rng);
    const auto [a1, b1] = interval(p1, x);
    const auto [a2, b2] = interval(p2, y);
    const double w = std::pow(10.0, -4.0 + 4.0 * u(rng));  // box sizes 1e-4 to 1
    const double lo1 = std::max(a1 + 1e-9, x - w * u(rng)), hi1 = std::min(b1 - 1e-9, x + w * u(rng));
    const double lo2 = std::max(a2 + 1e-9, y - w * u(rng)), hi2 = std::min(b2 - 1e-9, y + w * u(rng));
    const int lo = ev.onset_inertia(lo1, lo2);
    if (lo < 0 || lo != ev.onset_inertia(hi1, hi2)) continue;
    ++free_boxes;
    for (const Solution& r : ref.solutions)
      EXPECT_FALSE(r.t1 >= lo1 && r.t1 <= hi1 && r.t2 >= lo2 && r.t2 <= hi2)
          << "box [" << lo1 << ", " << hi1 << "] x [" << lo2 << ", " << hi2 << "] proved free holds SPP " << r.t1
          << ", " << r.t2;
  }
  EXPECT_GT(free_boxes, 1000);  // the check is not vacuous
  for (const Solution& r : ref.solutions) {
    const int lo = ev.onset_inertia(r.t1 - 1e-6, r.t2 - 1e-6);
    EXPECT_TRUE(lo < 0 || lo != ev.onset_inertia(r.t1 + 1e-6, r.t2 + 1e-6)) << r.t1 << ", " << r.t2;
  }
}

TEST(CertifiedSearch, ProvesTheWholeChainWindowWithTheSameRoots) {
  // certify_steps on the paper's chain window (0, 12]^2: every step outside the axis bands proved (zeroth-order
  // drift, curvature or onset inertia), status success, and the same 64 SPPs as the default trace.
  const System s = chain5();
  SolveOptions o;
  o.t1_max = 12;
  o.t2_max = 12;
  const SolveResult ref = solve(s, o);
  o.certify_steps = true;
  const SolveResult r = solve(s, o);
  EXPECT_EQ(r.status, SolveStatus::Success) << r.brief_report();
  EXPECT_GT(r.stats.certified_steps, 0);
  ASSERT_EQ(r.solutions.size(), ref.solutions.size());
  for (size_t i = 0; i < r.solutions.size(); ++i) {
    EXPECT_NEAR(r.solutions[i].t1, ref.solutions[i].t1, 1e-9);
    EXPECT_NEAR(r.solutions[i].t2, ref.solutions[i].t2, 1e-9);
  }
}
