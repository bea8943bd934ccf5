#include "search/evaluator.hpp"

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

}  // namespace spp::search
