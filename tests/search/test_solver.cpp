// The paper's examples (§5.2 chain, §5.3 rod with slip): every root is checked against the paper's own
// equations (eqs. 5.1a-b), independently of the modal form the solver uses; the orbits themselves in tests/orbit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <tuple>

#include "paper_examples.hpp"
#include "paper_reference.hpp"
#include "search/cell_trace.hpp"
#include "spp/core/generators.hpp"
#include "spp/io.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/modal/modal.hpp"
#include "spp/orbit/orbit.hpp"
#include "spp/search/solver.hpp"

using namespace spp;
using spp::test::chain5;
using spp::test::rod4;
using spp::test::solve_window;

namespace {

void check_paper_equations(const System& s, const SolveResult& r) {
  const ref::PaperForm pf(s);
  for (const Solution& sol : r.solutions) {
    const auto [sv, cond] = pf.residuals(sol.t1(), sol.t2());
    EXPECT_LT(sv, 1e-10) << "det R2 (eq. 5.1a) at t1 = " << sol.t1() << ", t2 = " << sol.t2();
    EXPECT_LT(cond, 1e-9) << "eq. (5.1b) at t1 = " << sol.t1() << ", t2 = " << sol.t2();
    EXPECT_LT(sol.residual, 1e-12);
  }
}

// The 5-dof chain's fundamental box, certified, one thread: success with its 28 SPPs (checked here).
SolveResult solve_chain5_box() {
  const System s = chain(5, {1.0}, {1.0}, 4, ContactSide::Upper, 1.0);
  SolveOptions o;
  std::tie(o.t1_max, o.t2_max) = fundamental_box(ModalForm(s));
  o.threads = 1;
  o.compute_return_error = false;
  SolveResult r = solve(s, o);
  EXPECT_EQ(r.status, SolveStatus::Success);
  EXPECT_EQ(r.solutions.size(), 28u);
  return r;
}

}  // namespace

TEST(PaperChain5, EveryRootSolvesThePapersOwnEquations) {
  const System s = chain5();
  check_paper_equations(s, solve_window(s, 12.0, 12.0));
}

TEST(PaperRod4, EveryRootSolvesThePapersOwnEquations) {
  const System s = rod4();
  check_paper_equations(s, solve_window(s, 12.0, 12.0));
}

TEST(Solver, RefusesZeroGapWithAPointerToTheParametricSolver) {
  const System s(Eigen::MatrixXd::Identity(2, 2), (Eigen::MatrixXd(2, 2) << 2, -1, -1, 1).finished(),
                 Eigen::Vector2d(0, -1), 0.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 5;
  try {
    solve(s, o);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("g0 = 0"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("parameter"), std::string::npos);
  }
}

TEST(Solver, OptionsAreValidatedWithTheirNames) {
  SolveOptions o;
  o.t1_max = 1.0;
  o.t2_max = -2.0;
  try {
    o.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("t2_max must be positive and finite, got -2"), std::string::npos);
  }
  o.t2_max = std::nan("");
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o.t2_max = 1.0;
  o.t1_min = 2.0;
  EXPECT_THROW(o.validate(), std::invalid_argument);
}

TEST(Solver, DecoupledModeDoesNotCreateSpuriousSolutions) {
  // Two identical chains side by side with contact on one: the other's modes never see the contact,
  // so the SPPs are those of the contacting chain alone.
  const System single = spp::chain(3, {1.0}, {1.0}, 2, ContactSide::Upper, 1.0);
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(6, 6), K = Eigen::MatrixXd::Zero(6, 6);
  K.topLeftCorner(3, 3) = single.K();
  K.bottomRightCorner(3, 3) = single.K() * 1.7;
  Eigen::VectorXd w = Eigen::VectorXd::Zero(6);
  w(2) = -1;
  const System both(M, K, w, 1.0);
  const SolveResult a = solve_window(single, 8.0, 8.0), b = solve_window(both, 8.0, 8.0);
  EXPECT_EQ(b.decoupled_modes, 3);
  ASSERT_EQ(a.solutions.size(), b.solutions.size());
  for (size_t i = 0; i < a.solutions.size(); ++i) {
    EXPECT_NEAR(a.solutions[i].t1(), b.solutions[i].t1(), 1e-10);
    EXPECT_NEAR(a.solutions[i].t2(), b.solutions[i].t2(), 1e-10);
    EXPECT_LT(b.solutions[i].orbit.x0.tail(3).norm(), 1e-12);
  }
}

