#include "spp/reduction/craig_bampton.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include "spp/detail/invalid.hpp"
#include "spp/detail/out_of_memory.hpp"

namespace spp {

namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A CHOLMOD factorisation L L^T (simplicial or supernodal, CHOLMOD chooses), quiet: a matrix that is not positive
// definite is reported through info(). Eigen's CholmodAuto keeps a simplicial LDL^T "as is", which factors indefinite
// matrices without complaint (measured: [[1, 3], [3, 1]] succeeds): final_ll = 1 makes both paths L L^T.
struct Cholmod {
  Eigen::CholmodDecomposition<SpMat, Eigen::Lower> llt;
  explicit Cholmod(const SpMat& A) {
    llt.cholmod().print = 0;
    llt.cholmod().final_asis = 0;
    llt.cholmod().final_ll = 1;
    llt.compute(A);
  }
  bool ok() const { return llt.info() == Eigen::Success; }
};

// Spectra's shift-invert operator y = (K_ii - sigma M_ii)^{-1} x at sigma = 0, through the factor of K_ii that psi
// also uses (Spectra's own SymShiftInvert would factor again, with SparseLU).
class CholmodInverse {
 public:
  using Scalar = double;
  explicit CholmodInverse(const Cholmod& f, Eigen::Index n) : f_(f), n_(n) {}
  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }
  void set_shift(double sigma) {
    if (sigma != 0.0) detail::invalid("CholmodInverse: only the shift 0 is factored");
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, n_);
    Eigen::Map<Eigen::VectorXd>(y_out, n_) = f_.llt.solve(x);
  }

 private:
  const Cholmod& f_;
  Eigen::Index n_;
};

// The rows/columns of A without index p: A_ii, and column p without its entry p: A_ip; A_pp.
void partition(const SpMat& A, int p, SpMat& Aii, Eigen::VectorXd& Aip, double& App) {
  const int n = static_cast<int>(A.rows());
  auto idx = [p](int k) { return k < p ? k : k - 1; };
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(A.nonZeros()));
  Aip = Eigen::VectorXd::Zero(n - 1);
  App = 0;
  for (int k = 0; k < A.outerSize(); ++k)
    for (SpMat::InnerIterator it(A, k); it; ++it) {
      const int r = static_cast<int>(it.row()), c = static_cast<int>(it.col());
      if (r == p && c == p)
        App += it.value();
      else if (c == p)
        Aip(idx(r)) += it.value();
      else if (r != p)
        t.emplace_back(idx(r), idx(c), it.value());
    }
  Aii.resize(n - 1, n - 1);
  Aii.setFromTriplets(t.begin(), t.end());
}

std::string fmt(double v, int digits = 6) {
  std::ostringstream os;
  os << std::setprecision(digits) << v;
  return os.str();
}

}  // namespace

void ReductionOptions::validate(int n) const {
  constexpr const char* where = "ReductionOptions";
  if (modes < 1) detail::invalid_option(where, "modes", modes, ">= 1");
  if (n > 0 && modes > n - 1)
    detail::invalid_option(
        where, "modes", modes,
        "<= n - 1 = " + std::to_string(n - 1) + " (the interior dofs of the " + std::to_string(n) + "-dof model)");
  if (!(eigen_tolerance > 0) || !(eigen_tolerance < 1))
    detail::invalid_option(where, "eigen_tolerance", eigen_tolerance, "in (0, 1)");
  if (max_iterations < 1) detail::invalid_option(where, "max_iterations", max_iterations, ">= 1");
  if (dense_interior < 0) detail::invalid_option(where, "dense_interior", dense_interior, ">= 0");
  if (static_cast<long>(expansion_dofs.size()) > kMaxExpansionDofs)
    detail::invalid_option(where, "expansion_dofs.size()", static_cast<double>(expansion_dofs.size()),
                           "at most kMaxExpansionDofs = " + std::to_string(kMaxExpansionDofs));
  for (size_t k = 0; k < expansion_dofs.size(); ++k)
    if (expansion_dofs[k] < 0 || (n > 0 && expansion_dofs[k] >= n))
      detail::invalid_option(where, "expansion_dofs[" + std::to_string(k) + "]", expansion_dofs[k],
                             "a dof from 0 to n - 1" + (n > 0 ? " = " + std::to_string(n - 1) : std::string()));
}

