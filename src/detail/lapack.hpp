#pragma once
// The BLAS / LAPACK routines spp calls (OpenBLAS ships them all), declared once: Fortran symbols, arguments by
// pointer, and the trailing size_t are gfortran's hidden lengths of the character arguments. Private to src/.

#include <cstddef>
#include <vector>

extern "C" {
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc, std::size_t, std::size_t);
void dsyevd_(const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* w, double* work,
             const int* lwork, int* iwork, const int* liwork, int* info, std::size_t, std::size_t);
void dsygvd_(const int* itype, const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* b,
             const int* ldb, double* w, double* work, const int* lwork, int* iwork, const int* liwork, int* info,
             std::size_t, std::size_t);
void dsytrd_(const char* uplo, const int* n, double* a, const int* lda, double* d, double* e, double* tau, double* work,
             const int* lwork, int* info, std::size_t);
void dormtr_(const char* side, const char* uplo, const char* trans, const int* m, const int* n, const double* a,
             const int* lda, const double* tau, double* c, const int* ldc, double* work, const int* lwork, int* info,
             std::size_t, std::size_t, std::size_t);
void dsytrf_(const char* uplo, const int* n, double* a, const int* lda, int* ipiv, double* work, const int* lwork,
             int* info, std::size_t);
void dsyconv_(const char* uplo, const char* way, const int* n, double* a, const int* lda, const int* ipiv, double* e,
              int* info, std::size_t, std::size_t);
void dlaed4_(const int* n, const int* i, const double* d, const double* z, double* delta, const double* rho,
             double* dlam, int* info);
#ifdef SPP_OPENBLAS
void openblas_set_num_threads(int);
int openblas_get_num_threads(void);
char* openblas_get_corename(void);
#endif
}

namespace spp::detail {

/// LAPACK's workspace protocol: call(work, lwork, iwork, liwork, info) once with lwork = liwork = -1 (the sizes are
/// returned in work[0] and iwork[0]), then with workspaces of those sizes. True when both calls report info = 0.
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

}  // namespace spp::detail