TEST(Solver, SolutionAtRefinesToTheNearestRoot) {
  const System s = chain5();
  const SolveResult r = solve_window(s, 12.0, 12.0);
  ASSERT_FALSE(r.solutions.empty());
  const Solution& ref = r.solutions.front();
  const SolutionAt at = solution_at(s, ref.t1() * (1 + 1e-5), ref.t2() * (1 - 1e-5));
  ASSERT_TRUE(at.found) << at.brief_report();
  EXPECT_NEAR(at.solution.t1(), ref.t1(), 1e-12);
  EXPECT_NEAR(at.solution.t2(), ref.t2(), 1e-12);
  EXPECT_NE(at.brief_report().find("SPP at"), std::string::npos) << at.brief_report();
  EXPECT_THROW(solution_at(s, -1.0, 1.0), std::invalid_argument);  // the caller's mistake
  // invalid options are refused as solve refuses them (an attack found admissibility_tol = -1 taken, and the admissible
  // SPP reported "not admissible"); the window is not used, so the default one is never in the way
  for (const auto& set : std::vector<std::function<void(SolveOptions&)>>{
           [](SolveOptions& o) { o.admissibility_tol = -1.0; },
           [](SolveOptions& o) { o.admissibility_tol = std::nan(""); }, [](SolveOptions& o) { o.max_turn = -1.0; },
           [](SolveOptions& o) { o.min_step = std::nan(""); }, [](SolveOptions& o) { o.threads = -3; }}) {
    SolveOptions o;
    set(o);
    EXPECT_THROW(solution_at(s, ref.t1(), ref.t2(), o), std::invalid_argument);
  }
  SolveOptions far;
  far.t1_max = far.t2_max = 1.0;  // a window that does not hold the point: not solution_at's business
  EXPECT_TRUE(solution_at(s, ref.t1(), ref.t2(), far).found);
}

TEST(Solver, SolutionAtFarFromAnyRootIsAStatusNotAnException) {
  // Newton from a point with no root near it is a numerical outcome: not found, with where Newton went.
  const System s = chain5();
  const SolveResult r = solve_window(s, 12.0, 12.0);
  int not_found = 0;
  for (double t1 : {0.7, 1.9, 3.3, 5.1})
    for (double t2 : {0.4, 1.3, 2.9}) {
      const bool near_root = std::any_of(r.solutions.begin(), r.solutions.end(), [&](const Solution& x) {
        return std::hypot(x.t1() - t1, x.t2() - t2) < 0.05 * (t1 + t2);
      });
      SolutionAt at;
      ASSERT_NO_THROW(at = solution_at(s, t1, t2));
      if (!near_root) {
        EXPECT_FALSE(at.found) << at.brief_report();
      }
      if (!at.found) {
        ++not_found;
        EXPECT_NE(at.brief_report().find("no SPP near"), std::string::npos) << at.brief_report();
      }
    }
  EXPECT_GT(not_found, 0);
}

TEST(Solver, ResultDoesNotDependOnTheNumberOfThreads) {
  const System s = chain5();
  SolveOptions o;
  o.t1_max = o.t2_max = 12.0;
  o.compute_return_error = false;
  o.threads = 1;
  const SolveResult a = solve(s, o);
  o.threads = 2;
  const SolveResult b = solve(s, o);
  ASSERT_EQ(a.solutions.size(), b.solutions.size());
  for (size_t i = 0; i < a.solutions.size(); ++i) {
    EXPECT_EQ(a.solutions[i].t1(), b.solutions[i].t1());
    EXPECT_EQ(a.solutions[i].t2(), b.solutions[i].t2());
  }
  EXPECT_EQ(a.stats.evaluations, b.stats.evaluations);
  EXPECT_EQ(a.stats.strip_pairs, b.stats.strip_pairs);
}

