// The proofs behind certified trace steps (issue: completeness you can trust, item 2): the onset inertia (an SPP
// makes H compressed to z^perp singular; Hc grows with t1 and t2 between pole lines) and the certified search.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "paper_examples.hpp"
#include "paper_reference.hpp"
#include "search/evaluator.hpp"
#include "search/step_certificate.hpp"
#include "spp/core/generators.hpp"
#include "spp/io.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"

using namespace spp;
using spp::test::chain5;

namespace {

// The pole-free interval of sorted poles holding x.
std::pair<double, double> interval(const std::vector<double>& poles, double x) {
  double lo = 0.0, hi = 1e300;
  for (double p : poles) {
    if (p <= x) lo = std::max(lo, p);
    if (p > x) hi = std::min(hi, p);
  }
  return {lo, hi};
}

SolveOptions window(double t1_min, double t1_max, double t2_min, double t2_max) {
  SolveOptions o;
  o.t1_min = t1_min;
  o.t1_max = t1_max;
  o.t2_min = t2_min;
  o.t2_max = t2_max;
  return o;
}

// Solves the window with the midpoint check and with certify_steps (the default): the certified run ends success with
// every step proved (outside the axis bands) and the same roots as the midpoint trace. Returns the certified result.
SolveResult expect_certified_with_default_roots(const System& s, SolveOptions o) {
  o.certify_steps = false;
  const SolveResult ref = solve(s, o);
  o.certify_steps = true;
  const SolveResult r = solve(s, o);
  EXPECT_EQ(r.status, SolveStatus::Success) << r.brief_report();
  EXPECT_GT(r.stats.certified_steps, 0);
  EXPECT_EQ(r.stats.uncertified_steps, 0);
  EXPECT_EQ(r.solutions.size(), ref.solutions.size());
  for (size_t i = 0; i < std::min(r.solutions.size(), ref.solutions.size()); ++i) {
    EXPECT_NEAR(r.solutions[i].t1(), ref.solutions[i].t1(), 1e-9);
    EXPECT_NEAR(r.solutions[i].t2(), ref.solutions[i].t2(), 1e-9);
  }
  return r;
}

// expect_certified_with_default_roots on a system of tests/data/ (without the return error, which these tests do not
// check).
SolveResult certified_data_window(const std::string& file, double t1_min, double t1_max, double t2_min, double t2_max) {
  SolveOptions o = window(t1_min, t1_max, t2_min, t2_max);
  o.compute_return_error = false;
  return expect_certified_with_default_roots(load_system(std::string(SPP_SOURCE_DIR) + "/tests/data/" + file), o);
}
}  // namespace

TEST(OnsetInertia, SingularAtAnSppAndCountsItsCrossing) {
  // Hc is singular at the paper's SPP: the count is uncertain there, and a small box around it has different counts
  // at its two Loewner corners.
  const ModalForm md(chain5());
  const auto eq = make_equations(md, Symmetry::Axial);
  search::DenseEvaluator ev(*eq);
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
  const auto eq = make_equations(md, Symmetry::Axial);
  search::DenseEvaluator ev(*eq);
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
      EXPECT_FALSE(r.t1() >= lo1 && r.t1() <= hi1 && r.t2() >= lo2 && r.t2() <= hi2)
          << "box [" << lo1 << ", " << hi1 << "] x [" << lo2 << ", " << hi2 << "] proved free holds SPP " << r.t1()
          << ", " << r.t2();
  }
  EXPECT_GT(free_boxes, 1000);  // the check is not vacuous
  for (const Solution& r : ref.solutions) {
    const int lo = ev.onset_inertia(r.t1() - 1e-6, r.t2() - 1e-6);
    EXPECT_TRUE(lo < 0 || lo != ev.onset_inertia(r.t1() + 1e-6, r.t2() + 1e-6)) << r.t1() << ", " << r.t2();
  }
}

TEST(CertifiedSearch, ProvesTheWholeChainWindowWithTheSameRoots) {
  // certify_steps on the paper's chain window (0, 12]^2: every step outside the axis bands proved (zeroth-order
  // drift, curvature, spectral bounds or onset inertia), status success, and the same 64 SPPs as the default trace.
  const System s = chain5();
  SolveOptions o;
  o.t1_max = 12;
  o.t2_max = 12;
  const SolveResult r = expect_certified_with_default_roots(s, o);
  EXPECT_EQ(r.solutions.size(), 64u);
}

namespace {

// The true point of curve k on the anti-diagonal t2 - t1 = s inside cell [a1, b1] x [A, B] (lambda_k increases
// along (1, 1)), by bisection on full eigenvalues: independent of the search's own root finder. False when the
// curve does not cross that anti-diagonal.
struct CurvePoint {
  double t1, t2;
  Eigen::VectorXd b;
  Eigen::VectorXd lam;
};
bool curve_point(const EquationSet& eq, double a1, double b1, double A, double B, double s, int k, CurvePoint& p) {
  double lo = std::max(a1, A - s), hi = std::min(b1, B - s);
  if (!(lo < hi)) return false;
  auto lam_k = [&](double t1) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(eq.H(t1, t1 + s));
    return es.eigenvalues()(k);
  };
  if (!(lam_k(lo) < 0 && lam_k(hi) > 0)) return false;
  for (int it = 0; it < 200 && hi - lo > 4e-16 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (lam_k(mid) < 0 ? lo : hi) = mid;
  }
  p.t1 = 0.5 * (lo + hi);
  p.t2 = p.t1 + s;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(eq.H(p.t1, p.t2));
  p.b = es.eigenvectors().col(k);
  p.lam = es.eigenvalues();
  return true;
}

