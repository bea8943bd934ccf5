// One evaluation of H (src/search/evaluator.hpp) as the search makes it, swept over the size m, on the fixed-free chain
// of m unit masses with contact on the last one (its top frequencies cluster ~1/m^2 apart). One thread, OpenBLAS's
// own threads off, as in the solver's workers. The points lie between pole lines (t1 = 0.3, t2 = 0.2 + 1e-7 i: t2
// moves at every iteration, as on a trace, so the contact part G e(t2) G^T is formed each time).
//   Eigenpair/m       at(t1, t2), the eigenvalue nearest the middle of the spectrum and its vector: a trace point
//   CornerCount/m     at(t1, t2) and the two counts of a certified corner, count_below(-e) and count_below(e)
//   OnsetInertia/m    Evaluator::onset_inertia (the inertia of H compressed to the onset hyperplane)
//   LdltCount/m       the kernel alone: detail::count_below_ldlt of H (dsytrf + its a posteriori bound)
//   Tridiagonal/m     the kernel alone: detail::SymmetricTridiagonal of H (dsytrd from m = 128 on)
#include <benchmark/benchmark.h>

#include <limits>
#include <memory>

#include "search/evaluator.hpp"
#include "search/loewner_contact.hpp"
#include "spp/core/generators.hpp"
#include "spp/detail/dense_products.hpp"
#include "spp/detail/symmetric_inertia.hpp"
#include "spp/detail/tridiagonal.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/modal/modal.hpp"

namespace {

struct Chain {
  explicit Chain(int m)
      : modal(spp::chain(m, {1.0}, {1.0}, m - 1, spp::ContactSide::Upper, 1.0)),
        eq(spp::make_equations(modal, spp::Symmetry::Axial)) {}
  spp::ModalForm modal;
  std::unique_ptr<spp::EquationSet> eq;
};

constexpr double kT1 = 0.3, kT2 = 0.2, kDt2 = 1e-7;

void Eigenpair(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Chain c(static_cast<int>(state.range(0)));
  spp::search::DenseEvaluator ev(*c.eq);
  int i = 0;
  for (auto _ : state) {
    const auto h = ev.at(kT1, kT2 + kDt2 * (++i % 1000));
    const double lam = h->eigenvalue(h->size() / 2);
    benchmark::DoNotOptimize(h->eigenvector(lam).data());
  }
  state.counters["structured"] = static_cast<double>(ev.structured());  // points whose H came from LoewnerContact
  state.counters["declined"] = static_cast<double>(ev.structured_declined());
}

void CornerCount(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Chain c(static_cast<int>(state.range(0)));
  spp::search::DenseEvaluator ev(*c.eq);
  int i = 0;
  for (auto _ : state) {
    const auto h = ev.at(kT1, kT2 + kDt2 * (++i % 1000));
    const double e = h->eigen_error();
    benchmark::DoNotOptimize(h->count_below(-e) + h->count_below(e));
  }
}

void OnsetInertia(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Chain c(static_cast<int>(state.range(0)));
  spp::search::DenseEvaluator ev(*c.eq);
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(ev.onset_inertia(kT1, kT2 + kDt2 * (++i % 1000)));
  state.counters["ldlt"] = static_cast<double>(ev.ldlt_inertias());  // decided by the LDL^T counts
  state.counters["ldlt_declined"] = static_cast<double>(ev.ldlt_declined());
}

Eigen::MatrixXd h_of(const Chain& c) {
  Eigen::MatrixXd H = c.eq->contact_part(kT2);
  H.diagonal() += c.eq->flight_part(kT1);
  return H;
}

// The Loewner-structured H alone (O(m^2)) and its a posteriori rounding bound, in units of m eps || |H| ||_inf
// (LoewnerContact accepts up to its budget, 4).
void LoewnerEntries(benchmark::State& state) {
  const Chain c(static_cast<int>(state.range(0)));
  const spp::search::LoewnerContact lc(c.modal);
  const Eigen::VectorXd f = c.eq->flight_part(kT1), e = c.eq->contact_eigs(kT2);
  Eigen::MatrixXd H;
  for (auto _ : state) benchmark::DoNotOptimize(lc.form(f, e, H));
  state.counters["bound_in_m_eps_H"] =
      lc.last_bound() / (static_cast<double>(H.rows()) * std::numeric_limits<double>::epsilon() * lc.last_norm());
}

void LdltCount(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Chain c(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd H = h_of(c);
  for (auto _ : state) benchmark::DoNotOptimize(spp::detail::count_below_ldlt(H, 0.0).below);
}

void Tridiagonal(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Chain c(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd H = h_of(c);
  for (auto _ : state) {
    const spp::detail::SymmetricTridiagonal T(H);
    benchmark::DoNotOptimize(T.count_below(0.0));
  }
}

}  // namespace

BENCHMARK(Eigenpair)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(CornerCount)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(OnsetInertia)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(LoewnerEntries)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(LdltCount)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Tridiagonal)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