TEST(Solver, CertifiedStepsStartTheirRootFromTheCurvesTangentAndBend) {
  // The certified trace's predictor for the next step's diagonal root is second order (the tangent -l2 / (l1 + l2) at
  // the step's start, the bend from the tangents of the last step), not the secant of the last step: the 5-dof chain's
  // fundamental box takes 59 593 evaluations instead of 65 659, for the same 28 SPPs and success.
  const SolveResult r = solve_chain5_box();
  EXPECT_LT(r.stats.evaluations, 62000);
}

TEST(Solver, CertifiedStepsGrowSlowlyAfterASpectralProofSoFewTriesAreRefused) {
  // After a step the spectral bounds proved, the next one is 1.05x longer, not 1.8x: the longer tries were refused
  // about every other time (each refusal a trace point and a full decomposition, no certified step). The 5-dof
  // chain's fundamental box took 59 593 evaluations, 10.1 per certified step; now 43 516, 7.2 per step, for the same
  // 28 SPPs and success.
  const SolveResult r = solve_chain5_box();
  EXPECT_LT(r.stats.evaluations, 50000);
  EXPECT_LT(static_cast<double>(r.stats.evaluations), 8.5 * static_cast<double>(r.stats.certified_steps));
}

TEST(Solver, CertifiedTriesOnWhichNoBoundHoldsShrinkFourfold) {
  // A try on which neither the Weyl gap nor the spectral bounds held (mostly the first tries of a piece, from its whole
  // span) is shrunk to a quarter, not halved: the 5-dof chain's fundamental box took 43 516 evaluations; now 38 844,
  // for the same 28 SPPs and success.
  const SolveResult r = solve_chain5_box();
  EXPECT_LT(r.stats.evaluations, 41000);
}

