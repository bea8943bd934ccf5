// Craig-Bampton reduction (reduction/craig_bampton.hpp): checked against the full model's dense generalised
// eigenproblem (an independent computation), the exact static stiffness (the Schur complement, or 1 / (w^T K^-1 w) for
// a general w), the dense eigensolver against Spectra's, and the refusals of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "spp/core/generators.hpp"
#include "spp/io.hpp"
#include "spp/reduction/craig_bampton.hpp"

using namespace spp;

namespace {
using SpMat = Eigen::SparseMatrix<double>;

// sqrt of the generalised eigenvalues of the full (dense) model, ascending
Eigen::VectorXd full_frequencies(const SparseSystem& s) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(s.K()), Eigen::MatrixXd(s.M()),
                                                               Eigen::EigenvaluesOnly);
  return es.eigenvalues().cwiseSqrt();
}

ReductionResult reduce_with(const SparseSystem& s, int m, int dense_interior = 400) {
  ReductionOptions o;
  o.modes = m;
  o.dense_interior = dense_interior;
  ReductionResult r = reduce(s, o);
  EXPECT_EQ(r.status, ReductionResult::Status::Success) << r.brief_report();
  return r;
}

// A random sparse SPD model: a banded random K made SPD, a random diagonal-dominant M.
SparseSystem random_model(int n, const Eigen::VectorXd& w, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, n), C = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - 2); j <= i; ++j) {
      B(i, j) = u(gen);
      C(i, j) = 0.3 * u(gen);
    }
  const Eigen::MatrixXd K = B * B.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd M = C * C.transpose() + Eigen::MatrixXd::Identity(n, n);
  return SparseSystem(M.sparseView(), K.sparseView(), w, 0.7, "random");
}
}  // namespace

TEST(CraigBampton, AllInteriorModesReproduceTheFullSpectrum) {
  // with m = n - 1 the basis T spans everything: the reduced model is the full one in other coordinates
  const SparseSystem bar50 = bar(50, BarMass::Consistent, 50, ContactSide::Upper, 1.0);
  const Eigen::VectorXd full = full_frequencies(bar50);
  const ReductionResult r = reduce_with(bar50, 49);
  ASSERT_EQ(r.reduced->n(), 50);
  for (int k = 0; k < 50; ++k) EXPECT_NEAR(r.reduced_frequencies(k) / full(k), 1.0, 1e-10) << k;
}

TEST(CraigBampton, ReducedFrequenciesConvergeFromAboveAsModesGrow) {
  // the bases of increasing m are nested subspaces: Rayleigh-Ritz upper bounds that decrease with m
  const SparseSystem bar50 = bar(50, BarMass::Consistent, 50, ContactSide::Upper, 1.0);
  const Eigen::VectorXd full = full_frequencies(bar50);
  double previous_error = 1e300;
  for (int m : {2, 5, 10, 20, 40}) {
    const ReductionResult r = reduce_with(bar50, m);
    for (int k = 0; k < std::min(m + 1, 5); ++k) EXPECT_GE(r.reduced_frequencies(k), full(k) * (1 - 1e-12));
    const double error = r.reduced_frequencies(0) / full(0) - 1;
    EXPECT_LT(error, previous_error) << "m = " << m;
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-6);  // m = 40: the lowest frequency within 1e-6 relative
}

