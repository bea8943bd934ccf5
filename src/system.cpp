#include "spp/system.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace spp {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument(what);
}

void check_finite(const Eigen::MatrixXd& A, const char* field) {
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = 0; i < A.rows(); ++i)
      if (!std::isfinite(A(i, j))) {
        std::ostringstream os;
        os << "system: " << field << "[" << i << "][" << j << "] must be finite, got " << A(i, j);
        fail(os.str());
      }
}

// Symmetric (relative tolerance) and positive definite; symmetrised copy returned.
Eigen::MatrixXd check_spd(const Eigen::MatrixXd& A, const char* field) {
  const double scale = A.cwiseAbs().maxCoeff();
  const double asym = (A - A.transpose()).cwiseAbs().maxCoeff();
  if (asym > kSymmetryTolerance * scale) {
    Eigen::Index i = 0, j = 0;
    (A - A.transpose()).cwiseAbs().maxCoeff(&i, &j);
    std::ostringstream os;
    os << "system: " << field << " must be symmetric (relative tolerance " << kSymmetryTolerance << "), got " << field
       << "[" << i << "][" << j << "] = " << A(i, j) << " but " << field << "[" << j << "][" << i << "] = " << A(j, i);
    fail(os.str());
  }
  Eigen::MatrixXd S = 0.5 * (A + A.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S, Eigen::EigenvaluesOnly);
  const double lmin = es.eigenvalues().minCoeff();
  const double lmax = es.eigenvalues().cwiseAbs().maxCoeff();
  // Positive definite with a margin above rounding: an eigenvalue at the level of rounding is singular.
  if (!(lmin > 1e3 * std::numeric_limits<double>::epsilon() * lmax * static_cast<double>(A.rows()))) {
    std::ostringstream os;
    os << "system: " << field << " must be positive definite, got smallest eigenvalue " << lmin << " (largest " << lmax
       << ")";
    fail(os.str());
  }
  return S;
}

}  // namespace

System::System(Eigen::MatrixXd M, Eigen::MatrixXd K, Eigen::VectorXd w, double g0, std::string name)
    : name_(std::move(name)) {
  if (M.rows() == 0) fail("system: M must have at least one row, got an empty matrix");
  if (M.rows() != M.cols()) {
    std::ostringstream os;
    os << "system: M must be square, got " << M.rows() << " x " << M.cols();
    fail(os.str());
  }
  const Eigen::Index n = M.rows();
  if (K.rows() != n || K.cols() != n) {
    std::ostringstream os;
    os << "system: K must be " << n << " x " << n << " like M, got " << K.rows() << " x " << K.cols();
    fail(os.str());
  }
  if (w.size() != n) {
    std::ostringstream os;
    os << "system: w must have " << n << " entries like M, got " << w.size();
    fail(os.str());
  }
  check_finite(M, "M");
  check_finite(K, "K");
  check_finite(w, "w");
  if (!std::isfinite(g0)) {
    std::ostringstream os;
    os << "system: g0 must be finite, got " << g0;
    fail(os.str());
  }
  M_ = check_spd(M, "M");
  K_ = check_spd(K, "K");
  const double nw = w.norm();
  if (!(nw > 0.0)) fail("system: w must be non-zero, got the zero vector");
  w_input_norm_ = nw;
  w_ = w / nw;
  g0_ = g0 / nw;
}

Eigen::MatrixXd System::contact_stiffness() const {
  // eq. (2.4): K~ = (I - w w^T M^{-1} / (w^T M^{-1} w)) K
  const Eigen::VectorXd Minv_w = M_.llt().solve(w_);
  const double wMw = w_.dot(Minv_w);
  return K_ - w_ * (Minv_w.transpose() * K_) / wMw;
}

}  // namespace spp
