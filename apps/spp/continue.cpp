// spp continue: every SPP of a window followed as the system's parameter varies.
#include <iostream>
#include <memory>

#include "command.hpp"
#include "spp/continuation/continuation.hpp"
#include "spp/io.hpp"
#include "tables.hpp"

namespace spp::cli {

namespace {

struct ContinueArgs {
  std::string system, json, symmetry = "axial";
  ContinueOptions options;
  bool quiet = false;
};

int run(ContinueArgs& a) {
  check_output(a.json, "--json", system_file_inputs(a.system));  // the system file and its Matrix Market files
  const ParametricSystem ps = load_parametric_system(a.system);
  a.options.symmetry = *symmetry_named(a.symmetry);  // CLI11 checked the name
  const ContinuationResult cr = naming_system_file(a.system, [&] { return continue_branches(ps, a.options); });
  const std::string json_text = a.json.empty() ? "" : continuation_json(ps, cr);
  if (!a.quiet) std::cout << continuation_table(cr);
  std::cout << cr.brief_report() << "\n";
  for (const auto& w : cr.warnings) std::cerr << "warning: " << w << "\n";
  if (!a.json.empty()) write_file_atomic(a.json, json_text);
  return 0;
}

}  // namespace

Subcommand add_continue(CLI::App& app) {
  auto a = std::make_shared<ContinueArgs>();
  auto* c = app.add_subcommand("continue", "follow every SPP of a window as the system's parameter varies");
  ContinueOptions& o = a->options;
  c->add_option("system", a->system, "parametric system JSON file (with \"parameter\")")->required();
  c->add_option("--t1-max", o.t1_max, "largest flight half-duration t1")->required();
  c->add_option("--t2-max", o.t2_max, "largest contact half-duration t2")->required();
  c->add_option("--t1-min", o.t1_min, "smallest t1 (default as solve)");
  c->add_option("--t2-min", o.t2_min, "smallest t2 (default as solve)");
  c->add_option("--seeds", o.seeds, "parameter values where solve seeds branches (default 9)");
  c->add_option("--max-step", o.max_step, "largest step in scaled arclength (default 0.02)");
  c->add_option("--json", a->json, "write branches, points and events as JSON");
  c->add_flag("--quiet", a->quiet, "print only the one-line summary");
  c->add_option("--symmetry", a->symmetry, "axial (SPPs, default) or point (det T2 = 0, paper §6.2)")
      ->check(CLI::IsMember({"axial", "point"}));
  return {c, [a] { return run(*a); }};
}

}  // namespace spp::cli
