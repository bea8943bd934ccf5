// spp solve: every SPP of a window (or, for a parametric system with g0 = 0, of (t1, t2, parameter), paper §6.1).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <tuple>

#include "command.hpp"
#include "parallel.hpp"
#include "spp/continuation/continuation.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"
#include "tables.hpp"
#include "spp/detail/invalid.hpp"

namespace spp::cli {

namespace {

struct SolveArgs {
  std::string system, json, csv, symmetry = "axial";
  SolveOptions options;
  bool quiet = false, box = false, dry_run = false;
  double at = 0.0;
  CLI::Option* at_given = nullptr;
  CLI::Option* t1_max_given = nullptr;
  CLI::Option* t2_max_given = nullptr;
};

// Ctrl-C (SIGINT) or SIGTERM (what SLURM sends at a time limit, and scancel) during a solve: the first one stops the
// search (the result found so far is reported and written, status incomplete), exit code 128 + the signal's number
// (130, 143, as a shell reports a process the signal ended); the handler then restores the default, so a second one
// ends the program at once. Holds the signal's number, 0 before any.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int sig) {
  g_interrupted = sig;
  std::signal(sig, SIG_DFL);
}
constexpr int kExitBySignal = 128;  // + the signal's number: the shell's convention

// The progress callback of the CLI: the progress line (ProgressLine, command.hpp) and the Ctrl-C check.
std::function<bool(const SolveProgress&)> cli_progress(ProgressLine& line) {
  return [&line](const SolveProgress& p) {
    line.show(p.line(), p.seconds, g_interrupted != 0);
    return g_interrupted == 0;
  };
}

// From this many dofs, spp solve announces its stages before the search (each O(n^3) stage takes seconds).
constexpr int kStageNotesFrom = 500;

// A parametric system with g0 = 0: its SPPs are gap closures along the parameter (continuation finds them).
int run_zero_gap(const SolveArgs& a) {
  if (ranks() > 1)
    detail::invalid(
        "the g0 = 0 solve (continuation in the parameter) does not run on several MPI ranks: "
        "run it with one rank, or build/spp");
  if (a.box) detail::invalid("--box: not available for the g0 = 0 solve (give --t1-max and --t2-max)");
  const ParametricSystem ps = load_parametric_system(a.system);
  if (ps.g0() != 0.0)
    detail::invalid(a.system + ": a parametric system with g0 != 0: give --at VALUE of \"" +
                                ps.parameter().name + "\", or follow its SPPs with spp continue");
  if (!a.csv.empty()) detail::invalid("--csv: not available for the g0 = 0 solve (use --json)");
  ContinueOptions co;
  co.t1_max = a.options.t1_max;
  co.t2_max = a.options.t2_max;
  co.t1_min = a.options.t1_min;
  co.t2_min = a.options.t2_min;
  co.threads = a.options.threads;
  co.symmetry = a.options.symmetry;
  const ContinuationResult cr = continue_branches(ps, co);
  const std::string json_text = a.json.empty() ? "" : zero_gap_json(ps, cr);
  if (!a.quiet) std::cout << zero_gap_table(cr);
  std::cout << "spp: g0 = 0, solved for (t1, t2, " << ps.parameter().name << "): " << gap_closures(cr).size()
            << (a.options.symmetry == Symmetry::Point ? " point-symmetric potential SPPs with " : " SPPs with ")
            << ps.parameter().name << " in [" << ps.parameter().min << ", " << ps.parameter().max << "] ("
            << cr.brief_report() << ")\n";
  for (const auto& w : cr.warnings) std::cerr << "warning: " << w << "\n";
  if (!a.json.empty()) write_file_atomic(a.json, json_text);
  return 0;
}

// The parametric system at --at, a refusal naming the option, the file and the value (M or K not positive definite
// there was reported as "M[0][0] must be finite" or the like, with no word of --at).
System system_at(const ParametricSystem& ps, double at, const std::string& path) {
  try {
    return ps.at(at);
  } catch (const std::invalid_argument& e) {
    std::ostringstream os;
    os << "--at " << at << ": " << path << " at " << ps.parameter().name << " = " << at << " is no valid system: "
       << e.what();
    detail::invalid(os.str());
  }
}

int run(SolveArgs& a) {
  a.options.symmetry = *symmetry_named(a.symmetry);  // CLI11 checked the name
  const bool maxes = a.t1_max_given->count() > 0 || a.t2_max_given->count() > 0;
  if (a.box && maxes)
    detail::invalid("--box sets the window's upper ends: give it or --t1-max/--t2-max: expected one of them, got both");
  if (!a.box && !(a.t1_max_given->count() > 0 && a.t2_max_given->count() > 0))
    detail::invalid(std::string("--t1-max and --t2-max are required (or --box: the fundamental box): expected both, "
                                "got ") +
                    (a.t1_max_given->count() > 0   ? "only --t1-max"
                     : a.t2_max_given->count() > 0 ? "only --t2-max"
                                                   : "neither"));
  if (!a.box) a.options.validate();                                // with --box, once the box is known (below)
  std::vector<std::string> inputs = system_file_inputs(a.system);  // the system file and its Matrix Market files
  check_output(a.json, "--json", inputs);
  inputs.push_back(a.json);
  check_output(a.csv, "--csv", inputs);
  const bool parametric = file_declares_parameter(a.system);
  const bool at_given = a.at_given->count() > 0;
  if (!parametric && at_given)
    detail::invalid("--at: " + a.system +
                    " is not a parametric system (it has no field \"parameter\"): expected "
                    "--at only with a parametric system file, got a system without a parameter");
  if (parametric && !at_given) return run_zero_gap(a);
  g_interrupted = 0;  // Ctrl-C from here on stops the search at its first report (and then reports what was found)
  // (on several MPI ranks there is no such report: mpirun forwards Ctrl-C, and it ends the run)
  if (ranks() == 1) {
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
  }
  const bool root = is_root();  // prints and writes (rank 0 on MPI)
  std::optional<ParametricSystem> ps;
  if (parametric) {
    if (!std::isfinite(a.at)) detail::invalid("--at: expected a finite parameter value, got " + std::to_string(a.at));
    ps = load_parametric_system(a.system);
    const Parameter& par = ps->parameter();
    if (root && (a.at < par.min || a.at > par.max))  // allowed (the system is affine in it), but likely a slip
      std::cerr << "note: --at " << a.at << " lies outside the range [" << par.min << ", " << par.max << "] that "
                << a.system << " declares for " << par.name << "\n";
  }
  // Large systems spend minutes before the search reports progress (reading, the O(n^3) checks and modal form):
  // each stage is announced on stderr with its time, so that the run is never silent.
  const auto clock_start = std::chrono::steady_clock::now();
  auto elapsed = [&clock_start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  };
  const System sys = parametric ? system_at(*ps, a.at, a.system) : load_system(a.system);
  const bool stages = root && !a.quiet && sys.n() >= kStageNotesFrom;
  if (stages)
    std::cerr << "spp: " << sys.n() << " dofs read and checked in " << std::setprecision(3) << elapsed()
              << " s; computing the modal form (O(n^3): two eigenproblems of size n)\n";
  const ModalForm modal = naming_system_file(a.system, [&] { return ModalForm(sys); });
  if (stages) std::cerr << "spp: modal form done at " << std::setprecision(3) << elapsed() << " s\n";
  if (a.box) {
    std::tie(a.options.t1_max, a.options.t2_max) = fundamental_box(modal);
    if (a.options.t1_min >= a.options.t1_max || a.options.t2_min >= a.options.t2_max) {
      std::ostringstream m;
      m << std::setprecision(10) << "--box: the fundamental box t1 <= " << a.options.t1_max
        << ", t2 <= " << a.options.t2_max << " does not reach beyond --t1-min " << a.options.t1_min << " / --t2-min "
        << a.options.t2_min;
      detail::invalid(m.str());
    }
    a.options.validate();
    if (root && !a.quiet)
      std::cout << "fundamental box: t1 <= pi / omega_1 = " << a.options.t1_max
                << ", t2 <= pi / d_1 = " << a.options.t2_max << "\n";
  }
  if (a.dry_run) {  // the work, before any: pole lines, cells, a rough time; nothing written
    if (!root) return 0;
    // an estimate is what --dry-run asks for, also of a window past --max-cells (it was refused like a solve; found by
    // an attack on issue 13): counted up to kDryRunMaxCells, whose pole lines (1e5 per axis) are listed in moments
    constexpr long kDryRunMaxCells = 10'000'000'000;
    // past that, said as such (counted without listing, O(n)): the refusal named max_cells = 1e10, an option the
    // user never set (found by an independent attack)
    const double lines1 = count_tangent_poles(modal.omega(), a.options.t1_min, a.options.t1_max);
    const double lines2 = count_tangent_poles(modal.d(), a.options.t2_min, a.options.t2_max);
    if ((lines1 + 1.0) * (lines2 + 1.0) > static_cast<double>(kDryRunMaxCells)) {
      std::ostringstream os;
      os << std::setprecision(3) << "solve --dry-run: the window (" << a.options.t1_min << ", " << a.options.t1_max
         << "] x (" << a.options.t2_min << ", " << a.options.t2_max << "] holds about "
         << (lines1 + 1.0) * (lines2 + 1.0) << " cells (" << lines1 << " x " << lines2
         << " pole lines): beyond what --dry-run can estimate (it plans "
         << "at most " << static_cast<double>(kDryRunMaxCells) << " cells; spp solve refuses more than --max-cells "
         << a.options.max_cells << "): expected a narrower window";
      detail::invalid(os.str());
    }
    SolveOptions counted = a.options;
    counted.max_cells = std::max(counted.max_cells, kDryRunMaxCells);
    const WindowEstimate e = estimate_window(sys, modal, counted);
    std::cout << std::setprecision(6) << "window (" << e.t1_min << ", " << e.t1_max << "] x (" << e.t2_min << ", "
              << e.t2_max << "]: " << e.flight_pole_lines << " flight and " << e.contact_pole_lines
              << " contact pole lines, " << e.cells << " cells\n"
              << std::setprecision(2) << "one evaluation of H here: " << e.seconds_per_evaluation * 1e3
              << " ms; estimate: " << e.cells << " cells x ~" << static_cast<long>(e.evaluations_per_cell)
              << " evaluations per cell (benchmarks' mean" << (a.options.certify_steps ? ", certified" : "") << ") / "
              << e.threads << " thread(s) ~ " << e.seconds << " s wall time (" << e.seconds * e.threads
              << " s CPU time; rough: actual CPU time measured 0.11x to 12x of this, larger systems higher; README)\n";
    if (e.cells > a.options.max_cells)
      std::cout << "the window exceeds --max-cells " << a.options.max_cells << ": spp solve refuses it (raise "
                << "--max-cells to run it, or narrow the window)\n";
    return 0;
  }
  ProgressLine line(a.quiet);
  a.options.progress = cli_progress(line);
  const SolveResult res = naming_system_file(a.system, [&] { return solve_window(sys, modal, a.options); });
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!root) return 0;  // rank 0 holds the merged result
  line.clear();
  // prepare every output before writing any
  const std::string json_text = a.json.empty() ? "" : result_json(sys, res);
  const std::string csv_text = a.csv.empty() ? "" : result_to_csv(res);
  if (std::abs(sys.w_input_norm() - 1.0) > kSameToRounding)  // (a unit w's norm may round to 1 - 1 ulp)
    std::cerr << "note: w was normalised (|w| = " << sys.w_input_norm() << "); g0 divided by it: g0 = " << sys.g0()
              << "\n";
  if (!a.quiet) std::cout << result_table(res);
  std::cout << res.brief_report() << "\n";
  for (const auto& w : res.warnings) std::cerr << "warning: " << w << "\n";
  if (!a.json.empty()) write_file_atomic(a.json, json_text);
  if (!a.csv.empty()) write_file_atomic(a.csv, csv_text);
  const char* by = g_interrupted == SIGTERM ? "SIGTERM" : "Ctrl-C";
  if (g_interrupted && res.stats.unsearched_cells == 0)
    std::cerr << "note: " << by << " came after the search had finished: the result is complete\n";
  if (res.stats.unsearched_cells > 0) {
    std::cerr << "interrupted" << (g_interrupted == SIGTERM ? " by SIGTERM" : "") << ": " << res.stats.unsearched_cells
              << " cell(s) not searched; the result "
              << "above (and its files) holds what was found before\n";
    return kExitBySignal + (g_interrupted == SIGTERM ? SIGTERM : SIGINT);
  }
  return 0;
}

}  // namespace

