#pragma once
// Step "evaluate H": the one interface between the search and the linear algebra of H(t1, t2) (modal form §2:
// H = W tan(W t1) + G D tan(D t2) G^T, or H_T for point symmetry). The search asks for inertia, the k-th eigenpair and
// two products; a faster evaluator (e.g. a structured O(m^2) one for large m) plugs in here without touching it.

#include <Eigen/Dense>
#include <memory>

#include "search/loewner_contact.hpp"
#include "spp/detail/tridiagonal.hpp"
#include "spp/modal/equation_set.hpp"

namespace spp::search {

/// H at one point (t1, t2): everything the search reads of it.
class HPoint {
 public:
  virtual ~HPoint() = default;
  virtual int size() const = 0;
  virtual int count_below(double x) const = 0;                        ///< number of eigenvalues < x (Sylvester inertia)
  virtual double eigenvalue(int k) const = 0;                         ///< k-th smallest, 0-based, to ~ eps |H|
  virtual Eigen::VectorXd eigenvector(double lambda) const = 0;       ///< unit vector for eigenvalue(k)
  virtual double norm_bound() const = 0;                              ///< a bound of |H|_2
  virtual Eigen::VectorXd apply(const Eigen::VectorXd& v) const = 0;  ///< H v
  /// x with [[H - lambda I, b], [b^T, 0]] [x; mu] = [rhs; 0] (first-order eigenvector perturbation).
  virtual Eigen::VectorXd solve_bordered(double lambda, const Eigen::VectorXd& b, const Eigen::VectorXd& rhs) const = 0;
  /// Absolute error bound of the computed eigenvalues (backward stable reduction: 8 m eps |H|).
  double eigen_error() const { return 8.0 * size() * std::numeric_limits<double>::epsilon() * norm_bound(); }
};

/// Makes HPoints; counts them (SolveStats::evaluations). One per thread: implementations may cache.
class Evaluator {
 public:
  virtual ~Evaluator() = default;
  virtual std::shared_ptr<const HPoint> at(double t1, double t2) = 0;
  /// Inertia of H compressed to the onset hyperplane, Hc = P^T H P with P an orthonormal basis of c(t2)^perp (c the
  /// equation set's onset_direction): its number of negative eigenvalues, or -1 when an eigenvalue lies within its
  /// error bound of 0. An SPP at (t1, t2) makes Hc singular (H b = 0 with c^T b = 0); Hc grows with t1 and t2 between
  /// pole lines when c is fixed (EquationSet::onset_direction_fixed).
  virtual int onset_inertia(double t1, double t2) = 0;
  long evaluations() const { return evaluations_; }

 protected:
  long evaluations_ = 0;
};

/// Dense: H formed explicitly, Householder tridiagonal form, Sturm counts, bisection and inverse iteration
/// (detail::SymmetricTridiagonal); bordered solves by LU of the (m + 1)-square bordered matrix. Below m = kLapackFrom
/// (128) H's contact part is the product G e(t2) G^T (O(m^3), cached for the last two t2: a cell's corners alternate
/// between two), as it always was, so results there stay bit for bit. From kLapackFrom on, where the modal form allows
/// it (LoewnerContact::applies), H's entries come from its Loewner structure in O(m^2) with an a posteriori bound of
/// their rounding (added to eigen_error), falling back to the product point by point where the bound exceeds 16 m eps
/// |H|; and onset_inertia's inertia from two Bunch–Kaufman LDL^T (detail::count_below_ldlt) instead of a
/// tridiagonalisation.
class DenseEvaluator final : public Evaluator {
 public:
  explicit DenseEvaluator(const EquationSet& equations);
  std::shared_ptr<const HPoint> at(double t1, double t2) override;
  /// Sturm count of the bordered matrix [[H, chat], [chat^T, 0]], chat = c / |c| (inertia of Hc plus one negative
  /// eigenvalue), formed in the modal basis or, when the contact part dominates (next to a contact pole line), in the
  /// contact basis G, and scaled by the size of its diagonal (Sylvester: the inertia is unchanged) so that the error
  /// bound 8 (m + 1) eps |A| stays O(eps) next to a pole line. From m = kLapackFrom on, the counts of A - delta I and
  /// A + delta I by LDL^T, delta = 8 * 8 (m + 1) eps || |A| ||_inf, each exact for a matrix within its a posteriori
  /// bound beta of A (detail::count_below_ldlt): where both betas are below delta, equal counts prove that no
  /// eigenvalue of A lies in [-delta + beta, delta - beta) (Weyl), so A's count at 0 is theirs, and unequal counts put
  /// one within 2 delta of 0 (-1 returned); where a beta reaches delta (element growth), the tridiagonal count decides
  /// as below.
  int onset_inertia(double t1, double t2) override;
  /// Points whose H came from the Loewner structure, and those that fell back to the product (m >= kLapackFrom).
  long structured() const { return structured_; }
  long structured_declined() const { return structured_declined_; }
  /// onset_inertia calls decided by the LDL^T counts, and those that fell back to the tridiagonal form.
  long ldlt_inertias() const { return ldlt_inertias_; }
  long ldlt_declined() const { return ldlt_declined_; }

 private:
  const Eigen::MatrixXd& contact_part(double t2);
  const EquationSet& eq_;
  std::unique_ptr<LoewnerContact> loewner_;  // m >= kLapackFrom and the structure holds
  bool ldlt_ = false;                        // m >= kLapackFrom
  double cached_t2_[2] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  Eigen::MatrixXd C_[2];
  int next_slot_ = 0;
  long structured_ = 0, structured_declined_ = 0, ldlt_inertias_ = 0, ldlt_declined_ = 0;
};

}  // namespace spp::search
