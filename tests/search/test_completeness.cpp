// Completeness: on small random systems, every potential SPP that a brute-force search built only on the
// paper's own 2n x 2n form finds is found by spp::solve, and every root spp::solve finds beyond it satisfies
// the paper's equations. The brute force looks, on a fine grid, for cells where
// det R2 and two adjugate conditions v . c_i (paper fig. 4) all change sign, then refines by 2-D Newton on
// (det R2, v . c_1) and keeps points where v . c_2 vanishes too.
#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "paper_reference.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"

using namespace spp;

namespace {

struct Pt {
  double t1, t2;
};

std::vector<Pt> brute_force(const ref::PaperForm& pf, double lo1, double hi1, double lo2, double hi2, int N) {
  std::vector<Eigen::Vector3d> F((N + 1) * (N + 1));
  auto at = [&](int i, int j) -> Eigen::Vector3d& { return F[static_cast<size_t>(i * (N + 1) + j)]; };
  const double h1 = (hi1 - lo1) / N, h2 = (hi2 - lo2) / N;
  for (int i = 0; i <= N; ++i)
    for (int j = 0; j <= N; ++j) at(i, j) = pf.det_and_conditions(lo1 + i * h1, lo2 + j * h2);
  std::vector<Pt> roots;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      bool all = true;
      for (int c = 0; c < 3 && all; ++c) {
        const double v[4] = {at(i, j)(c), at(i + 1, j)(c), at(i, j + 1)(c), at(i + 1, j + 1)(c)};
        const bool pos = std::any_of(v, v + 4, [](double x) { return x > 0; });
        const bool neg = std::any_of(v, v + 4, [](double x) { return x < 0; });
        all = pos && neg;
      }
      if (!all) continue;
      // Newton on (det, c1), scaled by their magnitudes on the cell
      double x = lo1 + (i + 0.5) * h1, y = lo2 + (j + 0.5) * h2;
      const double s0 = std::max(std::abs(at(i, j)(0)), std::abs(at(i + 1, j + 1)(0)));
      const double s1 = std::max(std::abs(at(i, j)(1)), std::abs(at(i + 1, j + 1)(1)));
      const double s2 = std::max(std::abs(at(i, j)(2)), std::abs(at(i + 1, j + 1)(2)));
      bool ok = false;
      for (int it = 0; it < 40; ++it) {
        const Eigen::Vector3d f = pf.det_and_conditions(x, y);
        const double e = 1e-7 * (h1 + h2);
        const Eigen::Vector3d fx = (pf.det_and_conditions(x + e, y) - pf.det_and_conditions(x - e, y)) / (2 * e);
        const Eigen::Vector3d fy = (pf.det_and_conditions(x, y + e) - pf.det_and_conditions(x, y - e)) / (2 * e);
        Eigen::Matrix2d J;
        J << fx(0) / s0, fy(0) / s0, fx(1) / s1, fy(1) / s1;
        const Eigen::Vector2d d = J.fullPivLu().solve(-Eigen::Vector2d(f(0) / s0, f(1) / s1));
        x += d(0);
        y += d(1);
        if (d.norm() < 1e-13 * (x + y)) {
          const Eigen::Vector3d g = pf.det_and_conditions(x, y);
          ok = std::abs(g(2)) < 1e-6 * s2;
          break;
        }
      }
      if (!ok || std::abs(x - (lo1 + (i + 0.5) * h1)) > 3 * h1 || std::abs(y - (lo2 + (j + 0.5) * h2)) > 3 * h2)
        continue;
      bool dup = false;
      for (const Pt& p : roots) dup |= std::hypot(p.t1 - x, p.t2 - y) < 1e-7 * (hi1 + hi2);
      if (!dup) roots.push_back({x, y});
    }
  return roots;
}