// A random step of a random curve in a random cell of (0, T1] x (0, T2] (cells shrunk by 1e-6 from their pole
// lines): the cell, the curve's index, the step's start s and length h (10^lo_exp to 10^(lo_exp + 4) of the cell's
// anti-diagonal range) and its two true curve points. False where either point is not on the curve.
struct RandomStep {
  double c1, d1, c2, d2;
  int k;
  double sa, h;
  CurvePoint pa, pb;
};
bool random_step(const EquationSet& eq, double T1, double T2, const std::vector<double>& p1,
                 const std::vector<double>& p2, double lo_exp, std::mt19937& rng, RandomStep& st) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto [a1, b1] = interval(p1, T1 * (0.02 + 0.96 * u(rng)));
  const auto [A, B] = interval(p2, T2 * (0.02 + 0.96 * u(rng)));
  st.c1 = a1 + 1e-6 * (b1 - a1);
  st.d1 = std::min(b1, T1) - 1e-6 * (b1 - a1);
  st.c2 = A + 1e-6 * (B - A);
  st.d2 = std::min(B, T2) - 1e-6 * (B - A);
  st.k = static_cast<int>(u(rng) * eq.modal().m());
  const double range = st.d2 - st.c1 - (st.c2 - st.d1);
  st.sa = (st.c2 - st.d1) + range * u(rng);
  st.h = range * std::pow(10.0, lo_exp + 4.0 * u(rng));
  return curve_point(eq, st.c1, st.d1, st.c2, st.d2, st.sa, st.k, st.pa) &&
         curve_point(eq, st.c1, st.d1, st.c2, st.d2, st.sa + st.h, st.k, st.pb);
}

}  // namespace

TEST(BorderedForm, SameNullVectorsShiftedInertiaAndMonotoneThroughThePole) {
  // Next to a flight and a contact pole line of the paper's chain: the bordered form borders both modes; its null
  // vectors are H's extended (B [b; nu] = 0), its inertia is H's plus the positive border values' count
  // (Haynsworth), its entries stay bounded where H's grow like 1 / distance, and it grows with t1 and t2 (Loewner).
  const ModalForm md(load_system(std::string(SPP_SOURCE_DIR) + "/examples/chain5.json"));
  const double P1 = M_PI / (2.0 * md.omega()(2)), P2 = 3.0 * M_PI / (2.0 * md.d()(3));
  const auto eq = make_equations(md, Symmetry::Axial);
  for (const double dist : {1e-2, 1e-5, 1e-8}) {
    const double lo1 = P1 - 2 * dist, hi1 = P1 - dist, lo2 = P2 + dist, hi2 = P2 + 2 * dist;
    const search::BorderedForm bf(*eq, lo1, hi1, lo2, hi2);
    EXPECT_GE(bf.bordered(), 2) << dist;
    const double t1 = 0.5 * (lo1 + hi1), t2 = 0.5 * (lo2 + hi2);
    const Eigen::MatrixXd H = eq->H(t1, t2), B = bf.matrix(t1, t2);
    EXPECT_LT(B.cwiseAbs().maxCoeff(), 10.0 * md.omega().maxCoeff()) << dist;
    EXPECT_GT(H.cwiseAbs().maxCoeff(), 0.1 / dist) << dist;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eh(H), eb(B);
    const Eigen::Index neg_h = (eh.eigenvalues().array() < 0).count(), neg_b = (eb.eigenvalues().array() < 0).count();
    // Haynsworth: inertia(B) = inertia(H) + inertia(-Lambda^-1) (f = omega tan(omega t1) > 0 left of its pole, c =
    // d tan(d t2) < 0 right of its pole: at least one of each sign here)
    const Eigen::VectorXd lam = bf.border_values(t1, t2);
    EXPECT_GE((lam.array() > 0).count(), 1);
    EXPECT_GE((lam.array() < 0).count(), 1);
    EXPECT_EQ(neg_b, neg_h + (lam.array() > 0).count()) << dist;
    // an eigenpair H b = mu b extends to B [b; nu] = [mu b; 0] (so null vectors of H to null vectors of B)
    for (int k = 0; k < md.m(); ++k) {
      const Eigen::VectorXd b = eh.eigenvectors().col(k), x = bf.extend(b, t1, t2);
      Eigen::VectorXd expect = Eigen::VectorXd::Zero(x.size());
      expect.head(md.m()) = eh.eigenvalues()(k) * b;
      EXPECT_LT((B * x - expect).norm(), 1e-9 * (1.0 + x.norm()) * H.norm()) << dist << " " << k;
    }
    // Loewner: B(t1', t2') - B(t1, t2) is positive semi-definite for t1' >= t1, t2' >= t2 in the box
    const Eigen::MatrixXd D = bf.matrix(hi1, hi2) - bf.matrix(lo1, lo2);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ed(D, Eigen::EigenvaluesOnly);
    EXPECT_GE(ed.eigenvalues().minCoeff(), -1e-14 * B.norm()) << dist;
  }
}

namespace {
// lambda_k of H(t1, t2) in long double (H formed from the modal form's double omega, d, G, taken as exact): the
// reference for the bordered eigenpairs next to a pole line, where H's double eigenvalues are off by 8 m eps |H|.
using MatL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
MatL h_long(const ModalForm& md, long double t1, long double t2) {
  const Eigen::Index m = md.m();
  MatL G = md.G().cast<long double>(), H = MatL::Zero(m, m);
  Eigen::Matrix<long double, Eigen::Dynamic, 1> e(md.d().size());
  for (Eigen::Index j = 0; j < e.size(); ++j) {
    const long double dj = md.d()(j);
    e(j) = dj * std::tan(dj * t2);
  }
  H = G * e.asDiagonal() * G.transpose();
  for (Eigen::Index i = 0; i < m; ++i) {
    const long double w = md.omega()(i);
    H(i, i) += w * std::tan(w * t1);
  }
  return H;
}
}  // namespace

