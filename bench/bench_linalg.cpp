// The dense kernels under one H evaluation and one step certificate, swept over the size m, Eigen's own against
// what spp calls (spp::detail::symmetric_eigen and SymmetricTridiagonal dispatch to LAPACK from m = kLapackFrom
// on, spp::detail::product to BLAS's dgemm). One thread: OpenBLAS's own threads off, as in the solver's workers.
//   EigenSyevd/m        Eigen::SelfAdjointEigenSolver, values and vectors
//   SppSymmetricEigen/m spp::detail::symmetric_eigen (dsyevd from kLapackFrom on)
//   EigenTridiagonal/m  Eigen::internal::tridiagonalization_inplace
//   SppTridiagonal/m    spp::detail::SymmetricTridiagonal's reduction (dsytrd from kLapackFrom on)
//   Bisection/m         SymmetricTridiagonal::eigenvalue_by_bisection (one Sturm count per halving), k = m / 2
//   SppEigenvalue/m     SymmetricTridiagonal::eigenvalue (two halvings per pass; the same result bit for bit)
//   EigenProduct/m      C = A * B (m x m), Eigen
//   SppProduct/m        spp::detail::product (dgemm from kLapackFrom on)
#include <benchmark/benchmark.h>

#include <random>

#include "spp/detail/dense_products.hpp"
#include "spp/detail/symmetric_eigen.hpp"
#include "spp/detail/tridiagonal.hpp"

namespace {

Eigen::MatrixXd random_symmetric(Eigen::Index m) {
  std::mt19937 rng(static_cast<unsigned>(m));
  std::normal_distribution<double> nd;
  Eigen::MatrixXd A(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j) A(i, j) = nd(rng);
  return A + A.transpose();
}

void EigenSyevd(benchmark::State& state) {
  const Eigen::MatrixXd A = random_symmetric(state.range(0));
  for (auto _ : state) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
    benchmark::DoNotOptimize(es.eigenvectors().data());
  }
}

void SppSymmetricEigen(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Eigen::MatrixXd A = random_symmetric(state.range(0));
  for (auto _ : state) {
    const spp::detail::SymmetricEigen es = spp::detail::symmetric_eigen(A);
    benchmark::DoNotOptimize(es.vectors.data());
  }
}

void EigenTridiagonal(benchmark::State& state) {
  const Eigen::Index m = state.range(0);
  const Eigen::MatrixXd A = random_symmetric(m);
  Eigen::VectorXd d(m), e(m - 1), h(m - 1);
  for (auto _ : state) {
    Eigen::MatrixXd a = A;
    Eigen::internal::tridiagonalization_inplace(a, d, e, h, false);
    benchmark::DoNotOptimize(a.data());
  }
}

void SppTridiagonal(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Eigen::MatrixXd A = random_symmetric(state.range(0));
  for (auto _ : state) {
    const spp::detail::SymmetricTridiagonal T(A);
    benchmark::DoNotOptimize(T.norm_bound());
  }
}

void Bisection(benchmark::State& state) {
  const spp::detail::SymmetricTridiagonal T(random_symmetric(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(T.eigenvalue_by_bisection(T.size() / 2));
}

void SppEigenvalue(benchmark::State& state) {
  const spp::detail::SymmetricTridiagonal T(random_symmetric(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(T.eigenvalue(T.size() / 2));
}

void EigenProduct(benchmark::State& state) {
  const Eigen::MatrixXd A = random_symmetric(state.range(0)), B = random_symmetric(state.range(0)).reverse();
  Eigen::MatrixXd C(A.rows(), A.cols());
  for (auto _ : state) {
    C.noalias() = A * B;
    benchmark::DoNotOptimize(C.data());
  }
}

void SppProduct(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Eigen::MatrixXd A = random_symmetric(state.range(0)), B = random_symmetric(state.range(0)).reverse();
  for (auto _ : state) {
    const Eigen::MatrixXd C = spp::detail::product(A, false, B, false);
    benchmark::DoNotOptimize(C.data());
  }
}

}  // namespace

BENCHMARK(EigenSyevd)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(SppSymmetricEigen)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(EigenTridiagonal)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(SppTridiagonal)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Bisection)->Arg(5)->Arg(10)->Arg(12)->Arg(20)->Arg(30)->Arg(100)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK(SppEigenvalue)->Arg(5)->Arg(10)->Arg(12)->Arg(20)->Arg(30)->Arg(100)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK(EigenProduct)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(SppProduct)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
