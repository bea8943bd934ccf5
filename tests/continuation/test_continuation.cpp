// continue_branches(): branches agree with independent solve() runs, events are located where they happen,
// and the zero-gap SPPs of paper §6.1 come out where the two flight frequencies are in an odd ratio.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "continuation/corrector.hpp"
#include "paper_examples.hpp"
#include "spp/continuation/continuation.hpp"
#include "spp/modal/modal.hpp"
#include "spp/orbit/orbit.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/simulator.hpp"

using namespace spp;

namespace {
// Paper §6.1, eq. (6.1): M = I, K = [[1 + k2, -k2], [-k2, k2]], obstacle on the second mass, g = g0 - x2.
ParametricSystem paper_61(double g0, double lo, double hi) {
  Eigen::MatrixXd K0(2, 2), K1(2, 2);
  K0 << 1, 0, 0, 0;
  K1 << 1, -1, -1, 1;
  return ParametricSystem(Eigen::MatrixXd::Identity(2, 2), {}, K0, K1, Eigen::Vector2d(0, -1), {}, g0, {"k2", lo, hi},
                          "paper 6.1");
}
using spp::test::paper_chain_k5;  // §5.2's chain, k5 in [lo, hi] (tests/paper_examples.hpp)
}  // namespace

// The two roots of ω2/ω1 = r (r odd) for eq. (6.1): ω^2 = ((1 + 2k) ± sqrt(1 + 4k^2)) / 2, so with
// q = (r^2 - 1) / (r^2 + 1): (1 + 4k^2) = q^2 (1 + 2k)^2, the larger root.
double k2_for_ratio(double r) {
  const double q = (r * r - 1) / (r * r + 1), a = 4 - 4 * q * q, b = -4 * q * q, c = 1 - q * q;
  return (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
}

TEST(Continuation, ZeroGapSppsOfSection61) {
  const ParametricSystem ps = paper_61(0.0, 1.0, 10.0);
  ContinueOptions o;
  o.t1_max = 3.0;
  o.t2_max = 1.0;
  const ContinuationResult r = continue_branches(ps, o);
  EXPECT_TRUE(r.warnings.empty()) << r.brief_report();
  const std::vector<BranchPoint> spps = gap_closures(r);
  ASSERT_EQ(spps.size(), 2u) << r.brief_report();
  const double ratios[] = {3.0, 5.0};
  for (int k = 0; k < 2; ++k) {
    const BranchPoint& p = spps[k];
    EXPECT_NEAR(p.mu, k2_for_ratio(ratios[k]), 1e-9);  // paper: k2 ≈ 5.716 for the ratio 5
    const ModalForm md(ps.at(p.mu));
    EXPECT_NEAR(md.omega()(1) / md.omega()(0), ratios[k], 1e-9);
    EXPECT_NEAR(p.t1, std::numbers::pi / (2 * md.omega()(0)), 1e-9);        // flight: half a slow period
    EXPECT_NEAR(p.t2, std::numbers::pi / (2 * std::sqrt(1 + p.mu)), 1e-9);  // contact: mass 1 half a period
    EXPECT_LT(p.x0.norm(), 1e-8);  // contact starts at the rest position, all velocity
    EXPECT_TRUE(p.admissible) << p.margin;
    EXPECT_NEAR(p.energy, 1.0, 1e-12);
    // Independent check: the event-driven simulator started there comes back after one period.
    SimulateOptions so;
    so.duration = p.period;
    const SimulationResult sim = simulate(ps.at(p.mu), p.x0, p.v0, so);
    ASSERT_FALSE(sim.samples.empty());
    const Sample& last = sim.samples.back();
    const double err = std::hypot((last.x - p.x0).norm(), (last.v - p.v0).norm()) / p.v0.norm();
    EXPECT_LT(err, 1e-8) << sim.brief_report();
    EXPECT_EQ(sim.impacts, 0) << sim.brief_report();
  }
  EXPECT_NEAR(spps[1].mu, 5.716, 5e-4);
}

TEST(Continuation, BranchesAgreeWithIndependentSolves) {
  const ParametricSystem ps = paper_61(1.0, 1.0, 10.0);
  ContinueOptions o;
  o.t1_max = 8.0;
  o.t2_max = 3.0;
  const ContinuationResult r = continue_branches(ps, o);
  ASSERT_GT(r.branches.size(), 10u);
  EXPECT_EQ(r.seed_crossings, r.seed_spps);
  EXPECT_EQ(r.status, ContinuationStatus::Success) << r.brief_report();
  EXPECT_EQ(r.incomplete_seed_solves + r.stalled_branches + r.unlisted_crossings, 0) << r.brief_report();
  int checked = 0;
  for (double mu : {2.3, 4.9, 7.7}) {  // not seed values
    SolveOptions so;
    so.t1_max = o.t1_max;
    so.t2_max = o.t2_max;
    const System sys = ps.at(mu);
    const SolveResult sr = solve(sys, so);
    for (const Solution& sol : sr.solutions) {
      // The branch segment that crosses mu, interpolated, then polished at fixed mu: the same SPP.
      double best = 1e300;
      Eigen::Vector2d guess;
      for (const Branch& b : r.branches)
        for (size_t i = 1; i < b.points.size(); ++i) {
          const BranchPoint &p = b.points[i - 1], &q = b.points[i];
          if ((p.mu - mu) * (q.mu - mu) > 0 || p.mu == q.mu) continue;
          const double s = (mu - p.mu) / (q.mu - p.mu);
          const Eigen::Vector2d x(p.t1 + s * (q.t1 - p.t1), p.t2 + s * (q.t2 - p.t2));
          const double d = std::hypot(x(0) - sol.t1(), x(1) - sol.t2());
          if (d < best) best = d, guess = x;
        }
      ASSERT_LT(best, 1e-2) << "mu " << mu << ": SPP (" << sol.t1() << ", " << sol.t2() << ") on no branch";
      const SolutionAt at = solution_at(sys, guess(0), guess(1));
      ASSERT_TRUE(at.found) << at.brief_report();
      const Solution& again = at.solution;
      EXPECT_NEAR(again.t1(), sol.t1(), 1e-9);
      EXPECT_NEAR(again.t2(), sol.t2(), 1e-9);
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

TEST(Continuation, AdmissibilityBoundariesAreLocated) {
  // The §5.2 chain with the last spring's stiffness k5 as the parameter.
  const ParametricSystem ps = paper_chain_k5(0.6, 0.9);
  ContinueOptions o;
  o.t1_max = 8.0;
  o.t2_max = 3.0;
  const ContinuationResult r = continue_branches(ps, o);
  int located = 0;
  for (const Branch& b : r.branches)
    for (const BranchEvent& e : b.events) {
      if (e.kind != BranchEventKind::AdmissibilityLost && e.kind != BranchEventKind::AdmissibilityGained) continue;
      if (e.at.t2 < 1e-2) continue;  // next to the t2 -> 0 axis
      EXPECT_LT(std::abs(e.at.margin), 1e-8) << e.at.mu;
      // Independent Newton at fixed parameter 1e-8 on each side: the margin changes sign across the event.
      auto margin_at = [&](double mu) {
        const System sys = ps.at(mu);
        const SolutionAt s = solution_at(sys, e.at.t1, e.at.t2);
        EXPECT_TRUE(s.found) << s.brief_report();
        return s.found ? admissibility_margin(ModalForm(sys), s.solution.orbit) : 0.0;
      };
      const double below = margin_at(e.at.mu - 1e-8), above = margin_at(e.at.mu + 1e-8);
      EXPECT_LT(below * above, 0.0) << "k5 = " << e.at.mu << ": " << below << " " << above;
      ++located;
    }
  EXPECT_GE(located, 2) << r.brief_report();
}

TEST(Continuation, FixedObstaclePointSymmetricPotentialSppsOfSection62) {
  // Point symmetry (det T2 = 0) on the §6.1 system with g0 = 0: a fixed obstacle needs zero normal velocity at
  // onset, one more equation, so isolated parameter values. For this system x(0) = 0 and the flight takes
  // (0, v) back to (0, v): omega_k t1 multiples of pi, so omega2 / omega1 is an integer here (one slow
  // half-period of flight), and the contact phase a whole half-oscillation of mass 1 (d1 t2 = pi).
  const ParametricSystem ps = paper_61(0.0, 1.0, 10.0);
  ContinueOptions o;
  o.t1_max = 5.0;
  o.t2_max = 1.5;
  o.symmetry = Symmetry::Point;
  const ContinuationResult r = continue_branches(ps, o);
  EXPECT_TRUE(r.warnings.empty()) << r.brief_report();
  const std::vector<BranchPoint> spps = gap_closures(r);
  ASSERT_EQ(spps.size(), 3u) << r.brief_report();
  const double ratios[] = {4.0, 5.0, 6.0};
  for (int k = 0; k < 3; ++k) {
    const BranchPoint& p = spps[k];
    EXPECT_NEAR(p.mu, k2_for_ratio(ratios[k]), 1e-9);
    const ModalForm md(ps.at(p.mu));
    EXPECT_NEAR(md.omega()(1) / md.omega()(0), ratios[k], 1e-9);
    EXPECT_NEAR(p.t1, std::numbers::pi / md.omega()(0), 1e-9);
    EXPECT_NEAR(p.t2, std::numbers::pi / std::sqrt(1 + p.mu), 1e-9);
    EXPECT_LT(p.x0.norm(), 1e-8);
    EXPECT_FALSE(p.admissible);
  }
}

TEST(Continuation, BranchesCutShortMakeTheResultIncompleteWithTheirCount) {
  const ParametricSystem ps = paper_61(1.0, 1.0, 10.0);
  ContinueOptions o;
  o.t1_max = 8.0;
  o.t2_max = 3.0;
  o.max_points = 10;  // the smallest allowed: branches stop after 10 points
  const ContinuationResult r = continue_branches(ps, o);
  ASSERT_FALSE(r.branches.empty());
  EXPECT_EQ(r.status, ContinuationStatus::Incomplete);
  long stalled = 0;
  for (const Branch& b : r.branches)
    for (const BranchEvent& e : b.events) stalled += e.kind == BranchEventKind::Stalled;
  EXPECT_GT(stalled, 0);
  EXPECT_EQ(r.stalled_branches, stalled);
  EXPECT_NE(r.brief_report().find("incomplete"), std::string::npos) << r.brief_report();
}

// The generic corrector on a curve known in closed form: the ellipse y0^2 + y1^2 = 1, y2 = y0 (F: R^3 -> R^2).
TEST(Corrector, NewtonLandsOnTheCurveInThePredictorsHyperplane) {
  auto linearize = [](const Eigen::VectorXd& y, Eigen::VectorXd& F, Eigen::MatrixXd& J) {
    F = Eigen::Vector2d(y(0) * y(0) + y(1) * y(1) - 1.0, y(2) - y(0));
    J.resize(2, 3);
    J << 2 * y(0), 2 * y(1), 0, -1, 0, 1;
  };
  const double a = 0.7;  // the curve point (cos a, sin a, cos a) and its tangent (-sin a, cos a, -sin a) / |.|
  const Eigen::Vector3d on(std::cos(a), std::sin(a), std::cos(a));
  const Eigen::Vector3d tau = Eigen::Vector3d(-std::sin(a), std::cos(a), -std::sin(a)).normalized();
  const Eigen::VectorXd pred = on + 0.05 * tau;
  Eigen::VectorXd y;
  const continuation::CorrectorResult r = continuation::correct_pseudo_arclength(linearize, pred, tau, y);
  ASSERT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 6);  // quadratic convergence with the exact Jacobian
  Eigen::VectorXd F;
  Eigen::MatrixXd J;
  linearize(y, F, J);
  EXPECT_LT(F.norm(), 1e-14);
  EXPECT_LT(std::abs(tau.dot(y - pred)), 1e-14);
  // The tangent there: the kernel of J, oriented along tau.
  const Eigen::VectorXd t = continuation::curve_tangent(J, tau);
  EXPECT_NEAR(t.norm(), 1.0, 1e-14);
  EXPECT_LT((J * t).norm(), 1e-14);
  EXPECT_GT(t.dot(tau), 0.9);
  EXPECT_LT(continuation::curve_tangent(J, -tau).dot(tau), -0.9);
}

TEST(Corrector, NoCurveInReachIsNotConverged) {
  // y0^2 + y1^2 = -1 has no real point: the Newton steps do not settle (or leave the branch), never "converged".
  auto linearize = [](const Eigen::VectorXd& y, Eigen::VectorXd& F, Eigen::MatrixXd& J) {
    F = Eigen::Vector2d(y(0) * y(0) + y(1) * y(1) + 1.0, y(2));
    J.resize(2, 3);
    J << 2 * y(0), 2 * y(1), 0, 0, 0, 1;
  };
  Eigen::VectorXd y;
  EXPECT_FALSE(continuation::correct_pseudo_arclength(linearize, Eigen::Vector3d(0.3, 0.2, 0.0),
                                                      Eigen::Vector3d(1.0, 0.0, 0.0), y)
                   .converged);
}

namespace {
// |rho - 1| at a located stability event: the bisection's bracket (locate_tol = 1e-13) times |d rho / ds| (< 10 on
// the chain's branches) plus rho's rounding (spectral_radius_error, ~1e-12); measured at most 2.6e-13 over the 39
// events of the chain with k5 in [0.9, 1] in (0, 12]^2 (README). The 1e-7 used before would let through an event
// 6e-8 from the crossing, as issue 14's last session reported one.
constexpr double kAtTheCrossing = 1e-11;
}  // namespace

TEST(Continuation, StabilityChangesAreLocated) {
  // The §5.2 chain with k5 as the parameter: between k5 = 0.9 and 1 the SPP near (t1, t2) = (5.7, 2.5) goes from
  // spectral radius 1.0038 to 0.9858 (independent solves); the branch must carry the event, with the radius 1 there
  // and on either side of 1 at k5 -+ 1e-6 (independent Newton and floquet()).
  const ParametricSystem ps = paper_chain_k5(0.9, 1.0);
  ContinueOptions o;
  o.t1_max = 8.0;
  o.t2_max = 3.0;
  o.seeds = 3;
  const ContinuationResult r = continue_branches(ps, o);
  int located = 0;
  for (const Branch& b : r.branches)
    for (const BranchEvent& e : b.events) {
      if (e.kind != BranchEventKind::StabilityLost && e.kind != BranchEventKind::StabilityGained) continue;
      EXPECT_NEAR(e.at.spectral_radius, 1.0, kAtTheCrossing) << e.at.mu;
      auto radius_at = [&](double mu) {
        const System sys = ps.at(mu);
        const SolutionAt s = solution_at(sys, e.at.t1, e.at.t2);
        EXPECT_TRUE(s.found) << s.brief_report();
        return s.found ? floquet(ModalForm(sys), s.solution.orbit).spectral_radius : 1.0;
      };
      const double below = radius_at(e.at.mu - 1e-6), above = radius_at(e.at.mu + 1e-6);
      EXPECT_LT((below - 1.0) * (above - 1.0), 0.0) << "k5 = " << e.at.mu << ": " << below << " " << above;
      ++located;
    }
  EXPECT_GE(located, 1) << r.brief_report();
}

// Found by the attack of issue 14: on the chain with k5 in [0.9, 1] and the window (0, 12]^2, a branch with
// dt1/dk5 ~ 230 reported stability_lost at k5 = 0.9423784260, (t1, t2) = (10.283443820, 4.518563173): an uncorrected
// predictor (the corrector failed there and the bisection kept the tangent's point), 6.6e-4 from the SPP in t1; the
// crossing is near k5 = 0.9423811. Each event's point must be the SPP there (independent Newton from it) and
// bracket the crossing.
TEST(Continuation, StabilityEventOnASteepBranchIsOnTheBranch) {
  const ParametricSystem ps = paper_chain_k5(0.9, 1.0);
  ContinueOptions o;
  o.t1_max = 12.0;
  o.t2_max = 12.0;
  const ContinuationResult r = continue_branches(ps, o);
  int steep = 0;
  for (const Branch& b : r.branches)
    for (const BranchEvent& e : b.events) {
      if (e.kind != BranchEventKind::StabilityLost && e.kind != BranchEventKind::StabilityGained) continue;
      const System sys = ps.at(e.at.mu);
      const SolutionAt s = solution_at(sys, e.at.t1, e.at.t2);
      ASSERT_TRUE(s.found) << s.brief_report();
      EXPECT_NEAR(s.solution.t1(), e.at.t1, 1e-9 * e.at.t1) << "k5 = " << e.at.mu;
      EXPECT_NEAR(s.solution.t2(), e.at.t2, 1e-9 * e.at.t2) << "k5 = " << e.at.mu;
      EXPECT_NEAR(e.at.spectral_radius, 1.0, kAtTheCrossing) << e.at.mu;
      if (std::abs(e.at.t1 - 10.2828) < 1e-2 && std::abs(e.at.mu - 0.942381) < 1e-5) ++steep;
    }
  EXPECT_EQ(steep, 1) << r.brief_report();
}

// Found by issue 14's last session: on the chain with k5 in [0.9, 1] and the window (0, 12]^2 one branch was traced as
// two (from the seeds at k5 = 0.95 and 1), each piece ending "stalled" on its side of k5 = 0.99604 ... 0.99631: the
// corrector demanded a Newton step below 1e-14 where F's rounding over an ill-conditioned J kept steps jittering above
// it, even from predictors 1e-9 away; the stability_lost between the pieces (k5 = 0.99616) was lost. Now: no stalled
// end, that branch whole from the window's edge (k5 = 0.94847) to k5 = 1 with the event, no two branches sharing a
// point, and every seed SPP on exactly one branch.
TEST(Continuation, BranchIsNotTracedTwiceInTwoStalledPieces) {
  const ParametricSystem ps = paper_chain_k5(0.9, 1.0);
  ContinueOptions o;
  o.t1_max = 12.0;
  o.t2_max = 12.0;
  const ContinuationResult r = continue_branches(ps, o);
  EXPECT_EQ(r.stalled_branches, 0) << r.brief_report();
  EXPECT_EQ(r.status, ContinuationStatus::Success) << r.brief_report();
  // scaled coordinates, as the tracer's
  auto scaled = [&](const BranchPoint& p) { return Eigen::Vector3d(p.t1 / 12.0, p.t2 / 12.0, (p.mu - 0.9) / 0.1); };
  int whole = 0;
  for (const Branch& b : r.branches) {
    const BranchPoint &first = b.points.front(), &last = b.points.back();
    const bool from_edge = std::abs(first.mu - 0.948466) < 1e-5 && std::abs(first.t2 - 12.0) < 1e-9;
    if (!from_edge) continue;
    EXPECT_NEAR(last.mu, 1.0, 1e-12);
    EXPECT_NEAR(last.t1, 10.4754, 1e-3);
    EXPECT_NEAR(last.t2, 10.9013, 1e-3);
    const bool lost = std::any_of(b.events.begin(), b.events.end(), [](const BranchEvent& e) {
      return e.kind == BranchEventKind::StabilityLost && std::abs(e.at.mu - 0.99616) < 1e-5;
    });
    EXPECT_TRUE(lost);
    ++whole;
  }
  EXPECT_EQ(whole, 1) << r.brief_report();
  // No two branches share a point: every point of one is farther than 1e-6 (scaled) from every point of another.
  constexpr double kSame = 1e-6;
  for (size_t i = 0; i < r.branches.size(); ++i)
    for (size_t j = i + 1; j < r.branches.size(); ++j) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const BranchPoint& p : r.branches[i].points)
        for (const BranchPoint& q : r.branches[j].points) nearest = std::min(nearest, (scaled(p) - scaled(q)).norm());
      EXPECT_GT(nearest, kSame) << "branches " << i << " and " << j;
    }
  // Every seed SPP is on exactly one branch: at its seed value, one branch passes within 1e-4 of it (scaled; points
  // interpolated linearly across the seed value, steps <= 0.02), and distinct SPPs there are farther apart.
  SolveOptions so;
  so.t1_min = r.t1_min;
  so.t2_min = r.t2_min;
  so.t1_max = 12.0;
  so.t2_max = 12.0;
  so.compute_return_error = false;
  for (int k = 0; k < o.seeds; ++k) {
    const double mu = 0.9 + 0.1 * k / (o.seeds - 1);
    for (const Solution& sol : solve(ps.at(mu), so).solutions) {
      const Eigen::Vector2d at(sol.t1() / 12.0, sol.t2() / 12.0);
      int on = 0;
      for (const Branch& b : r.branches) {
        bool passes = false;
        for (size_t i = 0; i + 1 < b.points.size() && !passes; ++i) {
          const BranchPoint &p = b.points[i], &q = b.points[i + 1];
          if ((p.mu - mu) * (q.mu - mu) > 0.0 || p.mu == q.mu) continue;
          const double t = (mu - p.mu) / (q.mu - p.mu);
          const Eigen::Vector3d y = scaled(p) + t * (scaled(q) - scaled(p));
          passes = (y.head<2>() - at).norm() < 1e-4;
        }
        on += passes;
      }
      EXPECT_EQ(on, 1) << "k5 = " << mu << ", (t1, t2) = (" << sol.t1() << ", " << sol.t2() << ")";
    }
  }
}

namespace {
// The multipliers outside the unit circle at the SPP near (t1, t2) of ps.at(mu) (independent Newton and floquet();
// the structural 1s are exactly 1 there and never outside).
std::vector<std::complex<double>> outside_circle(const ParametricSystem& ps, double mu, double t1, double t2) {
  const System sys = ps.at(mu);
  const SolutionAt s = solution_at(sys, t1, t2);
  EXPECT_TRUE(s.found) << s.brief_report();
  std::vector<std::complex<double>> out;
  if (s.found)
    for (const auto& z : floquet(ModalForm(sys), s.solution.orbit).multipliers)
      if (std::abs(z) > 1.0) out.push_back(z);
  return out;
}

// Which multiplier crosses at a stability event, found without the event's classification: the multipliers
// outside the circle 1e-6 before and after it in mu (none on the stable side; one real, or a conjugate pair, on the
// other). Returns the kind found, and checks the event's multipliers and angle against it.
MultiplierCrossing expect_crossing_as_the_multipliers_show(const ParametricSystem& ps, const BranchEvent& e) {
  const auto below = outside_circle(ps, e.at.mu - 1e-6, e.at.t1, e.at.t2);
  const auto above = outside_circle(ps, e.at.mu + 1e-6, e.at.t1, e.at.t2);
  EXPECT_NE(below.empty(), above.empty()) << "k = " << e.at.mu << ": " << below.size() << " / " << above.size();
  const auto& out = below.empty() ? above : below;
  if (out.empty() || out.size() > 2) {
    ADD_FAILURE() << "k = " << e.at.mu << ": " << out.size() << " multipliers outside";
    return MultiplierCrossing::None;
  }
  MultiplierCrossing kind = MultiplierCrossing::ComplexPair;
  if (out.size() == 1) {
    EXPECT_EQ(out[0].imag(), 0.0);
    kind = out[0].real() > 0.0 ? MultiplierCrossing::PlusOne : MultiplierCrossing::MinusOne;
  } else {
    EXPECT_EQ(out[0], std::conj(out[1]));
  }
  EXPECT_EQ(e.crossing, kind) << "k = " << e.at.mu << ": " << e.detail;
  EXPECT_NEAR(e.crossing_angle, std::abs(std::arg(out[0])), 1e-4) << e.detail;
  EXPECT_EQ(e.crossing_multipliers.size(), out.size()) << e.detail;
  for (const auto& z : e.crossing_multipliers) EXPECT_NEAR(std::abs(z), 1.0, 1e-6) << e.detail;
  EXPECT_NE(e.detail.find(kind == MultiplierCrossing::PlusOne    ? "through +1"
                          : kind == MultiplierCrossing::MinusOne ? "through -1 (period doubling"
                                                                 : "complex pair exp(+-i theta)"),
            std::string::npos)
      << e.detail;
  return kind;
}
}  // namespace

// A stability event says which multiplier crosses, checked against the multipliers on either side (independent
// solves). The chain with k5 as parameter has all three kinds (found by a search over k1, k4, k5, m5 in [0.5, 2]):
// its admissible SPP near (5.707, 2.510) gains stability through +1 at k5 = 0.983578 (a real multiplier, 1.0038 at
// k5 = 0.9); the (inadmissible) branch near (2.437, 3.328) through a complex pair at k5 = 0.997211, theta = 3.101;
// and the one near (2.416, 0.893) through -1 at k5 = 0.753447.
TEST(Continuation, StabilityEventsNameTheMultiplierThatCrosses) {
  struct Case {
    double lo, hi, mu, t1, t2;
    MultiplierCrossing expected;
  };
  const Case cases[] = {{0.9, 1.0, 0.9836, 5.70695, 2.50976, MultiplierCrossing::PlusOne},
                        {0.9, 1.0, 0.9972, 2.437039, 3.327548, MultiplierCrossing::ComplexPair},
                        {0.7, 0.8, 0.7534, 2.416482, 0.893344, MultiplierCrossing::MinusOne}};
  for (const Case& c : cases) {
    const ParametricSystem ps = paper_chain_k5(c.lo, c.hi);
    const SolutionAt seed = solution_at(ps.at(c.mu), c.t1, c.t2);
    ASSERT_TRUE(seed.found) << seed.brief_report();
    ContinueOptions o;
    o.t1_max = 8.0;
    o.t2_max = 4.0;
    const ContinuationResult r = continue_branch(ps, c.mu, seed.solution, o);
    int seen = 0;
    for (const BranchEvent& e : r.branches.at(0).events) {
      const bool stability = e.kind == BranchEventKind::StabilityLost || e.kind == BranchEventKind::StabilityGained;
      EXPECT_EQ(stability, e.crossing != MultiplierCrossing::None) << to_string(e.kind);
      if (!stability) continue;
      seen += expect_crossing_as_the_multipliers_show(ps, e) == c.expected;
    }
    EXPECT_GE(seen, 1) << "expected a " << to_string(c.expected) << " crossing on " << r.brief_report();
  }
}

// K(k2) of eq. (6.1) is positive definite only for k2 > 0: with the range starting just above 0 and long steps, the
// corrector, the tangent's differences and the range-end bisection try parameter values with no valid system. That
// is an outcome of the step (it fails and is shortened), not an error of the run (Tracer::try_at).
TEST(Continuation, TrialValuesBeyondTheRangeWithNoValidSystemFailTheStepNotTheRun) {
  const ParametricSystem ps = paper_61(1.0, 1e-3, 2.0);
  EXPECT_THROW(ps.at(-0.5), std::invalid_argument);
  ContinueOptions o;
  o.t1_max = 8.0;
  o.t2_max = 3.0;
  o.max_step = 0.5;  // half the scaled range per step: trial points land far below k2 = 0
  ContinuationResult r;
  ASSERT_NO_THROW(r = continue_branches(ps, o));
  ASSERT_FALSE(r.branches.empty());
  long range_ends_at_min = 0;
  for (const Branch& b : r.branches) {
    for (const BranchPoint& p : b.points) {
      EXPECT_GE(p.mu, 1e-3 * (1 - 1e-9));
      EXPECT_LE(p.mu, 2.0 * (1 + 1e-9));
    }
    for (const BranchEvent& e : b.events)
      range_ends_at_min += e.kind == BranchEventKind::RangeEnd && std::abs(e.at.mu - 1e-3) <= 1e-6;
  }
  EXPECT_GT(range_ends_at_min, 0);
}

// continue_branch: the branch through one SPP of solve() at a non-seed value is the branch continue_branches gives
// through the same point (same ends, same events), at the cost of that branch alone; a point that is no SPP there,
// or a mu outside the range, is refused.
TEST(Continuation, OneBranchFromOneSolutionIsTheBranchThroughIt) {
  const ParametricSystem ps = paper_61(1.0, 1.0, 10.0);
  ContinueOptions o;
  o.t1_max = 8.0;
  o.t2_max = 3.0;
  const ContinuationResult all = continue_branches(ps, o);
  const double mu = 4.9;
  SolveOptions so;
  so.t1_max = o.t1_max;
  so.t2_max = o.t2_max;
  const SolveResult sr = solve(ps.at(mu), so);
  ASSERT_GE(sr.solutions.size(), 3u);
  int compared = 0;
  for (size_t k = 0; k < sr.solutions.size(); k += 3) {
    const Solution& sol = sr.solutions[k];
    const ContinuationResult one = continue_branch(ps, mu, sol, o);
    ASSERT_EQ(one.branches.size(), 1u);
    EXPECT_EQ(one.status, ContinuationStatus::Success) << one.brief_report();
    EXPECT_LT(one.corrector_solves, all.corrector_solves);
    const Branch& b = one.branches.front();
    // it passes through the solution
    double nearest = 1e300;
    for (const BranchPoint& p : b.points)
      if (std::abs(p.mu - mu) <= 1e-12) nearest = std::min(nearest, std::hypot(p.t1 - sol.t1(), p.t2 - sol.t2()));
    EXPECT_LT(nearest, 1e-9);
    // the branch of continue_branches that holds a point within 1e-6 of both of its ends is the same branch
    const BranchPoint &first = b.points.front(), &last = b.points.back();
    auto near = [](const BranchPoint& p, const BranchPoint& q) {
      return std::abs(p.mu - q.mu) <= 1e-6 && std::hypot(p.t1 - q.t1, p.t2 - q.t2) <= 1e-6;
    };
    bool same = false;
    for (const Branch& c : all.branches) {
      const bool has_first = std::any_of(c.points.begin(), c.points.end(), [&](auto& p) { return near(p, first); });
      const bool has_last = std::any_of(c.points.begin(), c.points.end(), [&](auto& p) { return near(p, last); });
      same = same || (has_first && has_last && c.events.size() == b.events.size());
    }
    EXPECT_TRUE(same) << "branch from solution " << k << " ends at mu " << first.mu << " and " << last.mu;
    ++compared;
  }
  EXPECT_GE(compared, 1);
  // refused: no SPP there, mu outside the range
  Solution moved = sr.solutions.front();
  moved.orbit.t1 *= 1.3;
  EXPECT_THROW(continue_branch(ps, mu, moved, o), std::invalid_argument);
  EXPECT_THROW(continue_branch(ps, 11.0, sr.solutions.front(), o), std::invalid_argument);
}

// ContinueOptions::progress (Python's Ctrl-C, issue 13): called at each branch point and in the seed solves;
// returning false stops the continuation with the branches traced so far, Incomplete and interrupted.
TEST(Continuation, ProgressReturningFalseStopsWithTheBranchesTracedSoFar) {
  const ParametricSystem ps = paper_61(1.0, 1.0, 10.0);
  ContinueOptions o;
  o.t1_max = 8.0;
  o.t2_max = 3.0;
  const ContinuationResult full = continue_branches(ps, o);
  long calls = 0;
  o.progress = [&calls] { return ++calls < 50; };  // past the seed solves, into the branches
  const ContinuationResult r = continue_branches(ps, o);
  EXPECT_EQ(calls, 50);  // not called again once it said stop
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.status, ContinuationStatus::Incomplete);
  long points = 0, full_points = 0;
  for (const Branch& b : r.branches) points += static_cast<long>(b.points.size());
  for (const Branch& b : full.branches) full_points += static_cast<long>(b.points.size());
  EXPECT_LT(points, full_points);
  ASSERT_FALSE(r.branches.empty());
  EXPECT_EQ(r.branches.back().events.back().detail, "interrupted");
  EXPECT_FALSE(full.interrupted);
  o.progress = [] { return false; };  // at once: the first seed solve stops, nothing is traced
  const ContinuationResult none = continue_branches(ps, o);
  EXPECT_TRUE(none.interrupted && none.branches.empty() && none.unlisted_crossings == 0);
}
