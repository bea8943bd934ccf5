// spp simulate: the exact event-driven simulator from any initial state.
#include <iostream>
#include <memory>
#include <stdexcept>

#include "command.hpp"
#include "spp/io.hpp"
#include "spp/simulation/simulator.hpp"

namespace spp::cli {

namespace {

struct SimulateArgs {
  std::string system, x0, v0, csv, events;
  SimulateOptions options;
  double per_unit = 100.0;
};

int run(SimulateArgs& a) {
  const std::vector<std::string> inputs = system_file_inputs(a.system);  // the system file and its Matrix Market files
  check_output(a.csv, "--csv", inputs);
  check_output(a.events, "--events", inputs, {{"--csv", a.csv}});
  const System sys = load_system(a.system);
  const std::vector<double> x0 = parse_list(a.x0, "--x0"), v0 = parse_list(a.v0, "--v0");
  a.options.validate();
  a.options.sample_times = uniform_times(a.options.duration, a.per_unit);
  const SimulationResult r =
      simulate(sys, Eigen::Map<const Eigen::VectorXd>(x0.data(), static_cast<Eigen::Index>(x0.size())),
               Eigen::Map<const Eigen::VectorXd>(v0.data(), static_cast<Eigen::Index>(v0.size())), a.options);
  const std::string csv = simulation_csv(r);
  const std::string events = a.events.empty() ? "" : events_csv(r);
  std::cout << r.brief_report() << "\n";
  if (r.status == SimulationStatus::Stalled)  // a defect of the simulator: exit 1, nothing written (README)
    throw std::runtime_error("simulation stalled (over 100 events in a row without time passing) at t = " +
                             std::to_string(r.end_time) + ": please report it with the command line");
  write_file_atomic(a.csv, csv);
  if (!a.events.empty()) write_file_atomic(a.events, events);
  if (r.status != SimulationStatus::Success) {  // EventLimit: a partial result, exit 5
    std::cerr << "spp: simulation stopped: " << to_string(r.status) << " before t = " << a.options.duration
              << " (--max-events " << a.options.max_events << "); the CSV holds the trajectory up to t = " << r.end_time
              << " (exit code 5)\n";
    return 5;
  }
  return 0;
}

}  // namespace

Subcommand add_simulate(CLI::App& app) {
  auto a = std::make_shared<SimulateArgs>();
  auto* s = app.add_subcommand("simulate", "exact event-driven simulation from any initial state");
  s->add_option("system", a->system, "system JSON file")->required();
  s->add_option("--x0", a->x0, "initial positions, comma-separated")->required();
  s->add_option("--v0", a->v0, "initial velocities, comma-separated")->required();
  s->add_option("--duration", a->options.duration, "simulated time T (last row at t = T)")->required();
  s->add_option("--restitution", a->options.restitution, "Newton's coefficient e in [0, 1] (default 0)");
  s->add_option("--csv", a->csv, "output CSV: t, x1..xn, v1..vn, gap, force, contact")->required();
  s->add_option("--events", a->events, "output CSV of the impacts, contact onsets and releases");
  s->add_option("--samples-per-unit", a->per_unit,
                "rows per unit of time (default 100; 0: only t = 0, the events and t = T), plus one per event");
  s->add_option("--max-events", a->options.max_events, "stop after this many events (default 1e7)")
      ->transform(whole_number(1, kMaxCount));
  return {s, [a] { return run(*a); }};
}

}  // namespace spp::cli