TEST(Solver, TraceTerminatesOnClusteredPoleLines) {
  // Regression: on the 100-dof chain near t = pi/4 the top frequencies give pole lines 1e-4 apart and nearly
  // equal eigenvalues; the last step to a curve's exit used to be rejected forever. Every root reported must
  // still solve the paper's equations.
  const System s = spp::chain(100, {1.0}, {1.0}, 99, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = 0.7950900808498774;  // 10 flight pole lines
  o.t2_max = 0.7951882510930521;  // 10 contact pole lines
  o.compute_return_error = false;
  // The midpoint trace (what this test is about). Certified, the window takes 77 s and leaves 14 corners between the
  // clustered pole lines with an eigenvalue within its error bound of zero (incomplete).
  o.certify_steps = false;
  const SolveResult r = solve(s, o);
  EXPECT_EQ(r.stats.unresolved_pieces, 0) << r.brief_report();
  EXPECT_EQ(r.stats.unpaired_crossings + r.stats.unpolished_roots + r.stats.uncertified_corners, 0);
  for (const Solution& sol : r.solutions) {
    if (sol.flags.empty()) {
      EXPECT_LT(sol.residual, 1e-10);
    }
  }
}

TEST(Solver, WindowEdgeJustPastAPoleLineLeavesNoSliver) {
  // Regression: a window edge 1e-9 (relative) past a pole line left a sliver rectangle where H is ~1e9 and
  // the trace produced false sign changes. The edge now moves past the pole line (never onto it; tolerances.hpp
  // kEdgePole): same roots as a window ending just before it, status success.
  const System s = chain5();
  const ModalForm md(s);
  const double p1 = md.flight_poles(0.0, 12.0).back(), p2 = md.contact_poles(0.0, 12.0).back();
  SolveOptions o;
  o.compute_return_error = false;
  o.t1_max = p1 * (1 + 1e-9);
  o.t2_max = p2 * (1 + 1e-9);
  const SolveResult a = solve(s, o);
  o.t1_max = p1 * (1 - 1e-5);
  o.t2_max = p2 * (1 - 1e-5);
  const SolveResult b = solve(s, o);
  EXPECT_EQ(a.status, SolveStatus::Success) << a.brief_report();
  ASSERT_EQ(a.solutions.size(), b.solutions.size());
  for (size_t i = 0; i < a.solutions.size(); ++i) EXPECT_NEAR(a.solutions[i].t1(), b.solutions[i].t1(), 1e-12);
}

TEST(Solver, NullVectorThatSwingsAwayAndBackWithinAStepKeepsItsRoots) {
  // Paper §6.1's 2-dof at k2 = 5.5, g0 = 1: on one curve piece (t1 between the flight poles 4.16 and 5.09) the
  // null vector turns by ~80 degrees and back, so the ends of a single step differ by 0.18 rad only; the trace
  // used to take that step and lose the SPP at (4.8788, 0.9535) and its pair. Found again by continuation.
  const System s = two_dof(1.0, 1.0, 1.0, 5.5, 1.0);
  SolveOptions o;
  o.t1_max = 8.0;
  o.t2_max = 2.0;
  const SolveResult r = solve(s, o);
  EXPECT_EQ(r.status, SolveStatus::Success) << r.brief_report();
  EXPECT_EQ(r.solutions.size(), 13u) << r.brief_report();
  int found = 0;
  for (const Solution& x : r.solutions)
    found += std::abs(x.t1() - 4.8788176) < 1e-6 && std::abs(x.t2() - 0.95352151) < 1e-6;
  EXPECT_EQ(found, 1);
}

TEST(Solver, PointSymmetricPotentialSppsOfSection62) {
  // det T2 = 0 (paper §6.2): x(-t1) = 0 and x(t2) = 0, the force odd about t2, never admissible, and with
  // g0 != 0 the obstacle moving at w^T v0 = g0 / t2 during contact. Checked with the physical flows (matrix
  // exponentials of K and K~, not the modal form) and against Newton started from a grid.
  const System s = load_system(std::string(SPP_SOURCE_DIR) + "/examples/chain5.json");
  const ModalForm md(s);
  SolveOptions o;
  o.t1_max = 6.0;
  o.t2_max = 6.0;
  o.symmetry = Symmetry::Point;
  const SolveResult r = solve(s, o);
  // every step proved (the bordered form of H_T makes its onset direction constant; 31 s and incomplete before it)
  EXPECT_EQ(r.status, SolveStatus::Success) << r.brief_report();
  EXPECT_EQ(r.stats.uncertified_steps, 0);
  ASSERT_GT(r.solutions.size(), 10u);
  for (const Solution& x : r.solutions) {
    EXPECT_FALSE(x.admissible());
    EXPECT_LT(x.return_error, 1e-9) << x.t1() << " " << x.t2();
    EXPECT_LT(x.orbit.c.norm(), 1e-9 * x.orbit.p0dot.norm());  // p(t2) = 0
    const OrbitState mid_flight = orbit_state(md, x.orbit, 2 * x.t2() + x.t1());
    EXPECT_LT(mid_flight.x.norm(), 1e-8 * x.orbit.v0.norm() * x.period());  // x(-t1) = 0
    const OrbitState mid_contact = orbit_state(md, x.orbit, x.t2());
    EXPECT_LT(mid_contact.x.norm(), 1e-8 * x.orbit.v0.norm() * x.period());  // x(t2) = 0
    // odd force about t2: lambda(t2 + s) = -lambda(t2 - s)
    const double f1 = orbit_state(md, x.orbit, 0.3 * x.t2()).force, f2 = orbit_state(md, x.orbit, 1.7 * x.t2()).force;
    EXPECT_NEAR(f1, -f2, 1e-8 * (std::abs(f1) + 1e-3));
    EXPECT_LT(x.min_force(), 0.0);
    EXPECT_TRUE(x.admissibility.certified);  // "not admissible" is structural, not read off the samples
    EXPECT_NEAR(x.orbit.obstacle_velocity, s.g0() / x.t2(), 1e-9 * s.g0() / x.t2());
  }
  // Brute force in the paper's style (its fig. 4 trick), independent of the search: on a 240 x 240 grid, cells
  // where det N_T and two adjugate conditions z^T W^-1 sin(W t1) adj(N_T) e_i all change sign, refined by Newton
  // on (det, condition 1); each root where condition 2 vanishes too must be in the list.
  const auto point = make_equations(md, Symmetry::Point);
  auto conditions = [&](double t1, double t2) {
    const Eigen::MatrixXd N = point->N(t1, t2);
    const int m = static_cast<int>(N.rows());
    Eigen::MatrixXd adj(m, m);
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < m; ++c) {
        Eigen::MatrixXd minor(m - 1, m - 1);
        for (int a = 0, ia = 0; a < m; ++a) {
          if (a == r) continue;
          for (int b = 0, ib = 0; b < m; ++b) {
            if (b == c) continue;
            minor(ia, ib++) = N(a, b);
          }
          ++ia;
        }
        adj(c, r) = ((r + c) % 2 ? -1.0 : 1.0) * minor.determinant();
      }
    const Eigen::VectorXd zs = point->onset_position(t1, md.z());  // z^T W^-1 sin(W t1) (diagonal)
    return Eigen::Vector3d(N.determinant(), zs.dot(adj.col(0)), zs.dot(adj.col(1)));
  };
  const int G = 240;
  const double h = 6.0 / G;
  std::vector<Eigen::Vector3d> F((G + 1) * (G + 1));
  for (int a = 0; a <= G; ++a)
    for (int b = 0; b <= G; ++b) F[a * (G + 1) + b] = conditions(a * h + 1e-9, b * h + 1e-9);
  std::vector<Eigen::Vector2d> brute;
  for (int a = 1; a < G; ++a)
    for (int b = 1; b < G; ++b) {
      bool all = true;
      for (int c = 0; c < 3 && all; ++c) {
        const double v[4] = {F[a * (G + 1) + b](c), F[(a + 1) * (G + 1) + b](c), F[a * (G + 1) + b + 1](c),
                             F[(a + 1) * (G + 1) + b + 1](c)};
        all = std::any_of(v, v + 4, [](double q) { return q > 0; }) &&
              std::any_of(v, v + 4, [](double q) { return q < 0; });
      }
      if (!all) continue;
      double x = (a + 0.5) * h, y = (b + 0.5) * h;
      bool ok = false;
      for (int it = 0; it < 40; ++it) {
        const Eigen::Vector3d f = conditions(x, y);
        const double e = 1e-7;
        const Eigen::Vector3d fx = (conditions(x + e, y) - conditions(x - e, y)) / (2 * e);
        const Eigen::Vector3d fy = (conditions(x, y + e) - conditions(x, y - e)) / (2 * e);
        Eigen::Matrix2d J;
        J << fx(0), fy(0), fx(1), fy(1);
        const Eigen::Vector2d d = J.fullPivLu().solve(-Eigen::Vector2d(f(0), f(1)));
        x += d(0);
        y += d(1);
        if (d.norm() < 1e-12 * (x + y)) {
          const Eigen::Vector3d g = conditions(x, y);
          ok = std::abs(g(2)) < 1e-6 * (std::abs(fx(2)) + std::abs(fy(2))) * h;
          break;
        }
      }
      if (!ok || x < 0.05 || x > 6.0 || y < 0.05 || y > 6.0) continue;
      if (std::any_of(brute.begin(), brute.end(),
                      [&](const Eigen::Vector2d& q) { return std::hypot(q(0) - x, q(1) - y) < 1e-7; }))
        continue;
      brute.emplace_back(x, y);
      bool listed = false;
      for (const Solution& q : r.solutions) listed |= std::hypot(q.t1() - x, q.t2() - y) < 1e-7;
      EXPECT_TRUE(listed) << "(" << x << ", " << y << ") found by brute force, not listed";
    }
  // The grid sees every root of this window: the same count both ways.
  EXPECT_EQ(brute.size(), r.solutions.size());
}

