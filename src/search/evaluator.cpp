#include "search/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "spp/detail/dense_products.hpp"

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
    C_ = eq_.contact_part(t2);
    cached_t2_ = t2;
  }
  Eigen::MatrixXd H = C_;
  H.diagonal() += eq_.flight_part(t1);
  ++evaluations_;
  return std::make_shared<DenseHPoint>(std::move(H));
}

int DenseEvaluator::onset_inertia(double t1, double t2) {
  ++evaluations_;
  const ModalForm& md = eq_.modal();
  const Eigen::Index m = md.m();
  const Eigen::VectorXd f = eq_.flight_part(t1), e = eq_.contact_eigs(t2);
  const Eigen::VectorXd chat = eq_.onset_direction(t2).normalized();
  Eigen::MatrixXd A(m + 1, m + 1);
  if (e.cwiseAbs().maxCoeff() <= f.cwiseAbs().maxCoeff()) {  // modal basis
    A.topLeftCorner(m, m) = detail::congruence(md.G(), e);
    A.topLeftCorner(m, m).diagonal() += f;
    A.col(m).head(m) = chat;
  } else {  // contact basis: G^T H G = G^T F G + D tan(D t2)
    A.topLeftCorner(m, m) = detail::congruence_transposed(md.G(), f);
    A.topLeftCorner(m, m).diagonal() += e;
    A.col(m).head(m) = md.G().transpose() * chat;
  }
  A.row(m).head(m) = A.col(m).head(m).transpose();
  A(m, m) = 0.0;
  // Diagonal congruence: rows with a large diagonal (a pole mode) scaled to O(1) against the non-pole scale.
  const double ref = std::max(md.omega().maxCoeff(), std::numeric_limits<double>::min());
  Eigen::VectorXd s(m + 1);
  for (Eigen::Index i = 0; i < m; ++i) s(i) = 1.0 / std::sqrt(std::max(std::abs(A(i, i)), ref));
  s(m) = std::sqrt(ref);
  A = s.asDiagonal() * A * s.asDiagonal();
  const detail::SymmetricTridiagonal T(A);
  const double err = 8.0 * static_cast<double>(m + 1) * std::numeric_limits<double>::epsilon() * T.norm_bound();
  const int below = T.count_below(-err);
  if (below != T.count_below(err)) return -1;
  return below - 1;
}

}  // namespace spp::search
