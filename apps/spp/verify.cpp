// spp verify: every SPP of a result re-simulated by the exact event-driven simulator.
#include <iostream>
#include <memory>

#include "command.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"
#include "spp/simulation/verify.hpp"
#include "tables.hpp"

namespace spp::cli {

namespace {

struct VerifyArgs {
  std::string result, json;
  VerifyOptions options;
};

int run(const VerifyArgs& a) {
  check_output(a.json, "--json", {a.result});
  const ResultFile file = load_result_file(a.result);
  // the modal form the solver used: a system it refuses (a spectrum beyond double precision) is refused here too,
  // naming the file, not simulated for minutes to disagree (found by an independent attack)
  naming_system_file(a.result, [&] { return ModalForm(file.system); });
  const VerifyResult r = verify(file.system, file.result.solutions, a.options);
  const std::string json_text = a.json.empty() ? "" : verify_json(r);
  for (const std::string& w : r.warnings) std::cerr << "spp verify: warning: " << w << "\n";
  std::cout << verify_table(r) << r.brief_report() << "\n";
  if (!a.json.empty()) write_file_atomic(a.json, json_text);
  return r.all_consistent() ? 0 : 3;
}

}  // namespace

Subcommand add_verify(CLI::App& app) {
  auto a = std::make_shared<VerifyArgs>();
  auto* v = app.add_subcommand("verify", "re-simulate every SPP of a result and check it");
  v->add_option("result", a->result, "result JSON of spp solve")->required();
  v->add_option("--periods", a->options.periods, "simulated periods (default 1)");
  v->add_option("--perturb", a->options.perturbation,
                "relative size of a perturbation of the mid-flight state of each returning SPP");
  v->add_option("--restitution", a->options.restitution, "Newton's coefficient e for the simulations (default 0)");
  v->add_option("--json", a->json, "write the verification as JSON");
  return {v, [a] { return run(*a); }};
}

}  // namespace spp::cli