TEST(Progress, ReportsEveryCellAndStopsWithWhatWasFound) {
  // A callback that always continues changes nothing, and its last report has every cell traced.
  const System s5 = chain5();
  SolveOptions o;
  o.t1_max = 12;
  o.t2_max = 12;
  const SolveResult plain = solve(s5, o);
  SolveProgress last;
  int calls = 0;
  o.progress = [&](const SolveProgress& p) {
    last = p;
    ++calls;
    return true;
  };
  const SolveResult reported = solve(s5, o);
  EXPECT_GE(calls, 1);
  EXPECT_EQ(last.cells_done, last.cells_total);
  EXPECT_GE(last.candidates, static_cast<long>(plain.solutions.size()));  // sign changes, before polish
  ASSERT_EQ(reported.solutions.size(), plain.solutions.size());
  for (size_t i = 0; i < plain.solutions.size(); ++i) {
    EXPECT_EQ(reported.solutions[i].t1(), plain.solutions[i].t1());
    EXPECT_EQ(reported.solutions[i].t2(), plain.solutions[i].t2());
  }
  EXPECT_EQ(reported.stats.evaluations, plain.stats.evaluations);
  EXPECT_EQ(reported.status, SolveStatus::Success);

  // Stopped at its first report (0.2 s into a search of minutes): the cells not traced are counted and listed, the
  // status is Incomplete, and what was found is part of the whole window's result (checked on a sub-window).
  const System s20 = chain(20, {1.0}, {1.0}, 19, ContactSide::Upper, 1.0);
  SolveOptions big;
  std::tie(big.t1_max, big.t2_max) = fundamental_box(ModalForm(s20));
  big.threads = 2;
  big.progress = [](const SolveProgress&) { return false; };
  const SolveResult part = solve(s20, big);
  EXPECT_EQ(part.status, SolveStatus::Incomplete);
  EXPECT_GT(part.stats.unsearched_cells, 0);
  const bool listed = std::any_of(part.uncertified.begin(), part.uncertified.end(),
                                  [](const UncertifiedRegion& u) { return u.cause == "interrupted"; });
  EXPECT_TRUE(listed);
  for (const Solution& x : part.solutions) {
    SolveOptions around;
    around.t1_min = x.t1() * (1 - 1e-6);
    around.t1_max = x.t1() * (1 + 1e-6);
    around.t2_min = x.t2() * (1 - 1e-6);
    around.t2_max = x.t2() * (1 + 1e-6);
    const SolveResult r = solve(s20, around);
    ASSERT_EQ(r.solutions.size(), 1u) << x.t1() << " " << x.t2();
    EXPECT_NEAR(r.solutions[0].t1(), x.t1(), 1e-9 * x.t1());
    EXPECT_NEAR(r.solutions[0].t2(), x.t2(), 1e-9 * x.t2());
  }
}

