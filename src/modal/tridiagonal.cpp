#include "spp/detail/tridiagonal.hpp"

#include <climits>
#include <cmath>
#include <limits>

#include "detail/lapack.hpp"
#include "spp/detail/symmetric_eigen.hpp"

namespace spp::detail {

namespace {

constexpr Eigen::Index kTwoHalvingsFrom = 12;  // eigenvalue(): size from which two halvings per pass pay

// dsytrd with uplo = 'L' (reflectors below the sub-diagonal, as Eigen's; blocked, level-3 BLAS); false if LAPACK
// reports an error.
bool lapack_tridiagonalize(Eigen::MatrixXd& a, Eigen::VectorXd& diag, Eigen::VectorXd& sub, Eigen::VectorXd& tau) {
  const int n = static_cast<int>(a.rows());
  const char uplo = 'L';
  return call_with_workspace([&](double* work, const int* lwork, int*, const int*, int* info) {
    dsytrd_(&uplo, &n, a.data(), &n, diag.data(), sub.data(), tau.data(), work, lwork, info, 1);
  });
}

}  // namespace

SymmetricTridiagonal::SymmetricTridiagonal(const Eigen::MatrixXd& A) {
  const Eigen::Index m = A.rows();
  householder_ = A;
  hcoeffs_.resize(m > 1 ? m - 1 : 0);
  a_.resize(m);
  b_.resize(m > 1 ? m - 1 : 0);
  lapack_ = m >= kLapackFrom && m <= INT_MAX && lapack_tridiagonalize(householder_, a_, b_, hcoeffs_);
  if (!lapack_ && m > 1) {
    householder_ = A;  // (a failed dsytrd may have written into it)
    Eigen::internal::tridiagonalization_inplace(householder_, a_, b_, hcoeffs_, false);
  } else if (m == 1) {
    a_(0) = A(0, 0);
  }
  double bmax2 = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    const double r = (i > 0 ? std::abs(b_(i - 1)) : 0.0) + (i + 1 < m ? std::abs(b_(i)) : 0.0);
    bound_ = std::max(bound_, std::abs(a_(i)) + r);
    if (i + 1 < m) bmax2 = std::max(bmax2, b_(i) * b_(i));
  }
  pivmin_ = std::numeric_limits<double>::min() * std::max(1.0, bmax2);
}

int SymmetricTridiagonal::count_below(double x) const {
  const Eigen::Index m = a_.size();
  int count = 0;
  double q = a_(0) - x;
  if (std::abs(q) < pivmin_) q = -pivmin_;
  count += q < 0;
  for (Eigen::Index i = 1; i < m; ++i) {
    q = a_(i) - x - b_(i - 1) * b_(i - 1) / q;
    if (std::abs(q) < pivmin_) q = -pivmin_;
    count += q < 0;
  }
  return count;
}

// Sturm counts below x0, x1, x2 in one pass: the three recurrences are count_below's, operation for operation (so
// each count equals count_below's), interleaved so that their divisions overlap in the pipeline instead of waiting
// on each other (the recurrence is a chain of dependent divisions).
void SymmetricTridiagonal::count_below3(const double x[3], int count[3]) const {
  const Eigen::Index m = a_.size();
  double q[3];
  for (int j = 0; j < 3; ++j) {
    q[j] = a_(0) - x[j];
    if (std::abs(q[j]) < pivmin_) q[j] = -pivmin_;
    count[j] = q[j] < 0;
  }
  for (Eigen::Index i = 1; i < m; ++i) {
    const double bb = b_(i - 1) * b_(i - 1);
    for (int j = 0; j < 3; ++j) {
      q[j] = a_(i) - x[j] - bb / q[j];
      if (std::abs(q[j]) < pivmin_) q[j] = -pivmin_;
      count[j] += q[j] < 0;
    }
  }
}

// Bisection on the Sturm count, two halvings per pass: the midpoint mid of [lo, hi] and the midpoints of both halves
// are counted together (count_below3), and the two halvings then take exactly the steps, with the same midpoints
// and the same stopping tests, that one-at-a-time bisection takes: the result is bit for bit that of
// eigenvalue_by_bisection, at about half the latency (2 x 26 passes instead of 52 dependent ones). Below
// kTwoHalvingsFrom the plain bisection is as fast or faster (bench_linalg Bisection/m vs SppEigenvalue/m, CPU time:
// m = 5 0.59 vs 0.71 us, m = 10 1.61 vs 1.58 us, m = 30 7.4 vs 4.9 us, m = 100 29.7 vs 17.1 us), and is taken.
double SymmetricTridiagonal::eigenvalue(int k) const {
  if (a_.size() < kTwoHalvingsFrom) return eigenvalue_by_bisection(k);
  double lo = -bound_ - 1e-300, hi = bound_ + 1e-300;
  const double tol = 2.0 * std::numeric_limits<double>::epsilon() * bound_;
  int it = 0;
  while (it < 200 && hi - lo > tol) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    const double x[3] = {mid, 0.5 * (lo + mid), 0.5 * (mid + hi)};
    int count[3];
    count_below3(x, count);
    if (count[0] > k)
      hi = mid;
    else
      lo = mid;
    ++it;
    // the second halving, on the half just kept: its midpoint is x[1] (lower half) or x[2] (upper half)
    if (!(it < 200 && hi - lo > tol)) break;
    const int j = hi == mid ? 1 : 2;
    const double mid2 = 0.5 * (lo + hi);  // == x[j]
    if (mid2 == lo || mid2 == hi) break;
    if (count[j] > k)
      hi = mid2;
    else
      lo = mid2;
    ++it;
  }
  return 0.5 * (lo + hi);
}