TEST(BorderedEigen, PlacesRootsNextToClusteredPoleLinesWhereHCannot) {
  // Two flight modes of nearly equal frequencies (10 and 10 (1 + 1e-5), tests/data/near_coincident7.json) put two pole
  // lines 1.6e-6 apart, as the top modes of a long chain do. On vertical lines 1e-8 and 1e-11 right of the first,
  // bordered_eigenpair gives lambda_k(H)'s sign wherever a long double reference proves it, and its zeros are H's (to
  // B's own error over the slope), while H's double error bound there allows a position error 1e3 times larger.
  // (Mutation-checked: with p off by one, or b's eigenvalue index k instead of k + p, the signs disagree.)
  const ModalForm md(load_system(std::string(SPP_SOURCE_DIR) + "/tests/data/near_coincident7.json"));
  const auto eq = make_equations(md, Symmetry::Axial);
  const Eigen::Index m = md.m();
  Eigen::Index fast = -1;
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j)
      if (md.omega()(i) > md.omega()(j) && md.omega()(i) < md.omega()(j) * (1 + 1e-4)) fast = i;
  ASSERT_GE(fast, 0);
  const double P = M_PI / (2.0 * md.omega()(fast));
  // a contact pole interval around t2 = 0.2, kept 1e-3 of its width off both poles
  const std::vector<double> cp = tangent_poles(md.d(), 0.15, 0.25);
  double lo2 = 0.15, hi2 = 0.25;
  for (double p : cp) {
    if (p <= 0.2) lo2 = std::max(lo2, p);
    if (p > 0.2) hi2 = std::min(hi2, p);
  }
  const double w2 = hi2 - lo2;
  lo2 += 1e-3 * w2;
  hi2 -= 1e-3 * w2;
  int roots = 0;
  for (const double dist : {1e-8, 1e-11}) {
    const double t1 = P + dist;
    const search::BorderedForm bf(*eq, t1, t1, lo2, hi2);
    ASSERT_GE(bf.bordered(), 2) << dist;  // both nearly equal flight modes
    auto lam_ref = [&](double t2, int k) {
      Eigen::SelfAdjointEigenSolver<MatL> es(h_long(md, t1, t2), Eigen::EigenvaluesOnly);
      return es.eigenvalues()(k);
    };
    const int n = 200;
    for (int k = 0; k < m; ++k) {
      double prev_t2 = lo2, prev = search::bordered_eigenpair(bf, lo2, lo2, k).lam;
      for (int i = 0; i <= n; ++i) {
        const double t2 = lo2 + (hi2 - lo2) * i / n;
        const search::BorderedEigen be = search::bordered_eigenpair(bf, t1, t2, k);
        ASSERT_TRUE(be.ok) << dist << " " << k << " " << t2;
        // the sign of lambda_k(H), where the long double reference is well away from its rounding (1e-15 |H|)
        const long double ref = lam_ref(t2, k);
        const long double href = h_long(md, t1, t2).cwiseAbs().maxCoeff();
        if (std::abs(ref) > 1e-15L * href && std::abs(be.lam) > be.error) {
          EXPECT_EQ(be.lam > 0, ref > 0) << dist << " k " << k << " t2 " << t2;
        }
        if (i > 0 && (prev > 0) != (be.lam > 0) && std::abs(prev) > 0) {
          // a zero of curve k between prev_t2 and t2: bisection on B, and on the long double H
          double a = prev_t2, b = t2, ar = prev_t2, br = t2;
          for (int it = 0; it < 80; ++it) {
            const double c = 0.5 * (a + b), cr = 0.5 * (ar + br);
            ((search::bordered_eigenpair(bf, t1, c, k).lam > 0) == (be.lam > 0) ? b : a) = c;
            ((lam_ref(cr, k) > 0) == (be.lam > 0) ? br : ar) = cr;
          }
          const search::BorderedEigen at = search::bordered_eigenpair(bf, t1, a, k);
          ASSERT_TRUE(at.ok);
          const double allowed = 4.0 * (std::abs(at.lam) + at.error) / at.l2 + 1e-15;
          EXPECT_LT(std::abs(a - ar), allowed) << dist << " k " << k;
          // H's own double error bound there, over the same slope: the position H could give
          const double h_allowed = 8.0 * m * std::numeric_limits<double>::epsilon() * eq->H(t1, a).norm() / at.l2;
          EXPECT_GT(h_allowed, 1e3 * allowed) << dist << " k " << k;
          ++roots;
        }
        prev = be.lam;
        prev_t2 = t2;
      }
    }
  }
  EXPECT_GE(roots, 2);
}