TEST(Progress, TheCallbackIsNotCalledAgainOnceItReturnedFalse) {
  // It was called once more, at the end of the search, after it had asked to stop (found by an independent attack).
  const System s20 = chain(20, {1.0}, {1.0}, 19, ContactSide::Upper, 1.0);
  SolveOptions o;
  std::tie(o.t1_max, o.t2_max) = fundamental_box(ModalForm(s20));
  o.threads = 2;
  int calls = 0;
  o.progress = [&calls](const SolveProgress&) {
    ++calls;
    return false;
  };
  const SolveResult r = solve(s20, o);
  EXPECT_EQ(r.status, SolveStatus::Incomplete);
  EXPECT_EQ(calls, 1);
}

TEST(Progress, TheInterruptedRegionsLieInsideTheWindow) {
  // The window's ends next to pole lines make the plan reach past them (each edge moved clear of its line); the
  // regions not searched of a stopped search started below t2_min (found by an independent attack). Ends put just
  // inside pole lines, stopped at the first report: every "interrupted" region is inside the window.
  const System s20 = chain(20, {1.0}, {1.0}, 19, ContactSide::Upper, 1.0);
  const ModalForm md(s20);
  const auto [b1, b2] = fundamental_box(md);
  const std::vector<double> fp = md.flight_poles(0.2 * b1, b1), cp = md.contact_poles(0.2 * b2, b2);
  ASSERT_GE(fp.size(), 2u);
  ASSERT_GE(cp.size(), 2u);
  SolveOptions o;
  o.t1_min = fp.front() * (1 + 1e-7);
  o.t1_max = fp.back() * (1 - 1e-7);
  o.t2_min = cp.front() * (1 + 1e-7);
  o.t2_max = cp.back() * (1 - 1e-7);
  o.threads = 2;
  o.progress = [](const SolveProgress&) { return false; };
  const SolveResult r = solve(s20, o);
  int interrupted = 0;
  for (const UncertifiedRegion& u : r.uncertified) {
    if (u.cause != "interrupted") continue;
    ++interrupted;
    EXPECT_GE(u.t1_lo, o.t1_min);
    EXPECT_LE(u.t1_hi, o.t1_max);
    EXPECT_GE(u.t2_lo, o.t2_min);
    EXPECT_LE(u.t2_hi, o.t2_max);
    EXPECT_LT(u.t1_lo, u.t1_hi);
    EXPECT_LT(u.t2_lo, u.t2_hi);
  }
  EXPECT_GT(interrupted, 0);
}

