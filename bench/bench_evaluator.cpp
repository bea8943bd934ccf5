// One evaluation of H (src/search/evaluator.hpp) as the search makes it, swept over the size m, on the fixed-free chain
// of m unit masses with contact on the last one (its top frequencies cluster ~1/m^2 apart). One thread, OpenBLAS's
// own threads off, as in the solver's workers. The points lie between pole lines (t1 = 0.3, t2 = 0.2 + 1e-7 i: t2
// moves at every iteration, as on a trace, so the contact part G e(t2) G^T is formed each time).
//   Eigenpair/m       at(t1, t2), the eigenvalue nearest the middle of the spectrum and its vector: a trace point
//   CornerCount/m     at(t1, t2) and the two counts of a certified corner, count_below(-e) and count_below(e)
//   OnsetInertia/m    Evaluator::onset_inertia (the inertia of H compressed to the onset hyperplane)
//   LdltCount/m       the kernel alone: detail::count_below_ldlt of H (dsytrf + its a posteriori bound)
//   Tridiagonal/m     the kernel alone: detail::SymmetricTridiagonal of H (dsytrd from m = 128 on)
//   CertifiedStep/m   one certified step's spectral bounds as a trace makes them (step_certificate.hpp): from its start
//                     (eigenpairs and products cached) and from its end (new: full eigenpairs, the products Hp, Hp Gx,
//                     Gx^T Hp Gx, and |Hp E_box| for each end); the step's points t1 = 0.3 - j dt, t2 = 0.2 + j dt
//   BoxNormDense/m, BoxNormStructured/m   |Hp E_box|_F alone: the m^3 product against the O(m^2) expansion (the
//                     latter after its one m^3 product per point, prepare_box_products, outside the timing)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <limits>
#include <memory>

#include "search/evaluator.hpp"
#include "search/loewner_contact.hpp"
#include "search/step_certificate.hpp"
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

// Four points of a step chain (t1 down, t2 up, as on a curve), their box, and each point's unit eigenvector nearest 0
// (the traced null vector's stand-in: the bounds' cost does not depend on how small its eigenvalue is).
struct StepChain {
  explicit StepChain(const Chain& c) : bf(*c.eq, kT1 - 3 * kDt, kT1, kT2, kT2 + 3 * kDt) {
    for (int j = 0; j < 4; ++j) {
      spp::search::StepEnd& e = ends[j];
      e.s = 2 * j * kDt;
      e.t1 = kT1 - j * kDt;
      e.t2 = kT2 + j * kDt;
      const spp::detail::SymmetricEigen es = spp::detail::symmetric_eigen(bf.matrix(e.t1, e.t2));
      Eigen::Index k = 0;
      es.values.cwiseAbs().minCoeff(&k);
      b[j] = es.vectors.col(k).head(c.modal.m());
      e.b = &b[j];
    }
  }
  static constexpr double kDt = 1e-7;
  spp::search::BorderedForm bf;
  spp::search::StepEnd ends[4];
  Eigen::VectorXd b[4];
};

void CertifiedStep(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Chain c(static_cast<int>(state.range(0)));
  const StepChain sc(c);
  spp::search::EigenCache cache;  // three entries: with four points in turn, each step's end is new
  // the first step's start as a trace reaches it: its eigenpairs and products already formed
  spp::search::spectral_bounds(sc.bf, sc.ends[0], sc.ends[0].s, sc.ends[1].s, kT1 - 3 * StepChain::kDt, kT1, kT2,
                               kT2 + 3 * StepChain::kDt, &cache);
  int i = 0, evaluations = 0, valid = 0;
  for (auto _ : state) {
    const spp::search::StepEnd& a = sc.ends[i % 4];
    const spp::search::StepEnd& b = sc.ends[(i + 1) % 4];
    ++i;
    for (const spp::search::StepEnd* x : {&a, &b}) {
      const spp::search::SpectralBounds sb =
          spp::search::spectral_bounds(sc.bf, *x, std::min(a.s, b.s), std::max(a.s, b.s), kT1 - 3 * StepChain::kDt, kT1,
                                       kT2, kT2 + 3 * StepChain::kDt, &cache);
      evaluations += sb.evaluations;
      valid += sb.valid ? 1 : 0;
    }
  }
  state.counters["evaluations_per_step"] = static_cast<double>(evaluations) / static_cast<double>(i);
  state.counters["valid_bounds"] = static_cast<double>(valid);
}

// The products of one point and the box increments of a step of 3 dt (those spectral_bounds takes).
struct BoxInputs {
  explicit BoxInputs(const Chain& c) : sc(c) {
    const spp::detail::SymmetricEigen es = spp::detail::symmetric_eigen(sc.bf.matrix(kT1, kT2));
    Eigen::Index k = 0;
    es.values.cwiseAbs().minCoeff(&k);
    Eigen::VectorXd inv = es.values.cwiseInverse();
    inv(k) = 0.0;
    p.Hp = spp::detail::congruence(es.vectors, inv);
    p.HpG = spp::detail::product(p.Hp, false, sc.bf.Gx(), false);
    spp::search::prepare_box_products(p, sc.bf.Gx());
    dF = spp::search::phase_bounds(sc.bf.flight(), kT1 - 3 * StepChain::kDt, kT1).increment;
    dC = spp::search::phase_bounds(sc.bf.contact(), kT2, kT2 + 3 * StepChain::kDt).increment;
  }
  StepChain sc;
  spp::search::SpectralProducts p;
  Eigen::VectorXd dF, dC;
};

void BoxNormDense(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Chain c(static_cast<int>(state.range(0)));
  const BoxInputs in(c);
  for (auto _ : state)
    benchmark::DoNotOptimize(spp::search::dense_box_norm(in.p.Hp, in.p.HpG, in.sc.bf.Gx(), in.dF, in.dC));
}

void BoxNormStructured(benchmark::State& state) {
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  const Chain c(static_cast<int>(state.range(0)));
  const BoxInputs in(c);
  spp::search::BoxNorm r;
  for (auto _ : state) benchmark::DoNotOptimize(r = spp::search::structured_box_norm(in.p, in.dF, in.dC));
  const double dense = spp::search::dense_box_norm(in.p.Hp, in.p.HpG, in.sc.bf.Gx(), in.dF, in.dC);
  state.counters["relative_to_dense"] = r.value / dense - 1.0;
  state.counters["usable"] = r.usable ? 1.0 : 0.0;
}

}  // namespace

BENCHMARK(Eigenpair)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(CornerCount)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(OnsetInertia)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(LoewnerEntries)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(LdltCount)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Tridiagonal)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(CertifiedStep)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BoxNormDense)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BoxNormStructured)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