TEST(SpectralBounds, ContainTheSampledOnsetFunctionAndItsDerivative) {
  // Property: on random steps of random curves in random cells (the paper's chain and a stiff 5-dof system with
  // stiffness spread 1e5; H and H_T, point symmetry's, whose every contact mode is bordered), g = zhat^T b and dg/ds
  // sampled on the true curve (an independent bisection) lie within the ranges spectral_bounds gives from either end,
  // and the bounds are not vacuous (many valid, some sign-deciding).
  const std::vector<std::string> files = {std::string(SPP_SOURCE_DIR) + "/examples/chain5.json",
                                          std::string(SPP_SOURCE_DIR) + "/tests/data/stiff5_spread1e5.json"};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::pair<Symmetry, std::string>> cases;
  for (const Symmetry sym : {Symmetry::Axial, Symmetry::Point})
    for (const std::string& f : files) cases.emplace_back(sym, f);
  for (const auto& [sym, f] : cases) {
    const ModalForm md(load_system(f));
    const auto eq = make_equations(md, sym);
    const Eigen::VectorXd zhat = md.z().normalized();
    const double T1 = 8.0 * M_PI / (2.0 * md.omega().minCoeff()), T2 = 8.0 * M_PI / (2.0 * md.d().tail(1)(0));
    const std::vector<double> p1 = md.flight_poles(0.0, T1), p2 = md.contact_poles(0.0, T2);
    int valid = 0, deciding = 0, bordered = 0;
    for (int trial = 0; trial < 3000 && valid < 150; ++trial) {
      RandomStep st;
      if (!random_step(*eq, T1, T2, p1, p2, -5.0, rng, st)) continue;
      const auto& [c1, d1, c2, d2, k, sa, h, pa_, pb_] = st;
      CurvePoint pa = pa_, pb = pb_;
      // The box the bounds are taken over (it holds the true curve and the computed ends), and its bordered form:
      // the bounds are those of g = c^T x / |x| for the bordered form's null vector x = [b; nu] (same sign as
      // zhat^T b), sampled here with their own derivative.
      const double off = 1e-12 * (1.0 + std::max(pa.t1, pa.t2)) * (2.0 * u(rng) - 1.0);
      const double e = 2.0 * std::abs(off);
      const double lo1 = std::max(c1, std::min(pa.t1, pb.t1) - e), hi1 = std::min(d1, std::max(pa.t1, pb.t1) + e);
      const double lo2 = std::max(c2, std::min(pa.t2, pb.t2) - e), hi2 = std::min(d2, std::max(pa.t2, pb.t2) + e);
      const search::BorderedForm bf(*eq, lo1, hi1, lo2, hi2);
      if (!bf.valid()) continue;  // point symmetry: a zero of tan(d t2) in the box
      bordered += bf.bordered() > 0 ? 1 : 0;
      // samples of the true curve on [sa, sa + h], b oriented continuously from pa
      const int ns = 40;
      std::vector<double> gs, dgs;
      Eigen::VectorXd prev = pa.b;
      bool ok = true;
      for (int i = 0; i <= ns && ok; ++i) {
        const double s = sa + h * i / ns;
        CurvePoint q;
        ok = curve_point(*eq, c1, d1, c2, d2, s, k, q);
        if (!ok) break;
        const Eigen::VectorXd b = q.b.dot(prev) < 0 ? Eigen::VectorXd(-q.b) : q.b;
        prev = b;
        const Eigen::VectorXd x = bf.extend(b, q.t1, q.t2).normalized();
        gs.push_back(bf.onset().dot(x));
        // the bordered form's g has the sign of the onset condition itself (point: c(t2)^T b, c moving with t2)
        const Eigen::VectorXd c = sym == Symmetry::Axial ? zhat : eq->onset_direction(q.t2);
        if (std::abs(c.dot(b)) > 1e-8 * c.norm()) {
          EXPECT_EQ(c.dot(b) > 0, gs.back() > 0) << to_string(sym) << " " << f;
        }
        // dg/ds = -(B^+ c)^T B' x, B' = tau' dB/dt1 + (1 + tau') dB/dt2, tau' = -l2 / (l1 + l2) (first-order
        // perturbation of the null vector along the curve), with the pseudo-inverse from the full eigenpairs
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(bf.matrix(q.t1, q.t2));
        Eigen::Index kz = 0;
        es.eigenvalues().cwiseAbs().minCoeff(&kz);
        Eigen::VectorXd inv = es.eigenvalues().cwiseInverse();
        inv(kz) = 0.0;
        const Eigen::VectorXd v = es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose() * bf.onset();
        const Eigen::VectorXd Fx = bf.flight().d1(q.t1).cwiseProduct(x);
        const Eigen::VectorXd Cx = bf.Gx() * bf.contact().d1(q.t2).cwiseProduct(bf.Gx().transpose() * x);
        const double l1 = x.dot(Fx), l2 = x.dot(Cx), tp = -l2 / (l1 + l2);
        dgs.push_back(-v.dot(tp * Fx + (1.0 + tp) * Cx));
      }
      if (!ok) continue;
      if (pb.b.dot(prev) < 0) pb.b = -pb.b;
      // The ends as the tracer leaves them: off the curve along (1, 1) by up to pos_err (its bisection stops at
      // |lambda_k| ~ 1e-13 |H|), with the eigenvector computed there.
      auto end = [&](CurvePoint& p, double s, const Eigen::VectorXd& ref) {
        p.t1 += off;
        p.t2 += off;
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(eq->H(p.t1, p.t2));
        p.b = es.eigenvectors().col(k);
        if (p.b.dot(ref) < 0) p.b = -p.b;
        search::StepEnd x;
        x.s = s;
        x.t1 = p.t1;
        x.t2 = p.t2;
        x.b = &p.b;
        x.g = (sym == Symmetry::Axial ? zhat : eq->onset_direction(p.t2)).dot(p.b);
        x.pos_err = std::abs(off);
        return x;
      };
      const Eigen::VectorXd ra = pa.b, rb = pb.b;
      const search::StepEnd ea = end(pa, sa, ra), eb = end(pb, sa + h, rb);
      for (const search::StepEnd* x : {&ea, &eb}) {
        const search::SpectralBounds sb = search::spectral_bounds(bf, *x, sa, sa + h, lo1, hi1, lo2, hi2);
        if (!sb.valid) continue;
        ++valid;
        if (sb.g_lo > 0 || sb.g_hi < 0 || sb.dg_lo > 0 || sb.dg_hi < 0) ++deciding;
        const double gtol = 0.0, dtol = 1e-8 * (1.0 + std::abs(sb.dg_lo) + std::abs(sb.dg_hi));
        for (size_t i = 0; i < gs.size(); ++i) {
          EXPECT_GE(gs[i], sb.g_lo - gtol)
              << to_string(sym) << " " << f << " k " << k << " s " << sa + h * i / ns << " h " << h;
          EXPECT_LE(gs[i], sb.g_hi + gtol) << f << " k " << k << " s " << sa + h * i / ns << " h " << h;
          EXPECT_GE(dgs[i], sb.dg_lo - dtol) << f << " k " << k << " s " << sa + h * i / ns << " h " << h;
          EXPECT_LE(dgs[i], sb.dg_hi + dtol) << f << " k " << k << " s " << sa + h * i / ns << " h " << h;
        }
      }
    }
    EXPECT_GE(valid, 100) << f << " " << to_string(sym);
    EXPECT_GE(deciding, 30) << f << " " << to_string(sym);
    EXPECT_GE(bordered, 10) << f << " " << to_string(sym);  // next to pole lines (point: always)
  }
}

