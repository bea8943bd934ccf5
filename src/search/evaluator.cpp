#include "search/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "spp/detail/dense_products.hpp"
#include "spp/detail/symmetric_eigen.hpp"
#include "spp/detail/symmetric_inertia.hpp"

namespace spp::search {

namespace {
class DenseHPoint final : public HPoint {
 public:
  // entry_error: a bound of the rounding of H's entries in the 2-norm (0 for the product, whose rounding was never
  // counted); norm_bound() grows by entry_error / (8 m eps), so that eigen_error() = 8 m eps norm_bound() covers it on
  // top of the tridiagonalisation's 8 m eps |H| (still a bound of |H|_2, only looser).
  explicit DenseHPoint(Eigen::MatrixXd H, double entry_error = 0.0) : H_(std::move(H)), T_(H_) {
    if (entry_error > 0.0)
      extra_ = entry_error / (8.0 * static_cast<double>(T_.size()) * std::numeric_limits<double>::epsilon());
  }
  int size() const override { return T_.size(); }
  int count_below(double x) const override { return T_.count_below(x); }
  double eigenvalue(int k) const override { return T_.eigenvalue(k); }
  Eigen::VectorXd eigenvector(double lambda) const override { return T_.eigenvector(lambda); }
  double norm_bound() const override { return extra_ > 0.0 ? T_.norm_bound() + extra_ : T_.norm_bound(); }
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
  double extra_ = 0.0;
};

// The LDL^T shift of onset_inertia, in units of the tridiagonal path's 8 (m + 1) eps |A|: the a posteriori bound of
// a factorisation is 8 (m + 1) eps (|A| + |L||D||L^T|) >= 16 (m + 1) eps |A|, and the Loewner entries' bound may add up
// to 16 m eps |A| (twice 8 m eps |A|), so 8 leaves room for |L||D||L^T| up to ~3 |A|; where growth exceeds that
// (Bunch–Kaufman's |L||D||L^T| reached ~75-150 |A| on random dense matrices shifted into their spectrum), the
// tridiagonal count decides (DenseEvaluator::ldlt_declined counts those).
constexpr double kLdltShift = 8.0;

}  // namespace

DenseEvaluator::DenseEvaluator(const EquationSet& equations) : eq_(equations) {
  if (eq_.modal().m() >= detail::kLapackFrom) {
    ldlt_ = true;
    auto l = std::make_unique<LoewnerContact>(eq_.modal());
    if (l->applies()) loewner_ = std::move(l);
  }
}

const Eigen::MatrixXd& DenseEvaluator::contact_part(double t2) {
  for (int i = 0; i < 2; ++i)
    if (cached_t2_[i] == t2) return C_[i];
  const int i = next_slot_;
  next_slot_ = 1 - next_slot_;
  C_[i] = eq_.contact_part(t2);
  cached_t2_[i] = t2;
  return C_[i];
}

std::shared_ptr<const HPoint> DenseEvaluator::at(double t1, double t2) {
  ++evaluations_;
  if (loewner_) {
    Eigen::MatrixXd H;
    if (loewner_->form(eq_.flight_part(t1), eq_.contact_eigs(t2), H)) {
      ++structured_;
      return std::make_shared<DenseHPoint>(std::move(H), loewner_->last_bound());
    }
    ++structured_declined_;
  }
  Eigen::MatrixXd H = contact_part(t2);
  H.diagonal() += eq_.flight_part(t1);
  return std::make_shared<DenseHPoint>(std::move(H));
}

int DenseEvaluator::onset_inertia(double t1, double t2) {
  ++evaluations_;
  const ModalForm& md = eq_.modal();
  const Eigen::Index m = md.m();
  const Eigen::VectorXd f = eq_.flight_part(t1), e = eq_.contact_eigs(t2);
  const Eigen::VectorXd chat = eq_.onset_direction(t2).normalized();
  // Diagonal congruence: rows with a large diagonal (a pole mode) scaled to O(1) against the non-pole scale.
  const double ref = std::max(md.omega().maxCoeff(), std::numeric_limits<double>::min());
  Eigen::MatrixXd A(m + 1, m + 1);
  double entry_error = 0.0;  // of the scaled A's entries (2-norm), from the Loewner structure's bound
  if (e.cwiseAbs().maxCoeff() <= f.cwiseAbs().maxCoeff()) {  // modal basis
    Eigen::MatrixXd Hm;
    if (loewner_ && loewner_->form(f, e, Hm, 16.0, ref)) {
      A.topLeftCorner(m, m) = Hm;
      entry_error = loewner_->last_bound();
    } else {
      A.topLeftCorner(m, m) = detail::congruence(md.G(), e);
      A.topLeftCorner(m, m).diagonal() += f;
    }
    A.col(m).head(m) = chat;
  } else {  // contact basis: G^T H G = G^T F G + D tan(D t2)
    A.topLeftCorner(m, m) = detail::congruence_transposed(md.G(), f);
    A.topLeftCorner(m, m).diagonal() += e;
    A.col(m).head(m) = md.G().transpose() * chat;
  }
  A.row(m).head(m) = A.col(m).head(m).transpose();
  A(m, m) = 0.0;
  Eigen::VectorXd s(m + 1);
  for (Eigen::Index i = 0; i < m; ++i) s(i) = 1.0 / std::sqrt(std::max(std::abs(A(i, i)), ref));
  s(m) = std::sqrt(ref);
  A = s.asDiagonal() * A * s.asDiagonal();
  const double unit = 8.0 * static_cast<double>(m + 1) * std::numeric_limits<double>::epsilon();
  if (ldlt_) {
    const double delta = kLdltShift * unit * A.cwiseAbs().colwise().sum().maxCoeff();
    const detail::ShiftedInertia lo = detail::count_below_ldlt(A, -delta), hi = detail::count_below_ldlt(A, delta);
    if (lo.ok && hi.ok && lo.error_bound + entry_error < delta && hi.error_bound + entry_error < delta) {
      ++ldlt_inertias_;
      return lo.below == hi.below ? lo.below - 1 : -1;
    }
    ++ldlt_declined_;
  }
  const detail::SymmetricTridiagonal T(A);
  const double err = unit * T.norm_bound() + entry_error;
  const int below = T.count_below(-err);
  if (below != T.count_below(err)) return -1;
  return below - 1;
}

}  // namespace spp::search
