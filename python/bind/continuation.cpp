// Python bindings, continuation/: SPP branches in a parameter.
#include "spp/continuation/continuation.hpp"

#include <iomanip>
#include <sstream>

#include "common.hpp"
#include "spp/io.hpp"
#include "state.hpp"

namespace spp::python {

namespace {
// The run with Ctrl-C checked at each branch point (and in the seed solves): stopped, it returns the branches traced
// so far (status incomplete, interrupted) with a RuntimeWarning, as solve does.
template <class Run>
spp::ContinuationResult run_interruptible(const std::string& where, const py::object& cancel, spp::ContinueOptions& o,
                                          Run run) {
  ProgressHook hook(py::none(), where, cancel);
  o.progress = [&hook] { return hook.keep_going(); };
  spp::ContinuationResult r;
  {
    py::gil_scoped_release release;
    r = run();
  }
  hook.finish();
  hook.warn(r.interrupted ? where +
                                " interrupted (Ctrl-C): the result holds the branches traced before (status "
                                "incomplete, interrupted True)"
                          : std::string("Ctrl-C came after the continuation had finished: the result is complete"));
  return r;
}
}  // namespace

void bind_continuation(py::module_& m) {
  bind_outcome<spp::ContinuationStatus>(m, "ContinuationStatus",
               "ContinuationResult.status");
  bind_outcome<spp::BranchEventKind>(m, "BranchEventKind",
               "BranchEvent.kind");

  bind_outcome<spp::MultiplierCrossing>(m, "MultiplierCrossing",
               "BranchEvent.crossing");

  py::class_<spp::BranchPoint>(m, "BranchPoint")
      .def_readonly("mu", &spp::BranchPoint::mu)
      .def_readonly("t1", &spp::BranchPoint::t1)
      .def_readonly("t2", &spp::BranchPoint::t2)
      .def_readonly("period", &spp::BranchPoint::period)
      .def_readonly("admissible", &spp::BranchPoint::admissible)
      .def_readonly("margin", &spp::BranchPoint::margin, "admissibility margin (NaN where meaningless)")
      .def_readonly("spectral_radius", &spp::BranchPoint::spectral_radius,
                    "largest |Floquet multiplier| but the two structural 1s (NaN where not computed)")
      .def_readonly("spectral_radius_error", &spp::BranchPoint::spectral_radius_error,
                    "its error bound: rounding and the point's location error, large near a fold (NaN where not "
                    "computed, inf where unbounded)")
      .def_readonly("closure", &spp::BranchPoint::closure)
      .def_readonly("energy", &spp::BranchPoint::energy)
      .def_readonly("x0", &spp::BranchPoint::x0)
      .def_readonly("v0", &spp::BranchPoint::v0)
      .def(py::pickle([](const spp::BranchPoint& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::branch_point(t); }))
      .def("__repr__", [](const spp::BranchPoint& p) {
        std::ostringstream os;
        os << "<spp.BranchPoint mu=" << p.mu << " t1=" << p.t1 << " t2=" << p.t2
           << (p.admissible ? " admissible>" : " not admissible>");
        return os.str();
      });
  py::class_<spp::BranchEvent>(m, "BranchEvent")
      .def_property_readonly("kind", [](const spp::BranchEvent& e) { return outcome(e.kind); })
      .def_readonly("at", &spp::BranchEvent::at)
      .def_readonly("detail", &spp::BranchEvent::detail)
      .def_property_readonly(
          "crossing", [](const spp::BranchEvent& e) { return outcome(e.crossing); },
          "stability events: plus_one, minus_one (period doubling) or complex_pair (Neimark-Sacker); none otherwise")
      .def_property_readonly(
          "crossing_multipliers",
          [](const spp::BranchEvent& e) {
            return Eigen::VectorXcd(Eigen::Map<const Eigen::VectorXcd>(
                e.crossing_multipliers.data(), static_cast<Eigen::Index>(e.crossing_multipliers.size())));
          },
          "the crossing multiplier(s) at the located event: one real or a conjugate pair")
      .def_readonly("crossing_angle", &spp::BranchEvent::crossing_angle,
                    "arg of the crossing multiplier in [0, pi]: 0 (+1), pi (-1), theta (pair); NaN otherwise")
      .def(py::pickle([](const spp::BranchEvent& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::branch_event(t); }))
      .def("__repr__", [](const spp::BranchEvent& e) {
        std::ostringstream os;
        os << "<spp.BranchEvent " << spp::to_string(e.kind) << " at mu=" << e.at.mu << " t1=" << e.at.t1
           << " t2=" << e.at.t2 << ">";
        return os.str();
      });
  py::class_<spp::Branch>(m, "Branch")
      .def_readonly("points", &spp::Branch::points)
      .def_readonly("events", &spp::Branch::events)
      .def_property_readonly(
          "arrays",
          [](const spp::Branch& b) {
            Eigen::MatrixXd a(static_cast<Eigen::Index>(b.points.size()), 4);
            for (size_t i = 0; i < b.points.size(); ++i)
              a.row(static_cast<Eigen::Index>(i)) << b.points[i].mu, b.points[i].t1, b.points[i].t2, b.points[i].margin;
            return a;
          },
          "(N, 4): mu, t1, t2, margin of every point")
      .def(py::pickle([](const spp::Branch& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::branch(t); }))
      .def("__repr__", [](const spp::Branch& b) {
        std::ostringstream os;
        os << "<spp.Branch " << b.points.size() << " points";
        if (!b.points.empty()) os << ", mu " << b.points.front().mu << " .. " << b.points.back().mu;
        os << ", events:";
        for (const spp::BranchEvent& e : b.events) os << " " << spp::to_string(e.kind);
        return os.str() + ">";
      });
  py::class_<spp::ContinuationResult>(m, "ContinuationResult", py::dynamic_attr())
      .def_property_readonly("status", [](const spp::ContinuationResult& r) { return outcome(r.status); })
      .def_readonly("incomplete_seed_solves", &spp::ContinuationResult::incomplete_seed_solves)
      .def_readonly("stalled_branches", &spp::ContinuationResult::stalled_branches)
      .def_readonly("unlisted_crossings", &spp::ContinuationResult::unlisted_crossings)
      .def_readonly("branches", &spp::ContinuationResult::branches)
      .def_readonly("warnings", &spp::ContinuationResult::warnings)
      .def_readonly("interrupted", &spp::ContinuationResult::interrupted,
                    "Ctrl-C stopped the continuation: the branches traced before it (status incomplete)")
      .def("brief_report", &spp::ContinuationResult::brief_report)
      .def(
          "gap_closures", [](const spp::ContinuationResult& r) { return spp::gap_closures(r); },
          "GapClosure events sorted by mu: with g0 = 0, the SPPs of paper §6.1")
      .def(py::pickle([](const spp::ContinuationResult& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::continuation_result(t); }))
      // JSON as spp continue --json writes it and reads it back (io/continuation_file.hpp): the result had no JSON
      // in Python (issue 11: every result type round-trips through JSON; found by an independent attack)
      .def(
          "to_json",
          [](const py::object& self, const py::object& system) {
            const py::object sys = system.is_none() && py::hasattr(self, "system") ? self.attr("system") : system;
            if (!py::isinstance<spp::ParametricSystem>(sys))
              throw py::type_error(
                  "ContinuationResult.to_json: argument system must be the spp.ParametricSystem it was traced on "
                  "(or omitted for a result read by from_json: its own), got " +
                  typed_repr(sys));
            return spp::continuation_json(sys.cast<const spp::ParametricSystem&>(),
                                          self.cast<const spp::ContinuationResult&>());
          },
          "system"_a = py::none(),
          "The continuation JSON text, the same text spp continue --json writes, for the parametric `system` it was "
          "traced on.")
      .def_static(
          "from_json",
          [](const std::string& path) {
            require_existing_file(path);
            spp::ContinuationFile file = spp::load_continuation_file(path);
            py::object result = py::cast(std::move(file.result));
            result.attr("system") = std::move(file.system);
            return result;
          },
          "path"_a,
          "The ContinuationResult of a continuation file (spp continue --json, ContinuationResult.to_json), with its "
          "parametric system as attribute system. Raises ValueError naming the file and the field.")
      .def("__repr__",
           [](const spp::ContinuationResult& r) { return "<spp.ContinuationResult " + r.brief_report() + ">"; });
  OptionsBinding<spp::ContinueOptions>(
      m, "ContinueOptions",
      "Options of continue_branches (the C++ ContinueOptions, field by field; "
      "continue_branches(system, t1_max, t2_max, options, **fields) also takes any field "
      "as a keyword)")
      .field("t1_max", &spp::ContinueOptions::t1_max, "upper end of the window in t1 (> 0)")
      .field("t2_max", &spp::ContinueOptions::t2_max, "upper end of the window in t2 (> 0)")
      .field("t1_min", &spp::ContinueOptions::t1_min, "lower end (0: as solve)")
      .field("t2_min", &spp::ContinueOptions::t2_min, "lower end (0: as solve)")
      .field("seeds", &spp::ContinueOptions::seeds,
             "parameter values (min, max and evenly between) where solve seeds branches")
      .field("max_step", &spp::ContinueOptions::max_step,
             "largest step, in arclength of (t1/t1_max, t2/t2_max, mu/(max - min))")
      .field("min_step", &spp::ContinueOptions::min_step,
             "a branch whose step falls below this stops with a \"stalled\" event")
      .field("max_turn", &spp::ContinueOptions::max_turn, "largest angle (rad) between successive tangents")
      .field("max_points", &spp::ContinueOptions::max_points, "per branch and direction")
      .field("locate_tol", &spp::ContinueOptions::locate_tol, "events located to this, in the same scaled arclength")
      .field("threads", &spp::ContinueOptions::threads, "for the seeding solves (0: all)")
      .cls()
      .def_property(
          "symmetry", [](const spp::ContinueOptions& o) { return o.symmetry; },
          [](spp::ContinueOptions& o, const py::object& v) { o.symmetry = symmetry_of(v); },
          "Symmetry.axial (default) or Symmetry.point (or their names)")
      .def("validate", &spp::ContinueOptions::validate, "Raises ValueError naming the first invalid field.")
      .def("__repr__", [](const py::object& o) { return fields_repr(o, "ContinueOptions"); });
  m.def(
      "continue_branches",
      [](const spp::ParametricSystem& s, const py::object& t1_arg, const py::object& t2_arg, const py::object& options,
         const py::kwargs& fields) {
        const auto t1_max = optional_argument<double>(t1_arg, "spp.continue_branches: argument t1_max");
        const auto t2_max = optional_argument<double>(t2_arg, "spp.continue_branches: argument t2_max");
        py::dict rest;
        const RunControl control = take_run_control(fields, rest, false);
        spp::ContinueOptions o = with_fields<spp::ContinueOptions>(options, py::reinterpret_borrow<py::kwargs>(rest),
                                                                   "continue_branches", "ContinueOptions");
        if (t1_max) o.t1_max = *t1_max;
        if (t2_max) o.t2_max = *t2_max;
        o.validate();
        return run_interruptible("continue_branches", control.cancel, o, [&] { return spp::continue_branches(s, o); });
      },
      "system"_a, "t1_max"_a = py::none(), "t2_max"_a = py::none(), "options"_a = py::none(),
      ("Every SPP of the window followed over the parameter's range: continue_branches(system, t1_max=3, t2_max=1, "
       "seeds=9, ...), or with a ContinueOptions and any field also as a keyword. Ctrl-C or cancel=spp.Cancel() "
       "stops it: the branches traced so far are returned (status incomplete, interrupted True) with a "
       "RuntimeWarning." +
       std::string(kThreadRule) + " Raises ValueError.")
          .c_str());
  m.def(
      "continue_branch",
      [](const spp::ParametricSystem& s, const py::object& mu_arg, const spp::Solution& solution,
         const py::object& t1_arg, const py::object& t2_arg, const py::object& options, const py::kwargs& fields) {
        const double mu = scalar_argument<double>(mu_arg, "spp.continue_branch: argument mu");
        const auto t1_max = optional_argument<double>(t1_arg, "spp.continue_branch: argument t1_max");
        const auto t2_max = optional_argument<double>(t2_arg, "spp.continue_branch: argument t2_max");
        py::dict rest;
        const RunControl control = take_run_control(fields, rest, false);
        spp::ContinueOptions o = with_fields<spp::ContinueOptions>(options, py::reinterpret_borrow<py::kwargs>(rest),
                                                                   "continue_branch", "ContinueOptions");
        if (t1_max) o.t1_max = *t1_max;
        if (t2_max) o.t2_max = *t2_max;
        // the solution says which equations it solves, unless the caller said (then a mismatch is refused)
        if (options.is_none() && !fields.contains("symmetry")) o.symmetry = solution.orbit.symmetry;
        o.validate();
        return run_interruptible("continue_branch", control.cancel, o,
                                 [&] { return spp::continue_branch(s, mu, solution, o); });
      },
      "system"_a, "mu"_a, "solution"_a, "t1_max"_a = py::none(), "t2_max"_a = py::none(), "options"_a = py::none(),
      ("The one branch through `solution`, an SPP of system.at(mu) (e.g. spp.solve(system.at(mu), ...).solutions[i]), "
       "followed both ways over the parameter's range within the window t1 <= t1_max, t2 <= t2_max: "
       "continue_branch(system, mu, solution, t1_max=3, t2_max=1). No seed solves: the branch's cost alone. Ctrl-C "
       "or cancel=spp.Cancel() stops it as continue_branches." +
       std::string(kThreadRule) + " Raises ValueError when the solution is no SPP at mu.")
          .c_str());
}

}  // namespace spp::python
