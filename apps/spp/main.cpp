// spp: command-line tool. Each subcommand (one file each: solve.cpp, continue.cpp, modes.cpp, trajectory.cpp,
// simulate.cpp, verify.cpp, figures.cpp, generate.cpp, reduce.cpp) registers its options and runs: parse -> options ->
// validate -> run -> write (atomically, every output prepared before any is written).
// Exit codes: 0 success, 1 invalid input, usage error, failed run or internal error (message on stderr; an internal
// error, a defect of spp, says so), 3 verify: a simulation disagrees with the solver's admissibility.

#include <chrono>
#include <iostream>
#include <new>
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

int main(int argc, char** argv) {
  const spp::cli::Runtime runtime(argc, argv);  // MPI in spp-mpi (parallel.hpp)
  // OpenBLAS on the calling thread only, for the whole run: its results depend on its thread count (rounding), so
  // a run gives the same numbers on every machine; and its thread pool's start-up made --dry-run's timing probe
  // read 50-100x high (found by an independent attack).
  const spp::detail::SingleThreadedBlas single_threaded_blas;
  CLI::App app{"spp: periodic orbits with one lasting contact phase per period (SPPs) of vibro-impact systems"};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success (spp solve also when its status is incomplete: read the status); 1 invalid input, usage "
      "error, failed run, out of memory or internal error (one message on stderr naming what and where; no output "
      "file written); 3 spp verify: a simulation disagrees with the solver's admissibility; 4 spp sweep: at least one "
      "item failed (each named on stderr; the others' results and the table are written); 5 spp simulate stopped "
      "at --max-events before --duration (the CSV holds the trajectory up to the last event); 130 spp solve stopped "
      "by Ctrl-C (what was found is written, status incomplete).");
  std::vector<spp::cli::Subcommand> commands = {spp::cli::add_solve(app),    spp::cli::add_continue(app),
                                                spp::cli::add_modes(app),    spp::cli::add_trajectory(app),
                                                spp::cli::add_simulate(app), spp::cli::add_verify(app)};
  for (spp::cli::Subcommand& f : spp::cli::add_figures(app)) commands.push_back(std::move(f));
  commands.push_back(spp::cli::add_generate(app));
  commands.push_back(spp::cli::add_reduce(app));
  commands.push_back(spp::cli::add_sweep(app));
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
    if (spp::cli::is_root()) std::cerr << "spp: error: " << bounded(e.what()) << "\n(run with --help for the usage)\n";
    return 1;
  }
  // An error message: rank 0 prints it as spp does; another rank names itself. Under MPI every rank runs the same
  // checks of the input: another rank gives rank 0 a moment to print the same message and end the run (its own is then
  // not printed), and prints its own only when that did not happen (an error of that rank alone).
  auto error = [](const std::string& what, bool input_error) {
    if (spp::cli::is_root()) {
      std::cerr << "spp: error: " << what << "\n";
    } else {
      if (input_error) std::this_thread::sleep_for(std::chrono::seconds(5));
      std::cerr << "spp (rank " << spp::cli::rank() << "): error: " << what << "\n";
    }
    return spp::cli::end_on_error(1);
  };
  try {
    for (const spp::cli::Subcommand& c : commands)
      if (c.app->parsed()) {
        if (spp::cli::ranks() > 1 && !spp::cli::distributed(c.app->get_name()))
          spp::detail::invalid("spp " + c.app->get_name() +
                               " does not run on several MPI ranks (only solve and sweep do): run it with "
                               "build/spp, or with one rank");
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
