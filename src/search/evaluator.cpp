#include "search/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spp::search {

namespace {

class DenseHPoint final : public HPoint {
 public:
  explicit DenseHPoint(Eigen::MatrixXd H) : H_(std::move(H)), T_(H_) {}
  int size() const override { return T_.size(); }
  int count_below(double x) const override { return T_.count_below(x); }
  double eigenvalue(int k) const override { return T_.eigenvalue(k); }
  Eigen::VectorXd eigenvector(double lambda) const override { return T_.eigenvector(lambda); }
  double norm_bound() const override { return T_.norm_bound(); }
  Eigen::VectorXd apply(const Eigen::VectorXd& v) const override { return H_ * v; }
  Eigen::VectorXd solve_bordered(double lambda, const Eigen::VectorXd& b, const Eigen::VectorXd& rhs) const override {
    const Eigen::Index m = H_.rows();
    Eigen::MatrixXd B(m + 1, m + 1);
    B.topLeftCorner(m, m) = H_;
    B.topLeftCorner(m, m).diagonal().array() -= lambda;
    B.col(m).head(m) = b;
    B.row(m).head(m) = b.transpose();
    B(m, m) = 0.0;
    Eigen::VectorXd r(m + 1);
    r.head(m) = rhs;
    r(m) = 0.0;
    return B.partialPivLu().solve(r).head(m);
  }

 private:
  Eigen::MatrixXd H_;
  detail::SymmetricTridiagonal T_;
};

}  // namespace

std::shared_ptr<const HPoint> DenseEvaluator::at(double t1, double t2) {
  if (t2 != cached_t2_) {
    C_ = md_.contact_part(t2, sym_);
    cached_t2_ = t2;
  }
  Eigen::MatrixXd H = C_;
  H.diagonal() += md_.flight_part(t1, sym_);
  ++evaluations_;
  return std::make_shared<DenseHPoint>(std::move(H));
}

DenseEvaluator::Balanced DenseEvaluator::balanced(double t1, double t2, bool bordered) const {
  const Eigen::Index m = md_.m(), size = bordered ? m + 1 : m;
  const Eigen::VectorXd f = md_.flight_part(t1, sym_);
  const Eigen::VectorXd e = md_.contact_eigs(t2, sym_);
  const Eigen::VectorXd zhat = md_.z().normalized();
  Balanced out;
  out.A.resize(size, size);
  out.contact_basis = e.cwiseAbs().maxCoeff() > f.cwiseAbs().maxCoeff();
  auto A = out.A.topLeftCorner(m, m);
  if (!out.contact_basis) {  // modal basis
    A = md_.G() * e.asDiagonal() * md_.G().transpose();
    A.diagonal() += f;
  } else {  // contact basis: G^T H G = G^T F G + D tan(D t2)
    A = md_.G().transpose() * f.asDiagonal() * md_.G();
    A.diagonal() += e;
  }
  // Non-pole scale of the diagonal: the frequencies (axial, w tan(w t) ~ w) or their inverses (point, tan(w t) / w).
  const double ref = std::max(sym_ == Symmetry::Axial ? md_.omega().maxCoeff() : 1.0 / md_.omega().minCoeff(),
                              std::numeric_limits<double>::min());
  out.scale.resize(size);
  for (Eigen::Index i = 0; i < m; ++i) out.scale(i) = 1.0 / std::sqrt(std::max(std::abs(A(i, i)), ref));
  if (bordered) {
    out.A.col(m).head(m) = out.contact_basis ? Eigen::VectorXd(md_.G().transpose() * zhat) : zhat;
    out.A.row(m).head(m) = out.A.col(m).head(m).transpose();
    out.A(m, m) = 0.0;
    out.scale(m) = std::sqrt(ref);
  }
  out.A = out.scale.asDiagonal() * out.A * out.scale.asDiagonal();
  return out;
}

int DenseEvaluator::onset_inertia(double t1, double t2) {
  ++evaluations_;
  const detail::SymmetricTridiagonal T(balanced(t1, t2, true).A);
  const double err = 8.0 * static_cast<double>(md_.m() + 1) * std::numeric_limits<double>::epsilon() * T.norm_bound();
  const int below = T.count_below(-err);
  if (below != T.count_below(err)) return -1;
  return below - 1;
}

Eigen::VectorXd DenseEvaluator::balanced_eigenvector(double t1, double t2, int k) {
  ++evaluations_;
  const Balanced bal = balanced(t1, t2, false);
  const detail::SymmetricTridiagonal T(bal.A);
  Eigen::VectorXd b = bal.scale.cwiseProduct(T.eigenvector(T.eigenvalue(k)));
  if (bal.contact_basis) b = md_.G() * b;
  return b.normalized();
}

}  // namespace spp::search
