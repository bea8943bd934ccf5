// Python bindings, search/: solve (options, progress, result), the fundamental box, nearest_spp, the root map.
#include <iomanip>
#include <sstream>

#include "common.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/io.hpp"
#include "spp/search/root_map.hpp"
#include "spp/search/solver.hpp"
#include "state.hpp"

namespace spp::python {

void bind_search(py::module_& m) {
  bind_outcome<spp::SolveStatus>(m, "SolveStatus",
               "SolveResult.status (and NearestSpp.search_status): success (every check of completeness passed) or "
               "incomplete (SolveResult.uncertified says where and why)");
  // Results of solve() carry their system (attribute `system`), so that they pickle (as their result file's text,
  // the one format that holds every field) and can be plotted, verified or written without it being passed again.
  py::class_<spp::SolveResult>(m, "SolveResult", py::dynamic_attr())
      .def_property_readonly("status", [](const spp::SolveResult& r) { return outcome(r.status); })
      .def_readonly("solutions", &spp::SolveResult::solutions)
      .def_readonly("warnings", &spp::SolveResult::warnings)
      .def_readonly("t1_min", &spp::SolveResult::t1_min)
      .def_readonly("t1_max", &spp::SolveResult::t1_max)
      .def_readonly("t2_min", &spp::SolveResult::t2_min)
      .def_readonly("t2_max", &spp::SolveResult::t2_max)
      .def_property_readonly("symmetry", [](const spp::SolveResult& r) { return r.symmetry; })
      .def_property_readonly(
          "stats",
          [](const spp::SolveResult& r) {
            const spp::SolveStats& st = r.stats;
            py::dict d;  // the result file's "stats", key for key (tested against it)
            d["flight_pole_lines"] = st.flight_pole_lines;
            d["contact_pole_lines"] = st.contact_pole_lines;
            d["rectangles"] = st.rectangles;
            d["curve_pieces"] = st.curve_pieces;
            d["roots"] = st.roots;
            d["evaluations"] = st.evaluations;
            d["strip_pairs"] = st.strip_pairs;
            d["certified_steps"] = st.certified_steps;
            d["heuristic_steps"] = st.heuristic_steps;
            d["uncertified_steps"] = st.uncertified_steps;
            d["uncertified_corners"] = st.uncertified_corners;
            d["unpaired_crossings"] = st.unpaired_crossings;
            d["unresolved_pieces"] = st.unresolved_pieces;
            d["unpolished_roots"] = st.unpolished_roots;
            d["unsearched_cells"] = st.unsearched_cells;
            d["pole_line_artifacts"] = st.pole_line_artifacts;
            d["decoupled_modes"] = r.decoupled_modes;
            d["repeated_frequency_groups"] = r.repeated_groups;
            d["seconds"] = st.seconds;
            return d;
          },
          "counters of the search (dict, the result file's \"stats\")")
      .def_property_readonly(
          "uncertified",
          [](const spp::SolveResult& r) {
            py::list l;
            for (const spp::UncertifiedRegion& u : r.uncertified)
              l.append(py::dict("t1_lo"_a = u.t1_lo, "t1_hi"_a = u.t1_hi, "t2_lo"_a = u.t2_lo, "t2_hi"_a = u.t2_hi,
                                "cause"_a = u.cause));
            return l;
          },
          "parts of the window not certified, with their cause (empty exactly when status is success)")
      .def("brief_report", &spp::SolveResult::brief_report)
      .def(
          "to_json",
          [](const py::object& self, const py::object& system) {
            // the result's own system by default (results of solve() and load_result() carry it); a path is no
            // system (r.to_json("f.json") met pybind11's signature dump: found by an independent attack)
            const py::object sys = system.is_none() && py::hasattr(self, "system") ? self.attr("system") : system;
            if (!py::isinstance<spp::System>(sys))
              throw py::type_error(
                  "SolveResult.to_json: argument system must be an spp.System (or omitted: the result's own, "
                  "r.system), got " +
                  typed_repr(sys) +
                  (py::isinstance<py::str>(sys) ? " (to_json returns the text: open(path, \"w\").write(r.to_json()))"
                                                : ""));
            // (the CLI's indentation: the same text as spp solve --json, not one line; issue 11's attack)
            return spp::result_json(sys.cast<const spp::System&>(), self.cast<const spp::SolveResult&>());
          },
          "system"_a = py::none(),
          "The result JSON text, as spp solve --json writes it (the same text), for `system` (default: the result's "
          "own, r.system).")
      .def("__repr__", [](const spp::SolveResult& r) { return "<spp.SolveResult " + r.brief_report().substr(5) + ">"; })
      .def("_repr_html_",
           [](const spp::SolveResult& r) {
             std::ostringstream h;
             h << "<p><b>spp.SolveResult</b>: " << r.brief_report().substr(5) << "</p>";
             h << "<table><tr><th>#</th><th>t1</th><th>t2</th><th>period</th><th>admissible</th><th>min gap</th>"
                  "<th>min force</th><th>energy</th></tr>";
             const size_t shown = std::min<size_t>(r.solutions.size(), 20);
             h << std::setprecision(8);
             for (size_t i = 0; i < shown; ++i) {
               const spp::Solution& x = r.solutions[i];
               h << "<tr><td>" << i << "</td><td>" << x.t1() << "</td><td>" << x.t2() << "</td><td>" << x.period()
                 << "</td><td>" << (x.admissible() ? "yes" : "no") << "</td><td>" << x.min_gap() << "</td><td>"
                 << x.min_force() << "</td><td>" << x.energy() << "</td></tr>";
             }
             h << "</table>";
             if (shown < r.solutions.size()) h << "<p>(" << r.solutions.size() - shown << " more: to_dataframe())</p>";
             return h.str();
           })
      .def(py::pickle(
          [](const py::object& self) {
            if (!py::hasattr(self, "system") || !py::isinstance<spp::System>(self.attr("system")))
              detail::invalid(
                  "SolveResult pickle: its attribute system must be the spp.System it was "
                  "solved for (results of solve() have it)");
            const spp::System sys = self.attr("system").cast<spp::System>();
            const spp::SolveResult& r = self.cast<const spp::SolveResult&>();
            for (const spp::Solution& x : r.solutions)
              if (x.orbit.x0.size() != sys.n())
                detail::invalid("SolveResult pickle: its system has n = " + std::to_string(sys.n()) +
                                " dofs, its solutions " + std::to_string(x.orbit.x0.size()) +
                                ": expected solutions of " + std::to_string(sys.n()) + " dofs, got " +
                                std::to_string(x.orbit.x0.size()));
            return py::make_tuple(spp::result_json(sys, r, -1));
          },
          [](const py::tuple& state) {
            if (state.size() != 1) detail::invalid("SolveResult pickle: expected one field");
            const std::string text = state[0].cast<std::string>();
            spp::ResultFile file = spp::parse_result_file(text, "pickled SolveResult");
            py::dict attrs;
            attrs["system"] = std::move(file.system);
            return std::make_pair(std::move(file.result), attrs);
          }))
      .def_static(
          "from_json", &result_with_system, "path"_a,
          "The SolveResult of a result file (spp solve --json, SolveResult.to_json), with its system as attribute "
          "system: the status, solutions, stats, uncertified regions and warnings that were written. Raises "
          "ValueError naming the file and the field.");

  OptionsBinding<spp::SolveOptions>(m, "SolveOptions",
                                    "Options of solve (the C++ SolveOptions, field by field; solve(system, options, "
                                    "**fields) also takes any field as a keyword)")
      .field("t1_max", &spp::SolveOptions::t1_max, "upper end of the flight half-duration window (> 0)")
      .field("t2_max", &spp::SolveOptions::t2_max, "upper end of the contact half-duration window (> 0)")
      .field("t1_min", &spp::SolveOptions::t1_min, "lower end (0: from the axis)")
      .field("t2_min", &spp::SolveOptions::t2_min, "lower end (0: from the axis)")
      .field("max_cells", &spp::SolveOptions::max_cells, "refuse windows with more cells than this")
      .field("certify_steps", &spp::SolveOptions::certify_steps,
             "prove every trace step (default True: status success only if all are; False: the midpoint "
             "check, 3-25x faster, a heuristic, so the status is incomplete)")
      .field("pole_margin", &spp::SolveOptions::pole_margin)
      .field("max_turn", &spp::SolveOptions::max_turn)
      .field("min_step", &spp::SolveOptions::min_step)
      .field("admissibility_tol", &spp::SolveOptions::admissibility_tol)
      .field("admissible_only", &spp::SolveOptions::admissible_only)
      .field("compute_return_error", &spp::SolveOptions::compute_return_error)
      .field("compute_stability", &spp::SolveOptions::compute_stability)
      .field("threads", &spp::SolveOptions::threads, "worker threads (0: all)")
      .cls()
      .def_property(
          "symmetry", [](const spp::SolveOptions& o) { return o.symmetry; },
          [](spp::SolveOptions& o, const py::object& v) { o.symmetry = symmetry_of(v); },
          "Symmetry.axial (default) or Symmetry.point (or their names)")
      .def("validate", &spp::SolveOptions::validate, "Raises ValueError naming the first invalid field.")
      .def("__repr__", [](const spp::SolveOptions& o) {
        std::ostringstream os;
        os << "<spp.SolveOptions t1 in (" << o.t1_min << ", " << o.t1_max << "], t2 in (" << o.t2_min << ", "
           << o.t2_max << "], symmetry " << spp::to_string(o.symmetry)
           << (o.certify_steps ? "" : ", certify_steps=False") << ">";
        return os.str();
      });
  const auto solve_options = [](const py::object& options, const py::kwargs& fields, const char* where) {
    return with_fields<spp::SolveOptions>(options, fields, where, "SolveOptions");
  };
  py::class_<spp::SolveProgress>(m, "SolveProgress",
                                 "What a running solve reports to its progress callback (solve(..., progress=f)).")
      .def_readonly("cells_done", &spp::SolveProgress::cells_done, "cells of the window traced so far")
      .def_readonly("cells_total", &spp::SolveProgress::cells_total, "cells of the window")
      .def_readonly("candidates", &spp::SolveProgress::candidates, "sign changes of g found so far (before polish)")
      .def_readonly("seconds", &spp::SolveProgress::seconds, "time since the trace started")
      .def("__repr__", [](const spp::SolveProgress& p) { return "<spp.SolveProgress " + p.line() + ">"; });
  m.def(
      "solve",
      [solve_options](const spp::System& s, const py::object& options, const py::kwargs& fields) {
        py::dict rest;
        const RunControl control = take_run_control(fields, rest);
        spp::SolveOptions o = solve_options(options, py::reinterpret_borrow<py::kwargs>(rest), "solve");
        o.validate();
        ProgressHook hook(control.progress, "solve", control.cancel);
        o.progress = [&hook](const spp::SolveProgress& p) { return hook(p); };
        spp::SolveResult r;
        {
          py::gil_scoped_release release;
          r = spp::solve(s, o);
        }
        // a Ctrl-C that came after the last report (while the roots were polished): the result is complete, so it
        // is returned, not lost to a KeyboardInterrupt at the next line
        hook.finish();
        hook.warn(hook.late && r.stats.unsearched_cells == 0
                      ? std::string("Ctrl-C came after the search had finished: the result is complete")
                      : "solve interrupted (Ctrl-C): " + std::to_string(r.stats.unsearched_cells) +
                            " cell(s) not searched; the result holds what was found before (status incomplete)");
        py::object result = py::cast(std::move(r));
        result.attr("system") = s;
        return result;
      },
      "system"_a, "options"_a = py::none(),
      ("Every SPP with t1 in (t1_min, t1_max], t2 in (t2_min, t2_max]: solve(system, t1_max=12, t2_max=12), or "
       "solve(system, SolveOptions) with any field also given as a keyword (symmetry=\"point\": the point-symmetric "
       "potential SPPs of paper §6.2; certify_steps=False: the faster midpoint check, a heuristic, status incomplete). "
       "progress=True prints the cells traced on "
       "stderr; progress=f calls f(SolveProgress) every 0.2 s (returning False stops the search). Ctrl-C stops it "
       "too, and so does cancel=spp.Cancel() once its cancel() is called (from any thread): the result then holds "
       "what was found (status incomplete, stats['unsearched_cells'] > 0) and a RuntimeWarning says so." +
       std::string(kThreadRule) + " Raises ValueError.")
          .c_str());

  py::class_<spp::SolutionAt>(m, "SolutionAt",
                              "Result of solution_at: the SPP Newton reached from a point, or where it ended")
      .def_readonly("found", &spp::SolutionAt::found, "a root within 1e-3 (t1 + t2) of the start whose gap can close")
      .def_property_readonly(
          "solution", [](const spp::SolutionAt& r) { return r.found ? py::cast(r.solution) : py::none(); },
          "the polished SPP (a Solution), None when not found")
      .def_readonly("t1", &spp::SolutionAt::t1, "where Newton ended")
      .def_readonly("t2", &spp::SolutionAt::t2, "where Newton ended")
      .def_readonly("residual", &spp::SolutionAt::residual, "the equations' residual there")
      .def_property_readonly(
          "start", [](const spp::SolutionAt& r) { return py::make_tuple(r.start_t1, r.start_t2); },
          "(t1, t2) asked for")
      .def("brief_report", &spp::SolutionAt::brief_report)
      .def(py::pickle(
          [](const spp::SolutionAt& r) {
            return py::make_tuple(r.found, state::of(r.solution), r.t1, r.t2, r.residual, r.start_t1, r.start_t2);
          },
          [](const py::tuple& t) {
            state::sized(t, 7, "SolutionAt");
            spp::SolutionAt r;
            r.found = t[0].cast<bool>();
            r.solution = state::solution(t[1].cast<py::tuple>());
            r.t1 = t[2].cast<double>();
            r.t2 = t[3].cast<double>();
            r.residual = t[4].cast<double>();
            r.start_t1 = t[5].cast<double>();
            r.start_t2 = t[6].cast<double>();
            return r;
          }))
      .def("__repr__", [](const spp::SolutionAt& r) { return "<spp.SolutionAt " + r.brief_report() + ">"; });
  m.def(
      "solution_at",
      [solve_options](const spp::System& s, double t1, double t2, const py::object& options, const py::kwargs& fields) {
        // (no validate(): it requires the window, which solution_at does not use; each field is checked by its
        // setter, t1 and t2 by the C++ function)
        const spp::SolveOptions o = solve_options(options, fields, "solution_at");
        spp::SolutionAt r;
        {
          py::gil_scoped_release release;
          r = spp::solution_at(s, t1, t2, o);
        }
        return r;
      },
      "system"_a, "t1"_a, "t2"_a, "options"_a = py::none(),
      "The SPP at a given (t1, t2) (half-durations of flight and contact), as C++'s spp::solution_at: Newton on the "
      "SPP equations from that point (at most 12 steps), then the SPP's initial conditions, admissibility and (unless "
      "compute_stability=False) Floquet multipliers. solution_at(system, t1, t2) or with a SolveOptions and any field "
      "as a keyword (symmetry=\"point\"; the window fields are not used). Returns a SolutionAt: found is False (a "
      "numerical outcome, not an error) when Newton does not reach a root within 1e-3 (t1 + t2) of the point; "
      "solution is then None and brief_report() says where Newton ended. No search: for every SPP near a guess, "
      "nearest_spp. Raises ValueError for t1 or t2 not positive and finite, g0 = 0 or invalid options.");

  m.def(
      "fundamental_box", [](const spp::System& s) { return spp::fundamental_box(spp::ModalForm(s)); }, "system"_a,
      "(t1_max, t2_max) of the fundamental box: t1 <= pi / omega_1 (slowest free-flight mode that sees the contact), "
      "t2 <= pi / d_1 (slowest contact-phase oscillation): t1, t2 = fundamental_box(s); solve(s, t1_max=t1, "
      "t2_max=t2).");
  py::class_<spp::NearestSpp>(m, "NearestSpp", "Result of nearest_spp: the SPP nearest to a guess")
      .def_readonly("found", &spp::NearestSpp::found)
      .def_readonly("solution", &spp::NearestSpp::solution)
      .def_property_readonly("search_status", [](const spp::NearestSpp& r) { return outcome(r.search_status); })
      .def_readonly("candidates", &spp::NearestSpp::candidates, "SPPs in the window searched")
      .def_property_readonly(
          "window", [](const spp::NearestSpp& r) { return py::make_tuple(r.t1_lo, r.t1_hi, r.t2_lo, r.t2_hi); })
      .def(py::pickle([](const spp::NearestSpp& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::nearest_spp(t); }))
      .def("__repr__", [](const spp::NearestSpp& r) {
        std::ostringstream os;
        os << "<spp.NearestSpp ";
        if (r.found)
          os << "t1=" << r.solution.t1() << " t2=" << r.solution.t2()
             << (r.solution.admissible() ? " admissible" : " not admissible");
        else
          os << "none found";
        os << ", " << r.candidates << " SPPs in the window, search " << spp::to_string(r.search_status) << ">";
        return os.str();
      });
  m.def(
      "nearest_spp",
      [solve_options](const spp::System& s, const py::object& t1_arg, const py::object& t2_arg,
                      const py::object& radius_arg, const py::object& options, const py::kwargs& fields) {
        const double t1 = scalar_argument<double>(t1_arg, "spp.nearest_spp: argument t1"),
                     t2 = scalar_argument<double>(t2_arg, "spp.nearest_spp: argument t2"),
                     radius = scalar_argument<double>(radius_arg, "spp.nearest_spp: argument radius");
        py::dict rest;
        const RunControl control = take_run_control(fields, rest);
        spp::SolveOptions o = solve_options(options, py::reinterpret_borrow<py::kwargs>(rest), "nearest_spp");
        ProgressHook hook(control.progress, "nearest_spp", control.cancel);
        o.progress = [&hook](const spp::SolveProgress& p) { return hook(p); };
        spp::NearestSpp r;
        {
          py::gil_scoped_release release;
          r = spp::nearest_spp(s, t1, t2, radius, o);
        }
        hook.finish();
        hook.warn(hook.late && r.search_status == spp::SolveStatus::Success
                      ? std::string("Ctrl-C came after the search had finished: the result is complete")
                      : std::string("nearest_spp interrupted (Ctrl-C): search_status incomplete, the nearest SPP of "
                                    "the part of the window searched"));
        return r;
      },
      "system"_a, "t1"_a, "t2"_a, "radius"_a = 0.05, "options"_a = py::none(),
      ("The SPP nearest to a guess (t1, t2), e.g. read off the root map: the complete solver on the window "
       "(t1 (1 - radius), t1 (1 + radius)] x (t2 (1 - radius), t2 (1 + radius)], then the nearest root. "
       "found is False when that window holds none. progress=True|f as for solve (f(SolveProgress) returning False "
       "stops the search: search_status is then incomplete); Ctrl-C or cancel=spp.Cancel() stops it too, keeping "
       "what was found, with a RuntimeWarning." +
       std::string(kThreadRule) + " Raises ValueError.")
          .c_str());

  py::class_<spp::RootMapCell>(m, "RootMapCell", "One rectangle between pole lines, sampled on its own grid")
      .def_readonly("t1", &spp::RootMapCell::t1, "(n1,) ascending")
      .def_readonly("t2", &spp::RootMapCell::t2, "(n2,) ascending")
      .def_readonly("symmetric", &spp::RootMapCell::symmetric,
                    "(n2, n1) sign(det H) min|eig H|: its zero curves are eq. (5.1a)")
      .def_readonly("onset", &spp::RootMapCell::onset,
                    "(n2, n1) the same for P^T H P on z-perp: its zero curves are eq. (5.1b)")
      .def(py::pickle([](const spp::RootMapCell& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::root_map_cell(t); }))
      .def("__repr__", [](const spp::RootMapCell& c) {
        return "<spp.RootMapCell " + std::to_string(c.t1.size()) + " x " + std::to_string(c.t2.size()) + " points>";
      });
  py::class_<spp::RootMap>(m, "RootMap")
      .def_readonly("flight_poles", &spp::RootMap::flight_poles, "pole lines t1 = (k + 1/2) pi / omega_i")
      .def_readonly("contact_poles", &spp::RootMap::contact_poles, "pole lines t2 = (k + 1/2) pi / d_j")
      .def_readonly("cells", &spp::RootMap::cells)
      .def_readonly("evaluations", &spp::RootMap::evaluations)
      .def_readonly("unsampled_cells", &spp::RootMap::unsampled_cells,
                    "cells left out because progress (or Ctrl-C) stopped the map; 0: the whole window")
      .def(py::pickle([](const spp::RootMap& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::root_map(t); }))
      .def("__repr__", [](const spp::RootMap& r) {
        return "<spp.RootMap " + std::to_string(r.cells.size()) + " cells, " + std::to_string(r.flight_poles.size()) +
               " flight and " + std::to_string(r.contact_poles.size()) + " contact pole lines, " +
               std::to_string(r.evaluations) + " evaluations" +
               (r.unsampled_cells > 0 ? ", " + std::to_string(r.unsampled_cells) + " cells not sampled" : "") + ">";
      });
  py::class_<spp::RootMapProgress>(m, "RootMapProgress",
                                   "What a running root map reports to its progress callback (root_map(..., "
                                   "progress=f)).")
      .def_readonly("cells_done", &spp::RootMapProgress::cells_done, "cells sampled so far")
      .def_readonly("cells_total", &spp::RootMapProgress::cells_total, "cells of the window")
      .def_readonly("evaluations", &spp::RootMapProgress::evaluations, "grid points evaluated so far")
      .def_readonly("seconds", &spp::RootMapProgress::seconds, "time since the map started")
      .def("__repr__", [](const spp::RootMapProgress& p) { return "<spp.RootMapProgress " + p.line() + ">"; });
  OptionsBinding<spp::RootMapOptions>(m, "RootMapOptions",
                                      "Options of root_map (the C++ RootMapOptions, field by field; root_map(system, "
                                      "t1_max, t2_max, options, **fields) also takes any field as a keyword)")
      .field("t1_min", &spp::RootMapOptions::t1_min, "lower end of the window in t1 (>= 0)")
      .field("t1_max", &spp::RootMapOptions::t1_max, "upper end of the window in t1 (> t1_min)")
      .field("t2_min", &spp::RootMapOptions::t2_min, "lower end of the window in t2 (>= 0)")
      .field("t2_max", &spp::RootMapOptions::t2_max, "upper end of the window in t2 (> t2_min)")
      .field("t1_points", &spp::RootMapOptions::t1_points,
             "grid points across the window along t1 (>= 16), spread over the cells by their width: about "
             "t1_points x t2_points in all")
      .field("t2_points", &spp::RootMapOptions::t2_points, "grid points across the window along t2 (>= 16)")
      .field("min_cell_points", &spp::RootMapOptions::min_cell_points,
             "at least this many points per cell and axis (>= 2, default 2: the fewest a contour is drawn from)")
      .field("pole_margin", &spp::RootMapOptions::pole_margin,
             "distance kept from pole lines, relative to the cell width (in [0, 0.25))")
      .cls()
      .def("validate", &spp::RootMapOptions::validate, "Raises ValueError naming the first invalid field.")
      .def("__repr__", [](const py::object& o) { return fields_repr(o, "RootMapOptions"); });
  m.def(
      "root_map",
      [](const spp::System& s, std::optional<double> t1_max, std::optional<double> t2_max, const py::object& options,
         const py::kwargs& fields) {
        py::dict rest;
        const RunControl control = take_run_control(fields, rest);
        spp::RootMapOptions o = with_fields<spp::RootMapOptions>(options, py::reinterpret_borrow<py::kwargs>(rest),
                                                                 "root_map", "RootMapOptions");
        if (t1_max) o.t1_max = *t1_max;
        if (t2_max) o.t2_max = *t2_max;
        o.validate();
        ProgressHook hook(control.progress, "root_map", control.cancel);
        o.progress = [&hook](const spp::RootMapProgress& p) { return hook(p); };
        spp::RootMap r;
        {
          py::gil_scoped_release release;
          r = spp::root_map(s, o);
        }
        hook.finish();
        hook.warn(r.unsampled_cells == 0
                      ? std::string("Ctrl-C came after the map had finished: the map is complete")
                      : "root_map interrupted (Ctrl-C): " + std::to_string(r.unsampled_cells) +
                            " cell(s) not sampled; the map holds the cells sampled before (unsampled_cells > 0)");
        return r;
      },
      "system"_a, "t1_max"_a = py::none(), "t2_max"_a = py::none(), "options"_a = py::none(),
      ("Both conditions of the SPP equations sampled cell by cell over the window (root maps, Fig. 4): "
       "root_map(system, t1_max, t2_max, t1_points=400, ...) or root_map(system, options=RootMapOptions) with any "
       "field also as a keyword. progress=True prints the cells sampled on stderr; progress=f calls f(RootMapProgress) "
       "every 0.2 s (returning False stops the map: it holds the cells sampled, unsampled_cells counts the others). "
       "Ctrl-C or cancel=spp.Cancel() stops it too, keeping those cells, with a RuntimeWarning." +
       std::string(kThreadRule) + " Raises ValueError.")
          .c_str());
}

}  // namespace spp::python