TEST(SpectralBounds, ProductsKeptInTheCacheGiveTheSameBoundsAsFreshOnes) {
  // The EigenCache keeps the pseudo-inverse products beside the eigenpairs they come from: a step refused and retried
  // shorter from the same start, or from a start that was the previous step's end, must get bit for bit the bounds a
  // fresh computation gives (chain5 and a stiff 5-dof, both symmetries), with no new evaluation.
  const std::vector<std::string> files = {std::string(SPP_SOURCE_DIR) + "/examples/chain5.json",
                                          std::string(SPP_SOURCE_DIR) + "/tests/data/stiff5_spread1e5.json"};
  std::mt19937 rng(12);
  int compared = 0;
  for (const Symmetry sym : {Symmetry::Axial, Symmetry::Point})
    for (const std::string& f : files) {
      const ModalForm md(load_system(f));
      const auto eq = make_equations(md, sym);
      const Eigen::VectorXd zhat = md.z().normalized();
      const double T1 = 8.0 * M_PI / (2.0 * md.omega().minCoeff()), T2 = 8.0 * M_PI / (2.0 * md.d().tail(1)(0));
      const std::vector<double> p1 = md.flight_poles(0.0, T1), p2 = md.contact_poles(0.0, T2);
      search::EigenCache cache;
      for (int trial = 0; trial < 400; ++trial) {
        RandomStep st;
        if (!random_step(*eq, T1, T2, p1, p2, -5.0, rng, st)) continue;
        const auto& [c1, d1, c2, d2, k, sa, h, pa, pb_] = st;
        const double lo1 = std::min(pa.t1, pb_.t1), hi1 = std::max(pa.t1, pb_.t1);
        const double lo2 = std::min(pa.t2, pb_.t2), hi2 = std::max(pa.t2, pb_.t2);
        const search::BorderedForm bf(*eq, lo1, hi1, lo2, hi2);
        if (!bf.valid()) continue;
        search::StepEnd x;
        x.s = sa;
        x.t1 = pa.t1;
        x.t2 = pa.t2;
        x.b = &pa.b;
        x.g = (sym == Symmetry::Axial ? zhat : eq->onset_direction(pa.t2)).dot(pa.b);
        for (const double part : {1.0, 0.5, 0.25}) {  // the step, then retried shorter from the same start
          const search::SpectralBounds fresh = search::spectral_bounds(bf, x, sa, sa + part * h, lo1, hi1, lo2, hi2);
          const search::SpectralBounds kept =
              search::spectral_bounds(bf, x, sa, sa + part * h, lo1, hi1, lo2, hi2, &cache);
          EXPECT_EQ(kept.evaluations, part == 1.0 ? 1 : 0);
          ASSERT_EQ(fresh.valid, kept.valid) << f;
          if (!fresh.valid) continue;
          ++compared;
          EXPECT_EQ(fresh.g_lo, kept.g_lo);
          EXPECT_EQ(fresh.g_hi, kept.g_hi);
          EXPECT_EQ(fresh.dg_lo, kept.dg_lo);
          EXPECT_EQ(fresh.dg_hi, kept.dg_hi);
          EXPECT_EQ(fresh.g_err, kept.g_err);
          EXPECT_EQ(fresh.g_x, kept.g_x);
        }
      }
    }
  EXPECT_GE(compared, 100);
}

TEST(SpectralBounds, StructuredBoxNormBoundsTheDenseProductOnRandomAndClusteredSpectra) {
  // |Hp E_box|_F in O(m^2) per step (structured_box_norm) against the m^3 product it replaces (dense_box_norm) and
  // a long double reference of the same norm: pseudo-inverses Hp = U diag(1 / lam_j, j != k) U^T of random
  // orthogonal U with random spectra (a stiff spread 1e6, and clusters 1e-9 apart as the chain's top frequencies),
  // square and rectangular (bordered) orthonormal G, increments spread over 8 decades, and increments chosen so that
  // the flight and contact parts of E_box cancel (where the expansion must hand over to the dense product). The
  // structured value bounds the reference from above and, where usable, lies within 1e-6 of it.
  std::mt19937 rng(2026);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  auto orthonormal = [&](Eigen::Index rows, Eigen::Index cols) {
    Eigen::MatrixXd A(rows, rows);
    for (Eigen::Index i = 0; i < A.size(); ++i) A.data()[i] = normal(rng);
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
    return Eigen::MatrixXd(Q.leftCols(cols));
  };
  int usable = 0, handed_over = 0;
  for (const Eigen::Index n : {130, 170})
    for (const int spectrum : {0, 1}) {  // 0: random, stiff spread; 1: clustered
      for (int trial = 0; trial < 4; ++trial) {
        const Eigen::Index mG = trial % 2 == 0 ? n : n - 3;
        const Eigen::MatrixXd U = orthonormal(n, n), G = orthonormal(n, mG);
        Eigen::VectorXd lam(n);
        for (Eigen::Index j = 0; j < n; ++j)
          lam(j) = spectrum == 0 ? (u01(rng) < 0.5 ? -1.0 : 1.0) * std::pow(10.0, 6.0 * u01(rng) - 3.0)
                                 : (1.0 + static_cast<double>(j / 10)) * (j % 2 == 0 ? 1.0 : -1.0) + 1e-9 * (j % 10);
        const Eigen::Index k = n / 2;
        lam(k) = 1e-12;
        Eigen::VectorXd inv = lam.cwiseInverse();
        inv(k) = 0.0;
        search::SpectralProducts p;
        p.Hp = U * inv.asDiagonal() * U.transpose();
        p.HpG = p.Hp * G;
        search::prepare_box_products(p, G);
        for (int inc = 0; inc < 3; ++inc) {
          Eigen::VectorXd dF(n), dC(mG);
          for (Eigen::Index i = 0; i < n; ++i) dF(i) = std::pow(10.0, 8.0 * u01(rng) - 6.0);
          for (Eigen::Index i = 0; i < mG; ++i) dC(i) = std::pow(10.0, 8.0 * u01(rng) - 6.0);
          if (inc == 2) {  // E_box = G diag(dC) G^T - diag(dF) nearly 0: G's columns unit vectors, dC ~ dF
            dF.setConstant(1.0);
            dC = dF.head(mG) * (1.0 + 1e-7);
          }
          const Eigen::MatrixXd Gi = inc == 2 ? Eigen::MatrixXd(Eigen::MatrixXd::Identity(n, mG)) : G;
          search::SpectralProducts q = p;
          if (inc == 2) {
            q.HpG = q.Hp * Gi;
            search::prepare_box_products(q, Gi);
          }
          using LMat = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
          const LMat HpE =
              -q.Hp.cast<long double>() * dF.cast<long double>().asDiagonal() +
              q.HpG.cast<long double>() * dC.cast<long double>().asDiagonal() * Gi.cast<long double>().transpose();
          const double exact = static_cast<double>(HpE.norm());
          const double dense = search::dense_box_norm(q.Hp, q.HpG, Gi, dF, dC);
          const search::BoxNorm s = search::structured_box_norm(q, dF, dC);
          EXPECT_NEAR(dense, exact, 1e-10 * exact) << n << " " << spectrum << " " << inc;
          EXPECT_GE(s.value, exact * (1.0 - 1e-15)) << n << " " << spectrum << " " << inc;
          if (s.usable) {
            ++usable;
            EXPECT_LE(s.value, exact * (1.0 + 1e-6)) << n << " " << spectrum << " " << inc;
          } else {
            ++handed_over;
          }
        }
      }
    }
  EXPECT_GE(usable, 24);      // every increment drawn at random
  EXPECT_GE(handed_over, 1);  // the cancelling increments
}