void compare(const System& s, double T1, double T2, int N) {
  SolveOptions o;
  o.t1_max = T1;
  o.t2_max = T2;
  o.compute_return_error = false;
  const SolveResult r = solve(s, o);
  EXPECT_EQ(r.status, SolveStatus::Success) << r.brief_report();
  // compare inside a band away from the window edges and the axes (t1, t2 -> 0 are limits)
  const double lo1 = 0.02 * T1, hi1 = 0.98 * T1, lo2 = 0.02 * T2, hi2 = 0.98 * T2;
  const std::vector<Pt> bf = brute_force(ref::PaperForm(s), lo1, hi1, lo2, hi2, N);
  std::vector<Pt> sv;
  for (const Solution& x : r.solutions)
    if (x.t1() > lo1 && x.t1() < hi1 && x.t2() > lo2 && x.t2() < hi2) sv.push_back({x.t1(), x.t2()});
  const double tol = 1e-6 * (T1 + T2);
  for (const Pt& p : bf) {
    const bool found =
        std::any_of(sv.begin(), sv.end(), [&](const Pt& q) { return std::hypot(p.t1 - q.t1, p.t2 - q.t2) < tol; });
    EXPECT_TRUE(found) << "brute force root (" << p.t1 << ", " << p.t2 << ") missing from spp::solve";
  }
  // A root of spp's that the grid missed must satisfy the paper's own equations (then the grid was too
  // coarse for it: two roots in one cell, or Newton leaving the cell); otherwise it is a false root.
  const ref::PaperForm pf(s);
  int grid_missed = 0;
  for (const Pt& p : sv) {
    const bool found =
        std::any_of(bf.begin(), bf.end(), [&](const Pt& q) { return std::hypot(p.t1 - q.t1, p.t2 - q.t2) < tol; });
    if (found) continue;
    ++grid_missed;
    const auto [sv_rel, cond] = pf.residuals(p.t1, p.t2);
    EXPECT_LT(sv_rel, 1e-10) << "spp::solve root (" << p.t1 << ", " << p.t2 << ") fails det R2 = 0";
    EXPECT_LT(cond, 1e-9) << "spp::solve root (" << p.t1 << ", " << p.t2 << ") fails eq. (5.1b)";
  }
  EXPECT_GT(sv.size(), 0u);
  std::cout << "n = " << s.n() << ": " << sv.size() << " roots by spp::solve, " << bf.size() << " by brute force ("
            << grid_missed << " missed by the grid, confirmed by the paper's equations)\n";
}

}  // namespace

class Completeness : public ::testing::TestWithParam<std::pair<int, unsigned>> {};

TEST_P(Completeness, SameRootsAsBruteForceOnRandomSystem) {
  const auto [n, seed] = GetParam();
  const System s = ref::random_system(n, seed, 1.0, 0.5, 6.0);  // K's spread wider than the default
  const ModalForm md(s);
  // a few fundamental boxes in each direction (more for n = 2, which has few roots)
  const double boxes = n == 2 ? 5.0 : 2.0;
  const double T1 = boxes * std::numbers::pi / md.omega()(0), T2 = boxes * std::numbers::pi / md.d()(1);
  compare(s, T1, T2, 700);
}

INSTANTIATE_TEST_SUITE_P(RandomSystems, Completeness,
                         ::testing::Values(std::pair{2, 1u}, std::pair{2, 2u}, std::pair{3, 3u}, std::pair{3, 4u},
                                           std::pair{4, 5u}, std::pair{4, 6u}, std::pair{5, 7u}, std::pair{5, 8u},
                                           std::pair{6, 9u}, std::pair{6, 10u}));

TEST(Completeness, ChainBoxCountsMatchTheDesignNote) {
  // Shared design note §3b: fixed-free unit chain, contact on the last mass, box t1 <= pi/omega_1,
  // t2 <= pi/d_2: 1, 6, 14, 28, 51 potential SPPs for n = 2..6 (two independent codes agree).
  const int expected[] = {1, 6, 14, 28, 51};
  for (int n = 2; n <= 6; ++n) {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      K(i, i) = i + 1 < n ? 2.0 : 1.0;
      if (i > 0) K(i, i - 1) = K(i - 1, i) = -1.0;
    }
    Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
    w(n - 1) = -1.0;
    const System s(Eigen::MatrixXd::Identity(n, n), K, w, 1.0);
    const ModalForm md(s);
    SolveOptions o;
    o.t1_max = std::numbers::pi / md.omega()(0);
    o.t2_max = std::numbers::pi / md.d()(1);
    o.compute_return_error = false;
    const SolveResult r = solve(s, o);
    EXPECT_EQ(r.status, SolveStatus::Success);
    EXPECT_EQ(static_cast<int>(r.solutions.size()), expected[n - 2]) << "n = " << n;
  }
}
