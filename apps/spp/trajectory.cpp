// spp trajectory: one period of an SPP (of a result file, or the nearest to a guess) as CSV.
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "command.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"
#include "spp/detail/invalid.hpp"

namespace spp::cli {

namespace {

struct TrajectoryArgs {
  std::string system, csv, result;
  double t1 = 0, t2 = 0, radius = 0.05;
  int samples = 1001, solution = -1;
  CLI::Option* t1_given = nullptr;
};

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
    const System& solved = file->system;
    if (solved.n() != sys.n() || !solved.M().isApprox(sys.M(), kSameToRounding) ||
        !solved.K().isApprox(sys.K(), kSameToRounding) || !solved.w().isApprox(sys.w(), kSameToRounding) ||
        std::abs(solved.g0() - sys.g0()) > kSameToRounding * std::abs(sys.g0()))
      detail::invalid(a.result + ": was solved for another system than " + a.system + " (omit " + a.system +
                                  ": the result file holds its system)");
  }
  const ModalForm md(sys);  // once, for the search and the samples
  std::optional<Solution> loaded;
  if (!a.result.empty()) {
    if (a.solution < 0) detail::invalid("trajectory: --result needs --solution K (0-based)");
    const std::vector<Solution>& sols = file->result.solutions;
    if (static_cast<size_t>(a.solution) >= sols.size())
      detail::invalid(a.result + ": --solution " + std::to_string(a.solution) +
                                  " out of range, the file has " + std::to_string(sols.size()) + " solutions");
    loaded = sols[static_cast<size_t>(a.solution)];
  } else if (a.t1_given->count() == 0) {
    detail::invalid("trajectory: give --t1 and --t2, or --result and --solution");
  }
  SolveOptions o;
  o.compute_return_error = false;
  Solution s;
  if (loaded) {
    s = *loaded;  // an SPP of a result file, as it was solved (its orbit rebuilt in this modal basis if need be)
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
  t->add_option("--solution", a->solution, "index of the solution in --result");
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