Subcommand add_solve(CLI::App& app) {
  auto a = std::make_shared<SolveArgs>();
  auto* s = app.add_subcommand("solve", "find every SPP whose half-durations lie in a window");
  SolveOptions& o = a->options;
  s->add_option("system", a->system, "system JSON file")->required();
  a->t1_max_given = s->add_option("--t1-max", o.t1_max, "largest flight half-duration t1 (required, or --box)");
  a->t2_max_given = s->add_option("--t2-max", o.t2_max, "largest contact half-duration t2 (required, or --box)");
  s->add_flag("--box", a->box,
              "the fundamental box as window: t1 <= pi / omega_1, t2 <= pi / d_1 (slowest flight mode, slowest "
              "contact oscillation)");
  // what a lower end 0 gives (start_result reports from axis_band, 0.05 quarter periods; planned_window searches,
  // and the --max-cells refusal counts, from half of it): the help said 1e-4 quarter periods (default_lower_ends,
  // which the band overrides whenever the window reaches past it; found by an attack on issue 13)
  s->add_option("--t1-min", o.t1_min,
                "smallest t1 (default: from the axis: the window reported starts at 0.05 pi / (2 omega_max), as "
                "no root nearer the axis is resolvable, and is searched (and counted by --max-cells) from half of "
                "that)");
  s->add_option("--t2-min", o.t2_min,
                "smallest t2 (default: from the axis: the window reported starts at 0.05 pi / (2 d_max), searched "
                "from half of that)");
  s->add_option("--json", a->json, "write the result as JSON");
  s->add_option("--csv", a->csv, "write the solutions as CSV");
  s->add_flag("--admissible-only", o.admissible_only, "keep only admissible SPPs");
  s->add_flag("--quiet", a->quiet, "print only the one-line summary");
  s->add_flag("--dry-run", a->dry_run,
              "print the window's pole lines, cells and a rough time estimate, then stop (writes nothing)");
  s->add_option("--threads", o.threads, "worker threads (default 0: all hardware threads)");
  s->add_option("--max-cells", o.max_cells,
                "refuse windows holding more cells between pole lines than this (default 1e7)")
      ->transform(whole_number(1, kMaxCount));
  s->add_flag("--certify-steps,!--no-certify-steps", o.certify_steps,
              "prove every trace step (default; drift, curvature, spectral or onset-inertia bound): success only if "
              "every step is proved. --no-certify-steps: the midpoint check takes every step (3-25x faster, a "
              "heuristic: the status is then incomplete)");
  s->add_option("--symmetry", a->symmetry,
                "axial: the SPPs (default); point: the point-symmetric potential SPPs of det T2 = 0 (paper §6.2, "
                "never admissible, a moving obstacle)")
      ->check(CLI::IsMember({"axial", "point"}));
  a->at_given = s->add_option("--at", a->at,
                              "parametric system: solve at this parameter value (without it, a parametric system "
                              "with g0 = 0 is solved for (t1, t2, parameter), paper §6.1)");
  return {s, [a] { return run(*a); }};
}

}  // namespace spp::cli
