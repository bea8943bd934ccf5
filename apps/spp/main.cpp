// spp: command-line tool. parse -> options -> validate -> run -> write (atomically).
// Exit codes: 0 success, 1 invalid input or failed run (message on stderr), 2 usage error (CLI11),
// 3 verify: a simulation disagrees with the solver's admissibility.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <iostream>
#include <optional>
#include <sstream>

#include "spp/continuation.hpp"
#include "spp/generators.hpp"
#include "spp/io.hpp"
#include "spp/modal.hpp"
#include "spp/simulator.hpp"
#include "spp/solver.hpp"
#include "spp/verify.hpp"
#include "tables.hpp"

namespace {

// An output file named by option `opt`: refused before any work when it is one of the inputs (it would be replaced by
// the output) or when its directory does not exist (the work would be lost at the end).
void check_output(const std::string& out, const std::string& opt, std::initializer_list<std::string> inputs) {
  namespace fs = std::filesystem;
  if (out.empty()) return;
  std::error_code ec;
  for (const std::string& in : inputs)
    if (!in.empty() && fs::exists(out, ec) && fs::equivalent(out, in, ec))
      throw std::invalid_argument(opt + ": \"" + out + "\" is the input file \"" + in +
                                  "\": write the output to another file");
  const fs::path dir = fs::path(out).parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw std::invalid_argument(opt + ": the directory \"" + dir.string() + "\" of \"" + out + "\" does not exist");
}

std::vector<double> parse_list(const std::string& s, const char* opt) {
  std::vector<double> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      size_t pos = 0;
      v.push_back(std::stod(item, &pos));
      if (pos != item.size()) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw std::invalid_argument(std::string(opt) + ": expected comma-separated numbers, got \"" + s + "\"");
    }
  }
  if (v.empty()) throw std::invalid_argument(std::string(opt) + ": expected at least one number");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"spp: periodic orbits with one lasting contact phase per period (SPPs) of vibro-impact systems"};
  app.require_subcommand(1);

  // solve
  auto* solve = app.add_subcommand("solve", "find every SPP whose half-durations lie in a window");
  std::string sys_path, json_out, csv_out;
  spp::SolveOptions opt;
  bool quiet = false;
  solve->add_option("system", sys_path, "system JSON file")->required();
  solve->add_option("--t1-max", opt.t1_max, "largest flight half-duration t1")->required();
  solve->add_option("--t2-max", opt.t2_max, "largest contact half-duration t2")->required();
  solve->add_option("--t1-min", opt.t1_min, "smallest t1 (default: 1e-4 pi / (2 omega_max))");
  solve->add_option("--t2-min", opt.t2_min, "smallest t2 (default: 1e-4 pi / (2 d_max))");
  solve->add_option("--json", json_out, "write the result as JSON");
  solve->add_option("--csv", csv_out, "write the solutions as CSV");
  solve->add_flag("--admissible-only", opt.admissible_only, "keep only admissible SPPs");
  solve->add_flag("--quiet", quiet, "print only the one-line summary");
  solve->add_option("--threads", opt.threads, "worker threads (default 0: all hardware threads)");
  solve->add_option("--max-cells", opt.max_cells,
                    "refuse windows holding more cells between pole lines than this (default 1e7)")
      ->check(CLI::PositiveNumber);
  solve->add_flag("--certify-steps", opt.certify_steps,
                  "prove every trace step (drift, curvature or onset-inertia bound; 5-10x the evaluations); Incomplete unless all are");
  std::string solve_symmetry = "axial";
  solve
      ->add_option("--symmetry", solve_symmetry,
                   "axial: the SPPs (default); point: the point-symmetric potential SPPs of det T2 = 0 (paper "
                   "§6.2, never admissible, a moving obstacle)")
      ->check(CLI::IsMember({"axial", "point"}));
  double solve_at = 0.0;
  auto* o_at = solve->add_option("--at", solve_at,
                                 "parametric system: solve at this parameter value (without it, a parametric system "
                                 "with g0 = 0 is solved for (t1, t2, parameter), paper §6.1)");

  // continue
  auto* cont = app.add_subcommand("continue", "follow every SPP of a window as the system's parameter varies");
  std::string cont_sys, cont_json;
  spp::ContinueOptions copt;
  bool cont_quiet = false;
  cont->add_option("system", cont_sys, "parametric system JSON file (with \"parameter\")")->required();
  cont->add_option("--t1-max", copt.t1_max, "largest flight half-duration t1")->required();
  cont->add_option("--t2-max", copt.t2_max, "largest contact half-duration t2")->required();
  cont->add_option("--t1-min", copt.t1_min, "smallest t1 (default as solve)");
  cont->add_option("--t2-min", copt.t2_min, "smallest t2 (default as solve)");
  cont->add_option("--seeds", copt.seeds, "parameter values where solve seeds branches (default 9)");
  cont->add_option("--max-step", copt.max_step, "largest step in scaled arclength (default 0.02)");
  cont->add_option("--json", cont_json, "write branches, points and events as JSON");
  cont->add_flag("--quiet", cont_quiet, "print only the one-line summary");
  std::string cont_symmetry = "axial";
  cont->add_option("--symmetry", cont_symmetry, "axial (SPPs, default) or point (det T2 = 0, paper §6.2)")
      ->check(CLI::IsMember({"axial", "point"}));

  // trajectory
  auto* traj = app.add_subcommand("trajectory", "sample one period of an SPP: t, x, v, gap, force");
  std::string traj_sys, traj_csv, traj_result;
  double t1 = 0, t2 = 0;
  int samples = 1001, solution_index = -1;
  traj->add_option("system", traj_sys, "system JSON file")->required();
  auto* o_t1 = traj->add_option("--t1", t1, "flight half-duration (refined to the nearest SPP)");
  auto* o_t2 = traj->add_option("--t2", t2, "contact half-duration (refined to the nearest SPP)");
  double near_radius = 0.05;
  traj->add_option("--radius", near_radius,
                   "with --t1/--t2: relative half-width of the window searched around the guess (default 0.05)")
      ->check(CLI::Range(1e-12, 0.999));
  auto* o_res = traj->add_option("--result", traj_result, "result JSON of spp solve");
  traj->add_option("--solution", solution_index, "index of the solution in --result");
  traj->add_option("--csv", traj_csv, "output CSV")->required();
  traj->add_option("--samples", samples, "number of samples over one period")->check(CLI::Range(2, 10000000));
  o_t1->needs(o_t2);
  o_t2->needs(o_t1);
  o_res->excludes(o_t1);

  // simulate
  auto* simc = app.add_subcommand("simulate", "exact event-driven simulation from any initial state");
  std::string sim_sys, sim_x0, sim_v0, sim_csv, sim_events;
  spp::SimulateOptions sim_opt;
  double per_unit = 100.0;
  simc->add_option("system", sim_sys, "system JSON file")->required();
  simc->add_option("--x0", sim_x0, "initial positions, comma-separated")->required();
  simc->add_option("--v0", sim_v0, "initial velocities, comma-separated")->required();
  simc->add_option("--duration", sim_opt.duration, "simulated time T (last row at t = T)")->required();
  simc->add_option("--restitution", sim_opt.restitution, "Newton's coefficient e in [0, 1] (default 0)");
  simc->add_option("--csv", sim_csv, "output CSV: t, x1..xn, v1..vn, gap, force, contact")->required();
  simc->add_option("--events", sim_events, "output CSV of the impacts, contact onsets and releases");
  simc->add_option("--samples-per-unit", per_unit, "rows per unit of time (default 100), plus one per event");
  simc->add_option("--max-events", sim_opt.max_events, "stop after this many events (default 1e7)");

  // verify
  auto* ver = app.add_subcommand("verify", "re-simulate every SPP of a result and check it");
  std::string ver_result, ver_json;
  spp::VerifyOptions ver_opt;
  ver->add_option("result", ver_result, "result JSON of spp solve")->required();
  ver->add_option("--periods", ver_opt.periods, "simulated periods (default 1)");
  ver->add_option("--perturb", ver_opt.perturbation,
                  "relative size of a perturbation of the mid-flight state of each returning SPP");
  ver->add_option("--restitution", ver_opt.restitution, "Newton's coefficient e for the simulations (default 0)");
  ver->add_option("--json", ver_json, "write the verification as JSON");

  // plot and animate (delegated to the Python package: python3 -m spp plot|animate)
  auto* plotc = app.add_subcommand("plot", "figures of a result: root map, one per admissible SPP, frequency-energy");
  std::string plot_result, plot_out, plot_formats = "png,svg";
  int plot_points = 400;
  plotc->add_option("result", plot_result, "result JSON of spp solve")->required();
  plotc->add_option("--out", plot_out, "output directory")->required();
  plotc->add_option("--formats", plot_formats, "comma-separated png, svg, pdf (default png,svg)");
  plotc->add_option("--root-map-points", plot_points, "root map grid points per axis; 0: no root map (default 400)");
  auto* anim = app.add_subcommand("animate", "animation of one SPP of a result (GIF, or MP4 with ffmpeg)");
  std::string anim_result, anim_out, anim_layout = "auto";
  int anim_solution = -1, anim_frames = 120, anim_periods = 1, anim_fps = 25, anim_dpi = 80;
  anim->add_option("result", anim_result, "result JSON of spp solve")->required();
  anim->add_option("--solution", anim_solution, "index of the solution in the result (default: first admissible)");
  anim->add_option("--out", anim_out, "output file, .gif or .mp4")->required();
  anim->add_option("--frames", anim_frames, "frames per period (default 120)");
  anim->add_option("--periods", anim_periods, "periods shown (default 1)");
  anim->add_option("--fps", anim_fps, "frames per second (default 25)");
  anim->add_option("--dpi", anim_dpi, "resolution: the frame is 6.4 x 4.8 inches (default 80: 512 x 384)");
  anim->add_option("--layout", anim_layout, "auto, chain, plane or dofs (default auto: from M, K and w)");

  // generate
  auto* gen = app.add_subcommand("generate", "write a system JSON for one of the paper's models");
  gen->require_subcommand(1);
  std::string gen_out;
  auto* gchain = gen->add_subcommand("chain", "spring-mass chain fixed at one end (paper §5.2)");
  int cn = 5, cdof = 0;
  std::string cmass = "1", cstiff = "1", cside = "upper";
  double cg0 = 1.0;
  gchain->add_option("--n", cn, "number of masses")->check(CLI::Range(1, 100000));
  gchain->add_option("--masses", cmass, "one value or n comma-separated values");
  gchain->add_option("--stiffnesses", cstiff, "one value or n comma-separated values (k1 ties mass 1 to ground)");
  gchain->add_option("--contact-dof", cdof, "1-based dof that meets the obstacle (default: the last)");
  gchain->add_option("--side", cside, "obstacle above (upper: g = g0 - x) or below (lower: g = g0 + x)")
      ->check(CLI::IsMember({"upper", "lower"}));
  gchain->add_option("--g0", cg0, "gap at rest");
  gchain->add_option("--out", gen_out, "output JSON")->required();
  std::string gen_param, gen_range;
  gchain->add_option("--parameter", gen_param, "leave one value free: m<i> or k<i> (1-based); needs --range");
  gchain->add_option("--range", gen_range, "MIN,MAX of the --parameter");
  auto* grod = gen->add_subcommand("rod", "4-dof finite-element rod with slip (paper §5.3), obstacle y = a x + b");
  double ra = -0.25, rb = 0.25;
  grod->add_option("--a", ra, "slope of the obstacle line");
  grod->add_option("--b", rb, "intercept of the obstacle line");
  grod->add_option("--out", gen_out, "output JSON")->required();
  auto* g2 = gen->add_subcommand("two-dof", "2-dof system of paper §2.3");
  double m1 = 1, m2 = 1, k1 = 1, k2 = 1, g2g0 = 1;
  g2->add_option("--m1", m1);
  g2->add_option("--m2", m2);
  g2->add_option("--k1", k1);
  g2->add_option("--k2", k2);
  g2->add_option("--g0", g2g0);
  g2->add_option("--out", gen_out, "output JSON")->required();
  g2->add_option("--parameter", gen_param, "leave one value free: m1, m2, k1 or k2; needs --range");
  g2->add_option("--range", gen_range, "MIN,MAX of the --parameter");

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
    std::cerr << "spp: error: " << e.what() << "\n(run with --help for the usage)\n";
    return 1;
  }

  try {
    if (*solve) {
      opt.symmetry = solve_symmetry == "point" ? spp::Symmetry::Point : spp::Symmetry::Axial;
      opt.validate();
      check_output(json_out, "--json", {sys_path});
      check_output(csv_out, "--csv", {sys_path, json_out});
      const bool parametric = spp::file_declares_parameter(sys_path);
      if (!parametric && o_at->count() > 0)
        throw std::invalid_argument("--at: " + sys_path + " is not a parametric system (it has no field \"parameter\")");
      if (parametric && o_at->count() == 0) {
        const spp::ParametricSystem ps = spp::load_parametric_system(sys_path);
        if (ps.g0() != 0.0)
          throw std::invalid_argument(sys_path + ": a parametric system with g0 != 0: give --at VALUE of \"" +
                                      ps.parameter().name + "\", or follow its SPPs with spp continue");
        spp::ContinueOptions co;
        co.t1_max = opt.t1_max;
        co.t2_max = opt.t2_max;
        co.t1_min = opt.t1_min;
        co.t2_min = opt.t2_min;
        co.threads = opt.threads;
        co.symmetry = opt.symmetry;
        const spp::ContinuationResult cr = spp::continue_branches(ps, co);
        const std::string json_text = json_out.empty() ? "" : spp::zero_gap_json(ps, cr);
        if (!csv_out.empty()) throw std::invalid_argument("--csv: not available for the g0 = 0 solve (use --json)");
        if (!quiet) std::cout << spp::cli::zero_gap_table(cr);
        std::cout << "spp: g0 = 0, solved for (t1, t2, " << ps.parameter().name << "): " << spp::gap_closures(cr).size()
                  << (opt.symmetry == spp::Symmetry::Point ? " point-symmetric potential SPPs with " : " SPPs with ")
                  << "" << ps.parameter().name << " in [" << ps.parameter().min << ", " << ps.parameter().max << "] ("
                  << cr.brief_report() << ")\n";
        for (const auto& w : cr.warnings) std::cerr << "warning: " << w << "\n";
        if (!json_out.empty()) spp::write_file_atomic(json_out, json_text);
        return 0;
      }
      const spp::System sys =
          parametric ? spp::load_parametric_system(sys_path).at(solve_at) : spp::load_system(sys_path);
      const spp::SolveResult res = spp::solve(sys, opt);
      // prepare every output before writing any
      const std::string json_text = json_out.empty() ? "" : spp::result_json(sys, res);
      const std::string csv_text = csv_out.empty() ? "" : spp::result_to_csv(res);
      if (sys.w_input_norm() != 1.0)
        std::cerr << "note: w was normalised (|w| = " << sys.w_input_norm() << "); g0 divided by it: g0 = " << sys.g0()
                  << "\n";
      if (!quiet) std::cout << spp::cli::result_table(res);
      std::cout << res.brief_report() << "\n";
      for (const auto& w : res.warnings) std::cerr << "warning: " << w << "\n";
      if (!json_out.empty()) spp::write_file_atomic(json_out, json_text);
      if (!csv_out.empty()) spp::write_file_atomic(csv_out, csv_text);
      return 0;
    }
    if (*traj) {
      check_output(traj_csv, "--csv", {traj_sys, traj_result});
      const spp::System sys = spp::load_system(traj_sys);
      if (!traj_result.empty()) {
        if (solution_index < 0) throw std::invalid_argument("trajectory: --result needs --solution K (0-based)");
        const std::vector<spp::SppCandidate> sols = spp::load_result_candidates(traj_result);
        if (static_cast<size_t>(solution_index) >= sols.size())
          throw std::invalid_argument(traj_result + ": --solution " + std::to_string(solution_index) +
                                      " out of range, the file has " + std::to_string(sols.size()) + " solutions");
        t1 = sols[static_cast<size_t>(solution_index)].t1;
        t2 = sols[static_cast<size_t>(solution_index)].t2;
      } else if (o_t1->count() == 0) {
        throw std::invalid_argument("trajectory: give --t1 and --t2, or --result and --solution");
      }
      spp::SolveOptions o;
      o.compute_return_error = false;
      spp::Solution s;
      if (!traj_result.empty()) {
        s = spp::solution_at(sys, t1, t2, o);  // an SPP of a result file: polish it where it is
      } else {  // a guess (e.g. read off the root map): the complete solver around it, then the nearest SPP
        const spp::NearestSpp near = spp::nearest_spp(sys, t1, t2, near_radius, o);
        if (!near.found) {
          std::ostringstream os;
          os << "trajectory: no SPP near (t1, t2) = (" << t1 << ", " << t2 << "): the window (" << near.t1_lo << ", "
             << near.t1_hi << "] x (" << near.t2_lo << ", " << near.t2_hi << "] holds none (search "
             << spp::to_string(near.search_status) << "); widen it with --radius";
          throw std::invalid_argument(os.str());
        }
        s = near.solution;
        if (near.search_status != spp::SolveStatus::Success)
          std::cerr << "warning: the search around the guess ended " << spp::to_string(near.search_status) << "\n";
      }
      const spp::ModalForm md(sys);
      spp::write_file_atomic(traj_csv, spp::trajectory_csv(md, s.orbit, samples));
      std::cout << "trajectory of the SPP at t1 = " << s.t1 << ", t2 = " << s.t2 << " (period " << s.period << ", "
                << (s.admissible ? "admissible" : "not admissible") << ") written to " << traj_csv << "\n";
      return 0;
    }
    if (*simc) {
      check_output(sim_csv, "--csv", {sim_sys});
      const spp::System sys = spp::load_system(sim_sys);
      const std::vector<double> x0 = parse_list(sim_x0, "--x0"), v0 = parse_list(sim_v0, "--v0");
      sim_opt.validate();
      sim_opt.sample_times = spp::uniform_times(sim_opt.duration, per_unit);
      const spp::SimulationResult r =
          spp::simulate(sys, Eigen::Map<const Eigen::VectorXd>(x0.data(), static_cast<Eigen::Index>(x0.size())),
                        Eigen::Map<const Eigen::VectorXd>(v0.data(), static_cast<Eigen::Index>(v0.size())), sim_opt);
      const std::string csv = spp::simulation_csv(r);
      const std::string events = sim_events.empty() ? "" : spp::events_csv(r);
      std::cout << r.brief_report() << "\n";
      spp::write_file_atomic(sim_csv, csv);
      if (!sim_events.empty()) spp::write_file_atomic(sim_events, events);
      if (r.status != spp::SimulationStatus::Success) {
        std::cerr << "spp: error: simulation " << spp::to_string(r.status) << " before t = " << sim_opt.duration
                  << " (--max-events " << sim_opt.max_events << "; output written up to t = " << r.end_time << ")\n";
        return 1;
      }
      return 0;
    }
    if (*ver) {
      check_output(ver_json, "--json", {ver_result});
      const spp::System sys = spp::load_result_system(ver_result);
      const std::vector<spp::SppCandidate> spps = spp::load_result_candidates(ver_result);
      const spp::VerifyResult r = spp::verify(sys, spps, ver_opt);
      const std::string json_text = ver_json.empty() ? "" : spp::verify_json(r);
      std::cout << spp::cli::verify_table(r) << r.brief_report() << "\n";
      if (!ver_json.empty()) spp::write_file_atomic(ver_json, json_text);
      return r.all_consistent() ? 0 : 3;
    }
    if (*plotc || *anim) {
      // The build tree's package first, then wherever Debian's python3 finds an installed one.
      const char* old = std::getenv("PYTHONPATH");
      const std::string path = std::string(SPP_PYTHON_DIR) + (old && *old ? std::string(":") + old : "");
      ::setenv("PYTHONPATH", path.c_str(), 1);
      std::vector<std::string> args = {"/usr/bin/python3", "-m", "spp"};
      if (*plotc)
        args.insert(args.end(), {"plot", plot_result, "--out", plot_out, "--formats", plot_formats, "--root-map-points",
                                 std::to_string(plot_points)});
      else
        args.insert(args.end(),
                    {"animate", anim_result, "--out", anim_out, "--solution", std::to_string(anim_solution), "--frames",
                     std::to_string(anim_frames), "--periods", std::to_string(anim_periods), "--fps",
                     std::to_string(anim_fps), "--dpi", std::to_string(anim_dpi), "--layout", anim_layout});
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      throw std::runtime_error("cannot run /usr/bin/python3 for spp " + args[3] +
                               " (install python3 and the spp package)");
    }
    if (*cont) {
      check_output(cont_json, "--json", {cont_sys});
      const spp::ParametricSystem ps = spp::load_parametric_system(cont_sys);
      copt.symmetry = cont_symmetry == "point" ? spp::Symmetry::Point : spp::Symmetry::Axial;
      const spp::ContinuationResult cr = spp::continue_branches(ps, copt);
      const std::string json_text = cont_json.empty() ? "" : spp::continuation_json(ps, cr);
      if (!cont_quiet) std::cout << spp::cli::continuation_table(cr);
      std::cout << cr.brief_report() << "\n";
      for (const auto& w : cr.warnings) std::cerr << "warning: " << w << "\n";
      if (!cont_json.empty()) spp::write_file_atomic(cont_json, json_text);
      return 0;
    }
    if (*gen) {
      // The generator with the --parameter's value replaced by v.
      auto make = [&](std::optional<std::pair<std::string, double>> free) {
        auto take = [&](const std::string& name, double value) {
          return free && free->first == name ? free->second : value;
        };
        if (*gchain) {
          const int dof = cdof == 0 ? cn - 1 : cdof - 1;
          std::vector<double> ms = parse_list(cmass, "--masses"), ks = parse_list(cstiff, "--stiffnesses");
          if (ms.size() == 1) ms.assign(static_cast<size_t>(cn), ms[0]);
          if (ks.size() == 1) ks.assign(static_cast<size_t>(cn), ks[0]);
          for (size_t i = 0; i < ms.size(); ++i) ms[i] = take("m" + std::to_string(i + 1), ms[i]);
          for (size_t i = 0; i < ks.size(); ++i) ks[i] = take("k" + std::to_string(i + 1), ks[i]);
          return spp::chain(cn, ms, ks, dof, cside == "upper" ? spp::ContactSide::Upper : spp::ContactSide::Lower, cg0);
        }
        if (*grod) return spp::rod_with_slip(ra, rb);
        return spp::two_dof(take("m1", m1), take("m2", m2), take("k1", k1), take("k2", k2), g2g0);
      };
      if (!gen_param.empty() || !gen_range.empty()) {
        if (gen_param.empty() || gen_range.empty())
          throw std::invalid_argument("generate: --parameter and --range go together");
        const std::vector<double> range = parse_list(gen_range, "--range");
        if (range.size() != 2) throw std::invalid_argument("--range: expected MIN,MAX, got \"" + gen_range + "\"");
        const int n = *gchain ? cn : 2;
        bool known = false;
        for (int i = 1; i <= n; ++i)
          known |= gen_param == "m" + std::to_string(i) || gen_param == "k" + std::to_string(i);
        if (!known)
          throw std::invalid_argument("--parameter: expected m<i> or k<i> with i in 1.." + std::to_string(n) +
                                      ", got \"" + gen_param + "\"");
        const spp::ParametricSystem ps = spp::parametrize([&](double v) { return make(std::make_pair(gen_param, v)); },
                                                          {gen_param, range[0], range[1]});
        spp::write_file_atomic(gen_out, spp::parametric_system_json(ps));
        std::cout << "wrote " << ps.name() << " (n = " << ps.n() << ", " << gen_param << " in [" << range[0] << ", "
                  << range[1] << "]) to " << gen_out << "\n";
        return 0;
      }
      spp::System sys = make(std::nullopt);
      spp::write_file_atomic(gen_out, spp::system_json(sys));
      std::cout << "wrote " << sys.name() << " (n = " << sys.n() << ") to " << gen_out << "\n";
      return 0;
    }
  } catch (const std::invalid_argument& e) {
    std::cerr << "spp: error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "spp: error: out of memory: the system or the window needs more memory than this machine gives "
                 "(a smaller window, or --max-cells, bounds the work)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "spp: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
