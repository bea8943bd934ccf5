// spp: command-line tool. Each subcommand (one file each: solve.cpp, continue.cpp, modes.cpp, trajectory.cpp,
// simulate.cpp, verify.cpp, figures.cpp, generate.cpp, reduce.cpp) registers its options and runs: parse -> options ->
// validate -> run -> write (atomically, every output prepared before any is written).
// Exit codes: 0 success, 1 invalid input, usage error, failed run or internal error (message on stderr; an internal
// error, a defect of spp, says so), 3 verify: a simulation disagrees with the solver's admissibility.

#include <iostream>
#include <new>

#include "command.hpp"
#include "spp/detail/dense_products.hpp"
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

int main(int argc, char** argv) {
  // OpenBLAS on the calling thread only, for the whole run: its results depend on its thread count (rounding), so
  // a run gives the same numbers on every machine; and its thread pool's start-up made --dry-run's timing probe
  // read 50-100x high (found by an independent attack).
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  CLI::App app{"spp: periodic orbits with one lasting contact phase per period (SPPs) of vibro-impact systems"};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success (spp solve also when its status is incomplete: read the status); 1 invalid input, usage "
      "error, failed run, out of memory or internal error (one message on stderr naming what and where; no output "
      "file written); 3 spp verify: a simulation disagrees with the solver's admissibility; 130 spp solve stopped "
      "by Ctrl-C (what was found is written, status incomplete).");
  std::vector<spp::cli::Subcommand> commands = {spp::cli::add_solve(app),    spp::cli::add_continue(app),
                                                spp::cli::add_modes(app),    spp::cli::add_trajectory(app),
                                                spp::cli::add_simulate(app), spp::cli::add_verify(app)};
  for (spp::cli::Subcommand& f : spp::cli::add_figures(app)) commands.push_back(std::move(f));
  commands.push_back(spp::cli::add_generate(app));
  commands.push_back(spp::cli::add_reduce(app));
  app.set_version_flag("--version", std::string("spp ") + SPP_VERSION);
  // Usage errors exit 1 like every other error (README), not CLI11's 105-107; --help and --version exit 0.
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "spp: error: " << bounded(e.what()) << "\n(run with --help for the usage)\n";
    return 1;
  }
  try {
    for (const spp::cli::Subcommand& c : commands)
      if (c.app->parsed()) return c.run();
  } catch (const spp::detail::OutOfMemory& e) {  // names what was too large and its size
    std::cerr << "spp: error: " << bounded(e.what()) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "spp: error: out of memory: the system or the window needs more memory than this machine gives "
                 "(a smaller window, or --max-cells, bounds the work)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "spp: error: " << bounded(e.what()) << "\n";
    return 1;
  }
  return 0;
}
