#include "spp/distributed/window_work.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "search/search_steps.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/detail/invalid.hpp"

namespace spp {

namespace {

// The bytes of one unit's output: a header naming the unit and its strip (so that an output of another window or
// unit is refused), then the strip's counts, candidates, uncertified cells and pole-line hits. Doubles are copied
// whole (bit for bit); integers as 64-bit. Both ends run the same binary on the same kind of machine (one cluster).
constexpr std::uint64_t kMagic = 0x5350505354524950ULL;  // "SPPSTRIP"

class Writer {
 public:
  template <class T>
  void pod(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(&v);
    bytes_.append(p, sizeof(T));
  }
  void i64(long long v) { pod<std::int64_t>(static_cast<std::int64_t>(v)); }
  void f64(double v) { pod<double>(v); }
  void str(const std::string& s) {
    i64(static_cast<long long>(s.size()));
    bytes_.append(s);
  }
  void vec(const Eigen::VectorXd& v) {
    i64(v.size());
    bytes_.append(reinterpret_cast<const char*>(v.data()), sizeof(double) * static_cast<size_t>(v.size()));
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class Reader {
 public:
  Reader(const std::string& bytes, size_t unit) : bytes_(bytes), unit_(unit) {}
  template <class T>
  T pod() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  long long i64() { return static_cast<long long>(pod<std::int64_t>()); }
  double f64() { return pod<double>(); }
  size_t count() {
    const long long n = i64();
    if (n < 0 || static_cast<unsigned long long>(n) > bytes_.size()) fail("a count out of range");
    return static_cast<size_t>(n);
  }
  std::string str() {
    const size_t n = count();
    need(n);
    std::string s = bytes_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  Eigen::VectorXd vec() {
    const size_t n = count();
    need(n * sizeof(double));
    Eigen::VectorXd v(static_cast<Eigen::Index>(n));
    if (n) std::memcpy(v.data(), bytes_.data() + pos_, n * sizeof(double));
    pos_ += n * sizeof(double);
    return v;
  }
  void end() {
    if (pos_ != bytes_.size()) fail("bytes left after the end");
  }
  [[noreturn]] void fail(const std::string& what) const {
    detail::invalid("WindowWork::finish: the output of unit " + std::to_string(unit_) +
                                " is not one trace_unit wrote for this window (" + what + ")");
  }

 private:
  void need(size_t n) const {
    if (bytes_.size() - pos_ < n) fail("cut short");
  }
  const std::string& bytes_;
  size_t unit_;
  size_t pos_ = 0;
};

void write_stats(Writer& w, const SolveStats& s) {
  for (long v : {s.rectangles, s.curve_pieces, s.roots, s.evaluations, s.strip_pairs, s.certified_steps,
                 s.heuristic_steps, s.pole_line_artifacts, s.uncertified_steps, s.uncertified_corners,
                 s.unpaired_crossings, s.unresolved_pieces, s.unpolished_roots, s.unsearched_cells})
    w.i64(v);
}

SolveStats read_stats(Reader& r) {
  SolveStats s;
  for (long* v : {&s.rectangles, &s.curve_pieces, &s.roots, &s.evaluations, &s.strip_pairs, &s.certified_steps,
                  &s.heuristic_steps, &s.pole_line_artifacts, &s.uncertified_steps, &s.uncertified_corners,
                  &s.unpaired_crossings, &s.unresolved_pieces, &s.unpolished_roots, &s.unsearched_cells})
    *v = static_cast<long>(r.i64());
  return s;
}

void write_hits(Writer& w, const std::vector<std::vector<search::EdgeHit>>& lists) {
  for (const auto& list : lists) {
    w.i64(static_cast<long long>(list.size()));
    for (const search::EdgeHit& h : list) {
      w.f64(h.pos);
      w.f64(h.t1);
      w.f64(h.t2);
      w.f64(h.g);
      w.vec(h.b);
      w.i64(static_cast<long long>(h.cell));
    }
  }
}

std::vector<std::vector<search::EdgeHit>> read_hits(Reader& r, size_t cells) {
  std::vector<std::vector<search::EdgeHit>> lists(cells);
  for (auto& list : lists) {
    list.resize(r.count());
    for (search::EdgeHit& h : list) {
      h.pos = r.f64();
      h.t1 = r.f64();
      h.t2 = r.f64();
      h.g = r.f64();
      h.b = r.vec();
      h.cell = static_cast<size_t>(r.i64());
    }
  }
  return lists;
}

}  // namespace

struct WindowWork::Impl {
  System system;
  std::unique_ptr<EquationSet> user_eq;      // on the caller's modal form: builds the SPPs
  std::unique_ptr<search::SearchTime> time;  // the search's time unit and modal form (held: eq refers to it)
  std::unique_ptr<EquationSet> eq;           // on time->modal: what the units trace
  search::WindowPlan plan;
  SolveOptions options;
  std::chrono::steady_clock::time_point t0;
};

WindowWork::WindowWork(const System& system, const ModalForm& modal, const SolveOptions& options) {
  options.validate();
  search::check_solve_inputs(system, modal, "WindowWork");
  const auto t0 = std::chrono::steady_clock::now();
  auto user_eq = make_equations(modal, options.symmetry);
  auto time = std::make_unique<search::SearchTime>(modal, options);
  auto eq = make_equations(time->modal, options.symmetry);
  search::WindowPlan plan = search::plan_search(modal, options, *time);
  impl_ = std::make_unique<Impl>(
      Impl{system, std::move(user_eq), std::move(time), std::move(eq), std::move(plan), options, t0});
}

WindowWork::~WindowWork() = default;

size_t WindowWork::units() const {
  return impl_->plan.t2.cells();
}

long WindowWork::unit_cells(size_t j) const {
  if (j >= units())
    detail::invalid("WindowWork: unit " + std::to_string(j) + " of a window of " + std::to_string(units()) +
                                " units");
  return static_cast<long>(impl_->plan.t1.cells());
}

double WindowWork::unit_cost(size_t j) const {
  const auto& bp = impl_->plan.t2.bp;
  return static_cast<double>(unit_cells(j)) * impl_->time->to_user(bp[j + 1] - bp[j]);  // (the plan is in tau)
}

std::string WindowWork::trace_unit(size_t j) const {
  (void)unit_cells(j);
  const search::WindowPlan& plan = impl_->plan;
  const search::StripOut out = search::trace_strip(*impl_->eq, plan, j);
  Writer w;
  w.pod(kMagic);
  w.i64(static_cast<long long>(j));
  w.i64(static_cast<long long>(plan.t1.cells()));
  w.i64(static_cast<long long>(plan.t2.cells()));
  w.f64(plan.t2.bp[j]);
  w.f64(plan.t2.bp[j + 1]);
  write_stats(w, out.stats);
  w.i64(static_cast<long long>(out.candidates.size()));
  for (const search::Candidate& c : out.candidates) {
    w.f64(c.t1);
    w.f64(c.t2);
    w.i64(c.uncertified ? 1 : 0);
    w.i64(c.near_pole ? 1 : 0);
    w.vec(c.b);
  }
  w.i64(static_cast<long long>(out.uncertified.size()));
  for (const UncertifiedRegion& u : out.uncertified) {
    w.f64(u.t1_lo);
    w.f64(u.t1_hi);
    w.f64(u.t2_lo);
    w.f64(u.t2_hi);
    w.str(u.cause);
  }
  for (const auto* lists : {&out.left, &out.top, &out.right, &out.bottom}) write_hits(w, *lists);
  return w.take();
}

SolveResult WindowWork::finish(const std::vector<std::string>& outputs) const {
  const search::WindowPlan& plan = impl_->plan;
  const size_t I = plan.t1.cells(), J = plan.t2.cells();
  if (outputs.size() != J)
    detail::invalid("WindowWork::finish: expected the outputs of " + std::to_string(J) + " units, got " +
                                std::to_string(outputs.size()));
  std::vector<search::StripOut> strips(J);
  for (size_t j = 0; j < J; ++j) {
    Reader r(outputs[j], j);
    if (r.pod<std::uint64_t>() != kMagic) r.fail("no strip header");
    const long long unit = r.i64(), cells = r.i64(), units = r.i64();
    const double lo = r.f64(), hi = r.f64();
    if (unit != static_cast<long long>(j) || cells != static_cast<long long>(I) || units != static_cast<long long>(J) ||
        lo != plan.t2.bp[j] || hi != plan.t2.bp[j + 1])
      r.fail("unit " + std::to_string(unit) + " of a window of " + std::to_string(units) + " units");
    search::StripOut& out = strips[j];
    out.stats = read_stats(r);
    out.candidates.resize(r.count());
    for (search::Candidate& c : out.candidates) {
      c.t1 = r.f64();
      c.t2 = r.f64();
      c.uncertified = r.i64() != 0;
      c.near_pole = r.i64() != 0;
      c.b = r.vec();
    }
    out.uncertified.resize(r.count());
    for (UncertifiedRegion& u : out.uncertified) {
      u.t1_lo = r.f64();
      u.t1_hi = r.f64();
      u.t2_lo = r.f64();
      u.t2_hi = r.f64();
      u.cause = r.str();
    }
    for (auto* lists : {&out.left, &out.top, &out.right, &out.bottom}) *lists = read_hits(r, I);
    r.end();
  }
  SolveResult res = search::start_result(impl_->user_eq->modal(), plan, impl_->options, *impl_->time);
  search::TracedWindow traced = search::merge_strips(plan, strips, res);
  search::finish_search(impl_->system, *impl_->user_eq, *impl_->eq, *impl_->time, plan, traced, impl_->options, res);
  res.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - impl_->t0).count();
  return res;
}

}  // namespace spp
