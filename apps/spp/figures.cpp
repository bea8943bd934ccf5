// spp plot and spp animate: delegated to the Python package (python3 -m spp plot|animate), which draws with matplotlib.
#include <limits>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "command.hpp"

namespace spp::cli {

namespace {

// The Python package that belongs to this executable, found from where the executable is, not from a path fixed at
// compile time (a copied or installed binary ran whatever stale build tree it was compiled in): in a build tree, the
// executable is build/spp and the package build/python/spp (the layout CMakeLists.txt makes), so "python" beside the
// executable is put first on PYTHONPATH. Elsewhere (an installed or copied binary) nothing is added: python3 finds the
// installed package (cmake --install build --component python, or pip install .) on its normal path, after the
// user's PYTHONPATH. Empty when there is no build-tree package beside the executable.
std::string build_tree_python_dir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);  // Linux: the running file, links resolved
  if (ec) return "";
  const fs::path dir = exe.parent_path() / "python";
  return fs::is_regular_file(dir / "spp" / "__main__.py", ec) ? dir.string() : "";
}

// Replaces this process by /usr/bin/python3 -m spp <args>, with the package of build_tree_python_dir() first on the
// path when there is one. Returns only on failure.
[[noreturn]] void exec_python(std::vector<std::string> args) {
  const std::string own = build_tree_python_dir();
  if (!own.empty()) {
    const char* old = std::getenv("PYTHONPATH");
    const std::string path = own + (old && *old ? std::string(":") + old : "");
    ::setenv("PYTHONPATH", path.c_str(), 1);
  }
  args.insert(args.begin(), {"/usr/bin/python3", "-m", "spp"});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  ::execv(argv[0], argv.data());
  throw std::runtime_error("cannot run /usr/bin/python3 for spp " + args[3] + " (install python3 and the spp package)");
}

struct PlotArgs {
  std::string result, out, formats = "png,svg", solutions = "admissible";
  int points = 400;
};

struct AnimateArgs {
  std::string result, out, layout = "auto", fe_layout;
  int solution = -1, frames = 120, periods = 1, fps = 25, dpi = 125;  // dpi: animate.py's DEFAULT_DPI
};

}  // namespace

std::vector<Subcommand> add_figures(CLI::App& app) {
  auto p = std::make_shared<PlotArgs>();
  auto* plot = app.add_subcommand("plot", "figures of a result: root map, one per admissible SPP, frequency-energy");
  plot->add_option("result", p->result, "result JSON of spp solve")->required();
  plot->add_option("--out", p->out, "output directory")->required();
  plot->add_option("--formats", p->formats, "comma-separated png, svg, pdf (default png,svg)");
  plot->add_option("--root-map-points", p->points, "root map grid points per axis; 0: no root map (default 400)");
  plot->add_option("--solutions", p->solutions,
                   "SPPs drawn one figure each: admissible (default), all, or 0-based indices like 0,3,5 (an "
                   "inadmissible one is drawn as its potential orbit, the violations shaded)");
  auto a = std::make_shared<AnimateArgs>();
  auto* anim = app.add_subcommand("animate", "animation of one SPP of a result (GIF, or MP4 with ffmpeg)");
  anim->add_option("result", a->result, "result JSON of spp solve")->required();
  anim->add_option("--solution", a->solution, "index of the solution in the result (default: first admissible)")
      ->transform(whole_number(0, std::numeric_limits<int>::max()));
  anim->add_option("--out", a->out, "output file, .gif or .mp4")->required();
  anim->add_option("--frames", a->frames, "frames per period (default 120)");
  anim->add_option("--periods", a->periods, "periods shown (default 1)");
  anim->add_option("--fps", a->fps, "frames per second (default 25)");
  anim->add_option("--dpi", a->dpi, "resolution: the frame is 6.4 x 4.8 inches (default 125: 800 x 600)");
  anim->add_option("--layout", a->layout,
                   "auto, chain, plane, dofs or fe (default auto: from M, K and w; fe with --fe-layout)");
  anim->add_option("--fe-layout", a->fe_layout,
                   "a layout file (spp generate bar's <stem>.layout.json, spp reduce --layout's OUT.layout.json): "
                   "draw the finite-element model itself");
  auto run_plot = [p]() -> int {
    exec_python({"plot", p->result, "--out", p->out, "--formats", p->formats, "--root-map-points",
                 std::to_string(p->points), "--solutions", p->solutions});
  };
  auto run_animate = [a]() -> int {
    std::vector<std::string> args = {"animate", a->result, "--out", a->out, "--solution", std::to_string(a->solution),
                                     "--frames", std::to_string(a->frames), "--periods", std::to_string(a->periods),
                                     "--fps", std::to_string(a->fps), "--dpi", std::to_string(a->dpi), "--layout",
                                     a->layout};
    if (!a->fe_layout.empty()) args.insert(args.end(), {"--fe-layout", a->fe_layout});
    exec_python(args);
  };
  return {{plot, run_plot}, {anim, run_animate}};
}

}  // namespace spp::cli