const char* to_string(ReductionResult::Status status) {
  switch (status) {
    case ReductionResult::Status::NotRun: return "not run";
    case ReductionResult::Status::Success: return "success";
    case ReductionResult::Status::EigenNotConverged: return "eigen_not_converged";
  }
  return "?";
}

std::string ReductionResult::brief_report() const {
  std::ostringstream os;
  os << to_string(status);
  if (status == Status::NotRun) return os.str();
  os << ": " << n_full << " dofs -> " << modes + 1 << " (contact coordinate + " << modes << " fixed-interface modes"
     << (dense_eigensolver ? ", dense eigensolver" : "") << ")";
  if (reduced_frequencies.size() > 0) {
    os << "; lowest frequencies";
    for (int k = 0; k < std::min<int>(3, static_cast<int>(reduced_frequencies.size())); ++k)
      os << (k ? ", " : " ") << fmt(reduced_frequencies(k), 8);
  }
  os << "; " << fmt(timings.total_seconds, 3) << " s";
  return os.str();
}

namespace {

// The rows of x = A T q (the header) for the given full dofs: y_j (j != p) is row (psi_j, Phi_j) of the interior
// (index j, or j - 1 past p), y_p = u = q_0; x_j = y_j for j != p and x_p = u - sum_{j != p} (w_j / w_p) y_j.
Eigen::MatrixXd expansion_rows(const std::vector<int>& dofs, const Eigen::VectorXd& w, int p,
                               const Eigen::VectorXd& psi, const Eigen::Ref<const Eigen::MatrixXd>& Phi) {
  const Eigen::Index m = Phi.cols();
  const auto y_row = [&](int j) {
    Eigen::RowVectorXd r(m + 1);
    if (j == p) {
      r.setZero();
      r(0) = 1.0;
      return r;
    }
    const Eigen::Index i = j < p ? j : j - 1;
    r(0) = psi(i);
    r.tail(m) = Phi.row(i);
    return r;
  };
  Eigen::MatrixXd E(static_cast<Eigen::Index>(dofs.size()), m + 1);
  for (size_t r = 0; r < dofs.size(); ++r) {
    const int j = dofs[r];
    Eigen::RowVectorXd row = y_row(j);
    if (j == p)
      for (Eigen::Index k = 0; k < w.size(); ++k)
        if (k != p && w(k) != 0.0) row -= (w(k) / w(p)) * y_row(static_cast<int>(k));
    E.row(static_cast<Eigen::Index>(r)) = row;
  }
  return E;
}

}  // namespace