TEST(Progress, TheLineRecomputesTheTimeLeftAndDropsItWhenItCannotBeEstimated) {
  // "~0 s left" stuck on screen before the first cell was done and while the last cells ran (cells_done counts the
  // cells started; found by an independent attack).
  auto line = [](long done, long total, double seconds) { return SolveProgress{done, total, 0, seconds}.line(); };
  EXPECT_EQ(line(0, 100, 5.0).find("left"), std::string::npos) << line(0, 100, 5.0);
  EXPECT_EQ(line(100, 100, 50.0).find("left"), std::string::npos) << line(100, 100, 50.0);
  EXPECT_NE(line(100, 100, 50.0).find("finishing"), std::string::npos);
  EXPECT_NE(line(50, 100, 10.0).find("~10 s left"), std::string::npos) << line(50, 100, 10.0);
  EXPECT_NE(line(50, 100, 20.0).find("~20 s left"), std::string::npos) << line(50, 100, 20.0);  // recomputed
  EXPECT_NE(line(50, 100, 20.0).find("20.0 s elapsed"), std::string::npos) << line(50, 100, 20.0);
}

TEST(Progress, AStopRaisedDuringACellEndsItsPiecesAtTheNextStep) {
  // A stop was checked only between cells, and one certified cell of a 20-dof chain can take tens of seconds (Ctrl-C
  // did not end such a run within 30 s). The tracer now ends each piece at its next step: the cell of the paper's SPP
  // (3.2160302, 0.52773599), traced with the stop raised, is not certified and takes no step; without it, it is.
  const System s5 = chain5();
  const ModalForm md(s5);
  const auto eq = make_equations(md, Symmetry::Axial);
  SolveOptions o;
  o.t1_max = o.t2_max = 12;
  const std::vector<double> fp = md.flight_poles(0.0, 12.0), cp = md.contact_poles(0.0, 12.0);
  auto around = [](const std::vector<double>& poles, double t) {
    const auto hi = std::upper_bound(poles.begin(), poles.end(), t);
    return std::make_pair(*(hi - 1), *hi);
  };
  const auto [l1, h1] = around(fp, 3.2160302);
  const auto [l2, h2] = around(cp, 0.52773599);
  const double m1 = 1e-3 * (h1 - l1), m2 = 1e-3 * (h2 - l2);
  const search::Cell cell{l1 + m1, h1 - m1, l2 + m2, h2 - m2, true, true, true, true};
  for (const bool stopped : {false, true}) {
    SolveStats st;
    search::DenseEvaluator ev(*eq);
    const std::atomic<bool> stop{stopped};
    search::CellTracer tracer(*eq, o, st, ev, &stop);
    std::vector<search::EdgeHit> a, b, c, d;
    const bool certified = tracer.trace_cell(cell, 0, a, b, c, d);
    EXPECT_GT(st.curve_pieces, 0);
    if (stopped) {
      EXPECT_FALSE(certified);
      EXPECT_EQ(st.certified_steps, 0);
      EXPECT_TRUE(tracer.candidates().empty());
    } else {
      EXPECT_TRUE(certified);
      EXPECT_GT(st.certified_steps, 0);
      EXPECT_FALSE(tracer.candidates().empty());  // the paper's SPP: a sign change of g in this cell
    }
  }
}
