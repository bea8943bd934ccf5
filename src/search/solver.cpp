#include "spp/search/solver.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <limits>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "search/cell_trace.hpp"
#include "search/evaluator.hpp"
#include "search/pole_pairing.hpp"
#include "search/polish.hpp"
#include "search/search_steps.hpp"
#include "search/tolerances.hpp"
#include "search/window_plan.hpp"
#include "spp/detail/dense_products.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/modal/modal.hpp"

namespace spp {

const char* to_string(SolveStatus s) {
  switch (s) {
    case SolveStatus::NotRun: return "not_run";
    case SolveStatus::Success: return "success";
    case SolveStatus::Incomplete: return "incomplete";
  }
  return "unknown";
}

void SolveOptions::validate() const {
  auto positive_finite = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0)) {
      std::ostringstream os;
      os << "options: " << name << " must be positive and finite, got " << v;
      detail::invalid(os.str());
    }
  };
  positive_finite(t1_max, "t1_max");
  positive_finite(t2_max, "t2_max");
  auto lower = [](double v, double hi, const char* name, const char* hiname) {
    if (!(std::isfinite(v) && v >= 0.0 && v < hi)) {
      std::ostringstream os;
      os << "options: " << name << " must be >= 0 and < " << hiname << " = " << hi << " (0 = automatic), got " << v;
      detail::invalid(os.str());
    }
  };
  lower(t1_min, t1_max, "t1_min", "t1_max");
  lower(t2_min, t2_max, "t2_min", "t2_max");
  validate_fields_but_window();
}

void SolveOptions::validate_fields_but_window() const {
  auto in_open = [](double v, double lo, double hi, const char* name) {
    if (!(v > lo && v < hi)) {
      std::ostringstream os;
      os << "options: " << name << " must be in (" << lo << ", " << hi << "), got " << v;
      detail::invalid(os.str());
    }
  };
  in_open(pole_margin, 0.0, 0.1, "pole_margin");
  in_open(max_turn, 0.0, 1.0, "max_turn");
  in_open(min_step, 0.0, 1e-3, "min_step");
  in_open(admissibility_tol, 0.0, 1e-2, "admissibility_tol");
  if (threads < 0)
    detail::invalid("options: threads must be >= 0 (0 = all), got " + std::to_string(threads));
  if (max_cells < 1) detail::invalid("options: max_cells must be >= 1, got " + std::to_string(max_cells));
}

std::string SolveResult::brief_report() const {
  std::ostringstream os;
  long adm = std::count_if(solutions.begin(), solutions.end(), [](const Solution& s) { return s.admissible(); });
  os << "spp: " << to_string(status) << ", " << solutions.size() << " SPPs (" << adm << " admissible) in (" << t1_min
     << ", " << t1_max << "] x (" << t2_min << ", " << t2_max << "]; " << stats.rectangles << " rectangles, "
     << stats.curve_pieces << " curve pieces, " << stats.evaluations << " evaluations, " << stats.seconds << " s";
  return os.str();
}

namespace {

// Unpolished sign changes named one by one in the warnings; beyond, one line counts them (a thin strip across a pole
// line of a stiff system produced 1 856 of them).
constexpr long kListedUnpolished = 5;

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

using search::Candidate;
using search::polish;
using search::Polished;

// A point (t1, t2) given by a caller (a guess, or an SPP to polish) must be positive and finite.
void require_positive_guess(const char* who, double t1, double t2) {
  // (a denormal guess reached the window checks, which named t1_min, an option the user never gave)
  constexpr double kMin = std::numeric_limits<double>::min();
  if (!(std::isfinite(t1) && t1 >= kMin && std::isfinite(t2) && t2 >= kMin)) {
    std::ostringstream os;
    os << who << ": t1 and t2 must be positive and finite (normal doubles), got t1 = " << t1 << ", t2 = " << t2;
    detail::invalid(os.str());
  }
}

// The modal form given with a system must be that system's (computed by ModalForm(system)).
void require_modal_of(const System& system, const ModalForm& modal, const char* where) {
  if (modal.n() != system.n() || modal.g0() != system.g0()) {
    std::ostringstream os;
    os << where << ": the modal form given is not that of the system (n = " << modal.n() << ", g0 = " << modal.g0()
       << " against n = " << system.n() << ", g0 = " << system.g0() << "): pass ModalForm(system)";
    detail::invalid(os.str());
  }
}

// g0 = 0 is refused by every entry point with the same message.
void require_nonzero_gap(const System& system) {
  if (system.g0() == 0.0)
    detail::invalid(
        "system: g0 = 0 (obstacle touching the rest position): SPPs then exist only for special parameter "
        "values (paper §6.1) and need one more unknown: declare a parameter in the system file (\"parameter\": "
        "{\"name\", \"min\", \"max\"}, M/K/w affine in it) and run spp solve without --at, or "
        "continue_branches() and gap_closures().");
}

Solution build_solution(const System& system, const EquationSet& eq, const Polished& p, const SolveOptions& opt,
                        bool with_return_error) {
  const ModalForm& md = eq.modal();
  Solution s;
  s.residual = p.residual;
  s.orbit = make_orbit(eq, p.t1, p.t2, p.a);
  if (eq.can_be_admissible())
    s.admissibility = check_admissibility(md, s.orbit, opt.admissibility_tol);
  else  // the verdict is structural (point symmetry: an odd force); the minima only sampled
    s.admissibility = sample_point_admissibility(md, s.orbit);
  if (const char* flag = eq.solution_flag()) s.flags.push_back(flag);
  if (s.orbit.closure_ratio < search::kClosureDegenerate) s.flags.push_back("gap_closure_degenerate");
  for (Eigen::Index k = 0; k < md.omega_decoupled().size(); ++k) {
    const double r = md.omega_decoupled()(k) * (p.t1 + p.t2) / std::numbers::pi;
    if (std::abs(r - std::round(r)) < search::kResonance * std::max(1.0, r))
      s.flags.push_back("decoupled_mode_resonant");
  }
  if (with_return_error) s.return_error = return_error(system, s.orbit);
  if (opt.compute_stability && eq.can_be_admissible()) s.floquet = floquet(eq, s.orbit);
  return s;
}

}  // namespace

