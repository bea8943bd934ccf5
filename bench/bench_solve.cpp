// spp::solve swept over n. Cost follows the number of pole lines in the window, so the windows are fixed by
// pole-line counts, not by size:
//  - ChainBox: the chain's fundamental box t1 <= pi/omega_1, t2 <= pi/d_2;
//  - ChainWindow / RandomWindow: P x P pole lines, t1_max (t2_max) the smallest time with P poles of
//    tan(W t1) (tan(D t2)) below it (P pi / sum(omega) only holds once every mode has several poles).
//  - the cases without a suffix trace with the midpoint check (certify_steps = false, `--no-certify-steps`: a
//    heuristic, the speed baseline); *Certified: the same with certify_steps, the default (every step proved).
// Counters: pole lines, rectangles, curve pieces, roots, H evaluations, seconds per root.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>

#include "spp/core/generators.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"

namespace {

spp::System chain_system(int n) {
  return spp::chain(n, {1.0}, {1.0}, n - 1, spp::ContactSide::Upper, 1.0);
}

spp::System random_system(int n) { return spp::random_dense(n, static_cast<unsigned>(n)); }

void run(benchmark::State& state, const spp::System& s, const spp::SolveOptions& o) {
  spp::SolveResult r;
  for (auto _ : state) {
    r = spp::solve(s, o);
    benchmark::DoNotOptimize(r);
  }
  state.counters["n"] = s.n();
  state.counters["pole_lines_t1"] = r.stats.flight_pole_lines;
  state.counters["pole_lines_t2"] = r.stats.contact_pole_lines;
  state.counters["rectangles"] = static_cast<double>(r.stats.rectangles);
  state.counters["curve_pieces"] = static_cast<double>(r.stats.curve_pieces);
  state.counters["roots"] = static_cast<double>(r.solutions.size());
  state.counters["evaluations"] = static_cast<double>(r.stats.evaluations);
  state.counters["s_per_root"] = r.solutions.empty() ? 0.0 : r.stats.seconds / static_cast<double>(r.solutions.size());
  state.counters["complete"] = r.status == spp::SolveStatus::Success ? 1 : 0;
}

void chain_box(benchmark::State& state, bool certify) {
  const spp::System s = chain_system(static_cast<int>(state.range(0)));
  const spp::ModalForm md(s);
  spp::SolveOptions o;
  o.t1_max = std::numbers::pi / md.omega()(0);
  o.t2_max = std::numbers::pi / md.d()(1);
  o.compute_return_error = false;
  o.certify_steps = certify;
  run(state, s, o);
}
void ChainBox(benchmark::State& state) { chain_box(state, false); }
void ChainBoxCertified(benchmark::State& state) { chain_box(state, true); }

// Smallest t with at least P poles (k + 1/2) pi / f in (0, t], by bisection on the count.
double time_for_poles(const Eigen::VectorXd& freqs, int P) {
  auto count = [&](double t) {
    long c = 0;
    for (Eigen::Index k = 0; k < freqs.size(); ++k)
      if (freqs(k) > 0) c += static_cast<long>(std::floor(t * freqs(k) / std::numbers::pi + 0.5));
    return c;
  };
  double lo = 0.0, hi = 1.0;
  while (count(hi) < P) hi *= 2.0;
  for (int it = 0; it < 100; ++it) (count(0.5 * (lo + hi)) >= P ? hi : lo) = 0.5 * (lo + hi);
  return hi * (1.0 + 1e-9);
}

void window(benchmark::State& state, const spp::System& s, bool certify = false) {
  const spp::ModalForm md(s);
  const int P = static_cast<int>(state.range(1));
  spp::SolveOptions o;
  o.t1_max = time_for_poles(md.omega(), P);
  o.t2_max = time_for_poles(md.d(), P);
  o.compute_return_error = false;
  o.certify_steps = certify;
  run(state, s, o);
}

void ChainWindow(benchmark::State& state) {
  window(state, chain_system(static_cast<int>(state.range(0))));
}
void RandomWindow(benchmark::State& state) {
  window(state, random_system(static_cast<int>(state.range(0))));
}
void RandomWindowCertified(benchmark::State& state) {
  window(state, random_system(static_cast<int>(state.range(0))), true);
}

void chain5_window12(benchmark::State& state, bool certify) {
  spp::SolveOptions o;
  o.t1_max = o.t2_max = 12.0;
  o.compute_return_error = false;
  o.certify_steps = certify;
  run(state, chain_system(5), o);
}
void Chain5Window12(benchmark::State& state) { chain5_window12(state, false); }
void Chain5Window12Certified(benchmark::State& state) { chain5_window12(state, true); }

}  // namespace

BENCHMARK(Chain5Window12)->Unit(benchmark::kMillisecond);
BENCHMARK(Chain5Window12Certified)->Unit(benchmark::kMillisecond);
BENCHMARK(ChainBox)->DenseRange(2, 10)->Unit(benchmark::kMillisecond);
BENCHMARK(ChainBoxCertified)->DenseRange(2, 8)->Iterations(1)->Unit(benchmark::kMillisecond);
// {n, pole lines per direction}: what proofs cost on generic dense systems
BENCHMARK(RandomWindow)->Args({5, 20})->Args({10, 20})->Args({20, 20})->Unit(benchmark::kMillisecond);
BENCHMARK(RandomWindowCertified)->Args({5, 20})->Args({10, 20})->Args({20, 20})->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(ChainBox)->Arg(20)->Arg(30)->Iterations(1)->Unit(benchmark::kSecond);
// {n, pole lines per direction}: windows sized to run in minutes here; cost grows with the rectangles
void window_sweep(benchmark::internal::Benchmark* b) {
  b->Args({30, 100})->Args({100, 100})->Args({300, 6})->Iterations(1)->Unit(benchmark::kSecond);
}
BENCHMARK(ChainWindow)->Apply(window_sweep);
BENCHMARK(RandomWindow)->Apply(window_sweep);
BENCHMARK_MAIN();