TEST(CraigBampton, StaticStiffnessIsTheSchurComplement) {
  // fixed-free bar of unit length and EA = 1: the tip's static stiffness is EA / L = 1 for every mesh
  const SparseSystem b = bar(200, BarMass::Lumped, 200, ContactSide::Upper, 1.0);
  const ReductionResult r = reduce_with(b, 5);
  EXPECT_NEAR(r.static_stiffness, 1.0, 1e-10);
  EXPECT_NEAR(r.reduced->K()(0, 0), 1.0, 1e-10);  // the reduced model keeps it exactly
  // at an interior node c of the bar: 1 / (K^-1)_cc = 1 / x_c (a unit load at c moves c by its distance to the root)
  const SparseSystem mid = bar(200, BarMass::Consistent, 50, ContactSide::Lower, 1.0);
  const ReductionResult rm = reduce_with(mid, 5);
  EXPECT_EQ(rm.contact_dof, 49);
  EXPECT_NEAR(rm.static_stiffness, 4.0, 1e-9);
  EXPECT_NEAR(rm.reduced->K()(0, 0), 4.0, 1e-9);
  // the fixed-interface block is diagonal (lambda) and decoupled from u, to rounding
  const Eigen::MatrixXd& K = rm.reduced->K();
  for (int i = 1; i < 6; ++i) {
    EXPECT_NEAR(K(0, i), 0.0, 1e-9 * K.norm());
    EXPECT_NEAR(K(i, i), std::pow(rm.fixed_interface_frequencies(i - 1), 2), 1e-9 * K(i, i));
  }
}

TEST(CraigBampton, GeneralContactDirectionByAChangeOfCoordinates) {
  // w with three non-zeros: u = w^T x / w_p; its static stiffness is w_p^2 / (w^T K^-1 w) (minimum of x^T K x / 2
  // subject to w^T x = w_p u), and with every interior mode the spectrum is the full one.
  const int n = 30;
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  w(3) = 0.5;
  w(17) = -2.0;
  w(29) = 1.0;
  const SparseSystem s = random_model(n, w, 7);
  const ReductionResult r = reduce_with(s, n - 1);
  EXPECT_EQ(r.contact_dof, 17);
  EXPECT_EQ(r.w_nonzeros, 3);
  const Eigen::MatrixXd Kd(s.K());
  const double exact = 4.0 / w.dot(Kd.ldlt().solve(w));
  EXPECT_NEAR(r.static_stiffness / exact, 1.0, 1e-10);
  const Eigen::VectorXd full = full_frequencies(s);
  for (int k = 0; k < n; ++k) EXPECT_NEAR(r.reduced_frequencies(k) / full(k), 1.0, 1e-9) << k;
  // the reduced constraint: w = w_p e_0 normalised to -e_0 (w_p < 0), g0 divided by |w_p|
  EXPECT_EQ(r.reduced->w()(0), -1.0);
  EXPECT_EQ(r.reduced->w().tail(n - 1).norm(), 0.0);
  EXPECT_DOUBLE_EQ(r.reduced->g0(), 0.7 / 2.0);
}

TEST(CraigBampton, SpectraAgreesWithTheDenseEigensolver) {
  const SparseSystem b = bar(600, BarMass::Consistent, 600, ContactSide::Upper, 1.0);
  const ReductionResult sparse = reduce_with(b, 12, 0), dense = reduce_with(b, 12, 5000);
  EXPECT_FALSE(sparse.dense_eigensolver);
  EXPECT_TRUE(dense.dense_eigensolver);
  EXPECT_GT(sparse.eigen_operations, 0);
  for (int k = 0; k < 12; ++k) {
    EXPECT_NEAR(sparse.fixed_interface_frequencies(k) / dense.fixed_interface_frequencies(k), 1.0, 1e-10) << k;
    EXPECT_NEAR(sparse.reduced_frequencies(k) / dense.reduced_frequencies(k), 1.0, 1e-10) << k;
  }
}

TEST(CraigBampton, ASequenceOfModesEqualsSeparateReductions) {
  // the convergence study shares one eigensolve for the largest m: the same reduced models as one reduce() per m
  const SparseSystem b = bar(800, BarMass::Consistent, 800, ContactSide::Upper, 1.0);
  const std::vector<ReductionResult> seq = reduce(b, std::vector<int>{3, 8, 16});
  ASSERT_EQ(seq.size(), 3u);
  for (const ReductionResult& r : seq) {
    ASSERT_EQ(r.status, ReductionResult::Status::Success);
    const ReductionResult one = reduce_with(b, r.modes);
    ASSERT_EQ(r.reduced->n(), r.modes + 1);
    for (int k = 0; k <= r.modes; ++k)
      EXPECT_NEAR(r.reduced_frequencies(k) / one.reduced_frequencies(k), 1.0, 1e-10) << r.modes << " " << k;
    EXPECT_NEAR(r.reduced->K()(0, 0), one.reduced->K()(0, 0), 1e-12);
  }
  EXPECT_THROW(reduce(b, std::vector<int>{8, 3}), std::invalid_argument);
  EXPECT_THROW(reduce(b, std::vector<int>{}), std::invalid_argument);
}