std::pair<double, double> default_lower_ends(const ModalForm& md, double t1_max, double t2_max) {
  const double pi = std::numbers::pi, dmax = md.d().maxCoeff();
  using search::kDefaultLower, search::kDefaultLowerCap;
  return {std::min(kDefaultLower * pi / (2.0 * md.omega().maxCoeff()), kDefaultLowerCap * t1_max),
          std::min(dmax > 0 ? kDefaultLower * pi / (2.0 * dmax) : kDefaultLower * t2_max, kDefaultLowerCap * t2_max)};
}

std::pair<double, double> fundamental_box(const ModalForm& md) {
  const double pi = std::numbers::pi;
  double dmin = 0.0;
  for (Eigen::Index j = 0; j < md.d().size(); ++j)
    if (md.d()(j) > 0 && (dmin == 0.0 || md.d()(j) < dmin)) dmin = md.d()(j);
  if (md.m() == 0 || dmin == 0.0)
    detail::invalid(
        "fundamental box: the system has no contact-phase oscillation (one coupled mode or none), so "
        "no box: give the window's upper ends t1_max, t2_max");
  return {pi / md.omega().minCoeff(), pi / dmin};
}

std::pair<double, double> axis_band(const ModalForm& md) {
  const double pi = std::numbers::pi, dmax = md.d().maxCoeff();
  return {search::kAxisBand * pi / (2.0 * md.omega().maxCoeff()),
          dmax > 0 ? search::kAxisBand * pi / (2.0 * dmax) : 0.0};
}

SolutionAt solution_at(const System& system, double t1, double t2, const SolveOptions& options) {
  require_positive_guess("solution_at", t1, t2);
  require_nonzero_gap(system);
  return solution_at(system, ModalForm(system), t1, t2, options);
}

SolutionAt solution_at(const System& system, const ModalForm& md, double t1, double t2, const SolveOptions& options) {
  // (the window is not used; an admissibility_tol of -1 gave an admissible SPP "not admissible", found by an attack)
  options.validate_fields_but_window();
  require_positive_guess("solution_at", t1, t2);
  require_nonzero_gap(system);
  require_modal_of(system, md, "solution_at");
  // Newton in the search's time, as solve() polishes (search::SearchTime); the SPP built at the user's times
  const search::SearchTime time(md, options);
  const std::unique_ptr<EquationSet> user_eq = make_equations(md, options.symmetry);
  const std::unique_ptr<EquationSet> eq = make_equations(time.modal, options.symmetry);
  Polished p = polish(*eq, t1 * time.rate, t2 * time.rate);
  const bool root = p.converged && std::hypot(p.t1 - t1 * time.rate, p.t2 - t2 * time.rate) <=
                                       search::kPolishReach * (t1 + t2) * time.rate &&
                    gap_can_close(*eq, p.t1, p.a);
  p.t1 = time.to_user(p.t1);
  p.t2 = time.to_user(p.t2);
  SolutionAt out;
  out.start_t1 = t1;
  out.start_t2 = t2;
  out.t1 = p.t1;
  out.t2 = p.t2;
  out.residual = p.residual;
  out.found = root;
  if (out.found) out.solution = build_solution(system, *user_eq, p, options, options.compute_return_error);
  return out;
}

