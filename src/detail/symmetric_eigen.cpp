#include "spp/detail/symmetric_eigen.hpp"

#include <climits>
#include <cstddef>
#include <vector>

// LAPACK's Fortran symbols (OpenBLAS ships them); the trailing size_t are gfortran's hidden lengths of the
// character arguments.
extern "C" {
void dsyevd_(const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* w, double* work,
             const int* lwork, int* iwork, const int* liwork, int* info, std::size_t, std::size_t);
void dsygvd_(const int* itype, const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* b,
             const int* ldb, double* w, double* work, const int* lwork, int* iwork, const int* liwork, int* info,
             std::size_t, std::size_t);
}

namespace spp::detail {

namespace {

// The workspace query (lwork = liwork = -1), then the call.
template <class Call>
bool call_with_workspace(Call call) {
  int lwork = -1, liwork = -1, info = 0, iwork_size = 0;
  double work_size = 0.0;
  call(&work_size, &lwork, &iwork_size, &liwork, &info);
  if (info != 0) return false;
  lwork = static_cast<int>(work_size) + 1;
  liwork = iwork_size;
  std::vector<double> work(static_cast<std::size_t>(lwork));
  std::vector<int> iwork(static_cast<std::size_t>(liwork));
  call(work.data(), &lwork, iwork.data(), &liwork, &info);
  return info == 0;
}

}  // namespace

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
