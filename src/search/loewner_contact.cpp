#include "search/loewner_contact.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

#include "detail/lapack.hpp"

namespace spp::search {

LoewnerContact::LoewnerContact(const ModalForm& modal) {
  const Eigen::Index m = modal.m();
  if (m < 2 || m > INT_MAX) return;
  const Eigen::VectorXd& w = modal.omega();
  a_ = w.array().square().matrix();
  z_ = modal.z();
  for (Eigen::Index k = 0; k < m; ++k) {
    if (z_(k) == 0.0) return;
    if (k > 0 && !(a_(k) > a_(k - 1))) return;
  }
  // -S = -W^2 + z z^T: dlaed4 wants D ascending (-a reversed), rho > 0 and a unit z; its i-th root (ascending) is
  // -x_j with j = m - i, and DELTA(k') = D(k') - root = x_j - a_k (k' = m - 1 - k).
  const int n = static_cast<int>(m);
  Eigen::VectorXd D(m), Z(m), delta(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    D(k) = -a_(m - 1 - k);
    Z(k) = z_(m - 1 - k);
  }
  const double rho = Z.squaredNorm();
  Z /= std::sqrt(rho);
  r_.resize(m, m);
  r2_.resize(m, m);
  const Eigen::VectorXd& d = modal.d();
  const double eps = std::numeric_limits<double>::epsilon();
  for (int i = 1; i <= n; ++i) {
    double lam = 0.0;
    int info = 0;
    dlaed4_(&n, &i, D.data(), Z.data(), delta.data(), &rho, &lam, &info);
    if (info != 0) return;
    const Eigen::Index j = m - i;
    // the modal form's d_j (dsyevd of S) must be this root to rounding, or the columns would not match
    if (std::abs(-lam - d(j) * d(j)) > 64.0 * static_cast<double>(m) * eps * a_(m - 1)) return;
    for (Eigen::Index kp = 0; kp < m; ++kp) {
      const double dkj = -delta(kp);  // a_k - x_j
      if (dkj == 0.0 || !std::isfinite(dkj)) return;
      const Eigen::Index k = m - 1 - kp;
      r_(k, j) = 1.0 / dkj;
      r2_(k, j) = r_(k, j) * r_(k, j);
    }
  }
  ra_ = r_.cwiseAbs();
  n2_ = r2_.transpose() * z_.array().square().matrix();  // N_j^2 = sum_k z_k^2 / delta_kj^2
  applies_ = true;
}

bool LoewnerContact::contact_part(const Eigen::VectorXd& e, Eigen::MatrixXd& C, double budget) const {
  return form(Eigen::VectorXd::Zero(e.size()), e, C, budget);
}

bool LoewnerContact::form(const Eigen::VectorXd& f, const Eigen::VectorXd& e, Eigen::MatrixXd& H, double budget,
                          double ref) const {
  if (!applies_ || !e.allFinite() || !f.allFinite()) return false;
  const Eigen::Index m = a_.size();
  const double eps = std::numeric_limits<double>::epsilon();
  const double gamma = 2.0 * static_cast<double>(m + 4) * eps;
  const Eigen::VectorXd c = e.cwiseQuotient(n2_), ca = c.cwiseAbs();
  const Eigen::VectorXd phi = r_ * c, dphi = r2_ * c, psi = ra_ * ca, psi2 = r2_ * ca;
  H.resize(m, m);
  Eigen::VectorXd bound(m), rows(m), s = Eigen::VectorXd::Ones(m);
  for (Eigen::Index l = 0; l < m; ++l) {
    const double hll = f(l) + z_(l) * z_(l) * dphi(l);
    H(l, l) = hll;
    if (ref > 0.0) s(l) = 1.0 / std::sqrt(std::max(std::abs(hll), ref));
    bound(l) = (gamma * z_(l) * z_(l) * psi2(l) + 2.0 * eps * (std::abs(hll) + std::abs(f(l)))) * s(l) * s(l);
    rows(l) = std::abs(hll) * s(l) * s(l);
  }
  for (Eigen::Index l = 0; l < m; ++l) {
    for (Eigen::Index k = l + 1; k < m; ++k) {
      const double zz = z_(k) * z_(l), gap = a_(l) - a_(k);
      const double v = zz * (phi(k) - phi(l)) / gap;
      H(k, l) = v;
      H(l, k) = v;
      const double sk = s(k) * s(l);
      const double b = (gamma * std::abs(zz) * (psi(k) + psi(l)) / std::abs(gap) + 3.0 * eps * std::abs(v)) * sk;
      bound(k) += b;
      bound(l) += b;
      rows(k) += std::abs(v) * sk;
      rows(l) += std::abs(v) * sk;
    }
  }
  last_bound_ = bound.maxCoeff();
  last_norm_ = rows.maxCoeff();
  return last_bound_ <= budget * static_cast<double>(m) * eps * last_norm_;
}

}  // namespace spp::search