TEST(AlongCurve, BoundsTheSampledPerturbationOfTheNullVectorAlongTheCurve) {
  // Property: on random steps of random curves (the paper's chain and stiff 5- and 7-dof systems), E(s) = B(s) - B_x
  // sampled on the true curve satisfies the signed bounds: |Hp E b_x| and |Gx^T Hp E b_x| componentwise, |Hp E| and
  // |v_x^T E b_x|, with kappa taken at the largest sampled angle of b(s) to b_x, over boxes widened like certify_step's
  // margins. (Mutation-checked: dropping the progress mismatch kappa fails it; dropping the phases' nonlinearity rho,
  // a mean-value bound, is not detected on these samples, 1 500 steps per system either.)
  const std::vector<std::string> files = {std::string(SPP_SOURCE_DIR) + "/examples/chain5.json",
                                          std::string(SPP_SOURCE_DIR) + "/tests/data/stiff5_spread1e5.json",
                                          std::string(SPP_SOURCE_DIR) + "/tests/data/near_coincident7.json",
                                          std::string(SPP_SOURCE_DIR) + "/tests/data/stiff7_axis_limit.json"};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const std::string& f : files) {
    const ModalForm md(load_system(f));
    const auto eq = make_equations(md, Symmetry::Axial);
    const double T1 = 8.0 * M_PI / (2.0 * md.omega().minCoeff()), T2 = 8.0 * M_PI / (2.0 * md.d().tail(1)(0));
    const std::vector<double> p1 = md.flight_poles(0.0, T1), p2 = md.contact_poles(0.0, T2);
    int checked = 0, tighter = 0;
    for (int trial = 0; trial < 4000 && checked < 120; ++trial) {
      RandomStep st;
      if (!random_step(*eq, T1, T2, p1, p2, -4.0, rng, st)) continue;
      const auto& [c1, d1, c2, d2, k, sa, h, pa, pb] = st;
      // the box of the step, widened on each side by up to 30% (as certify_step's margins for the ends' position
      // errors do), inside the cell
      auto widen = [&](double a, double b, double lo, double hi) {
        const double w = b - a;
        return std::pair{std::max(lo, a - 0.3 * w * u(rng)), std::min(hi, b + 0.3 * w * u(rng))};
      };
      const auto [lo1, hi1] = widen(std::min(pa.t1, pb.t1), std::max(pa.t1, pb.t1), c1, d1);
      const auto [lo2, hi2] = widen(std::min(pa.t2, pb.t2), std::max(pa.t2, pb.t2), c2, d2);
      const search::BorderedForm bf(*eq, lo1, hi1, lo2, hi2);
      const search::PhaseBounds F = search::phase_bounds(bf.flight(), lo1, hi1);
      const search::PhaseBounds C = search::phase_bounds(bf.contact(), lo2, hi2);
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(bf.size()), zeroC = Eigen::VectorXd::Zero(bf.Gx().cols());
      const search::AlongCurve along(bf, F, C, h, hi1 - lo1, hi2 - lo2, zero, zeroC);
      if (!along.valid()) continue;
      // x = the step's start (on the curve), its pseudo-inverse from the full eigenpairs
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(bf.matrix(pa.t1, pa.t2));
      Eigen::Index kz = 0;
      es.eigenvalues().cwiseAbs().minCoeff(&kz);
      Eigen::VectorXd inv = es.eigenvalues().cwiseInverse();
      inv(kz) = 0.0;
      const Eigen::MatrixXd Hp = es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose();
      const Eigen::MatrixXd HpG = Hp * bf.Gx(), GHpG = bf.Gx().transpose() * HpG;
      const Eigen::VectorXd bx = es.eigenvectors().col(kz), yb = bf.Gx().transpose() * bx;
      const Eigen::VectorXd vx = Hp * bf.onset(), yv = bf.Gx().transpose() * vx;
      // samples of the true curve, b oriented continuously from x
      const Eigen::MatrixXd Bx = bf.matrix(pa.t1, pa.t2);
      std::vector<Eigen::MatrixXd> Es;
      double S = 0.0;
      Eigen::VectorXd prev = bx;
      bool ok = true;
      for (int i = 1; i <= 30 && ok; ++i) {
        CurvePoint q;
        ok = curve_point(*eq, c1, d1, c2, d2, sa + h * i / 30.0, k, q);
        if (!ok) break;
        Eigen::VectorXd x = bf.extend(q.b, q.t1, q.t2).normalized();
        if (x.dot(prev) < 0) x = -x;
        prev = x;
        S = std::max(S, std::sqrt(std::max(0.0, 1.0 - std::pow(x.dot(bx), 2))));
        Es.push_back(bf.matrix(q.t1, q.t2) - Bx);
      }
      if (!ok || S > 0.5) continue;
      ++checked;
      const double kap = along.kappa(bx.cwiseAbs(), yb.cwiseAbs(), 1.01 * S + 1e-12);
      const search::AlongCurve::FirstOrder t =
          along.first_order(bx, yb, kap, Hp, HpG, Hp.cwiseAbs(), HpG.cwiseAbs(), GHpG.cwiseAbs());
      const double k2 = along.k2(kap, Hp, HpG), bil = along.bilinear(vx, yv, bx, yb, kap);
      const double unsigned_k1 = (Hp.cwiseAbs() * F.increment.cwiseProduct(bx.cwiseAbs()) +
                                  HpG.cwiseAbs() * C.increment.cwiseProduct(yb.cwiseAbs()))
                                     .norm();
      tighter += t.F.norm() < 0.5 * unsigned_k1 ? 1 : 0;
      const double tol = 1e-9 * (1.0 + Bx.norm()) * (Hp.norm() + 1.0);
      for (const Eigen::MatrixXd& E : Es) {
        const Eigen::VectorXd w = Hp * E * bx;
        for (Eigen::Index i = 0; i < w.size(); ++i) EXPECT_LE(std::abs(w(i)), t.F(i) + tol) << f << " h " << h;
        const Eigen::VectorXd wc = bf.Gx().transpose() * w;
        for (Eigen::Index i = 0; i < wc.size(); ++i) EXPECT_LE(std::abs(wc(i)), t.C(i) + tol) << f << " h " << h;
        EXPECT_LE((Hp * E).norm(), k2 + tol) << f << " h " << h;
        EXPECT_LE(std::abs(vx.dot(E * bx)), bil + tol * (1.0 + vx.norm())) << f << " h " << h;
      }
    }
    EXPECT_GE(checked, 60) << f;
    EXPECT_GE(tighter, 1) << f;  // the signed bound is the one that matters somewhere (stiff modes moving together)
    std::cout << f << ": " << checked << " steps checked, signed first-order bound < half the unsigned on " << tighter
              << "\n";
  }
}

