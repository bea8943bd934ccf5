// spp::Simulator swept over n: the chain of the paper's §5.2 (unit masses and springs, obstacle at g0 = 0.1 above
// the last mass), started at rest with a velocity that makes it hit the obstacle repeatedly, e = 0.5, over 50
// time units. Setup (two eigenproblems, O(n^3)) and the run (O(n^2) per event and per sample) are measured
// apart. Counters: events, impacts, seconds per event.
#include <benchmark/benchmark.h>

#include "spp/core/generators.hpp"
#include "spp/simulation/simulator.hpp"

namespace {

spp::System chain_system(int n) {
  return spp::chain(n, {1.0}, {1.0}, n - 1, spp::ContactSide::Upper, 0.1);
}

void BM_SimulatorSetup(benchmark::State& state) {
  const spp::System s = chain_system(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(spp::Simulator(s));
}

void BM_Simulate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const spp::Simulator sim(chain_system(n));
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(n), v0 = Eigen::VectorXd::Zero(n);
  v0(n - 1) = 2.0;
  spp::SimulateOptions o;
  o.duration = 50.0;
  o.restitution = 0.5;
  o.sample_times = spp::uniform_times(o.duration, 10.0);
  long events = 0, impacts = 0;
  for (auto _ : state) {
    const spp::SimulationResult r = sim.run(x0, v0, o);
    events = static_cast<long>(r.events.size());
    impacts = r.impacts;
  }
  state.counters["events"] = static_cast<double>(events);
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["s_per_event"] = benchmark::Counter(
      static_cast<double>(events), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(BM_SimulatorSetup)->Arg(5)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Simulate)->Arg(5)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
