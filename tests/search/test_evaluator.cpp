// One evaluation of H (src/search/evaluator.hpp) at large m: the Loewner-structured contact part against the dense
// product, the LDL^T inertia against eigenvalues, and the onset inertia decided by LDL^T against a full
// eigendecomposition of the compressed H (issue 12: a cheaper evaluation that weakens no certificate).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "search/evaluator.hpp"
#include "search/loewner_contact.hpp"
#include "spp/core/generators.hpp"
#include "spp/detail/dense_products.hpp"
#include "spp/detail/symmetric_eigen.hpp"
#include "spp/detail/symmetric_inertia.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/modal/modal.hpp"

using namespace spp;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

System chain_system(int n) {
  return chain(n, {1.0}, {1.0}, n - 1, ContactSide::Upper, 1.0);
}

System random_system(int n) {
  return random_dense(n, static_cast<unsigned>(n));
}

// Q diag(lambda) Q^T with a random orthogonal Q.
Eigen::MatrixXd with_spectrum(const Eigen::VectorXd& lambda, unsigned seed) {
  const Eigen::Index m = lambda.size();
  std::mt19937 rng(seed);
  std::normal_distribution<double> nd;
  Eigen::MatrixXd A(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j) A(i, j) = nd(rng);
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
  Eigen::MatrixXd S = Q * lambda.asDiagonal() * Q.transpose();
  return 0.5 * (S + S.transpose());
}

}  // namespace

// Counts from dsytrf agree with the eigenvalues wherever the nearest eigenvalue is farther than the a posteriori
// bound, on a spread spectrum and on one with a cluster of 20 eigenvalues 1e-10 apart (shifts inside the cluster).
TEST(LdltCount, AgreesWithTheEigenvaluesBeyondItsBound) {
  const int m = 160;
  for (const bool clustered : {false, true}) {
    Eigen::VectorXd lambda(m);
    for (int i = 0; i < m; ++i) lambda(i) = -3.0 + 6.0 * i / (m - 1);
    if (clustered)
      for (int i = 0; i < 20; ++i) lambda(70 + i) = 0.25 + 1e-10 * i;
    std::sort(lambda.data(), lambda.data() + m);
    const Eigen::MatrixXd A = with_spectrum(lambda, clustered ? 7u : 3u);
    int checked = 0;
    for (int i = 0; i + 1 < m; ++i) {
      const double x = 0.5 * (lambda(i) + lambda(i + 1));
      const detail::ShiftedInertia r = detail::count_below_ldlt(A, x);
      ASSERT_TRUE(r.ok);
      EXPECT_GT(r.error_bound, 0.0);
      EXPECT_TRUE(std::isfinite(r.growth));
      if (std::min(x - lambda(i), lambda(i + 1) - x) <= r.error_bound) {
        continue;
      }
      EXPECT_EQ(r.below, i + 1) << "x = " << x << (clustered ? " (clustered)" : "");
      ++checked;
    }
    EXPECT_GT(checked, clustered ? m - 25 : m - 2);
  }
}

