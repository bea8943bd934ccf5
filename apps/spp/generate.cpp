// spp generate: system files of the paper's models (chain, rod, two-dof) and of random dense systems, optionally with
// one value left free as the parameter of a parametric system; and a large sparse model (bar: a finite-element rod, M
// and K in Matrix Market files beside the JSON, to reduce with spp reduce).
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "command.hpp"
#include "spp/core/generators.hpp"
#include "spp/core/parametric.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/io.hpp"

namespace spp::cli {

namespace {

struct GenerateArgs {
  std::string out, parameter, range;
  CLI::App *chain = nullptr, *rod = nullptr, *bar = nullptr, *random = nullptr;
  int bar_n = 1000, bar_contact_node = 0;  // 0: the free end
  int random_n = 10;
  unsigned seed = 1;
  bool bar_lumped = false;
  int n = 5, contact_dof = 0;  // contact_dof 1-based, 0: the last
  std::string masses = "1", stiffnesses = "1", side = "upper";
  double chain_g0 = 1.0;
  double a = -0.25, b = 0.25;
  double m1 = 1, m2 = 1, k1 = 1, k2 = 1, two_dof_g0 = 1;
};

// Masses and stiffnesses a generated system may have: the solver needs frequencies within [1e-50, 1e50] rad per time
// unit (src/modal/modal.cpp, kMaxFrequency), so omega^2 ~ k / m within [1e-100, 1e100]; each value within
// [1e-50, 1e50] keeps the ratio there and the sums of K's diagonal finite. Masses of 1e308 were reported as "the
// eigenvalues of M did not converge" (an overflow; found by an independent attack).
constexpr double kMinValue = 1e-50, kMaxValue = 1e50;

// The value named `name` (m3, k1) given by option `opt`, within [kMinValue, kMaxValue].
double checked(double value, const std::string& name, const std::string& opt) {
  if (!(value >= kMinValue && value <= kMaxValue)) {
    std::ostringstream os;
    os << opt << ": expected " << name << " from 1e-50 to 1e50 (masses and stiffnesses whose frequencies sqrt(k/m) "
       << "the solver holds in double precision; another unit of mass or time brings them there), got " << value;
    detail::invalid(os.str());
  }
  return value;
}

// The chosen generator with the value named `free->first` (if any) replaced by `free->second`.
System make(const GenerateArgs& g, const std::optional<std::pair<std::string, double>>& free) {
  // the value named `name`, from option `opt` or, when it is the free parameter, from --range
  auto take = [&](const std::string& name, double value, const std::string& opt) {
    return free && free->first == name ? checked(free->second, name, "--range") : checked(value, name, opt);
  };
  if (*g.chain) {
    std::vector<double> ms = parse_list(g.masses, "--masses"), ks = parse_list(g.stiffnesses, "--stiffnesses");
    if (ms.size() == 1) ms.assign(static_cast<size_t>(g.n), ms[0]);
    if (ks.size() == 1) ks.assign(static_cast<size_t>(g.n), ks[0]);
    for (size_t i = 0; i < ms.size(); ++i) ms[i] = take("m" + std::to_string(i + 1), ms[i], "--masses");
    for (size_t i = 0; i < ks.size(); ++i) ks[i] = take("k" + std::to_string(i + 1), ks[i], "--stiffnesses");
    const int dof = g.contact_dof == 0 ? g.n - 1 : g.contact_dof - 1;
    return chain(g.n, ms, ks, dof, g.side == "upper" ? ContactSide::Upper : ContactSide::Lower, g.chain_g0);
  }
  if (*g.rod) return rod_with_slip(g.a, g.b);
  if (*g.random) return random_dense(g.random_n, g.seed, g.chain_g0);
  return two_dof(take("m1", g.m1, "--m1"), take("m2", g.m2, "--m2"), take("k1", g.k1, "--k1"), take("k2", g.k2, "--k2"),
                 g.two_dof_g0);
}

// The bar: sparse, its M and K written as Matrix Market files beside the JSON (<stem>.M.mtx, <stem>.K.mtx).
int run_bar(const GenerateArgs& g) {
  const std::vector<std::string> mtx = sparse_system_matrix_files(g.out);
  const std::string layout_path = (std::filesystem::path(g.out).parent_path() /
                                   (std::filesystem::path(g.out).stem().string() + ".layout.json")).string();
  check_output(g.out, "--out", {});
  for (const std::string& f : mtx) check_output(f, "--out (its Matrix Market file)", {g.out});
  check_output(layout_path, "--out (its layout file)", {g.out, mtx[0], mtx[1]});
  const int node = g.bar_contact_node == 0 ? g.bar_n : g.bar_contact_node;
  const SparseSystem sys = bar(g.bar_n, g.bar_lumped ? BarMass::Lumped : BarMass::Consistent, node,
                               g.side == "upper" ? ContactSide::Upper : ContactSide::Lower, g.chain_g0);
  write_sparse_system(sys, g.out,
                      "fixed-free bar, unit length, EA = rhoA = 1, " + std::to_string(g.bar_n) + " linear elements, " +
                          (g.bar_lumped ? "lumped" : "consistent") + " mass, contact at node " + std::to_string(node));
  // the layout (io/layout_file.hpp): dof i moves node i + 1, at x = (i + 1) / n, along the bar
  FeLayout layout;
  layout.model_dofs = g.bar_n;
  layout.coordinates.resize(g.bar_n, 1);
  layout.directions = Eigen::MatrixXd::Ones(g.bar_n, 1);
  for (int i = 0; i < g.bar_n; ++i) {
    layout.dofs.push_back(i);
    layout.coordinates(i, 0) = static_cast<double>(i + 1) / g.bar_n;
  }
  write_file_atomic(layout_path, fe_layout_json(layout));
  std::cout << "wrote " << sys.name() << " (n = " << sys.n() << ", " << (g.bar_lumped ? "lumped" : "consistent")
            << " mass, contact at node " << node << ") to " << g.out << " with " << mtx[0] << ", " << mtx[1]
            << " and its layout " << layout_path << " (spp reduce --layout)\n";
  return 0;
}

int run(const GenerateArgs& g) {
  if (*g.bar) return run_bar(g);
  if (g.parameter.empty() && g.range.empty()) {
    const System sys = make(g, std::nullopt);
    write_file_atomic(g.out, system_json(sys));
    std::cout << "wrote " << sys.name() << " (n = " << sys.n() << ") to " << g.out << "\n";
    return 0;
  }
  if (g.parameter.empty() || g.range.empty())
    detail::invalid(std::string("generate: --parameter and --range go together: expected both or neither, got only ") +
                    (g.parameter.empty() ? "--range" : "--parameter"));
  const std::vector<double> range = parse_list(g.range, "--range");
  if (range.size() != 2) detail::invalid("--range: expected MIN,MAX, got \"" + g.range + "\"");
  const int n = *g.chain ? g.n : 2;
  bool known = false;
  for (int i = 1; i <= n; ++i)
    known |= g.parameter == "m" + std::to_string(i) || g.parameter == "k" + std::to_string(i);
  if (!known)
    detail::invalid("--parameter: expected m<i> or k<i> with i in 1.." + std::to_string(n) + ", got \"" + g.parameter +
                    "\"");
  const ParametricSystem ps =
      parametrize([&](double v) { return make(g, std::make_pair(g.parameter, v)); }, {g.parameter, range[0], range[1]});
  write_file_atomic(g.out, parametric_system_json(ps));
  std::cout << "wrote " << ps.name() << " (n = " << ps.n() << ", " << g.parameter << " in [" << range[0] << ", "
            << range[1] << "]) to " << g.out << "\n";
  return 0;
}

}  // namespace

Subcommand add_generate(CLI::App& app) {
  auto g = std::make_shared<GenerateArgs>();
  auto* gen = app.add_subcommand("generate", "write a system JSON for one of the paper's models");
  gen->require_subcommand(1);
  g->chain = gen->add_subcommand("chain", "spring-mass chain fixed at one end (paper §5.2)");
  g->chain->add_option("--n", g->n, "number of masses")->check(CLI::Range(1, 100000));
  g->chain->add_option("--masses", g->masses, "one value or n comma-separated values");
  g->chain->add_option("--stiffnesses", g->stiffnesses,
                       "one value or n comma-separated values (k1 ties mass 1 to ground)");
  g->chain->add_option("--contact-dof", g->contact_dof, "1-based dof that meets the obstacle (default: the last)")
      ->check(CLI::Range(1, 100000));
  g->chain->add_option("--side", g->side, "obstacle above (upper: g = g0 - x) or below (lower: g = g0 + x)")
      ->check(CLI::IsMember({"upper", "lower"}));
  g->chain->add_option("--g0", g->chain_g0, "gap at rest");
  g->chain->add_option("--out", g->out, "output JSON")->required();
  g->chain->add_option("--parameter", g->parameter, "leave one value free: m<i> or k<i> (1-based); needs --range");
  g->chain->add_option("--range", g->range, "MIN,MAX of the --parameter");
  g->rod = gen->add_subcommand("rod", "4-dof finite-element rod with slip (paper §5.3), obstacle y = a x + b");
  g->rod->add_option("--a", g->a, "slope of the obstacle line");
  g->rod->add_option("--b", g->b, "intercept of the obstacle line");
  g->rod->add_option("--out", g->out, "output JSON")->required();
  g->bar = gen->add_subcommand("bar",
                               "fixed-free finite-element bar (sparse; M and K as Matrix Market files beside the "
                               "JSON): reduce it with spp reduce");
  g->bar->add_option("--n", g->bar_n, "number of linear rod elements = dofs (default 1000)")
      ->check(CLI::Range(1, 100000000));
  g->bar->add_flag("--lumped", g->bar_lumped, "lumped mass (default: consistent mass)");
  g->bar
      ->add_option("--contact-node", g->bar_contact_node, "node 1..n that meets the obstacle (default: the free end n)")
      ->check(CLI::Range(1, 100000000));
  g->bar->add_option("--side", g->side, "obstacle beyond the end (upper: g = g0 - x) or before it (lower: g = g0 + x)")
      ->check(CLI::IsMember({"upper", "lower"}));
  g->bar->add_option("--g0", g->chain_g0, "gap at rest (default 1)");
  g->bar->add_option("--out", g->out, "output JSON (the .mtx files go beside it)")->required();
  g->random = gen->add_subcommand("random",
                                  "random dense system (spp::random_dense: w ~ N(0, I), K and M with random "
                                  "eigenvectors and eigenvalues uniform in [0.5, 2n] and [0.5, 2]), one per --seed");
  g->random->add_option("--n", g->random_n, "number of dofs (default 10)")->check(CLI::Range(1, kMaxDenseDofs));
  g->random->add_option("--seed", g->seed, "seed of the random draws (default 1)");
  g->random->add_option("--g0", g->chain_g0, "gap at rest (default 1)");
  g->random->add_option("--out", g->out, "output JSON")->required();
  auto* two = gen->add_subcommand("two-dof", "2-dof system of paper §2.3");
  two->add_option("--m1", g->m1);
  two->add_option("--m2", g->m2);
  two->add_option("--k1", g->k1);
  two->add_option("--k2", g->k2);
  two->add_option("--g0", g->two_dof_g0);
  two->add_option("--out", g->out, "output JSON")->required();
  two->add_option("--parameter", g->parameter, "leave one value free: m1, m2, k1 or k2; needs --range");
  two->add_option("--range", g->range, "MIN,MAX of the --parameter");
  return {gen, [g] { return run(*g); }};
}

}  // namespace spp::cli