std::string SolutionAt::brief_report() const {
  std::ostringstream os;
  if (found)
    os << "SPP at (t1, t2) = (" << solution.t1() << ", " << solution.t2() << "), period " << solution.period() << ", "
       << (solution.admissible() ? "admissible" : "not admissible");
  else if (std::isfinite(residual) && std::isfinite(t1) && std::isfinite(t2))
    os << "no SPP near (t1, t2) = (" << start_t1 << ", " << start_t2 << "): Newton reached residual " << residual
       << " at (" << t1 << ", " << t2 << ")";
  else  // (a start far below the axis band, e.g. 1e-300: the equations overflow there; "residual -nan" said nothing)
    os << "no SPP near (t1, t2) = (" << start_t1 << ", " << start_t2 << "): Newton left the finite numbers (the "
       << "equations are not resolvable there: start at t1 and t2 comparable to the system's quarter periods)";
  return os.str();
}

namespace search {

namespace {
// An "interrupted" region (cells not searched) as part of the window searched: the planned axes reach past the
// window's ends (an edge moved clear of a pole line), and a region reported below t2_min told the user to rerun a
// range they had not asked for (found by an independent attack). Nothing is listed when none of it is in the window.
void add_interrupted(const SolveOptions& opt, double a1, double b1, double a2, double b2,
                     std::vector<UncertifiedRegion>& out) {
  const double lo1 = std::max(a1, opt.t1_min), hi1 = std::min(b1, opt.t1_max);
  const double lo2 = std::max(a2, opt.t2_min), hi2 = std::min(b2, opt.t2_max);
  if (lo1 < hi1 && lo2 < hi2) out.push_back({lo1, hi1, lo2, hi2, "interrupted"});
}
}  // namespace

StripOut trace_strip(const EquationSet& eq, const WindowPlan& plan, size_t j, const std::atomic<bool>* stop,
                     TraceCounters* counters) {
  const SolveOptions& opt = plan.options;
  const AxisPlan &a1 = plan.t1, &a2 = plan.t2;
  const size_t I = a1.cells();
  StripOut out;
  out.left.resize(I);
  out.top.resize(I);
  out.right.resize(I);
  out.bottom.resize(I);
  DenseEvaluator evaluator(eq);
  CellTracer tracer(eq, opt, out.stats, evaluator, stop);
  for (size_t i = 0; i < I; ++i) {
    if (stop && *stop) {  // stopped: the rest of the strip is listed as not searched
      out.stats.unsearched_cells += static_cast<long>(I - i);
      add_interrupted(opt, a1.bp[i], a1.bp[I], a2.bp[j], a2.bp[j + 1], out.uncertified);
      break;
    }
    const size_t found_before = tracer.candidates().size();
    const Cell cell{a1.bp[i] + a1.margin[i],
                    a1.bp[i + 1] - a1.margin[i + 1],
                    a2.bp[j] + a2.margin[j],
                    a2.bp[j + 1] - a2.margin[j + 1],
                    a1.pole[i],
                    a1.pole[i + 1],
                    a2.pole[j],
                    a2.pole[j + 1]};
    if (counters) ++counters->cells_done;
    if (!(cell.a1 < cell.b1 && cell.A < cell.B)) continue;
    // curves leave through the left edge (pole line i) into the right edge of cell i - 1, and through the top edge
    // (pole line j + 1) into the bottom edge of strip j + 1
    if (!tracer.trace_cell(cell, i, out.left[i], out.top[i], out.right[i], out.bottom[i])) {
      const bool cut = stop && stop->load();  // stopped inside the cell: its pieces ended early, not searched
      if (cut) {
        ++out.stats.unsearched_cells;
        add_interrupted(opt, cell.a1, cell.b1, cell.A, cell.B, out.uncertified);
      } else {
        out.uncertified.push_back({cell.a1, cell.b1, cell.A, cell.B, "step"});
      }
    }
    if (counters) counters->candidates_found += static_cast<long>(tracer.candidates().size() - found_before);
  }
  out.candidates = std::move(tracer.candidates());
  out.stats.evaluations += evaluator.evaluations();  // plus those of the step certificates
  return out;
}

TracedWindow merge_strips(const WindowPlan& plan, std::vector<StripOut>& strips, SolveResult& res) {
  const size_t I = plan.t1.cells(), J = plan.t2.cells();
  if (strips.size() != J)
    detail::invalid("merge_strips: expected " + std::to_string(J) + " strip outputs, got " +
                                std::to_string(strips.size()));
  TracedWindow tw;
  tw.hits.v_from.assign(I + 1, std::vector<std::vector<EdgeHit>>(J));
  tw.hits.v_to = tw.hits.v_from;
  tw.hits.h_from.assign(J + 1, std::vector<std::vector<EdgeHit>>(I));
  tw.hits.h_to = tw.hits.h_from;
  for (size_t j = 0; j < J; ++j) {
    StripOut& out = strips[j];
    if (out.left.size() != I || out.top.size() != I || out.right.size() != I || out.bottom.size() != I)
      detail::invalid("merge_strips: strip " + std::to_string(j) + " holds hits of " +
                                  std::to_string(out.left.size()) + " cells, expected " + std::to_string(I));
    for (size_t i = 0; i < I; ++i) {
      tw.hits.v_from[i][j] = std::move(out.left[i]);
      tw.hits.h_from[j + 1][i] = std::move(out.top[i]);
      tw.hits.v_to[i + 1][j] = std::move(out.right[i]);
      tw.hits.h_to[j][i] = std::move(out.bottom[i]);
    }
    const SolveStats& s = out.stats;
    res.stats.rectangles += s.rectangles;
    res.stats.curve_pieces += s.curve_pieces;
    res.stats.evaluations += s.evaluations;
    res.stats.certified_steps += s.certified_steps;
    res.stats.heuristic_steps += s.heuristic_steps;
    res.stats.uncertified_steps += s.uncertified_steps;
    res.stats.uncertified_corners += s.uncertified_corners;
    res.stats.unresolved_pieces += s.unresolved_pieces;
    res.stats.unsearched_cells += s.unsearched_cells;
    for (auto& c : out.candidates) tw.candidates.push_back(std::move(c));
    for (auto& u : out.uncertified) res.uncertified.push_back(std::move(u));
  }
  return tw;
}

}  // namespace search

