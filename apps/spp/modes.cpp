// spp modes: the families of symmetric k-IPPs (nonsmooth modes, e = 1) continued in energy from their grazing starts
// (docs/modes.md). Exit 0 also when the status is incomplete (a family stalled: read the status), 1 on invalid input,
// 130 when Ctrl-C stopped the tracing (the families traced before it are printed and written, status incomplete).
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "command.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/io.hpp"
#include "spp/io/modes_file.hpp"
#include "spp/modes/nonsmooth_modes.hpp"

namespace spp::cli {

namespace {

// Ctrl-C during the tracing: the first one stops it before the next family point (the families traced so far are
// reported and written, exit code 130, as spp solve); the handler then restores the default, so a second one ends
// the program at once. (Before, Ctrl-C killed spp modes by the signal and the families traced were lost.)
volatile std::sig_atomic_t g_modes_interrupted = 0;
extern "C" void on_modes_interrupt(int) {
  g_modes_interrupted = 1;
  std::signal(SIGINT, SIG_DFL);
}

struct ModesArgs {
  std::string system, k, json;
  modes::ModesOptions options;
  bool no_branches = false, quiet = false;
};

/// "3" -> {3}; "1..4" -> {1, 2, 3, 4}; anything else is refused naming --k.
std::vector<int> parse_k(const std::string& s) {
  const auto bad = [&] {
    std::ostringstream os;
    os << "--k: expected K or K1..K2 with 1 <= K1 <= K2 <= " << modes::kMaxImpactsPerPeriod << ", got \""
       << s.substr(0, 40) << (s.size() > 40 ? "..." : "") << "\"";
    detail::invalid(os.str());
  };
  int a = 0, b = 0;
  char tail = 0;
  if (std::sscanf(s.c_str(), "%d..%d%c", &a, &b, &tail) == 2) {
  } else if (std::sscanf(s.c_str(), "%d%c", &a, &tail) == 1) {
    b = a;
  } else {
    bad();
  }
  if (a < 1 || b < a || b > modes::kMaxImpactsPerPeriod) bad();
  std::vector<int> ks;
  for (int k = a; k <= b; ++k) ks.push_back(k);
  return ks;
}

std::string table(const modes::ModesResult& r) {
  std::ostringstream os;
  char line[512];
  std::snprintf(line, sizeof line, "%4s %3s %-44s %6s %12s %12s %11s %11s  %s\n", "#", "k", "family", "points",
                "E_start", "E_end", "f_start", "f_end", "end");
  os << line;
  int i = 0;
  for (const modes::ModeFamily& f : r.families) {
    std::snprintf(line, sizeof line, "%4d %3d %-44s %6zu %12.6g %12.6g %11.7g %11.7g  %s\n", i++, f.k, f.label.c_str(),
                  f.points.size(), f.points.front().energy, f.points.back().energy, f.points.front().frequency,
                  f.points.back().frequency, modes::to_string(f.events.back().kind));
    os << line;
  }
  return os.str();
}

int run(ModesArgs& a) {
  check_output(a.json, "--json", system_file_inputs(a.system));
  a.options.k_values = parse_k(a.k);
  a.options.branch_points = !a.no_branches;
  a.options.validate();
  const System sys = load_system(a.system);
  g_modes_interrupted = 0;
  // the progress line of spp solve (ProgressLine), rewritten at most every 0.2 s (the callback runs per point)
  ProgressLine line(a.quiet);
  double last = -1.0;
  a.options.progress = [&line, &last](const modes::ModesProgress& p) {
    if (p.seconds - last >= 0.2 || g_modes_interrupted != 0) {
      line.show(p.line(), p.seconds, g_modes_interrupted != 0);
      last = p.seconds;
    }
    return g_modes_interrupted == 0;
  };
  std::signal(SIGINT, on_modes_interrupt);
  const modes::ModesResult r = naming_system_file(a.system, [&] { return modes::nonsmooth_modes(sys, a.options); });
  std::signal(SIGINT, SIG_DFL);
  line.clear();
  const std::string json_text = a.json.empty() ? "" : modes_json(sys, r);
  std::cout << table(r) << r.brief_report() << "\n";
  if (!a.json.empty()) write_file_atomic(a.json, json_text);
  if (r.interrupted) {
    std::cerr << "interrupted: the families above (and in the JSON) are those traced before Ctrl-C (status "
                 "incomplete; a family cut short ends with an event \"interrupted\")\n";
    return 130;
  }
  if (g_modes_interrupted) std::cerr << "note: Ctrl-C came after the tracing had finished: the result is complete\n";
  return 0;
}

}  // namespace

Subcommand add_modes(CLI::App& app) {
  auto a = std::make_shared<ModesArgs>();
  auto* c = app.add_subcommand("modes", "families of periodic orbits with k elastic impacts per period (e = 1)");
  c->add_option("system", a->system, "system JSON file (g0 > 0)")->required();
  c->add_option("--k", a->k, "impacts per period: K or K1..K2 (e.g. 1..3)")->required();
  c->add_option("--energy-max", a->options.energy_max, "families end at this energy")->required();
  c->add_option("--json", a->json, "write families, points and events as JSON (docs/modes.md)");
  c->add_option("--max-step", a->options.max_step, "largest step in scaled arclength (default 0.05)");
  c->add_flag("--quiet", a->quiet, "no progress line on stderr (shown when stderr is a terminal, from 1 s on)");
  c->add_flag("--no-branches", a->no_branches, "do not follow the genuine k-IPPs branching off the repetitions");
  c->add_option("--multiples", a->options.period_multiples,
                "with k = 1: 1-IPP families also from each mode's grazing orbit seen with period j times its own, "
                "j = 2..J (default 1: none; docs/modes.md §3)");
  c->add_option("--seed-period-max", a->options.seed_period_max,
                "also seed families from the plane of their two flight durations, periods up to this (symmetric "
                "k = 2, 3, 4 with one impact inside the half orbit; docs/modes.md §3)");
  c->add_flag("--through-inadmissible", a->options.through_inadmissible,
              "follow each family's solution curve through its inadmissible orbits (not listed): where it is "
              "admissible again below --energy-max a new family starts (event admissibility_regained)");
  return {c, [a] { return run(*a); }};
}

}  // namespace spp::cli