TEST(CertifiedSearch, ProvesAStiffWindowWithTheSameRoots) {
  // A random 4-dof system with stiffness spread 1e5, 8 x 8 quarter periods: with the Davis-Kahan bounds alone, 1 092
  // of its steps could not be proved (they divide the stiff modes' part by the small gap); with the spectral bounds
  // every step is proved, and the 12 SPPs are the default trace's.
  const System s = load_system(std::string(SPP_SOURCE_DIR) + "/tests/data/stiff4_spread1e5.json");
  const SolveResult r = expect_certified_with_default_roots(
      s, window(0.00036243646429314516, 0.057989834286903234, 0.00037129305864861035, 0.05940688938379228));
  EXPECT_EQ(r.solutions.size(), 12u);
}

TEST(CertifiedSearch, MonotoneRunsProveARootWhereTwoCurvesRunSideBySide) {
  // A 10-dof chain with random masses (survey_status.py chains, seed 2), one curve piece: lambda_{k+1} ~ 1e-3 along
  // the curve and g' ~ -3.7e-3 at its root, so the bounds prove g monotone only on steps below ~1e-8, while g's error
  // bound (~2e-10) needs ~1e-7 to be passed: no single step both. Before monotone runs the window ended incomplete
  // (293 steps left to the midpoint check in the whole box); chained, the run from the last point of proved sign to
  // the next proves the one root.
  const SolveResult r = certified_data_window("rchain10_seed2.json", 20.80, 20.83, 1.52, 1.55);
  ASSERT_EQ(r.solutions.size(), 1u);
  EXPECT_NEAR(r.solutions[0].t1(), 20.81549, 1e-5);
  EXPECT_NEAR(r.solutions[0].t2(), 1.53669, 1e-5);
}

TEST(CertifiedSearch, FindsBothRootsOnTwoNearlyCoincidentCurvesOfAStiff7DofSystem) {
  // The situation in which an earlier search missed two real SPPs of a random stiff 7-dof system: two zero curves of
  // det H nearly coincide (two modes of frequencies 10 and 10 (1 + 1e-5) that barely see the contact; lambda_{k+1}
  // ~ 1.6e-3 at the roots) and the onset function is small along both (tests/crosscheck/make_near_coincident.py).
  // Each curve holds one SPP, 3.6e-6 apart in t1; the independent brute force (brute_force.py) finds only the first.
  // The certified search proves the window and returns both, each a root of the paper's own 2n x 2n equations.
  const SolveResult r = certified_data_window("near_coincident7.json", 0.110, 0.113, 0.201, 0.204);
  ASSERT_EQ(r.solutions.size(), 2u);
  const double expected[2][2] = {{0.111823204333, 0.202333000865}, {0.111819649129, 0.202339666461}};
  const ref::PaperForm pf(load_system(std::string(SPP_SOURCE_DIR) + "/tests/data/near_coincident7.json"));
  for (const auto& e : expected) {
    const auto it = std::find_if(r.solutions.begin(), r.solutions.end(), [&](const Solution& x) {
      return std::abs(x.t1() - e[0]) < 1e-10 && std::abs(x.t2() - e[1]) < 1e-10;
    });
    ASSERT_NE(it, r.solutions.end()) << "missing (" << e[0] << ", " << e[1] << ")";
    const auto [sv_rel, onset] = pf.residuals(it->t1(), it->t2());
    EXPECT_LT(sv_rel, 1e-12);
    EXPECT_LT(onset, 1e-10);
  }
}

TEST(CertifiedSearch, ProvesACurveReachingTheAxisLimitPointOfAStiffMode) {
  // A random stiff 7-dof system (survey_status.py stiff7, seed 8): in its first column of cells a curve runs to the
  // axis limit point (0, 4 pi / d_6) of the stiff contact mode d_6 = 433.42, next to the flight mode 433.91. Along it
  // the two stiff entries of H move together and cancel on b; the entrywise bounds added them and proved steps of
  // ~1e-7 only, so the step budget ran out (incomplete, 4 of the 40 systems). The signed bounds (AlongCurve) prove it.
  const System s = load_system(std::string(SPP_SOURCE_DIR) + "/tests/data/stiff7_axis_limit.json");
  SolveOptions o = window(0.0, 0.0037, 0.027, 0.0289935123210162);
  o.compute_return_error = false;
  const SolveResult r = solve(s, o);
  EXPECT_EQ(r.status, SolveStatus::Success) << r.brief_report();
  EXPECT_EQ(r.stats.uncertified_steps, 0);
  EXPECT_GT(r.stats.curve_pieces, 0);
  EXPECT_TRUE(r.solutions.empty());
}