namespace {

// Steps 2-3, over all cells: strips between t2 breakpoints are independent, so workers take whole strips
// (search::trace_strip); the merge is in strip order, so the result does not depend on the number of threads.
search::TracedWindow trace_cells(const EquationSet& eq, const search::WindowPlan& plan, SolveResult& res) {
  const SolveOptions& opt = plan.options;
  const size_t I = plan.t1.cells(), J = plan.t2.cells();
  std::vector<search::StripOut> strips(J);
  std::atomic<size_t> next_strip{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  // progress (SolveOptions::progress): counted by the workers, reported by the calling thread, which may stop them
  search::TraceCounters counters;
  std::atomic<bool> stop{false};
  std::atomic<size_t> workers_done{0};
  auto worker = [&]() {
    try {
      for (size_t j = next_strip++; j < J; j = next_strip++)
        strips[j] = search::trace_strip(eq, plan, j, &stop, &counters);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      failure = std::current_exception();
      stop = true;
    }
    ++workers_done;
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const size_t nthreads = std::min<size_t>(J, opt.threads > 0 ? static_cast<size_t>(opt.threads) : hw);
  std::vector<std::thread> pool;
  const detail::SingleThreadedBlas single_threaded_blas;  // the workers call BLAS / LAPACK at once (no-op if done)
  if (!opt.progress) {
    for (size_t t = 1; t < nthreads; ++t) pool.emplace_back(worker);
    worker();
  } else {  // the workers trace, this thread reports (a callback may need this thread, e.g. Python's GIL)
    for (size_t t = 0; t < nthreads; ++t) pool.emplace_back(worker);
    const auto t0 = std::chrono::steady_clock::now();
    auto report = [&] {
      const SolveProgress p{counters.cells_done.load(), static_cast<long>(I * J), counters.candidates_found.load(),
                            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
      return opt.progress(p);
    };
    // once the callback has returned false it is not called again (the final report too: a second "stop" report
    // after the caller's own, found by an independent attack)
    bool declined = false;
    try {
      auto last = t0;
      while (workers_done.load() < nthreads) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        if (std::chrono::steady_clock::now() - last >= std::chrono::milliseconds(200)) {
          last = std::chrono::steady_clock::now();
          if (!declined && !report()) declined = stop = true;
        }
      }
      if (!declined) report();
    } catch (...) {  // the callback threw: stop the workers, then pass it on
      stop = true;
      for (auto& th : pool) th.join();
      throw;
    }
  }
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);
  return search::merge_strips(plan, strips, res);
}

}  // namespace

std::string SolveProgress::line() const {
  const double done = static_cast<double>(cells_done), total = static_cast<double>(cells_total);
  const double pct = cells_total > 0 ? 100.0 * done / total : 100.0;
  std::ostringstream os;
  os << std::fixed << "cells " << cells_done << " / " << cells_total << " (" << std::setprecision(0) << pct << "%), "
     << candidates << " sign changes of g, " << std::setprecision(1) << seconds << " s elapsed";
  // The time left is recomputed at each report from the mean time per cell so far. It cannot be estimated before a
  // cell is done, nor once every cell has been started (cells_done counts started cells: the last ones can take long,
  // and "~0 s left" stuck on screen while they ran, found by an independent attack): then none is shown.
  if (cells_done > 0 && cells_done < cells_total)
    os << ", ~" << std::setprecision(0) << seconds * (total - done) / done << " s left";
  else if (cells_done >= cells_total && cells_total > 0)
    os << ", finishing the last cells";
  return os.str();
}

namespace {

// True when (t1, t2) lies within kOnPoleLine (relative) of a flight or contact pole line.
bool on_pole_line(const ModalForm& md, double t1, double t2) {
  const double r = search::kOnPoleLine;
  return !md.flight_poles(t1 * (1 - r), t1 * (1 + r)).empty() || !md.contact_poles(t2 * (1 - r), t2 * (1 + r)).empty();
}

// Step 5: polish every candidate, keep the roots inside the half-open window, deduplicate, build orbits.
// Everything here is in the search's time (eq, plan, candidates) but the SPPs, built on user_eq at the user's times,
// and the warnings, which name the user's times.
void polish_candidates(const System& system, const EquationSet& user_eq, const EquationSet& eq,
                       const search::SearchTime& time, const search::WindowPlan& plan,
                       const std::vector<Candidate>& candidates, bool with_return_error, SolveResult& res) {
  const ModalForm& md = eq.modal();
  const SolveOptions& opt = plan.options;
  const double window_scale = opt.t1_max + opt.t2_max;
  // The axes are lines of limits: each point (0, m pi / d_j) where a curve leaves the axis t1 = 0 satisfies both
  // equations in the limit (pure contact oscillation), and there g vanishes with t1 while its rounding error grows
  // like 1 / t1 (the gap to the next eigenvalue is O(t1)): sign changes within 5% of the fastest quarter period of
  // the axis are not resolvable in double precision (an independent brute force sees rounding noise there) and are
  // not reported, whatever the window, so that tilings stay consistent (axis_band). Likewise for t2 -> 0.
  // The window is the user's, in the user's time (start_result put it in res, raised to the axis bands): the
  // half-open rule compares the roots, taken back to the user's time, with the edges the user gave, so that tiles cut
  // at a root's coordinate share it exactly (in the search's time each edge carries the rounding of t * rate).
  const double lo1 = res.t1_min, lo2 = res.t2_min, hi1 = res.t1_max, hi2 = res.t2_max;
  // a root within rounding of an edge is on it (search::kOnEdgeUlps): the half-open rule then gives it to one tile
  // or within Newton's own resolution, where polish stops (kPolishStep of t1 + t2): two tiles' Newton land anywhere
  // within that of each other (up to ~30 ulps of t2 for chain5's root at (3.216, 0.528): a cut 3 ulps below it gave
  // the root to neither tile once the search ran in its own time)
  auto on_edge = [](double t, double edge, double resolution) {
    const double d = std::max(search::kOnEdgeUlps * std::numeric_limits<double>::epsilon() * std::abs(edge), resolution);
    return std::abs(t - edge) <= d ? edge : t;
  };
  auto inside = [&](double tau1, double tau2) {
    const double t1 = time.to_user(tau1), t2 = time.to_user(tau2), r = search::kPolishStep * (t1 + t2);
    const double s1 = on_edge(on_edge(t1, hi1, r), lo1, r), s2 = on_edge(on_edge(t2, hi2, r), lo2, r);
    return s1 > lo1 && s1 <= hi1 && s2 > lo2 && s2 <= hi2;
  };
  // The same place, at the rounding level of the roots: each root, unpolished sign change or artifact counts once.
  auto same_place = [&](double a1, double a2, double b1, double b2) {
    return std::hypot(a1 - b1, a2 - b2) <= search::kSameRoot * window_scale;
  };
  std::vector<std::pair<double, double>> artifacts;  // places of the pole-line artifacts dismissed so far
  std::vector<std::pair<double, double>> roots;      // places of the SPPs kept so far (search time)
  for (const Candidate& c : candidates) {
    const Polished p = polish(eq, c.t1, c.t2, c.b);
    // A candidate that does not polish is not reported as an SPP. Where Newton stalls with a small residual next to a
    // pole line, it stalled on the pole line's artifact of the pole-free form (stats.pole_line_artifacts): dismissed.
    // Anywhere else it is a gap in the search (seen only on such artifacts so far: a stiff 5-dof and the 30-mass
    // chain, both on contact pole lines, both confirmed root-free by the brute force), and the status says so.
    if (!p.converged && p.residual < search::kStalledResidual && on_pole_line(md, p.t1, p.t2)) {
      // counted once per place (many sign changes of the noise along the line stall on the same artifact)
      const bool seen = std::any_of(artifacts.begin(), artifacts.end(), [&](const std::pair<double, double>& a) {
        return same_place(a.first, a.second, p.t1, p.t2);
      });
      if (!seen) {
        artifacts.emplace_back(p.t1, p.t2);
        ++res.stats.pole_line_artifacts;
      }
      continue;
    }
    if (!p.converged) {
      if (!inside(c.t1, c.t2)) continue;
      // the same sign change reached from several steps counts once
      if (std::any_of(res.uncertified.begin(), res.uncertified.end(), [&](const UncertifiedRegion& u) {
            return u.cause == "polish" && same_place(u.t1_lo, u.t2_lo, c.t1, c.t2);
          }))
        continue;
      ++res.stats.unpolished_roots;
      res.uncertified.push_back({c.t1, c.t1, c.t2, c.t2, "polish"});
      // The first kListedUnpolished are named; the rest are counted in one line (finalize), all are in uncertified.
      if (res.stats.unpolished_roots <= kListedUnpolished) {
        std::ostringstream os;
        os << "a sign change of g near (t1, t2) = (" << time.to_user(c.t1) << ", " << time.to_user(c.t2)
           << ") did not polish to a root (residual "
           << p.residual << ")";
        res.warnings.push_back(os.str());
      }
      continue;
    }
    if (!inside(p.t1, p.t2)) continue;
    if (std::any_of(roots.begin(), roots.end(),
                    [&](const std::pair<double, double>& r) { return same_place(r.first, r.second, p.t1, p.t2); }))
      continue;
    if (!gap_can_close(eq, p.t1, p.a)) {  // u^T W^-1 p0 = 0 exactly: eq. (5.2) has no scale
      std::ostringstream os;
      os << "root skipped: at (t1, t2) = (" << time.to_user(p.t1) << ", " << time.to_user(p.t2)
         << ") the gap cannot close (u^T W^-1 p0 = 0)";
      res.warnings.push_back(os.str());
      continue;
    }
    roots.emplace_back(p.t1, p.t2);
    Polished user_p = p;  // N's null vector a does not depend on the time unit (N scales by a power of rate)
    user_p.t1 = time.to_user(p.t1);
    user_p.t2 = time.to_user(p.t2);
    Solution s = build_solution(system, user_eq, user_p, opt, with_return_error);
    if (c.uncertified) s.flags.push_back("uncertified_step");
    if (c.near_pole) s.flags.push_back("near_pole_line");
    res.solutions.push_back(std::move(s));
  }
}

// Step 6: order, filter, status with its counted causes.
void finalize(const SolveOptions& options, SolveResult& res) {
  res.stats.roots = static_cast<long>(res.solutions.size());
  std::sort(res.solutions.begin(), res.solutions.end(),
            [](const Solution& a, const Solution& b) { return a.period() < b.period(); });
  if (options.admissible_only)
    res.solutions.erase(
        std::remove_if(res.solutions.begin(), res.solutions.end(), [](const Solution& s) { return !s.admissible(); }),
        res.solutions.end());
  const SolveStats& st = res.stats;
  auto cause = [&](long count, const char* what) {
    if (count > 0) res.warnings.push_back(std::to_string(count) + " " + what);
  };
  cause(st.uncertified_steps,
        "trace step(s) were not proved, only taken by the midpoint check (a heuristic): certify_steps off, or steps "
        "no bound proved within the step budget (two zero curves side by side, g small and flat, a curve hugging a "
        "pole line); "
        "or g touches zero within the bounds' resolution at the minimum step length (a near-double root)");
  cause(st.unresolved_pieces,
        "curve piece(s) whose null vector could not be followed (step budget spent, or a turn "
        "beyond max_turn within the minimum step: eigenvalues within rounding of each other, "
        "e.g. next to a pole line): a root there is not excluded (cell in 'uncertified')");
  cause(st.uncertified_corners, "cell corner(s) kept an eigenvalue within its error bound of zero");
  cause(st.unsearched_cells,
        "cell(s) were not searched: the search was stopped (progress callback, or Ctrl-C); the strips next to pole "
        "lines were not paired either. What was found is reported; rerun the window (or the cells listed in "
        "'uncertified') for the rest");
  cause(st.unpaired_crossings,
        "curve crossing(s) of a pole line could not be paired: a root in that thin strip is "
        "not excluded");
  cause(st.unpolished_roots - kListedUnpolished,
        "more sign change(s) of g did not polish to a root (each in "
        "'uncertified')");
  for (const Solution& s : res.solutions)
    if (!s.admissibility.certified) res.warnings.push_back("admissibility of an SPP not certified to tolerance");
  res.status = res.warnings.empty() && res.uncertified.empty() ? SolveStatus::Success : SolveStatus::Incomplete;
}

}  // namespace

namespace search {

double reference_frequency(const ModalForm& md) {
  if (md.m() == 0) return 1.0;
  return std::sqrt(md.omega().minCoeff()) * std::sqrt(md.omega().maxCoeff());  // (no overflow of the product)
}

SearchTime::SearchTime(const ModalForm& user, const SolveOptions& user_options)
    : rate(reference_frequency(user)), modal(user.in_time_unit(rate)), options(user_options) {
  options.t1_min *= rate;
  options.t1_max *= rate;
  options.t2_min *= rate;
  options.t2_max *= rate;
}

WindowPlan plan_search(const ModalForm& md, const SolveOptions& options, const SearchTime& time) {
  const auto [band1, band2] = axis_band(md);
  if (options.t1_max <= band1 || options.t2_max <= band2) {
    std::ostringstream os;
    os << "options: the window (" << options.t1_min << ", " << options.t1_max << "] x (" << options.t2_min << ", "
       << options.t2_max << "] lies inside the band next to an axis where roots are not resolvable (t1 <= " << band1
       << " or t2 <= " << band2 << ": 5% of the fastest quarter period of each phase): raise t1_max / t2_max";
    detail::invalid(os.str());
  }
  // refused naming the window as planned in the user's time; the plan below counts the same cells
  check_window_size(md, planned_window(md, options));
  return plan_window(time.modal, time.options);
}

void check_solve_inputs(const System& system, const ModalForm& md, const char* where) {
  require_nonzero_gap(system);
  require_modal_of(system, md, where);
}

SolveResult start_result(const ModalForm& md, const WindowPlan& plan, const SolveOptions& options,
                         const SearchTime& time) {
  SolveResult res;
  res.decoupled_modes = static_cast<int>(md.omega_decoupled().size());
  res.repeated_groups = md.repeated_groups();
  res.symmetry = options.symmetry;
  // the user's ends as given; the automatic lower ends (plan.options) back from the search's time
  const auto [band1, band2] = axis_band(md);
  res.t1_min = std::max(options.t1_min > 0 ? options.t1_min : time.to_user(plan.options.t1_min), band1);
  res.t1_max = options.t1_max;
  res.t2_min = std::max(options.t2_min > 0 ? options.t2_min : time.to_user(plan.options.t2_min), band2);
  res.t2_max = options.t2_max;
  res.stats.flight_pole_lines = plan.t1.poles();
  res.stats.contact_pole_lines = plan.t2.poles();
  return res;
}

void finish_search(const System& system, const EquationSet& user_eq, const EquationSet& eq, const SearchTime& time,
                   const WindowPlan& plan, TracedWindow& traced, const SolveOptions& options, SolveResult& res) {
  // 4. pair the curves across the thin strips around pole lines (a stopped search has no hits from the cells it
  // skipped: its strips are left unpaired, and the status says that the search was stopped)
  if (res.stats.unsearched_cells == 0)
    pair_across_pole_lines(traced.hits, plan.t1, plan.t2, res.stats, res.uncertified, traced.candidates);
  // 5. polish into roots, keep those of the window
  polish_candidates(system, user_eq, eq, time, plan, traced.candidates, options.compute_return_error, res);
  // back to the user's time: the regions not certified (the SPPs are built there already)
  for (UncertifiedRegion& u : res.uncertified) {
    u.t1_lo = time.to_user(u.t1_lo);
    u.t1_hi = time.to_user(u.t1_hi);
    u.t2_lo = time.to_user(u.t2_lo);
    u.t2_hi = time.to_user(u.t2_hi);
  }
  // 6. finalize
  finalize(options, res);
}

}  // namespace search

SolveResult solve(const System& system, const SolveOptions& options) {
  options.validate();
  require_nonzero_gap(system);
  // the modal form too: OpenBLAS's results depend on its thread count (rounding), a solve must not
  const detail::SingleThreadedBlas single_threaded_blas;
  return solve(system, ModalForm(system), options);
}

SolveResult solve(const System& system, const ModalForm& md, const SolveOptions& options) {
  options.validate();
  require_nonzero_gap(system);
  require_modal_of(system, md, "solve");
  const auto t0 = std::chrono::steady_clock::now();
  // the search runs in its own time unit (search::SearchTime), the SPPs are built in the user's
  const search::SearchTime time(md, options);
  const std::unique_ptr<EquationSet> user_eq = make_equations(md, options.symmetry);
  const std::unique_ptr<EquationSet> eq = make_equations(time.modal, options.symmetry);
  // 1. plan the window: search region, pole lines, cells (refused if too many) before any evaluation
  const search::WindowPlan plan = search::plan_search(md, options, time);
  SolveResult res = search::start_result(md, plan, options, time);
  // 2-3. count at the corners and trace the pieces, cell by cell
  search::TracedWindow traced = trace_cells(*eq, plan, res);
  // 4-6. pair, polish, finalize
  search::finish_search(system, *user_eq, *eq, time, plan, traced, options, res);
  res.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

WindowEstimate estimate_window(const System& system, const ModalForm& md, const SolveOptions& options) {
  options.validate();
  require_nonzero_gap(system);
  require_modal_of(system, md, "estimate_window");
  const search::SearchTime time(md, options);
  const search::WindowPlan plan = search::plan_search(md, options, time);
  const SolveResult window = search::start_result(md, plan, options, time);
  WindowEstimate e;
  e.t1_min = window.t1_min;
  e.t1_max = window.t1_max;
  e.t2_min = window.t2_min;
  e.t2_max = window.t2_max;
  e.flight_pole_lines = plan.t1.poles();
  e.contact_pole_lines = plan.t2.poles();
  e.cells = static_cast<long>(plan.t1.cells() * plan.t2.cells());
  // one evaluation as the trace makes it: H, its inertia, the eigenpair nearest the middle of the spectrum
  const std::unique_ptr<EquationSet> eq = make_equations(md, options.symmetry);
  search::DenseEvaluator ev(*eq);
  constexpr int kSamples = 8;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < kSamples; ++i) {
    const double f = (i + 0.5) / kSamples;  // points along the window's diagonal (t2 changes: no cached part)
    const auto h = ev.at(e.t1_min + f * (e.t1_max - e.t1_min), e.t2_min + f * (e.t2_max - e.t2_min));
    const int k = h->size() / 2;
    const double lam = h->eigenvalue(k);
    (void)h->count_below(0.0);
    (void)h->eigenvector(lam);
  }
  e.seconds_per_evaluation = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / kSamples;
  e.evaluations_per_cell = options.certify_steps ? 480.0 : 120.0;
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  e.threads = static_cast<int>(std::min<size_t>(std::max<size_t>(1, plan.t2.cells()),
                                                options.threads > 0 ? static_cast<size_t>(options.threads) : hw));
  e.seconds = static_cast<double>(e.cells) * e.evaluations_per_cell * e.seconds_per_evaluation / e.threads;
  return e;
}

NearestSpp nearest_spp(const System& system, double t1, double t2, double radius, const SolveOptions& options) {
  require_positive_guess("nearest_spp", t1, t2);
  require_nonzero_gap(system);
  return nearest_spp(system, ModalForm(system), t1, t2, radius, options);
}

NearestSpp nearest_spp(const System& system, const ModalForm& modal, double t1, double t2, double radius,
                       const SolveOptions& options) {
  require_positive_guess("nearest_spp", t1, t2);
  if (!(radius > 0 && radius < 1)) {
    std::ostringstream os;
    os << "nearest_spp: radius must be in (0, 1), got " << radius;
    detail::invalid(os.str());
  }
  SolveOptions o = options;
  o.t1_min = t1 * (1 - radius);
  o.t1_max = t1 * (1 + radius);
  o.t2_min = t2 * (1 - radius);
  o.t2_max = t2 * (1 + radius);
  o.admissible_only = false;
  // refused here with what nearest_spp's caller can change (solve's own refusal suggests max_cells, which spp
  // trajectory has no option for)
  o.validate();
  search::check_window_size(modal, o, "nearest_spp (the window searched around the guess)",
                            "give a guess nearer the origin (the SPPs of a result of spp solve), or a smaller radius "
                            "(--radius)");
  const SolveResult r = solve(system, modal, o);
  NearestSpp out;
  out.search_status = r.status;
  out.t1_lo = o.t1_min;
  out.t1_hi = o.t1_max;
  out.t2_lo = o.t2_min;
  out.t2_hi = o.t2_max;
  out.candidates = static_cast<long>(r.solutions.size());
  double best = std::numeric_limits<double>::infinity();
  for (const Solution& s : r.solutions) {
    const double d = std::hypot((s.t1() - t1) / t1, (s.t2() - t2) / t2);
    if (d < best) {
      best = d;
      out.solution = s;
      out.found = true;
    }
  }
  return out;
}

}  // namespace spp
