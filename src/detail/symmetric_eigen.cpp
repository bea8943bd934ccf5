#include "spp/detail/symmetric_eigen.hpp"

#include <climits>
#include <utility>

#include "detail/lapack.hpp"

namespace spp::detail {

SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& A, bool vectors) {
  SymmetricEigen r;
  const Eigen::Index m = A.rows();
  if (m < kLapackFrom || m > INT_MAX) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(
        A, vectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
    r.ok = es.info() == Eigen::Success;
    r.values = es.eigenvalues();
    if (vectors) r.vectors = es.eigenvectors();
    return r;
  }
  const int n = static_cast<int>(m);
  Eigen::MatrixXd a = A;
  r.values.resize(m);
  const char jobz = vectors ? 'V' : 'N', uplo = 'L';
  r.ok = call_with_workspace([&](double* work, const int* lwork, int* iwork, const int* liwork, int* info) {
    dsyevd_(&jobz, &uplo, &n, a.data(), &n, r.values.data(), work, lwork, iwork, liwork, info, 1, 1);
  });
  if (vectors) r.vectors = std::move(a);
  return r;
}

SymmetricEigen generalized_symmetric_eigen(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M) {
  SymmetricEigen r;
  const Eigen::Index m = K.rows();
  if (m < kLapackFrom || m > INT_MAX) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
    r.ok = es.info() == Eigen::Success;
    r.values = es.eigenvalues();
    r.vectors = es.eigenvectors();
    return r;
  }
  const int n = static_cast<int>(m), itype = 1;
  Eigen::MatrixXd a = K, b = M;
  r.values.resize(m);
  const char jobz = 'V', uplo = 'L';
  r.ok = call_with_workspace([&](double* work, const int* lwork, int* iwork, const int* liwork, int* info) {
    dsygvd_(&itype, &jobz, &uplo, &n, a.data(), &n, b.data(), &n, r.values.data(), work, lwork, iwork, liwork, info, 1,
            1);
  });
  r.vectors = std::move(a);
  return r;
}

}  // namespace spp::detail
