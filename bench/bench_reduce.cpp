// spp::reduce (Craig-Bampton, reduction/craig_bampton.hpp) swept over n: the fixed-free bar of spp generate bar
// (consistent mass, contact at the free end), m = 20 fixed-interface modes, Spectra's path (n - 1 > 400 interior
// dofs). Counters: the stages' seconds (coordinates and partition, the two CHOLMOD factorisations, the eigensolver,
// the projection) and Spectra's solves with the factor. Peak memory is not measured here (one process runs every
// case): README gives /usr/bin/time -v of spp reduce.
#include <benchmark/benchmark.h>

#include "spp/core/generators.hpp"
#include "spp/reduction/craig_bampton.hpp"

namespace {

void BM_ReduceBar(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const spp::SparseSystem bar = spp::bar(n, spp::BarMass::Consistent, n, spp::ContactSide::Upper, 1.0);
  spp::ReductionOptions o;
  o.modes = static_cast<int>(state.range(1));
  spp::ReductionResult r;
  for (auto _ : state) {
    r = spp::reduce(bar, o);
    benchmark::DoNotOptimize(r.reduced);
  }
  if (r.status != spp::ReductionResult::Status::Success) state.SkipWithError(r.brief_report().c_str());
  state.counters["transform_s"] = r.timings.transform_seconds;
  state.counters["factor_s"] = r.timings.factorization_seconds;
  state.counters["eigen_s"] = r.timings.eigen_seconds;
  state.counters["project_s"] = r.timings.projection_seconds;
  state.counters["solves"] = r.eigen_operations;
  state.counters["omega_1"] = r.reduced_frequencies(0);
}

}  // namespace

BENCHMARK(BM_ReduceBar)->Args({1000, 20})->Args({10000, 20})->Args({100000, 20})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