double SymmetricTridiagonal::eigenvalue_by_bisection(int k) const {
  double lo = -bound_ - 1e-300, hi = bound_ + 1e-300;
  const double tol = 2.0 * std::numeric_limits<double>::epsilon() * bound_;
  for (int it = 0; it < 200 && hi - lo > tol; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    if (count_below(mid) > k)
      hi = mid;
    else
      lo = mid;
  }
  return 0.5 * (lo + hi);
}

Eigen::VectorXd SymmetricTridiagonal::eigenvector(double lambda) const {
  // Inverse iteration on T - lambda I with a tridiagonal LU with partial pivoting (two super-diagonals).
  const Eigen::Index m = a_.size();
  Eigen::VectorXd y = Eigen::VectorXd::Ones(m);
  if (m == 1) return y;
  const double eps = std::numeric_limits<double>::epsilon() * std::max(bound_, 1e-300);
  Eigen::VectorXd d(m), u1(m), u2(m), l(m);
  Eigen::VectorXi swapped(m);
  // factor
  for (Eigen::Index i = 0; i < m; ++i) {
    d(i) = a_(i) - lambda;
    u1(i) = i + 1 < m ? b_(i) : 0.0;
    u2(i) = 0.0;
  }
  Eigen::VectorXd lower = b_;  // sub-diagonal entries to eliminate
  for (Eigen::Index i = 0; i + 1 < m; ++i) {
    const double sub = lower(i);
    if (std::abs(d(i)) >= std::abs(sub)) {
      swapped(i) = 0;
      if (d(i) == 0.0) d(i) = eps;
      l(i) = sub / d(i);
      d(i + 1) -= l(i) * u1(i);
      // u2(i) stays 0; row i+1's super-diagonal unchanged
    } else {
      swapped(i) = 1;
      // swap rows i and i+1: row i+1 = [sub, d(i+1), u1(i+1)]
      l(i) = d(i) / sub;
      const double nd = sub, nu1 = d(i + 1), nu2 = i + 1 < m - 1 ? u1(i + 1) : 0.0;
      const double od = d(i), ou1 = u1(i);
      d(i) = nd;
      u1(i) = nu1;
      u2(i) = nu2;
      d(i + 1) = ou1 - l(i) * nu1;
      if (i + 1 < m - 1) u1(i + 1) = -l(i) * nu2;
      (void)od;
    }
  }
  if (d(m - 1) == 0.0) d(m - 1) = eps;
  for (int iter = 0; iter < 3; ++iter) {
    // forward: apply L^{-1} with the recorded swaps
    for (Eigen::Index i = 0; i + 1 < m; ++i) {
      if (swapped(i)) std::swap(y(i), y(i + 1));
      y(i + 1) -= l(i) * y(i);
    }
    // back substitution with U (d, u1, u2)
    for (Eigen::Index i = m - 1; i >= 0; --i) {
      double s = y(i);
      if (i + 1 < m) s -= u1(i) * y(i + 1);
      if (i + 2 < m) s -= u2(i) * y(i + 2);
      y(i) = s / (std::abs(d(i)) > 0 ? d(i) : eps);
    }
    y /= y.norm();
  }
  // back to the basis of A: v = Q y, Q the product of the Householder reflectors
  if (lapack_) {
    const char side = 'L', uplo = 'L', trans = 'N';
    const int rows = static_cast<int>(m), one = 1;
    int info = 0, lwork = 1;
    double work = 0.0;
    dormtr_(&side, &uplo, &trans, &rows, &one, householder_.data(), &rows, hcoeffs_.data(), y.data(), &rows, &work,
            &lwork, &info, 1, 1, 1);
    return y / y.norm();
  }
  Eigen::HouseholderSequence<Eigen::MatrixXd, Eigen::VectorXd> Q(householder_, hcoeffs_);
  Q.setLength(m - 1).setShift(1);
  Eigen::VectorXd v = Q * y;
  return v / v.norm();
}

}  // namespace spp::detail
