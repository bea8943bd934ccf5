#pragma once
// The spp command line: one file per subcommand (solve.cpp, continue.cpp, ...), each registering its options on the
// application and returning how to run it. Exit codes (README "Exit codes", spp --help's footer; main.cpp maps usage
// errors and exceptions): 0 success (also an incomplete status), 1 invalid input, usage error or failed run (message
// on stderr), 3 verify: the result disagrees with the simulation or the system (admissibility, stability, x0/v0),
// 4 sweep: at least one item failed, 5 simulate: stopped at --max-events (the CSV holds the trajectory so far), 130
// solve, modes: stopped by Ctrl-C, 143 solve: stopped by SIGTERM.

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "spp/detail/invalid.hpp"

namespace spp::cli {

/// A registered subcommand: run() is called when the user chose it (after parsing); returns the exit code.
struct Subcommand {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Subcommand add_solve(CLI::App& app);
Subcommand add_continue(CLI::App& app);
/// modes: k-IPP families (nonsmooth modes, e = 1), docs/modes.md.
Subcommand add_modes(CLI::App& app);
Subcommand add_trajectory(CLI::App& app);
Subcommand add_simulate(CLI::App& app);
Subcommand add_verify(CLI::App& app);
/// plot and animate: delegated to the Python package (python3 -m spp plot|animate).
std::vector<Subcommand> add_figures(CLI::App& app);
Subcommand add_generate(CLI::App& app);
/// reduce: a large sparse model to a small system file (Craig-Bampton).
Subcommand add_reduce(CLI::App& app);
/// sweep: one solve per parameter value or system file, resumable; on MPI spread over the ranks (parallel.hpp).
Subcommand add_sweep(CLI::App& app);

/// An output of a run and the option that names it, e.g. {"--json", "r.json"}.
struct NamedOutput {
  std::string option, path;
};
/// An output file named by option `opt`: refused before any work when it is one of `inputs` (files the run reads, or
/// outputs not named in `outputs`) or one of the run's other `outputs` (it would be replaced; the message names the
/// option of that output), or when its directory does not exist or cannot be written (a probe file is created there
/// and removed: the work would be lost at the end).
void check_output(const std::string& out, const std::string& opt, const std::vector<std::string>& inputs,
                  const std::vector<NamedOutput>& outputs = {});
/// "1,2.5,3" -> {1, 2.5, 3}; anything else is refused naming the option.
/// The whole of `item` read as one number (std::stod), or nullopt ("1.5xyz", "", out of range).
std::optional<double> parse_number(const std::string& item);
std::vector<double> parse_list(const std::string& s, const char* opt);
/// f(), with a refusal of the system itself re-thrown naming the file it came from: the checks made when the modal
/// form is built or a solve starts (g0 = 0, a spectrum beyond double precision) say "system: ..." and know no path.
template <class F>
decltype(auto) naming_system_file(const std::string& path, F&& f) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    if (m.rfind("system: ", 0) == 0) detail::invalid(path + ": " + m.substr(8));
    if (m.rfind("KippModel: ", 0) == 0) detail::invalid(path + ": " + m.substr(11));  // (spp modes)
    // the system at one parameter value (spp continue: "parametric system at k2 = 0.5: ..." named no file; issue 11)
    if (m.rfind("parametric system", 0) == 0) detail::invalid(path + ": " + m);
    throw;
  }
}
/// A count option's check: "1e7" reads as 10000000 (as --help writes defaults), anything not a whole number in
/// [min, max] is refused naming the option (CLI11 read "1e3" as an error and 1e20 as some long).
CLI::Validator whole_number(double min, double max);
/// Empty when `text` is a decimal number parse_number reads; else what is wrong with it ("expected a decimal number
/// ..., got ..." or "... is beyond the range of a double ..."), for the messages of options and lists.
std::string number_problem(const std::string& text);
/// The progress line of a long run (spp solve, spp modes) on stderr, rewritten in place: only when stderr is a
/// terminal and not --quiet, and only from 1 s on (short runs stay silent); " (stopping)" once Ctrl-C came. clear()
/// blanks it once the run is over (blanks, then back to the line's start): the summary and the table replace it.
class ProgressLine {
 public:
  explicit ProgressLine(bool quiet);
  void show(const std::string& line, double seconds, bool stopping);
  void clear();

 private:
  bool tty_ = false, shown_ = false;
  int width_ = 0;  // the longest line written, so that clear() blanks it all
};
/// The largest count an option takes: every such count stays exact in a double.
inline constexpr double kMaxCount = 1e15;

}  // namespace spp::cli
