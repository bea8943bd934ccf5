// spp: command-line tool. Each subcommand (one file each: solve.cpp, continue.cpp, modes.cpp, trajectory.cpp,
// simulate.cpp, verify.cpp, figures.cpp, generate.cpp, reduce.cpp) registers its options and runs: parse -> options ->
// validate -> run -> write (atomically, every output prepared before any is written).
// Exit codes: 0 success, 1 invalid input, usage error, failed run or internal error (message on stderr; an internal
// error, a defect of spp, says so), 3 verify, 4 sweep, 5 simulate, 130 solve, modes, 143 solve (command.hpp lists
// them; the footer below and README say the same, tests/cli checks both and drives each).

#include <algorithm>
#include <chrono>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <new>
#include <set>
#include <stdexcept>
#include <thread>

#include "command.hpp"
#include "parallel.hpp"
#include "spp/detail/dense_products.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/detail/out_of_memory.hpp"

namespace {
// Every message printed, at most 4000 characters: the last guard against echoing unbounded input (a message quotes
// the user's text shortened, but CLI11's quote option values whole).
std::string bounded(const char* what) {
  const std::string m(what);
  constexpr size_t kMax = 4000;
  return m.size() > kMax ? m.substr(0, kMax) + "... (message cut at " + std::to_string(kMax) + " characters)" : m;
}
}  // namespace

namespace spp::cli {
// Every option that takes a value, the files and directories written (and --parameter, --values) worded as such: an
// empty text is refused naming the option (`--json ""` was silently ignored, `spp trajectory --csv ""` failed with
// 'cannot write "": rename failed'; found by an independent attack), on every subcommand, nested ones (generate chain)
// included.
void refuse_empty_texts(CLI::App& app) {
  static const std::map<std::string, std::string> kExpected = {{"json", "a file path"},
                                                               {"csv", "a file path"},
                                                               {"out", "a path"},
                                                               {"out-dir", "a directory's path"},
                                                               {"events", "a file path"},
                                                               {"spp-csv", "a file path"},
                                                               {"parameter", "the parameter's name"},
                                                               {"values", "values (start:stop:step or 1,2.5,3)"}};
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    for (CLI::Option* opt : sub->get_options([](CLI::Option*) { return true; })) {
      if (opt->get_type_size_min() <= 0) continue;  // a flag
      // every option that takes a value (CLI11 read `--t1-max ""` as 0); the paths' and names' wording from the list
      std::string expected = "a value";
      for (const std::string& name : opt->get_lnames())
        if (const auto it = kExpected.find(name); it != kExpected.end()) expected = it->second;
      opt->check(CLI::Validator(
          [expected](std::string& text) {
            return text.empty() ? "expected " + expected + ", got an empty text" : std::string();
          },
          ""));
      // every whole-number option reads counts as --help writes them (1e6; CLI11 said "Could not convert"); its own
      // range is checked by its options' validate()
      if (opt->get_type_name() == "INT") opt->transform(whole_number(-kMaxCount, kMaxCount));
      // every real option decimal, as the lists and values are (CLI11 read `--t1-max 0x3` as 3; found by an
      // independent attack); its own range is checked by its options' validate()
      if (opt->get_type_name() == "FLOAT")
        opt->check(CLI::Validator([](std::string& text) { return text.empty() ? "" : number_problem(text); }, ""));
    }
    refuse_empty_texts(*sub);
  }
}
}  // namespace spp::cli

namespace {
// CLI11's "Could not convert: --periods = 1000000000000" of a whole number as "expected ... from INT_MIN to INT_MAX,
// got ..."; any other conversion failure as CLI11 says it.
std::string out_of_int_range(const std::string& message) {
  const std::string head = "Could not convert: ";
  const size_t eq = message.find(" = ");
  if (message.rfind(head, 0) != 0 || eq == std::string::npos) return message;
  const std::string opt = message.substr(head.size(), eq - head.size()), value = message.substr(eq + 3);
  const size_t digits = value.find_first_not_of("+-") == std::string::npos ? 0 : value.find_first_not_of("+-");
  if (value.empty() || value.find_first_not_of("0123456789", digits) != std::string::npos || digits > 1) return message;
  return opt + ": expected a whole number from " + std::to_string(std::numeric_limits<int>::min()) + " to " +
         std::to_string(std::numeric_limits<int>::max()) +
         " (the option's integer; its own range is checked next), got " + value + ": out of range";
}
}  // namespace

