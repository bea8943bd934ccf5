// orbit/: initial conditions, flows, samples and admissibility of the SPPs the search finds, checked against the
// exact physical flows (tests/physical_flow.hpp), independently of the modal form; and the guard on modal bases.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "paper_examples.hpp"
#include "physical_flow.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"
#include "spp/orbit/orbit.hpp"
#include "spp/orbit/solution.hpp"
#include "spp/search/solver.hpp"
#include "spp/stability/floquet.hpp"

using namespace spp;
using spp::test::chain5;
using spp::test::rod4;
using spp::test::solve_window;

namespace {

// All the properties the issue lists for an admissible SPP, checked with physical flows.
void check_admissible_orbit(const System& s, const Solution& sol) {
  const ref::PhysicalFlow flow(s);
  const int n = s.n();
  Eigen::VectorXd X0(2 * n);
  X0 << sol.orbit.x0, sol.orbit.v0;
  const double xs = X0.norm();
  // returns to its initial state after one period (contact 2 t2, then flight 2 t1)
  const Eigen::VectorXd XT = flow.flight(flow.contact(X0, 2 * sol.t2()), 2 * sol.t1());
  EXPECT_LT((XT - X0).norm() / xs, 1e-10);
  EXPECT_LT(sol.return_error, 1e-10);
  // (1.3c): zero normal velocity and acceleration at contact onset; (1.3d) gap closed
  EXPECT_LT(std::abs(s.w().dot(sol.orbit.v0)), 1e-10 * xs);
  EXPECT_LT(std::abs(flow.normal_acceleration_free(X0)), 1e-10 * xs);
  EXPECT_LT(std::abs(flow.gap(X0)), 1e-12 * (xs + std::abs(s.g0())));
  // Theorem 3.1: axes of symmetry at t = -t1 (flight) and t = t2 (contact)
  for (double f : {0.13, 0.5, 0.91}) {
    const double tau = f * sol.t1();
    const Eigen::VectorXd a = flow.flight(X0, -sol.t1() + tau), b = flow.flight(X0, -sol.t1() - tau);
    EXPECT_LT((a.head(n) - b.head(n)).norm(), 1e-10 * xs);
    EXPECT_LT((a.tail(n) + b.tail(n)).norm(), 1e-10 * xs);
    const double sig = f * sol.t2();
    const Eigen::VectorXd c = flow.contact(X0, sol.t2() + sig), d = flow.contact(X0, sol.t2() - sig);
    EXPECT_LT((c.head(n) - d.head(n)).norm(), 1e-10 * xs);
    EXPECT_LT((c.tail(n) + d.tail(n)).norm(), 1e-10 * xs);
  }
  // non-negative gap in flight and force in contact, sampled densely (tolerance at rounding level)
  for (int i = 0; i <= 400; ++i) {
    EXPECT_GE(flow.gap(flow.flight(X0, -2 * sol.t1() * i / 400.0)), -1e-10 * (xs + std::abs(s.g0())));
    EXPECT_GE(flow.force(flow.contact(X0, 2 * sol.t2() * i / 400.0)), -1e-10 * xs);
  }
}

// Solves the window, checks every admissible SPP, returns how many there are.
int check_every_admissible(const System& s, const SolveResult& r) {
  EXPECT_EQ(r.status, SolveStatus::Success) << r.brief_report();
  int admissible = 0;
  for (const Solution& sol : r.solutions)
    if (sol.admissible()) {
      ++admissible;
      SCOPED_TRACE("t1 = " + std::to_string(sol.t1()) + ", t2 = " + std::to_string(sol.t2()));
      check_admissible_orbit(s, sol);
    }
  return admissible;
}

}  // namespace

TEST(PaperChain5, EveryAdmissibleSppIsAPeriodicSymmetricAdmissibleOrbit) {
  const System s = chain5();
  // The paper's fig. 4 marks several admissible SPPs (A and B among them) in this window; the complete search finds
  // 7 (and 64 roots in all), each checked here.
  EXPECT_EQ(check_every_admissible(s, solve_window(s, 12.0, 12.0)), 7);
}

TEST(PaperRod4, EveryAdmissibleSppIsAPeriodicSymmetricAdmissibleOrbit) {
  const System s = rod4();
  const SolveResult r = solve_window(s, 12.0, 12.0);
  EXPECT_EQ(check_every_admissible(s, r), 2);  // the paper's fig. 7 shows one; the complete search finds 2 of 26
}

