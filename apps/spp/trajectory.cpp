// spp trajectory: one period of an SPP (of a result file, or the nearest to a guess) as CSV.
#include <algorithm>
#include <limits>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "command.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/verify.hpp"

namespace spp::cli {

namespace {

struct TrajectoryArgs {
  std::string system, csv, result;
  double t1 = 0, t2 = 0, radius = 0.05;
  int samples = 1001, solution = -1;
  CLI::Option* t1_given = nullptr;
};

// The SPP at the (t1, t2) of solution K of a result file, polished again (its verdicts recomputed, not read), refused
// unless it is the file's solution: x0, v0 and the admissibility verdict the same (a file edited by hand, or whose
// x0 belongs to another orbit, would otherwise be drawn as an SPP it is not).
Solution file_solution(const System& sys, const ModalForm& md, const Solution& stored, const SolveOptions& o,
                       const std::string& file, int k) {
  // relative: polishing again moves a well-conditioned root by ~1e-13, an edit by O(1); at least the problem's own
  // error: the file's state and the one polished again each within spp verify's state tolerance (100 eps_s,
  // docs/result-files.md) of the SPP. With a fixed 1e-8, a genuine SPP of a chain with a spring 1e6 times the others
  // (moved by 1.25e-7) was refused as "edited" (issue 11 finding).
  constexpr double kSameSpp = 1e-8, kTwoStates = 2.0 * 100.0;
  const double tol = std::max(kSameSpp, kTwoStates * expected_state_error(sys, md, stored.period()));
  const std::string which = file + ": solution " + std::to_string(k);
  const SolutionAt at = solution_at(sys, md, stored.t1(), stored.t2(), o);
  if (!at.found) {
    std::ostringstream os;
    os.precision(3);
    os << which << " could not be polished again at its (t1, t2): " << at.brief_report() << " (the file says residual "
       << stored.residual << ", the solver's acceptance): the equations are not resolved to that precision there (a "
       << "stiff or ill-conditioned system), or the file was edited";
    detail::invalid(os.str());
  }
  const Solution& s = at.solution;
  const double wmin = md.m() > 0 ? md.omega().minCoeff() : 1.0;  // v / wmin: a length, like x
  const double scale = s.x0().norm() + s.v0().norm() / wmin + std::abs(sys.g0());
  const double moved = (s.x0() - stored.x0()).norm() + (s.v0() - stored.v0()).norm() / wmin;
  if (!(moved <= tol * scale)) {
    std::ostringstream os;
    os.precision(3);
    os << which << " is no SPP of its system: its x0, v0 differ from those of the SPP polished again at its (t1, t2) = ("
       << stored.t1() << ", " << stored.t2() << ") by " << moved / scale << " (relative), more than the tolerance "
       << tol << " (the problem's own error, docs/result-files.md): the file was edited, or its SPP is another "
       << "system's (load_result reads a file as written; trajectory and verify check its SPPs against the system)";
    detail::invalid(os.str());
  }
  if (s.admissible() != stored.admissible())
    detail::invalid(which + " says " + (stored.admissible() ? "admissible" : "not admissible") +
                    ", but the SPP at its (t1, t2) is " + (s.admissible() ? "admissible" : "not admissible"));
  return s;
}

int run(TrajectoryArgs& a) {
  std::vector<std::string> inputs = system_file_inputs(a.system);  // the system file and its Matrix Market files
  inputs.push_back(a.result);
  check_output(a.csv, "--csv", inputs);
  if (a.system.empty() && a.result.empty())
    detail::invalid("trajectory: give SYSTEM.json with --t1 and --t2, or --result and --solution");
  // a result file holds the system it was solved for: SYSTEM.json is then optional, and must be that system
  std::optional<ResultFile> file;
  if (!a.result.empty()) file = load_result_file(a.result);
  const System sys = a.system.empty() ? file->system : load_system(a.system);
  check_trajectory_csv_size(a.samples, sys.n(), "--samples");  // before the search and any sample is computed
  if (file && !a.system.empty()) {
    if (!same_system(file->system, sys))
      detail::invalid(a.result + ": was solved for another system than " + a.system + " (omit " + a.system +
                      ": the result file holds its system)");
  }
  // once, for the search and the samples; a refusal of the system names the file it came from
  const ModalForm md = naming_system_file(a.system.empty() ? a.result : a.system, [&] { return ModalForm(sys); });
  std::optional<Solution> loaded;
  if (!a.result.empty()) {
    if (a.solution < 0)
      detail::invalid("trajectory: --result needs --solution K (0-based): expected both, got --result alone");
    const std::vector<Solution>& sols = file->result.solutions;
    if (static_cast<size_t>(a.solution) >= sols.size())
      detail::invalid(
          a.result + ": --solution " + std::to_string(a.solution) + " out of range, the file has " +
          std::to_string(sols.size()) + " solutions: expected " +
          (sols.empty() ? std::string("none (no solution to show)") : "0 to " + std::to_string(sols.size() - 1)) +
          ", got " + std::to_string(a.solution));
    loaded = sols[static_cast<size_t>(a.solution)];
  } else if (a.t1_given->count() == 0) {
    detail::invalid("trajectory: give --t1 and --t2, or --result and --solution");
  }
  SolveOptions o;
  o.compute_return_error = false;
  Solution s;
  if (loaded) {  // an SPP of a result file: polished again where it is, and checked to be the file's solution
    o.symmetry = file->result.symmetry;
    s = file_solution(sys, md, *loaded, o, a.result, a.solution);
  } else {  // a guess (e.g. read off the root map): the complete solver around it, then the nearest SPP
    const NearestSpp near = nearest_spp(sys, md, a.t1, a.t2, a.radius, o);
    if (!near.found) {
      std::ostringstream os;
      os << "trajectory: no SPP near (t1, t2) = (" << a.t1 << ", " << a.t2 << "): the window (" << near.t1_lo << ", "
         << near.t1_hi << "] x (" << near.t2_lo << ", " << near.t2_hi << "] holds none (search "
         << to_string(near.search_status) << "); widen it with --radius";
      detail::invalid(os.str());
    }
    s = near.solution;
    if (near.search_status != SolveStatus::Success)
      std::cerr << "warning: the search around the guess ended " << to_string(near.search_status) << "\n";
  }
  write_file_atomic(a.csv, trajectory_csv(md, s.orbit, a.samples));
  std::cout << "trajectory of the SPP at t1 = " << s.t1() << ", t2 = " << s.t2() << " (period " << s.period() << ", "
            << (s.admissible() ? "admissible" : "not admissible") << ") written to " << a.csv << "\n";
  return 0;
}

}  // namespace

Subcommand add_trajectory(CLI::App& app) {
  auto a = std::make_shared<TrajectoryArgs>();
  auto* t = app.add_subcommand("trajectory", "sample one period of an SPP: t, x, v, gap, force");
  t->add_option("system", a->system, "system JSON file (optional with --result, whose file holds it)");
  a->t1_given = t->add_option("--t1", a->t1, "flight half-duration (refined to the nearest SPP)");
  auto* t2 = t->add_option("--t2", a->t2, "contact half-duration (refined to the nearest SPP)");
  t->add_option("--radius", a->radius,
                "with --t1/--t2: relative half-width of the window searched around the guess (default 0.05)")
      ->check(CLI::Range(1e-12, 0.999));
  auto* res = t->add_option("--result", a->result, "result JSON of spp solve");
  t->add_option("--solution", a->solution, "index of the solution in --result (0-based)")
      ->transform(whole_number(0, std::numeric_limits<int>::max()));
  t->add_option("--csv", a->csv, "output CSV")->required();
  t->add_option("--samples", a->samples,
                "number of samples over one period (default 1001; at most 2e7 values, samples x (2n + 3), in the CSV)")
      ->check(CLI::Range(2, 10000000));
  a->t1_given->needs(t2);
  t2->needs(a->t1_given);
  res->excludes(a->t1_given);
  return {t, [a] { return run(*a); }};
}

}  // namespace spp::cli