// The Loewner-structured contact part against a long double reference G_L diag(e) G_L^T (G_L: the eigenvectors of S
// in long double, the same e): never worse than the dense double product G diag(e) G^T beyond its own a posteriori
// bound, on the chain (top frequencies ~1/m^2 apart) and on a random dense system, away from and next to a contact pole
// line; accepted (its bound within half of 8 m eps |H|) at the ordinary points.
TEST(LoewnerContact, AtLeastAsAccurateAsTheDenseProduct) {
  using LD = long double;
  using MatL = Eigen::Matrix<LD, Eigen::Dynamic, Eigen::Dynamic>;
  for (const bool is_chain : {true, false}) {
    const System s = is_chain ? chain_system(160) : random_system(140);
    const ModalForm md(s);
    const std::unique_ptr<EquationSet> eq = make_equations(md, Symmetry::Axial);
    const search::LoewnerContact lc(md);
    ASSERT_TRUE(lc.applies());
    const Eigen::Index m = md.m();
    MatL S = md.omega().cast<LD>().array().square().matrix().asDiagonal();
    S -= md.z().cast<LD>() * md.z().cast<LD>().transpose();
    const Eigen::SelfAdjointEigenSolver<MatL> es(S);
    const double d_top = md.d().maxCoeff(), pole = 0.5 * 3.14159265358979323846 / d_top;
    int accepted = 0, points = 0;
    for (const double t2 : {0.1, 0.2345, 0.5 * pole, pole * (1 - 1e-6), pole * (1 + 1e-9)}) {
      const Eigen::VectorXd e = eq->contact_eigs(t2);
      const MatL CL = es.eigenvectors() * e.cast<LD>().asDiagonal() * es.eigenvectors().transpose();
      const Eigen::MatrixXd Cd = detail::congruence(md.G(), e);
      Eigen::MatrixXd Cs;
      ASSERT_TRUE(lc.form(Eigen::VectorXd::Zero(m), e, Cs, 1e300));  // any bound: compare all
      EXPECT_LE(static_cast<double>((Cs.cast<LD>() - CL).cwiseAbs().rowwise().sum().maxCoeff()),
                lc.last_bound() + static_cast<double>((Cd.cast<LD>() - CL).cwiseAbs().rowwise().sum().maxCoeff()));
      const double err_s = static_cast<double>((Cs.cast<LD>() - CL).cwiseAbs().maxCoeff());
      const double err_d = static_cast<double>((Cd.cast<LD>() - CL).cwiseAbs().maxCoeff());
      EXPECT_LE(err_s, std::max(2.0 * err_d, lc.last_bound())) << "t2 = " << t2 << (is_chain ? " chain" : " random");
      ++points;
      if (lc.form(Eigen::VectorXd::Zero(m), e, Cs)) ++accepted;
    }
    EXPECT_GE(accepted, 2) << (is_chain ? "chain" : "random") << ": accepted at " << accepted << " of " << points;
  }
}

// onset_inertia at m >= 128 (LDL^T counts, Loewner entries) gives the number of negative eigenvalues of H compressed
// to the onset hyperplane, computed independently by a full eigendecomposition, wherever it does not return -1, at
// points spread over several cells of the 150-mass chain.
TEST(OnsetInertia, ByLdltMatchesTheEigenvaluesOfTheCompressedH) {
  const System s = chain_system(150);
  const ModalForm md(s);
  const std::unique_ptr<EquationSet> eq = make_equations(md, Symmetry::Axial);
  search::DenseEvaluator ev(*eq);
  const Eigen::Index m = md.m();
  const Eigen::VectorXd c = md.z().normalized();
  // orthonormal basis of c^perp: the last m - 1 columns of the Householder Q of c
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(c).householderQ();
  const Eigen::MatrixXd P = Q.rightCols(m - 1);
  int decided = 0;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u1(0.05, 3.0), u2(0.05, 3.0);
  for (int i = 0; i < 40; ++i) {
    const double t1 = u1(rng), t2 = u2(rng);
    const int got = ev.onset_inertia(t1, t2);
    Eigen::MatrixXd H = eq->contact_part(t2);
    H.diagonal() += eq->flight_part(t1);
    const Eigen::MatrixXd Hc = P.transpose() * H * P;
    const detail::SymmetricEigen es = detail::symmetric_eigen(Hc, false);
    ASSERT_TRUE(es.ok);
    const double tol = 1e-9 * es.values.cwiseAbs().maxCoeff();
    const int neg = static_cast<int>((es.values.array() < 0.0).count());
    const bool near_zero = (es.values.array().abs() < tol).any();
    if (got < 0) continue;
    ++decided;
    if (!near_zero) {
      EXPECT_EQ(got, neg) << "t1 = " << t1 << ", t2 = " << t2;
    }
  }
  EXPECT_GE(decided, 30);
  EXPECT_GE(ev.ldlt_inertias(), decided / 2);  // the LDL^T path decided most of them (else it proves nothing here)
}
