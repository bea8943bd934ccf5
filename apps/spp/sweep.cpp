// spp sweep: one solve per parameter value (a parametric system file) or per system file; one result file each in
// --out-dir, then the table of every SPP with its value. A stopped sweep run again resumes from the files written.
#include "spp/distributed/sweep.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "command.hpp"
#include "parallel.hpp"
#include "spp/io/files.hpp"
#include "spp/detail/invalid.hpp"

namespace spp::cli {

namespace {

// Most values one sweep takes (each is a solve and a file); README, "Sweeps and MPI".
constexpr double kMaxSweepValues = 1e6;

struct SweepArgs {
  std::vector<std::string> systems;
  std::string parameter, values, out_dir, csv, json, symmetry = "axial";
  SolveOptions options;
  bool quiet = false;
};

// "start:stop:step" or "1,2.5,3". start:stop:step gives the decimal values a user expects: count = (stop - start) /
// step rounded when within 1e-9 (relative) of a whole number (then the last value is stop exactly), else its floor;
// value i = start + i step, snapped to 15 significant digits of the range's scale (1.7, not 1.7000000000000002 =
// 1 + 7 x 0.1; 0, not 5.6e-17) and never past stop (0.1:0.7:0.1 ended at 0.7000000000000001; found by an
// independent attack).
std::vector<double> parse_values(const std::string& text) {
  if (text.find(':') == std::string::npos) return parse_list(text, "--values");
  const std::string shown = text.size() > 80 ? text.substr(0, 80) + "..." : text;
  const std::string bad =
      "--values: expected start:stop:step (step > 0, stop >= start) or comma-separated numbers, got \"" + shown + "\"";
  double v[3];
  std::stringstream ss(text);
  std::string item;
  int k = 0;
  while (std::getline(ss, item, ':')) {
    if (k == 3) detail::invalid(bad);
    const std::optional<double> x = parse_number(item);
    if (!x) detail::invalid(bad);
    v[k] = *x;
    ++k;
  }
  const double start = v[0], stop = v[1], step = v[2];
  if (k != 3 || !std::isfinite(start) || !std::isfinite(stop) || !(step > 0) || !std::isfinite(step) || stop < start)
    detail::invalid(bad);
  const double steps = (stop - start) / step;  // may overflow to inf (1:2:1e-320)
  if (!(steps + 1 <= kMaxSweepValues)) {
    char about[32];
    std::snprintf(about, sizeof about, "%.3g", steps + 1);
    detail::invalid("--values: expected at most " + std::to_string(static_cast<long>(kMaxSweepValues)) +
                    " values (each is a solve and a file), got about " + about + " from \"" + shown + "\"");
  }
  const double whole = std::round(steps);
  const bool reaches_stop = std::abs(steps - whole) <= 1e-9 * std::max(1.0, steps);
  const long count = static_cast<long>(reaches_stop ? whole : std::floor(steps)) + 1;
  const double scale = std::max({std::abs(start), std::abs(stop), step});
  const double quantum = std::pow(10.0, std::floor(std::log10(scale)) - 14);
  std::vector<double> raw, values;
  for (long i = 0; i < count; ++i) {
    const double x = start + static_cast<double>(i) * step;
    raw.push_back(std::min(x, stop));
    char buf[40];
    // (a subnormal quantum, values near 1e-300, has too few bits to snap to: those are only rounded to 15 digits)
    std::snprintf(buf, sizeof buf, "%.15g", quantum > 1e-290 ? std::round(x / quantum) * quantum : x);
    values.push_back(std::min(std::strtod(buf, nullptr), stop));
  }
  if (reaches_stop) values.back() = raw.back() = stop;
  // a step near the last digits of the scale (1e6:1e6+1e-6:1e-12): snapping would merge values; kept unsnapped
  for (size_t i = 1; i < values.size(); ++i)
    if (!(values[i] > values[i - 1])) return raw;
  return values;
}

// The shortest text that reads back to v (-0.9, not -0.90000000000000002).
std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string item_name(const Sweep& sweep, size_t i) {
  const SweepItem& item = sweep.items()[i];
  std::ostringstream os;
  os << "[" << i << "] ";
  if (sweep.parameter().empty())
    os << item.system_file;
  else
    os << sweep.parameter() << " = " << shortest(item.value);
  return os.str();
}

int run(SweepArgs& a) {
  a.options.symmetry = *symmetry_named(a.symmetry);
  a.options.validate();
  const bool by_value = !a.parameter.empty();
  if (by_value != !a.values.empty())
    detail::invalid(
        std::string("--parameter and --values go together (a sweep over the values of a parametric system's "
                    "parameter); without them, give system files: expected both or neither, got only ") +
        (by_value ? "--parameter" : "--values"));
  if (by_value && a.systems.size() != 1)
    detail::invalid("--parameter: give one parametric system file, got " +
                                std::to_string(a.systems.size()) + " files");
  const std::string csv = a.csv.empty() ? a.out_dir + "/sweep.csv" : a.csv;
  const std::string json = a.json.empty() ? a.out_dir + "/sweep.json" : a.json;
  const Sweep sweep = by_value ? Sweep::over_values(a.systems.front(), a.parameter, parse_values(a.values), a.out_dir)
                               : Sweep::over_files(a.systems, a.out_dir);
  // before any solve and any file written: the out-dir can be written, and the result files already there are this
  // sweep's (a refused resume rewrote the table with every item failed; found by an independent attack)
  check_sweep_outputs(sweep, a.options);
  std::vector<std::string> inputs = a.systems;
  std::vector<NamedOutput> outputs;
  for (const SweepItem& item : sweep.items())
    outputs.push_back({"the result of " + item_name(sweep, item.index), item.result_file});
  check_output(csv, "--csv", inputs, outputs);
  inputs.push_back(csv);
  check_output(json, "--json", inputs, outputs);
  const bool root = is_root();
  if (root)
    for (const std::string& note : sweep.notes()) std::cerr << "spp sweep: note: " << note << "\n";
  auto on_done = [&](size_t i, const SweepItemOutcome& o) {
    if (root && !a.quiet)
      std::cerr << "  " << item_name(sweep, i) << ": " << to_string(o.status) << " (" << i + 1 << " / "
                << sweep.items().size() << ")\n";
  };
  const std::vector<SweepItemOutcome> outcomes = sweep_items(sweep, a.options, on_done);
  if (!root) return 0;  // rank 0 holds every outcome and writes the table
  const SweepTable table = sweep_table(sweep, outcomes);
  const std::string csv_text = sweep_table_csv(table), json_text = sweep_table_json(table);
  write_file_atomic(csv, csv_text);
  write_file_atomic(json, json_text);
  for (size_t i = 0; i < outcomes.size(); ++i)
    if (outcomes[i].status == SweepItemStatus::Failed)
      std::cerr << "sweep: " << item_name(sweep, i) << " failed: " << outcomes[i].message << "\n";
  std::cout << table.brief_report() << "; table: " << csv << ", " << json << "\n";
  return table.failed() > 0 ? 4 : 0;
}

}  // namespace

Subcommand add_sweep(CLI::App& app) {
  auto a = std::make_shared<SweepArgs>();
  auto* s = app.add_subcommand(
      "sweep",
      "one solve per parameter value (--parameter, --values) or per system file, one result file each in --out-dir, "
      "and the table of every SPP with its value; run again, it resumes from the result files already written; on "
      "MPI (mpirun -n P spp-mpi sweep) the items are spread over the ranks");
  SolveOptions& o = a->options;
  s->add_option("systems", a->systems, "system JSON files (one parametric file with --parameter)")->required();
  s->add_option("--parameter", a->parameter, "the parameter swept: the name the parametric system file declares");
  s->add_option("--values", a->values,
                "the parameter's values: start:stop:step (stop included when a whole number of steps reaches it; at "
                "most 1e6 values) or 1,2.5,3");
  s->add_option("--out-dir", a->out_dir, "directory of the result files (one per item) and the table")->required();
  s->add_option("--csv", a->csv, "the table as CSV (default <out-dir>/sweep.csv)");
  s->add_option("--json", a->json, "the table as JSON (default <out-dir>/sweep.json)");
  s->add_option("--t1-max", o.t1_max, "largest flight half-duration t1 (required)")->required();
  s->add_option("--t2-max", o.t2_max, "largest contact half-duration t2 (required)")->required();
  s->add_option("--t1-min", o.t1_min, "smallest t1 (default: 1e-4 pi / (2 omega_max))");
  s->add_option("--t2-min", o.t2_min, "smallest t2 (default: 1e-4 pi / (2 d_max))");
  s->add_option("--threads", o.threads,
                "worker threads of each solve (on MPI: per rank; default 0: all hardware threads, divided by the "
                "ranks on the node)");
  s->add_option("--max-cells", o.max_cells, "refuse windows holding more cells than this (default 1e7)")
      ->transform(whole_number(1, kMaxCount));
  s->add_flag("--certify-steps,!--no-certify-steps", o.certify_steps, "as spp solve (default: certify)");
  s->add_flag("--admissible-only", o.admissible_only, "keep only admissible SPPs");
  s->add_option("--symmetry", a->symmetry, "axial (default) or point, as spp solve")
      ->check(CLI::IsMember({"axial", "point"}));
  s->add_flag("--quiet", a->quiet, "no line per item");
  return {s, [a] { return run(*a); }};
}

}  // namespace spp::cli