TEST(CertifiedSearch, ProvesCornerCountsNextToClusteredPoleLinesOfA100DofChain) {
  // The 100-dof chain's top frequencies cluster (~1/n^2 apart), so near t = pi/4 its pole lines are 1e-4 apart and
  // every cell corner sits within the pole margin of one: |H| ~ 1e8 there, and H's eigenvalue error bound (8 m eps
  // |H|) could not prove the count at 9 corners of this window (14 in (0, 0.79509] x (0, 0.79519]), even moved:
  // incomplete. The bordered form's count (entries O(1)) proves them all.
  const System s = chain(100, {1.0}, {1.0}, 99, ContactSide::Upper, 1.0);
  SolveOptions o = window(0.785, 0.786, 0.785, 0.786);
  o.compute_return_error = false;
  o.threads = 1;
  const SolveResult r = solve(s, o);
  EXPECT_EQ(r.status, SolveStatus::Success) << r.brief_report();
  EXPECT_EQ(r.stats.uncertified_corners, 0);
  EXPECT_GT(r.stats.curve_pieces, 0);
  o.certify_steps = false;  // the midpoint trace, which takes H's counts as they are, finds no SPP either
  EXPECT_EQ(solve(s, o).solutions.size(), r.solutions.size());
}

TEST(CertifiedSearch, ProvesTheSignOfGAtAnExitPointNextToAContactPoleLine) {
  // The 15-dof chain (spp generate chain --n 15) has an SPP 1e-5 in s past a contact pole line (t1 10.10686, t2
  // 8.73727): the curve leaves the cell below that line with g ~ -1.2e-6. H placed the exit point on the edge (t2
  // fixed) with its bordered-form test taking the slope l1 + l2 instead of the edge's l1, and point() kept H's
  // position error (6.8e-8, from H's eigenvalue error 1.2e-6 next to the pole) although the bordered form's was 4e-14:
  // g's error bound there (8e-6) exceeded |g|, the last step's monotone run was not closed and the fundamental box
  // ended incomplete (1 step). The window (9.8, 10.3] x (8.68, 8.75] around that cell reproduces it; in the wider
  // (9.5, 10.6] x (8.3, 9.1], as in the box, the cell's edge lies where H's error at the exit (6.3e-7) stays below
  // the bordered threshold either way (3.7e-8 in t1): only the retry of that step's end with the bordered estimate
  // proves its sign there.
  const System s = chain(15, {1.0}, {1.0}, 14, ContactSide::Upper, 1.0);
  for (const auto& w : {std::array<double, 4>{9.8, 10.3, 8.68, 8.75}, std::array<double, 4>{9.5, 10.6, 8.3, 9.1}}) {
    SolveOptions o = window(w[0], w[1], w[2], w[3]);
    o.compute_return_error = false;
    o.threads = 1;
    const SolveResult r = expect_certified_with_default_roots(s, o);
    ASSERT_EQ(r.solutions.size(), 1u);
    EXPECT_NEAR(r.solutions[0].t1(), 10.106858, 1e-6);
    EXPECT_NEAR(r.solutions[0].t2(), 8.7372681, 1e-6);
  }
}

TEST(CertifiedSearch, ProvesTheRodWindow) {
  // The paper's rod (§5.3) in (0, 20]^2: 76 SPPs. Certified before the true-point errors, then incomplete (87 steps:
  // the offset of a point next to a pole line entered the Davis-Kahan numerator unweighted), certified again since.
  const System s = load_system(std::string(SPP_SOURCE_DIR) + "/examples/rod4.json");
  SolveOptions o;
  o.t1_max = 20;
  o.t2_max = 20;
  EXPECT_EQ(expect_certified_with_default_roots(s, o).solutions.size(), 76u);
}

TEST(BorderedEigen, ScalingTimeScalesTheBorderedEigenpairAsH) {
  // Bug (583ef30..92db2da): B's border block -1/f scaled like 1 / sqrt(s) when K was scaled by s, while H' scaled like
  // sqrt(s); B's error bound (eps |B|) then swamped the eigenvalue carrying lambda_k(H), and chain5 with K x 1e16 left
  // 26 sign changes unpolished (K x 1e24, 1e-16: not finished in 100 s). Balanced, B at (t1, t2) / sqrt(s) is
  // sqrt(s) times B at (t1, t2): the same eigenvalue over |B|, error over |B|, null vector and slopes over |B|.
  const System s0 = chain5();
  const ModalForm md0(s0);
  const double P = M_PI / (2.0 * md0.omega().maxCoeff());
  for (const double f : {1e-16, 1e16}) {
    const double r = std::sqrt(f);
    const ModalForm md1(System(s0.M(), f * s0.K(), s0.w(), s0.g0()));
    const auto eq0 = make_equations(md0, Symmetry::Axial), eq1 = make_equations(md1, Symmetry::Axial);
    const double t1 = P * (1 + 1e-9), lo2 = 0.3, hi2 = 0.35;
    const search::BorderedForm b0(*eq0, t1, t1, lo2, hi2), b1(*eq1, t1 / r, t1 / r, lo2 / r, hi2 / r);
    ASSERT_GE(b0.bordered(), 1);
    ASSERT_EQ(b0.key(), b1.key());
    for (int k = 0; k < md0.m(); ++k)
      for (const double t2 : {lo2, 0.5 * (lo2 + hi2), hi2}) {
        const search::BorderedEigen e0 = search::bordered_eigenpair(b0, t1, t2, k);
        const search::BorderedEigen e1 = search::bordered_eigenpair(b1, t1 / r, t2 / r, k);
        ASSERT_TRUE(e0.ok && e1.ok) << f << " " << k;
        EXPECT_NEAR(e1.lam / e1.scale, e0.lam / e0.scale, 1e-12) << f << " " << k << " " << t2;
        EXPECT_NEAR(e1.error / e1.scale, e0.error / e0.scale, 1e-20) << f << " " << k;
        EXPECT_NEAR(std::abs(e1.b.dot(e0.b)), 1.0, 1e-9) << f << " " << k;
        EXPECT_NEAR(e1.l1 / (r * e1.scale), e0.l1 / e0.scale, 1e-9 * (1 + e0.l1 / e0.scale)) << f << " " << k;
      }
  }
}