std::vector<ReductionResult> reduce(const SparseSystem& system, const std::vector<int>& modes,
                                    const ReductionOptions& options) {
  const int n = system.n();
  if (modes.empty()) detail::invalid("reduce: expected at least one number of modes, got none");
  for (size_t k = 0; k < modes.size(); ++k) {
    ReductionOptions o = options;
    o.modes = modes[k];
    o.validate(n);
    if (k > 0 && modes[k] <= modes[k - 1])
      detail::invalid_option(
          "reduce", "modes[" + std::to_string(k) + "]", modes[k],
          "> modes[" + std::to_string(k - 1) + "] = " + std::to_string(modes[k - 1]) + " (increasing)");
  }
  if (n < 2)
    detail::invalid("reduce: the model has " + std::to_string(n) +
                    " dof: nothing to reduce: expected a model of at least 2 dofs, got " + std::to_string(n));
  const auto t_start = Clock::now();
  ReductionTimings shared;

  // the contact coordinate u = w^T x / w_p (the header), and the partition {u} + interior
  auto t0 = Clock::now();
  const Eigen::VectorXd& w = system.w();
  Eigen::Index p_index = 0;
  w.cwiseAbs().maxCoeff(&p_index);
  const int p = static_cast<int>(p_index);
  const double wp = w(p);
  const int w_nonzeros = static_cast<int>((w.array() != 0.0).count());
  SpMat M = system.M(), K = system.K();
  if (w_nonzeros > 1) {
    std::vector<Eigen::Triplet<double>> t;
    for (int j = 0; j < n; ++j) {
      t.emplace_back(j, j, 1.0);
      if (j != p && w(j) != 0.0) t.emplace_back(p, j, -w(j) / wp);
    }
    SpMat A(n, n);
    A.setFromTriplets(t.begin(), t.end());
    const SpMat At = A.transpose();
    M = SpMat(At * system.M() * A);
    K = SpMat(At * system.K() * A);
  }
  SpMat Kii, Mii;
  Eigen::VectorXd Kip, Mip;
  double Kpp = 0, Mpp = 0;
  partition(K, p, Kii, Kip, Kpp);
  partition(M, p, Mii, Mip, Mpp);
  const int ni = n - 1;
  shared.transform_seconds = seconds_since(t0);

  // one factorisation of K_ii for psi and the eigensolver; M's for the check
  t0 = Clock::now();
  const Cholmod Kf(Kii);
  if (!Kf.ok())
    detail::invalid("reduce: K must be positive definite: its Cholesky factorisation (CHOLMOD) with dof " +
                    std::to_string(p + 1) + " clamped failed");
  const Eigen::VectorXd psi = -Kf.llt.solve(Kip);      // static constraint mode
  const double static_stiffness = Kpp + Kip.dot(psi);  // Schur complement of K_ii
  // the Schur complement loses ~cond digits to cancellation: below 1e-12 of K_pp it is rounding, not a stiffness
  constexpr double kStaticStiffnessFloor = 1e-12;
  if (!(static_stiffness > kStaticStiffnessFloor * std::abs(Kpp)))
    detail::invalid("reduce: K must be positive definite: its static stiffness at dof " + std::to_string(p + 1) +
                    " (the Schur complement K_pp - K_pi K_ii^-1 K_ip) is " + fmt(static_stiffness) +
                    " against K_pp = " + fmt(Kpp));
  {
    const Cholmod Mf(M);
    if (!Mf.ok()) detail::invalid("reduce: M must be positive definite: its Cholesky factorisation (CHOLMOD) failed");
  }
  shared.factorization_seconds = seconds_since(t0);

  // the fixed-interface modes of the largest m: the lowest m' of them are those of every smaller m'
  t0 = Clock::now();
  const int m_max = modes.back();
  Eigen::VectorXd lambda;
  Eigen::MatrixXd Phi;
  const bool dense = ni <= options.dense_interior || 2 * m_max > ni;
  bool converged = true;
  int iterations = 0, operations = 0;
  if (dense) {
    Eigen::MatrixXd Kd, Md;
    detail::naming_allocation("reduce: the dense interior eigenproblem, two " + detail::dense_size(ni, ni), [&] {
      Kd = Eigen::MatrixXd(Kii);
      Md = Eigen::MatrixXd(Mii);
    });
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kd, Md);
    if (es.info() != Eigen::Success)
      detail::invalid("reduce: M must be positive definite (the dense eigensolver failed)");
    lambda = es.eigenvalues().head(m_max);
    Phi = es.eigenvectors().leftCols(m_max);  // M_ii-normalised
  } else {
    CholmodInverse op(Kf, ni);
    Spectra::SparseSymMatProd<double> bop(Mii);
    const int ncv = std::min(ni, std::max(2 * m_max + 1, m_max + 20));
    Spectra::SymGEigsShiftSolver<CholmodInverse, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert>
        eigs(op, bop, m_max, ncv, 0.0);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestMagn, options.max_iterations, options.eigen_tolerance,
                 Spectra::SortRule::SmallestAlge);
    iterations = static_cast<int>(eigs.num_iterations());
    operations = static_cast<int>(eigs.num_operations());
    converged = eigs.info() == Spectra::CompInfo::Successful;
    if (converged) {
      lambda = eigs.eigenvalues();
      Phi = eigs.eigenvectors();
      for (int k = 0; k < m_max; ++k) Phi.col(k) /= std::sqrt(Phi.col(k).dot(Mii * Phi.col(k)));  // M_ii-normalised
    }
  }
  shared.eigen_seconds = seconds_since(t0);

  std::vector<ReductionResult> results;
  const Eigen::VectorXd Miipsi = Mii * psi, Kiipsi = Kii * psi;
  for (int m : modes) {
    ReductionResult res;
    res.n_full = n;
    res.modes = m;
    res.contact_dof = p;
    res.w_nonzeros = w_nonzeros;
    res.dense_eigensolver = dense;
    res.static_stiffness = static_stiffness;
    res.eigen_iterations = iterations;
    res.eigen_operations = operations;
    res.timings = shared;
    if (!converged) {
      res.status = ReductionResult::Status::EigenNotConverged;
      res.timings.total_seconds = seconds_since(t_start);
      results.push_back(std::move(res));
      continue;
    }
    // projection: T^T M T and T^T K T by blocks (the header's T)
    t0 = Clock::now();
    const auto Phim = Phi.leftCols(m);
    res.fixed_interface_frequencies = lambda.head(m).cwiseMax(0.0).cwiseSqrt();
    const Eigen::MatrixXd MiiPhi = Mii * Phim, KiiPhi = Kii * Phim;
    Eigen::MatrixXd Mr(m + 1, m + 1), Kr(m + 1, m + 1);
    Mr(0, 0) = Mpp + 2 * Mip.dot(psi) + psi.dot(Miipsi);
    Kr(0, 0) = Kpp + 2 * Kip.dot(psi) + psi.dot(Kiipsi);
    Mr.block(1, 0, m, 1) = Phim.transpose() * (Mip + Miipsi);
    Kr.block(1, 0, m, 1) = Phim.transpose() * (Kip + Kiipsi);
    Mr.block(1, 1, m, m) = Phim.transpose() * MiiPhi;
    Kr.block(1, 1, m, m) = Phim.transpose() * KiiPhi;
    Mr.block(0, 1, 1, m) = Mr.block(1, 0, m, 1).transpose();
    Kr.block(0, 1, 1, m) = Kr.block(1, 0, m, 1).transpose();
    Mr = (0.5 * (Mr + Mr.transpose())).eval();
    Kr = (0.5 * (Kr + Kr.transpose())).eval();
    Eigen::VectorXd wr = Eigen::VectorXd::Zero(m + 1);
    wr(0) = wp;
    const std::string base = system.name().empty() ? "model" : system.name();
    res.reduced.emplace(std::move(Mr), std::move(Kr), std::move(wr), system.g0(), base + "-cb" + std::to_string(m));
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> red(res.reduced->K(), res.reduced->M(),
                                                                  Eigen::EigenvaluesOnly);
    res.reduced_frequencies = red.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    res.expansion = expansion_rows(options.expansion_dofs, w, p, psi, Phim);
    res.timings.projection_seconds = seconds_since(t0);
    res.timings.total_seconds = seconds_since(t_start);
    res.status = ReductionResult::Status::Success;
    results.push_back(std::move(res));
  }
  return results;
}

ReductionResult reduce(const SparseSystem& system, const ReductionOptions& options) {
  options.validate(system.n());
  return std::move(reduce(system, std::vector<int>{options.modes}, options).front());
}

}  // namespace spp