TEST(PaperChain5, InadmissibleRootsViolateAnInequality) {
  // A potential but inadmissible SPP must show a negative gap in flight or a negative force in contact.
  const System s = chain5();
  const SolveResult r = solve_window(s, 12.0, 12.0);
  const ref::PhysicalFlow flow(s);
  for (const Solution& sol : r.solutions) {
    if (sol.admissible()) continue;
    Eigen::VectorXd X0(2 * s.n());
    X0 << sol.orbit.x0, sol.orbit.v0;
    double gmin = 1e300, fmin = 1e300;
    for (int i = 1; i < 2000; ++i) {
      gmin = std::min(gmin, flow.gap(flow.flight(X0, -2 * sol.t1() * i / 2000.0)));
      fmin = std::min(fmin, flow.force(flow.contact(X0, 2 * sol.t2() * i / 2000.0)));
    }
    // either a clear violation in the samples, or the violation sits at the phase ends (end-order check)
    const bool clear = gmin < -1e-9 * X0.norm() || fmin < -1e-9 * X0.norm();
    EXPECT_TRUE(clear || !sol.admissibility.ends_ok) << "t1 = " << sol.t1() << ", t2 = " << sol.t2();
  }
}

TEST(Remark41, NoRootIsAdmissibleForBothSignsOfG0) {
  for (const System& s : {chain5(), rod4()}) {
    const System flipped(s.M(), s.K(), s.w(), -s.g0(), s.name());
    const SolveResult a = solve_window(s, 12.0, 12.0), b = solve_window(flipped, 12.0, 12.0);
    ASSERT_EQ(a.solutions.size(), b.solutions.size());  // the roots do not depend on g0
    for (size_t i = 0; i < a.solutions.size(); ++i) {
      EXPECT_NEAR(a.solutions[i].t1(), b.solutions[i].t1(), 1e-12);
      EXPECT_NEAR(a.solutions[i].t2(), b.solutions[i].t2(), 1e-12);
      EXPECT_FALSE(a.solutions[i].admissible() && b.solutions[i].admissible());
    }
  }
}

TEST(Orbit, PointAdmissibilityFromSamplesAloneIsNotCertified) {
  // sample_point_admissibility claimed certified for every orbit: a force zero at every sample (here the zero orbit)
  // reads as admissible, and that verdict rests on the samples only.
  const ModalForm md(load_system(std::string(SPP_SOURCE_DIR) + "/examples/chain5.json"));
  Orbit o;
  o.t1 = o.t2 = 1.0;
  o.symmetry = Symmetry::Point;
  o.a = o.c = o.p0 = o.p0dot = Eigen::VectorXd::Zero(md.m());
  o.x0 = o.v0 = Eigen::VectorXd::Zero(md.n());
  const Admissibility adm = sample_point_admissibility(md, o);
  EXPECT_TRUE(adm.admissible);
  EXPECT_FALSE(adm.certified);
}

