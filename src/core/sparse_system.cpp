#include "spp/core/sparse_system.hpp"

#include <cmath>
#include <sstream>

#include "spp/core/names.hpp"
#include "spp/core/system.hpp"
#include "spp/detail/invalid.hpp"

namespace spp {

namespace {
void check_matrix(const Eigen::SparseMatrix<double>& A, const char* name, int n) {
  std::ostringstream os;
  if (A.rows() != n || A.cols() != n) {
    os << "SparseSystem: " << name << " must be " << n << " x " << n << " (the size of M), got " << A.rows() << " x "
       << A.cols();
    detail::invalid(os.str());
  }
  double largest = 0.0;
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      if (!std::isfinite(it.value())) {
        os << "SparseSystem: " << name << " must be finite, got " << it.value() << " at (" << it.row() + 1 << ", "
           << it.col() + 1 << ")";
        detail::invalid(os.str());
      }
      largest = std::max(largest, std::abs(it.value()));
    }
  const Eigen::SparseMatrix<double> At = A.transpose();
  const Eigen::SparseMatrix<double> diff = A - At;
  double asym = 0.0;
  for (int k = 0; k < diff.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(diff, k); it; ++it) asym = std::max(asym, std::abs(it.value()));
  if (asym > kSymmetryTolerance * largest) {
    os << "SparseSystem: " << name << " must be symmetric (|A - A^T|_max <= " << kSymmetryTolerance
       << " |A|_max), got |A - A^T|_max = " << asym << " with |A|_max = " << largest;
    detail::invalid(os.str());
  }
  const Eigen::VectorXd d = A.diagonal();
  for (int i = 0; i < n; ++i)
    if (!(d(i) > 0)) {
      os << "SparseSystem: " << name << " must be positive definite: its diagonal must be positive, got " << name << "("
         << i + 1 << ", " << i + 1 << ") = " << d(i);
      detail::invalid(os.str());
    }
}
}  // namespace

SparseSystem::SparseSystem(Eigen::SparseMatrix<double> M, Eigen::SparseMatrix<double> K, Eigen::VectorXd w, double g0,
                           std::string name)
    : M_(std::move(M)), K_(std::move(K)), w_(std::move(w)), g0_(g0), name_(std::move(name)) {
  check_name(name_, "SparseSystem: name");
  if (M_.rows() < 1 || M_.rows() != M_.cols())
    detail::invalid("SparseSystem: M must be square and non-empty, got " + std::to_string(M_.rows()) + " x " +
                    std::to_string(M_.cols()));
  const int n = static_cast<int>(M_.rows());
  check_matrix(M_, "M", n);
  check_matrix(K_, "K", n);
  M_.makeCompressed();
  K_.makeCompressed();
  if (w_.size() != n)
    detail::invalid("SparseSystem: w must have n = " + std::to_string(n) + " entries, got " +
                    std::to_string(w_.size()));
  if (!w_.allFinite()) detail::invalid("SparseSystem: w must be finite");
  if (!(w_.norm() > 0))
    detail::invalid_option("SparseSystem", "|w|", w_.norm(), "positive (w is the contact direction)");
  if (!std::isfinite(g0_)) detail::invalid_option("SparseSystem", "g0", g0_, "finite");
}

}  // namespace spp
