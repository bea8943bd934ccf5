// continue_branches swept over n: the chain of the paper's §5.2 (unit masses and springs, obstacle at g0 = 1 above
// the last mass) with the last spring's stiffness k_n in [0.8, 1.25] as the parameter, window
// t1 <= pi / omega_1, t2 <= pi / (2 d_1) (a few branches per n). Counters: branches, points, events, corrector
// solves.
#include <benchmark/benchmark.h>

#include <numbers>

#include "spp/continuation/continuation.hpp"
#include "spp/core/generators.hpp"
#include "spp/modal/modal.hpp"

namespace {

void BM_Continue(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto make = [n](double k) {
    std::vector<double> ks(static_cast<size_t>(n), 1.0);
    ks.back() = k;
    return spp::chain(n, {1.0}, ks, n - 1, spp::ContactSide::Upper, 1.0);
  };
  const spp::ParametricSystem ps = spp::parametrize(make, {"kn", 0.8, 1.25});
  const spp::ModalForm md(make(1.0));
  spp::ContinueOptions o;
  o.t1_max = std::numbers::pi / md.omega()(0);
  o.t2_max = std::numbers::pi / (2.0 * md.d()(1));
  o.seeds = 5;
  o.threads = 1;
  spp::ContinuationResult r;
  for (auto _ : state) r = spp::continue_branches(ps, o);
  long points = 0, events = 0;
  for (const auto& b : r.branches)
    points += static_cast<long>(b.points.size()), events += static_cast<long>(b.events.size());
  state.counters["branches"] = static_cast<double>(r.branches.size());
  state.counters["points"] = static_cast<double>(points);
  state.counters["events"] = static_cast<double>(events);
  state.counters["corrector_solves"] = static_cast<double>(r.corrector_solves);
}

}  // namespace

BENCHMARK(BM_Continue)->Arg(2)->Arg(3)->Arg(5)->Arg(10)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
