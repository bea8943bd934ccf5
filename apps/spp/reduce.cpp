// spp reduce: a large sparse model (spp generate bar, or M and K from a finite-element code as Matrix Market files) to
// its contact coordinate plus m fixed-interface modes (Craig-Bampton, reduction/craig_bampton.hpp): a small system
// file that spp solve reads. Several m (--modes 10,20,40) give one file each and a table of the reduced frequencies
// against m (the convergence study); --window also solves each reduced model there and lists its admissible SPPs.
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "command.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"
#include "spp/reduction/craig_bampton.hpp"
#include "spp/search/solver.hpp"
#include "spp/detail/invalid.hpp"

namespace spp::cli {

namespace {

struct ReduceArgs {
  std::string model, out, modes = "20", window, csv, spp_csv, layout;
  int frequencies = 6;
  int threads = 0;
  bool certify_steps = true;
};

std::vector<int> parse_modes(const std::string& s) {
  std::vector<int> ms;
  for (double v : parse_list(s, "--modes")) {
    if (v != std::floor(v) || v < 1 || v > 1e6)
      detail::invalid("--modes: expected positive whole numbers (e.g. 10,20,40), got \"" + s + "\"");
    ms.push_back(static_cast<int>(v));
  }
  for (size_t i = 1; i < ms.size(); ++i)
    if (ms[i] <= ms[i - 1])
      detail::invalid("--modes: expected increasing numbers of modes, got \"" + s + "\"");
  return ms;
}

// --out R.json with one m: R.json; with several: R-m10.json, R-m20.json, ...
std::string out_name(const std::string& out, int m, bool several) {
  if (!several) return out;
  namespace fs = std::filesystem;
  const fs::path p(out);
  return (p.parent_path() / (p.stem().string() + "-m" + std::to_string(m) + p.extension().string())).string();
}

// The layout file of a reduced model R.json: R.layout.json beside it (python3 -m spp animate --fe-layout)
std::string layout_name(const std::string& out) {
  namespace fs = std::filesystem;
  const fs::path p(out);
  return (p.parent_path() / (p.stem().string() + ".layout.json")).string();
}

int run(const ReduceArgs& a) {
  const std::vector<int> modes = parse_modes(a.modes);
  const bool several = modes.size() > 1;
  std::vector<double> window;
  if (!a.window.empty()) {
    window = parse_list(a.window, "--window");
    if (window.size() != 2 || !(window[0] > 0) || !(window[1] > 0))
      detail::invalid("--window: expected T1MAX,T2MAX (both positive), got \"" + a.window + "\"");
  }
  // outputs: none an input (the model or its Matrix Market files), none another output, directories existing
  const std::vector<std::string> inputs = system_file_inputs(a.model);
  std::vector<NamedOutput> outputs;
  for (int m : modes) outputs.push_back({"--out", out_name(a.out, m, several)});
  if (!a.csv.empty()) outputs.push_back({"--csv", a.csv});
  if (!a.spp_csv.empty()) {
    if (window.empty())
      detail::invalid(
          "--spp-csv: needs --window (the SPPs of the reduced models): expected --window with it, got none");
    outputs.push_back({"--spp-csv", a.spp_csv});
  }
  if (!a.layout.empty())
    for (int m : modes) outputs.push_back({"--layout (the reduced layout)", layout_name(out_name(a.out, m, several))});
  for (size_t k = 0; k < outputs.size(); ++k)
    check_output(outputs[k].path, outputs[k].option, inputs, {outputs.begin(), outputs.begin() + k});

  const SparseSystem model = load_sparse_system(a.model);
  // the reduced model keeps g0: with g0 = 0 spp solve would refuse it after the reduction's work
  if (model.g0() == 0.0)
    detail::invalid(a.model +
                                ": g0 = 0 (obstacle touching the rest position): spp solve refuses such a "
                                "model (SPPs then exist only for special parameter values, paper §6.1), so it is not "
                                "reduced; give the gap at rest a non-zero g0");
  std::cout << model.name() << ": " << model.n() << " dofs, " << model.K().nonZeros() << " non-zeros in K\n";

  // the dofs to draw (--layout): their rows of the reduction basis go into each reduced model's layout file
  ReductionOptions ro;
  FeLayout layout;
  if (!a.layout.empty()) {
    layout = read_fe_layout(a.layout, model.n());
    if (layout.basis.size() > 0)
      detail::invalid(a.layout + ": a layout with a \"basis\" belongs to a reduced model: expected the full model's "
                      "layout (dofs, coordinates, directions), got a basis");
    layout = sample_fe_layout(layout, kMaxExpansionDofs);
    layout.model_dofs = model.n();
    for (const long d : layout.dofs) ro.expansion_dofs.push_back(static_cast<int>(d));
  }
  // one factorisation and one eigensolve (for the largest m) serve every m
  std::vector<ReductionResult> results = reduce(model, modes, ro);
  for (const ReductionResult& r : results) {
    std::cout << "m = " << r.modes << ": " << r.brief_report() << "\n";
    if (r.status != ReductionResult::Status::Success)
      throw std::runtime_error("reduce: m = " + std::to_string(r.modes) + ": " + to_string(r.status) +
                               " (the fixed-interface modes did not converge): nothing written");
  }
  const ReductionTimings& t = results.back().timings;
  std::cout << std::setprecision(3) << "stages: coordinates " << t.transform_seconds << " s, factorisations "
            << t.factorization_seconds << " s, " << modes.back() << " fixed-interface modes " << t.eigen_seconds
            << " s (" << (results.back().dense_eigensolver ? "dense eigensolver" : "Spectra") << "), total "
            << t.total_seconds << " s\n";

  // the convergence table: the lowest natural frequencies of each reduced model
  const int k_show = std::min<int>(a.frequencies, modes.front() + 1);
  std::ostringstream table, csv;
  table << std::setw(6) << "m" << std::setw(7) << "dofs";
  csv << "m,dofs";
  for (int k = 1; k <= k_show; ++k) {
    table << std::setw(19) << ("omega_" + std::to_string(k));
    csv << ",omega_" << k;
  }
  table << std::setw(12) << "elapsed s\n";
  csv << ",elapsed_seconds\n";
  for (const ReductionResult& r : results) {
    table << std::setw(6) << r.modes << std::setw(7) << r.modes + 1;
    csv << r.modes << "," << r.modes + 1;
    for (int k = 0; k < k_show; ++k) {
      table << std::setw(19) << std::setprecision(12) << r.reduced_frequencies(k);
      csv << "," << std::setprecision(17) << r.reduced_frequencies(k);
    }
    table << std::setw(11) << std::setprecision(3) << r.timings.total_seconds << "\n";
    csv << "," << std::setprecision(6) << r.timings.total_seconds << "\n";
  }
  std::cout << "\nlowest natural frequencies of the reduced models (rad per unit time):\n" << table.str();
  if (several) {
    const ReductionResult &last = results.back(), &prev = results[results.size() - 2];
    double change = 0;
    for (int k = 0; k < k_show; ++k)
      change = std::max(
          change, std::abs(last.reduced_frequencies(k) - prev.reduced_frequencies(k)) / last.reduced_frequencies(k));
    std::cout << "largest relative change of these from m = " << prev.modes << " to m = " << last.modes << ": "
              << std::setprecision(3) << change << "\n";
  }

  // optionally, the admissible SPPs of each reduced model in one window
  std::ostringstream spp_csv;
  if (!window.empty()) {
    spp_csv << "m,t1,t2,period,mid_flight_gap,energy\n";
    std::cout << "\nadmissible SPPs of the reduced models in t1 <= " << window[0] << ", t2 <= " << window[1]
              << " (mid-flight gap: g at t = -t1, where the velocity vanishes):\n";
    for (const ReductionResult& r : results) {
      const System& sys = *r.reduced;
      SolveOptions so;
      so.t1_max = window[0];
      so.t2_max = window[1];
      so.admissible_only = true;
      so.threads = a.threads;
      so.certify_steps = a.certify_steps;
      so.validate();
      const SolveResult sr = solve(sys, ModalForm(sys), so);
      std::cout << "m = " << r.modes << ": " << sr.brief_report() << "\n";
      for (const Solution& s : sr.solutions) {
        std::cout << std::setprecision(10) << "    t1 = " << std::setw(14) << s.t1() << "  t2 = " << std::setw(14) << s.t2()
                  << "  mid-flight gap = " << std::setw(14) << s.admissibility.mid_flight_gap << "\n";
        spp_csv << r.modes << std::setprecision(17) << "," << s.t1() << "," << s.t2() << "," << s.period() << ","
                << s.admissibility.mid_flight_gap << "," << s.energy() << "\n";
      }
    }
  }

  // every output prepared: write them
  std::vector<std::string> texts;
  for (const ReductionResult& r : results) texts.push_back(system_json(*r.reduced));
  for (size_t i = 0; i < results.size(); ++i) {
    write_file_atomic(out_name(a.out, results[i].modes, several), texts[i]);
    std::cout << "wrote " << out_name(a.out, results[i].modes, several) << "\n";
    if (!a.layout.empty()) {
      layout.basis = results[i].expansion;
      // (a layout of another reduced model with as many dofs is then refused where it is drawn: animate --fe-layout)
      layout.fingerprint = model_fingerprint(*results[i].reduced);
      const std::string name = layout_name(out_name(a.out, results[i].modes, several));
      write_file_atomic(name, fe_layout_json(layout));
      std::cout << "wrote " << name << " (" << layout.dofs.size() << " dofs of the model for python3 -m spp animate "
                << "--fe-layout)\n";
    }
  }
  if (!a.csv.empty()) write_file_atomic(a.csv, csv.str());
  if (!a.spp_csv.empty()) write_file_atomic(a.spp_csv, spp_csv.str());
  return 0;
}

}  // namespace

Subcommand add_reduce(CLI::App& app) {
  auto a = std::make_shared<ReduceArgs>();
  auto* r = app.add_subcommand("reduce",
                               "reduce a large sparse model to its contact coordinate plus m fixed-interface modes "
                               "(Craig-Bampton): a small system file for spp solve");
  r->add_option("model", a->model, "system JSON (M and K as lists of rows or Matrix Market files, read sparse)")
      ->required();
  r->add_option("--modes", a->modes,
                "fixed-interface modes m (default 20), or an increasing list (10,20,40,80): one file per m and a "
                "convergence table");
  r->add_option("--out", a->out, "reduced system JSON (several m: OUT-m10.json, OUT-m20.json, ...)")->required();
  r->add_option("--frequencies", a->frequencies, "how many of the lowest reduced frequencies to tabulate (default 6)")
      ->check(CLI::Range(1, 1000));
  r->add_option("--csv", a->csv, "write the frequency table as CSV");
  r->add_option("--window", a->window,
                "T1MAX,T2MAX: also solve each reduced model in this window and list its admissible SPPs (the cost "
                "grows fast with m: the pole lines of the fast modes fill the window)");
  r->add_option("--spp-csv", a->spp_csv, "with --window: write the admissible SPPs per m as CSV");
  r->add_option("--threads", a->threads, "with --window: worker threads of each solve (default 0: all)");
  r->add_option("--layout", a->layout,
                "the model's layout file (node coordinates and directions of its dofs, io/layout_file.hpp; spp "
                "generate bar writes one): each reduced model gets OUT.layout.json, for python3 -m spp animate "
                "--fe-layout (at most 4000 dofs kept, evenly spaced)");
  r->add_flag("--certify-steps,!--no-certify-steps", a->certify_steps,
              "with --window: prove every trace step (default), as spp solve");
  return {r, [a] { return run(*a); }};
}

}  // namespace spp::cli