TEST(Orbit, SampledPeriodStartsAtTheOnsetAndComesBack) {
  // sample_orbit (spp trajectory, Python's spp.trajectory): row 0 is the onset state with a closed gap, the force is
  // zero in flight, and the last row, one period later, is the onset state again.
  const System s = chain5();
  const ModalForm md(s);
  const SolveResult r = solve_window(s, 12.0, 12.0);
  int checked = 0;
  for (const Solution& sol : r.solutions) {
    if (!sol.admissible()) continue;
    const OrbitSamples smp = sample_orbit(md, sol.orbit, 201);
    const double xs = sol.x0().norm() + std::abs(s.g0());
    ASSERT_EQ(smp.x.rows(), 201);
    EXPECT_DOUBLE_EQ(smp.t(200), sol.period());
    EXPECT_LT((smp.x.row(0).transpose() - sol.x0()).norm(), 1e-12 * xs);
    EXPECT_LT((smp.x.row(200).transpose() - sol.x0()).norm(), 1e-9 * xs);
    EXPECT_LT((smp.v.row(200).transpose() - sol.v0()).norm(), 1e-9 * (sol.v0().norm() + 1.0));
    EXPECT_LT(std::abs(smp.gap(0)), 1e-12 * xs);
    for (int k = 0; k < 201; ++k) {
      if (smp.t(k) > 2.0 * sol.t2() * (1 + 1e-12)) {
        EXPECT_EQ(smp.force(k), 0.0);
        EXPECT_GE(smp.gap(k), -1e-10 * xs);
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, 7);
}

TEST(Orbit, ModalCoordinatesOfAnotherBasisAreRebuiltFromX0V0) {
  // Eigenvectors are defined up to sign: an orbit whose modal coordinates came from another machine's modal form
  // (e.g. read from its result file) once sampled into a wrong trajectory without a word. Simulated here by flipping
  // the coupled mode that carries most of the orbit, as a flipped eigenvector would, and by dropping the modal
  // coordinates altogether (a result file without its "orbit" block): both must give the original's trajectory,
  // admissibility and multipliers, rebuilt from x0, v0.
  const System s = chain5();
  const ModalForm md(s);
  const SolveResult r = solve_window(s, 12.0, 12.0);
  const auto sol =
      std::find_if(r.solutions.begin(), r.solutions.end(), [](const Solution& x) { return x.admissible(); });
  ASSERT_NE(sol, r.solutions.end());
  Orbit flipped = sol->orbit;
  Eigen::Index k = 0;
  flipped.p0.cwiseAbs().maxCoeff(&k);
  for (Eigen::VectorXd* v : {&flipped.a, &flipped.c, &flipped.p0, &flipped.p0dot}) (*v)(k) = -(*v)(k);
  Orbit bare = sol->orbit;
  bare.a = bare.c = bare.p0 = bare.p0dot = Eigen::VectorXd();
  const OrbitSamples ref = sample_orbit(md, sol->orbit, 41);
  const Admissibility adm = check_admissibility(md, sol->orbit);
  const Floquet fl = floquet(md, sol->orbit);
  for (const Orbit* o : {&flipped, &bare}) {
    const Orbit back = in_modal_basis(md, *o);
    EXPECT_LE((back.p0 - sol->orbit.p0).norm(), 1e-10 * sol->orbit.p0.norm());
    EXPECT_LE((back.a - sol->orbit.a).norm(), 1e-10 * sol->orbit.a.norm());
    EXPECT_LE((back.c - sol->orbit.c).norm(), 1e-10 * sol->orbit.c.norm());
    const OrbitSamples smp = sample_orbit(md, *o, 41);
    EXPECT_LE((smp.x - ref.x).norm(), 1e-10 * ref.x.norm());
    EXPECT_LE((smp.force - ref.force).norm(), 1e-10 * ref.force.norm());
    const Admissibility a2 = check_admissibility(md, *o);
    EXPECT_EQ(a2.admissible, adm.admissible);
    EXPECT_NEAR(a2.min_force, adm.min_force, 1e-10 * std::abs(adm.mid_contact_force));
    EXPECT_NEAR(admissibility_margin(md, *o), admissibility_margin(md, sol->orbit), 1e-10);
    const Floquet f2 = floquet(md, *o);
    EXPECT_NEAR(f2.spectral_radius, fl.spectral_radius, 1e-10);
  }
  // The same basis: returned as it is, bit for bit.
  const Orbit same = in_modal_basis(md, sol->orbit);
  EXPECT_EQ(same.p0, sol->orbit.p0);
  EXPECT_EQ(same.a, sol->orbit.a);
}

TEST(Orbit, OrbitOfAnotherSystemIsRefused) {
  // x0, v0 with a part outside the coupled modes' span (here of a system with other masses) are no motion of this
  // system: refused, naming the function, not sampled into something else.
  const System s = chain5();
  const ModalForm md(s);
  const SolveResult r = solve_window(s, 12.0, 12.0);
  ASSERT_FALSE(r.solutions.empty());
  const ModalForm md4(rod4());
  // M = I, K = diag(1, 2, 3), w = (1, 1, 0): the third mode never sees the contact, so an x0 moving it is no orbit
  // of this system's coupled modes.
  const ModalForm md3(System(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 2, 3).asDiagonal().toDenseMatrix(),
                             Eigen::Vector3d(1, 1, 0), 1.0));
  ASSERT_EQ(md3.m(), 2);
  Orbit other;
  other.t1 = other.t2 = 1.0;
  other.x0 = Eigen::Vector3d(-0.5, -0.5, 0.3);
  other.v0 = Eigen::Vector3d::Zero();
  for (int which = 0; which < 3; ++which) {
    try {
      if (which == 0) sample_orbit(md4, r.solutions.front().orbit, 11);  // 4 dofs, not 5
      if (which == 1) floquet(md, Orbit{});                             // no x0 at all
      if (which == 2) sample_orbit(md3, other, 11);
      ADD_FAILURE() << "expected a refusal (" << which << ")";
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      EXPECT_TRUE(msg.find("dofs") != std::string::npos || msg.find("another system") != std::string::npos) << msg;
    }
  }
}

TEST(Orbit, SolutionReadBackFromItsResultFileSamplesLikeTheOriginal) {
  // A result file keeps each orbit's modal coordinates: read back on the machine that wrote it, the Solution is the
  // same and samples the same trajectory.
  const System s = rod4();
  const ModalForm md(s);
  const SolveResult r = solve_window(s, 12.0, 12.0);
  const SolveResult back = parse_result(result_json(s, r), "rod4 result");
  ASSERT_EQ(back.solutions.size(), r.solutions.size());
  for (size_t i = 0; i < r.solutions.size(); ++i) {
    const OrbitSamples a = sample_orbit(md, r.solutions[i].orbit, 31),
                       b = sample_orbit(md, back.solutions[i].orbit, 31);
    EXPECT_LE((a.x - b.x).norm(), 1e-13 * (a.x.norm() + 1.0)) << i;
    EXPECT_LE((a.force - b.force).norm(), 1e-13 * (a.force.norm() + 1.0)) << i;
  }
}