TEST(CraigBampton, ReducedModelIsASystemFile) {
  const SparseSystem b = bar(300, BarMass::Consistent, 300, ContactSide::Upper, 0.5);
  const ReductionResult r = reduce_with(b, 6);
  const std::string path = testing::TempDir() + "spp_reduced_bar.json";
  write_file_atomic(path, system_json(*r.reduced));
  const System back = load_system(path);
  EXPECT_EQ((back.M() - r.reduced->M()).norm(), 0.0);
  EXPECT_EQ((back.K() - r.reduced->K()).norm(), 0.0);
  EXPECT_EQ(back.g0(), 0.5);
  EXPECT_EQ(back.w()(0), -1.0);
  EXPECT_NE(r.brief_report().find("success: 300 dofs -> 7"), std::string::npos) << r.brief_report();
}

TEST(CraigBampton, BadInputIsRefusedNamingWhy) {
  const SparseSystem b = bar(20, BarMass::Consistent, 20, ContactSide::Upper, 1.0);
  auto expect_refused = [](auto&& f, const std::string& part) {
    try {
      f();
      ADD_FAILURE() << "no error; expected \"" << part << "\"";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expect_refused([&] { reduce(b, ReductionOptions{0}); }, "modes must be >= 1, got 0");
  expect_refused([&] { reduce(b, ReductionOptions{20}); }, "modes must be <= n - 1 = 19");
  // K with positive diagonal but indefinite: [[1, 2], [2, 1]] in a 3-dof model
  Eigen::MatrixXd K(3, 3), M = Eigen::MatrixXd::Identity(3, 3);
  K << 1, 2, 0, 2, 1, 0, 0, 0, 1;
  const Eigen::Vector3d w(0, 0, 1);
  expect_refused([&] { reduce(SparseSystem(M.sparseView(), K.sparseView(), w, 1.0), ReductionOptions{1}); },
                 "K must be positive definite");
  // indefinite through the contact dof: the clamped K_ii is fine, the Schur complement is not
  K << 1, 0, 2, 0, 1, 0, 2, 0, 1;
  expect_refused([&] { reduce(SparseSystem(M.sparseView(), K.sparseView(), w, 1.0), ReductionOptions{1}); },
                 "K must be positive definite: its static stiffness");
  K = Eigen::MatrixXd::Identity(3, 3);
  Eigen::MatrixXd Mbad = M;
  Mbad(0, 1) = Mbad(1, 0) = 3;
  expect_refused([&] { reduce(SparseSystem(Mbad.sparseView(), K.sparseView(), w, 1.0), ReductionOptions{1}); },
                 "M must be positive definite");
  expect_refused([&] { SparseSystem(M.sparseView(), K.sparseView(), Eigen::Vector3d::Zero(), 1.0); },
                 "|w| must be positive");
  Eigen::MatrixXd Kasym = K;
  Kasym(0, 1) = 0.5;
  expect_refused([&] { SparseSystem(M.sparseView(), Kasym.sparseView(), w, 1.0); }, "K must be symmetric");
  expect_refused([&] { SparseSystem(M.sparseView(), K.sparseView(), Eigen::Vector2d(1, 0), 1.0); },
                 "w must have n = 3 entries, got 2");
  Eigen::MatrixXd Kneg = K;
  Kneg(2, 2) = -1;
  expect_refused([&] { SparseSystem(M.sparseView(), Kneg.sparseView(), w, 1.0); }, "K(3, 3) = -1");
}

TEST(CraigBampton, IndefiniteMassIsNotFactoredAsLdlt) {
  // Eigen's CholmodAuto keeps CHOLMOD's simplicial L D L^T, which factors an indefinite matrix without complaint: M
  // with the block [[1, 3], [3, 1]] (eigenvalue -2) was accepted and reduced. The factorisations are now L L^T.
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(4, 4), K = 2 * Eigen::MatrixXd::Identity(4, 4);
  M(0, 1) = M(1, 0) = 3;
  const SparseSystem s(M.sparseView(), K.sparseView(), Eigen::Vector4d(0, 0, 0, 1), 1.0);
  EXPECT_THROW(reduce(s, ReductionOptions{2}), std::invalid_argument);
}

TEST(CraigBampton, GeneralContactDirectionThroughSpectra) {
  // the change of coordinates on a model large enough for Spectra: w on the last two nodes of a 600-element bar
  const SparseSystem b = bar(600, BarMass::Consistent, 600, ContactSide::Upper, 1.0);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(600);
  w(598) = 0.5;
  w(599) = -1.0;
  const SparseSystem s(b.M(), b.K(), w, 1.0);
  const ReductionResult sparse = reduce_with(s, 10, 0), dense = reduce_with(s, 10, 5000);
  EXPECT_FALSE(sparse.dense_eigensolver);
  for (int k = 0; k < 11; ++k)
    EXPECT_NEAR(sparse.reduced_frequencies(k) / dense.reduced_frequencies(k), 1.0, 1e-10) << k;
  const Eigen::MatrixXd Kd(s.K());
  EXPECT_NEAR(sparse.static_stiffness * w.dot(Kd.ldlt().solve(w)), 1.0, 1e-9);  // w_p^2 = 1
}

TEST(CraigBampton, DefaultResultSaysNotRun) {
  const ReductionResult r;
  EXPECT_EQ(r.status, ReductionResult::Status::NotRun);
  EXPECT_EQ(r.brief_report(), "not run");
  EXPECT_FALSE(r.reduced.has_value());
}

// Issue 13: the finite-element picture of a reduced model (spp reduce --layout) needs the displacements of the full
// model's dofs from q: the rows of the reduction basis A T. With every dof listed they are the basis itself: its
// projections give the reduced M and K, and the constraint sees u = q_0 only (w^T A T = w_p e_0).
TEST(CraigBampton, ExpansionRowsAreTheReductionBasis) {
  const int n = 30;
  for (const bool general : {false, true}) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
    w(17) = -2.0;
    if (general) w(3) = 0.5, w(29) = 1.0;
    const SparseSystem s = random_model(n, w, 11);
    ReductionOptions o;
    o.modes = 6;
    for (int j = n - 1; j >= 0; --j) o.expansion_dofs.push_back(j);  // any order
    const ReductionResult r = reduce(s, o);
    ASSERT_EQ(r.expansion.rows(), n);
    ASSERT_EQ(r.expansion.cols(), 7);
    Eigen::MatrixXd E(n, 7);
    for (int j = 0; j < n; ++j) E.row(o.expansion_dofs[j]) = r.expansion.row(j);
    const Eigen::MatrixXd Md(s.M()), Kd(s.K());
    EXPECT_LT((E.transpose() * Md * E - r.reduced->M()).norm(), 1e-10 * r.reduced->M().norm()) << general;
    EXPECT_LT((E.transpose() * Kd * E - r.reduced->K()).norm(), 1e-10 * r.reduced->K().norm()) << general;
    Eigen::RowVectorXd wt = w.transpose() * E, expected = Eigen::RowVectorXd::Zero(7);
    expected(0) = -2.0;
    EXPECT_LT((wt - expected).norm(), 1e-12) << general;
  }
  ReductionOptions bad;
  bad.expansion_dofs = {0, 30};
  EXPECT_THROW(reduce(random_model(n, Eigen::VectorXd::Unit(n, 2), 1), bad), std::invalid_argument);
}
