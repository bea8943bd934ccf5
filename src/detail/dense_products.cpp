#include "spp/detail/dense_products.hpp"

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <cstring>

#include "detail/lapack.hpp"
#include "spp/detail/blas_core.hpp"
#include "spp/detail/symmetric_eigen.hpp"

namespace spp::detail {

namespace {

bool use_blas(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const Eigen::Index big = std::max({A.rows(), A.cols(), B.rows(), B.cols()});
  const Eigen::Index small = std::min({A.rows(), A.cols(), B.rows(), B.cols()});
  return big >= kLapackFrom && small > 0 && big <= INT_MAX;
}

Eigen::MatrixXd dgemm(const Eigen::MatrixXd& A, bool ta, const Eigen::MatrixXd& B, bool tb) {
  const int m = static_cast<int>(ta ? A.cols() : A.rows()), n = static_cast<int>(tb ? B.rows() : B.cols());
  const int k = static_cast<int>(ta ? A.rows() : A.cols());
  const int lda = static_cast<int>(A.rows()), ldb = static_cast<int>(B.rows());
  const char opa = ta ? 'T' : 'N', opb = tb ? 'T' : 'N';
  const double one = 1.0, zero = 0.0;
  Eigen::MatrixXd C(m, n);
  dgemm_(&opa, &opb, &m, &n, &k, &one, A.data(), &lda, B.data(), &ldb, &zero, C.data(), &m, 1, 1);
  return C;
}

}  // namespace

#ifdef SPP_OPENBLAS
SingleThreadedBlas::SingleThreadedBlas() : saved_(openblas_get_num_threads()) {
  if (saved_ != 1) openblas_set_num_threads(1);
}
SingleThreadedBlas::~SingleThreadedBlas() {
  if (saved_ != 1) openblas_set_num_threads(saved_);
}
const char* blas_core_advice() {
#if defined(__x86_64__) && defined(__GNUC__)
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return "";
  const char* core = openblas_get_corename();
  if (core == nullptr || std::strcmp(core, "Prescott") != 0) return "";
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
#endif
  return "";
}
#else
SingleThreadedBlas::SingleThreadedBlas() = default;
SingleThreadedBlas::~SingleThreadedBlas() = default;
const char* blas_core_advice() {
  return "";
}
#endif

Eigen::MatrixXd product(const Eigen::MatrixXd& A, bool transpose_a, const Eigen::MatrixXd& B, bool transpose_b) {
  if (use_blas(A, B)) return dgemm(A, transpose_a, B, transpose_b);
  if (transpose_a) return transpose_b ? Eigen::MatrixXd(A.transpose() * B.transpose()) : A.transpose() * B;
  return transpose_b ? Eigen::MatrixXd(A * B.transpose()) : A * B;
}

Eigen::MatrixXd congruence(const Eigen::MatrixXd& G, const Eigen::VectorXd& e) {
  if (use_blas(G, G)) return dgemm(G * e.asDiagonal(), false, G, true);
  return G * e.asDiagonal() * G.transpose();
}

Eigen::MatrixXd congruence_transposed(const Eigen::MatrixXd& G, const Eigen::VectorXd& e) {
  if (use_blas(G, G)) return dgemm(G, true, e.asDiagonal() * G, false);
  return G.transpose() * e.asDiagonal() * G;
}

}  // namespace spp::detail
