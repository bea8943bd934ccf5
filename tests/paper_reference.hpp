#pragma once
// The paper's own formulation, written independently of the modal form, for cross-checks in tests:
//   K1 = M^{-1/2} K M^{-1/2} = L1^2,  J1 K1 = L2^2 with J1 = I - w1 w1^T / |w1|^2, w1 = M^{-1/2} w (§3.1-3.2),
//   R2(t1,t2) = [[L1 sin(t1 L1), cos(t1 L1)], [-L2 sin(t2 L2), cos(t2 L2)]]   (eq. 5.1a),
//   condition (5.1b): w^T M^{-1} K M^{-1/2} y(0) = 0 with y(0) the first half of a null vector of R2.

#include <Eigen/Dense>
#include <complex>
#include <random>

#include "spp/core/system.hpp"

namespace spp::ref {

class PaperForm {
 public:
  explicit PaperForm(const System& s) : n_(s.n()) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> em(s.M());
    Mih_ = em.eigenvectors() * em.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() *
           em.eigenvectors().transpose();  // M^{-1/2}
    const Eigen::MatrixXd K1 = Mih_ * s.K() * Mih_;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> e1(0.5 * (K1 + K1.transpose()));
    Q1_ = e1.eigenvectors();
    mu1_ = e1.eigenvalues();
    const Eigen::VectorXd w1 = Mih_ * s.w();
    const Eigen::MatrixXd J1 = Eigen::MatrixXd::Identity(n_, n_) - w1 * w1.transpose() / w1.squaredNorm();
    Eigen::EigenSolver<Eigen::MatrixXd> e2(J1 * K1);  // diagonalisable, real non-negative spectrum (§3.2)
    V2_ = e2.eigenvectors().real();
    mu2_ = e2.eigenvalues().real().cwiseMax(0.0);
    V2inv_ = V2_.inverse();
    v_ = (s.w().transpose() * s.M().llt().solve(s.K()) * Mih_).transpose();  // w^T M^-1 K M^-1/2
  }

  Eigen::MatrixXd R2(double t1, double t2) const {
    Eigen::MatrixXd R(2 * n_, 2 * n_);
    R.topLeftCorner(n_, n_) = f1([t1](double r) { return r * std::sin(t1 * r); });
    R.topRightCorner(n_, n_) = f1([t1](double r) { return std::cos(t1 * r); });
    R.bottomLeftCorner(n_, n_) = -f2([t2](double r) { return r * std::sin(t2 * r); });
    R.bottomRightCorner(n_, n_) = f2([t2](double r) { return std::cos(t2 * r); });
    return R;
  }

  /// Relative smallest singular value of R2 and the relative (5.1b) residual of its null vector.
  std::pair<double, double> residuals(double t1, double t2) const {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(R2(t1, t2), Eigen::ComputeFullV);
    const auto& sv = svd.singularValues();
    const Eigen::VectorXd y0 = svd.matrixV().col(2 * n_ - 1).head(n_);
    return {sv(2 * n_ - 1) / sv(0), std::abs(v_.dot(y0)) / (v_.norm() * y0.norm())};
  }

  /// det R2 and v . y for y the first half of columns 0 and 1 of adj(R2): all three are entire in (t1, t2).
  /// (R2 adj(R2) = det R2 I, so the columns of adj(R2) span the kernel when det R2 = 0; the paper's
  /// "columns of adj(R2)^T" before eq. 4.3 are left null vectors unless adj denotes the cofactor matrix.)
  Eigen::Vector3d det_and_conditions(double t1, double t2) const {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(R2(t1, t2));
    const double det = lu.determinant();
    const Eigen::MatrixXd inv = lu.inverse();
    return {det, det * v_.dot(inv.col(0).head(n_)), det * v_.dot(inv.col(1).head(n_))};
  }

 private:
  template <class F>
  Eigen::MatrixXd f1(F f) const {
    Eigen::VectorXd d(n_);
    for (int k = 0; k < n_; ++k) d(k) = f(std::sqrt(std::max(mu1_(k), 0.0)));
    return Q1_ * d.asDiagonal() * Q1_.transpose();
  }
  template <class F>
  Eigen::MatrixXd f2(F f) const {
    Eigen::VectorXd d(n_);
    for (int k = 0; k < n_; ++k) d(k) = f(std::sqrt(mu2_(k)));
    return V2_ * d.asDiagonal() * V2inv_;
  }
  int n_;
  Eigen::MatrixXd Mih_, Q1_, V2_, V2inv_;
  Eigen::VectorXd mu1_, mu2_, v_;
};

/// Random SPD matrix with a controlled spread of eigenvalues.
template <class Rng>
Eigen::MatrixXd random_spd(int n, Rng& rng, double lo = 0.5, double hi = 3.0) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(lo, hi);
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = u(rng);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::MatrixXd Q = qr.householderQ();
  Eigen::VectorXd ev(n);
  for (int i = 0; i < n; ++i) ev(i) = e(rng);
  return Q * ev.asDiagonal() * Q.transpose();
}

/// Random system of n dofs with gap g0: contact direction w ~ N(0, 1), then K (eigenvalues in [k_lo, k_hi]), then M
/// (in [0.5, 3]) random SPD (that order: the systems the modal and completeness tests were checked on).
inline System random_system(int n, unsigned seed, double g0 = 0.7, double k_lo = 0.5, double k_hi = 3.0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> nd;
  Eigen::VectorXd w(n);
  for (int i = 0; i < n; ++i) w(i) = nd(rng);
  const Eigen::MatrixXd K = random_spd(n, rng, k_lo, k_hi);
  const Eigen::MatrixXd M = random_spd(n, rng);
  return System(M, K, w, g0);
}

}  // namespace spp::ref