int main(int argc, char** argv) {
  const spp::cli::Runtime runtime(argc, argv);  // MPI in spp-mpi (parallel.hpp)
  // OpenBLAS on the calling thread only, for the whole run: its results depend on its thread count (rounding), so
  // a run gives the same numbers on every machine; and its thread pool's start-up made --dry-run's timing probe
  // read 50-100x high (found by an independent attack).
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  CLI::App app{"spp: periodic orbits with one lasting contact phase per period (SPPs) of vibro-impact systems"};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success (also when the status of spp solve, continue, modes or a sweep item is incomplete: read "
      "the status); 1 invalid input, usage "
      "error, failed run, out of memory or internal error (one message on stderr naming what and where; no output "
      "file written); 3 spp verify: the result disagrees with the simulation or the system (an admissibility the "
      "simulation contradicts, a claimed stability the recomputed multipliers contradict, or x0, v0 that are not the "
      "orbit at (t1, t2)), or an SPP was not checked (status incomplete: its simulation would pass the simulator's "
      "limit; a warning names it); 4 spp sweep: at least one "
      "item failed (each named on stderr; the others' results and the table are written); 5 spp simulate stopped "
      "at --max-events before --duration (the CSV holds the trajectory up to the last event); 130 spp solve or "
      "modes stopped by Ctrl-C (what was found is written, status incomplete); 143 spp solve stopped by SIGTERM "
      "(SLURM's time limit, scancel: the same as Ctrl-C); any other subcommand ends at once on Ctrl-C, by the signal "
      "(a shell shows 130 too).");
  std::vector<spp::cli::Subcommand> commands = {spp::cli::add_solve(app),    spp::cli::add_continue(app),
                                                spp::cli::add_modes(app),    spp::cli::add_trajectory(app),
                                                spp::cli::add_simulate(app), spp::cli::add_verify(app)};
  for (spp::cli::Subcommand& f : spp::cli::add_figures(app)) commands.push_back(std::move(f));
  commands.push_back(spp::cli::add_generate(app));
  commands.push_back(spp::cli::add_reduce(app));
  commands.push_back(spp::cli::add_sweep(app));
  spp::cli::refuse_empty_texts(app);
  app.set_version_flag("--version", std::string("spp ") + SPP_VERSION);
  // on every subcommand too (`spp solve --version` was a usage error, exit 1; found by an independent attack)
  std::function<void(CLI::App&)> version_everywhere = [&](CLI::App& parent) {
    for (CLI::App* sub : parent.get_subcommands([](CLI::App*) { return true; })) {
      sub->set_version_flag("--version", std::string("spp ") + SPP_VERSION);
      version_everywhere(*sub);
    }
  };
  version_everywhere(app);
  // A first word that is neither an option nor a subcommand is named, with the subcommands (CLI11 said "A subcommand
  // is required", as if none had been given; found by an independent attack); so is the second word of a subcommand
  // that requires one of its own (`spp generate foo` said the same; found by an attack on issue 13).
  CLI::App* parent = &app;
  for (int word = 1; word < argc && argv[word][0] != '-' && parent->get_require_subcommand_min() > 0; ++word) {
    const std::vector<CLI::App*> subcommands = parent->get_subcommands([](CLI::App*) { return true; });
    const auto match = std::find_if(subcommands.begin(), subcommands.end(),
                                    [&](CLI::App* sub) { return sub->check_name(argv[word]); });
    if (match == subcommands.end()) {
      if (spp::cli::is_root()) {
        std::string names;
        for (const CLI::App* sub : subcommands) names += (names.empty() ? "" : ", ") + sub->get_name();
        std::cerr << "spp: error: unknown " << (parent == &app ? "subcommand" : parent->get_name() + " subcommand")
                  << " \"" << bounded(argv[word]) << "\": expected one of " << names
                  << "\n(run with --help for the usage)\n";
      }
      return 1;
    }
    parent = *match;
  }
  // Usage errors exit 1 like every other error (README), not CLI11's 105-107; --help and --version exit 0.
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {  // under mpirun, printed by rank 0 only (found by an independent attack)
    return spp::cli::is_root() ? app.exit(e) : 0;
  } catch (const CLI::CallForAllHelp& e) {
    return spp::cli::is_root() ? app.exit(e) : 0;
  } catch (const CLI::CallForVersion& e) {
    return spp::cli::is_root() ? app.exit(e) : 0;
  } catch (const CLI::ConversionError& e) {
    // a whole number that passed whole_number (|n| <= 1e15) but that the option's int cannot hold: said with the range
    // (--periods 1e12 and --threads 99999999999 said "Could not convert"; found by fuzzing, issue 11)
    if (spp::cli::is_root())
      std::cerr << "spp: error: " << bounded(out_of_int_range(e.what()).c_str())
                << "\n(run with --help for the usage)\n";
    return 1;
  } catch (const CLI::ParseError& e) {
    if (spp::cli::is_root()) std::cerr << "spp: error: " << bounded(e.what()) << "\n(run with --help for the usage)\n";
    return 1;
  }
  // An error message: rank 0 prints it as spp does; another rank names itself. Under MPI every rank runs the same
  // checks of the input: another rank gives rank 0 a moment to print the same message and end the run (its own is then
  // not printed), and prints its own only when that did not happen (an error of that rank alone).
  // An input error found by every rank (they validate alike) ends them all through MPI_Finalize, exit code 1 and one
  // message; only an error of one rank alone aborts the others (every_rank_failed waits kAgreeSeconds for them).
  constexpr double kAgreeSeconds = 10.0;
  auto error = [](const std::string& what, bool input_error) {
    if (spp::cli::is_root()) std::cerr << "spp: error: " << what << "\n" << std::flush;
    if (input_error && spp::cli::every_rank_failed(kAgreeSeconds)) return 1;
    if (!spp::cli::is_root()) std::cerr << "spp (rank " << spp::cli::rank() << "): error: " << what << "\n";
    return spp::cli::end_on_error(1);
  };
  try {
    for (const spp::cli::Subcommand& c : commands)
      if (c.app->parsed()) {
        if (spp::cli::ranks() > 1 && !spp::cli::distributed(c.app->get_name()))
          spp::detail::invalid("spp " + c.app->get_name() +
                               " does not run on several MPI ranks (only solve and sweep do): run it with "
                               "build/spp, or with one rank");
        // the subcommands that build modal forms and solve eigenproblems (plot and animate through the Python
        // package, which inherits the variable); generate, --help and --version start at once (they re-executed
        // the binary too, found by a review)
        static const std::set<std::string> kDenseAlgebra = {"solve",  "continue", "modes",   "trajectory", "simulate",
                                                            "verify", "plot",     "animate", "reduce",     "sweep"};
        if (kDenseAlgebra.count(c.app->get_name()) != 0) spp::cli::prefer_fast_blas(argv);
        return c.run();
      }
  } catch (const spp::detail::OutOfMemory& e) {  // names what was too large and its size
    return error(bounded(e.what()), false);
  } catch (const std::bad_alloc&) {
    return error(
        "out of memory: the system or the window needs more memory than this machine gives "
        "(a smaller window, or --max-cells, bounds the work)",
        false);
  } catch (const std::invalid_argument& e) {
    return error(bounded(e.what()), true);
  } catch (const std::exception& e) {
    return error(bounded(e.what()), false);
  }
  return 0;
}
