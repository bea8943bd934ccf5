// Python bindings, simulation/: the exact event-driven simulator and verify.
#include <iomanip>
#include <sstream>

#include "common.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/io.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/simulator.hpp"
#include "spp/simulation/verify.hpp"
#include "state.hpp"

namespace spp::python {

namespace {
// One column of the samples as an (N,) array, or a vector field as an (N, n) array.
Eigen::VectorXd scalars(const spp::SimulationResult& r, double spp::Sample::*field) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(r.samples.size()));
  for (size_t k = 0; k < r.samples.size(); ++k) out(static_cast<Eigen::Index>(k)) = r.samples[k].*field;
  return out;
}
Eigen::MatrixXd rows(const spp::SimulationResult& r, Eigen::VectorXd spp::Sample::*field) {
  const Eigen::Index n = r.samples.empty() ? 0 : (r.samples[0].*field).size();
  Eigen::MatrixXd out(static_cast<Eigen::Index>(r.samples.size()), n);
  for (size_t k = 0; k < r.samples.size(); ++k)
    out.row(static_cast<Eigen::Index>(k)) = (r.samples[k].*field).transpose();
  return out;
}
}  // namespace

void bind_simulation(py::module_& m) {
  bind_outcome<spp::SimulationStatus>(m, "SimulationStatus",
               "SimulationResult.status");
  bind_outcome<spp::EventKind>(m, "EventKind",
               "Event.kind");
  bind_outcome<spp::VerifyStatus>(m, "VerifyStatus",
      "VerifyResult.status: inconsistent when the result disagrees with the simulation or the system (admissibility, "
      "claimed stability, x0/v0: the three counters), interrupted when Ctrl-C stopped it before every SPP was "
      "checked (unchecked counts those left) and none checked disagrees, incomplete when an SPP's simulation would "
      "pass the simulator's limit (beyond_simulator_limit, a warning each), else success");
  bind_outcome<spp::Verdict>(m, "Verdict", "SppCheck.verdict");
  py::class_<spp::Event>(m, "Event")
      .def_readonly("t", &spp::Event::t)
      .def_property_readonly("kind", [](const spp::Event& e) { return outcome(e.kind); })
      .def_readonly("x", &spp::Event::x)
      .def_readonly("v_before", &spp::Event::v_before)
      .def_readonly("v_after", &spp::Event::v_after)
      .def_readonly("normal_velocity_before", &spp::Event::normal_velocity_before)
      .def_readonly("normal_velocity_after", &spp::Event::normal_velocity_after)
      .def_readonly("force", &spp::Event::force)
      .def(py::pickle([](const spp::Event& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::event(t); }))
      .def("__repr__", [](const spp::Event& e) {
        std::ostringstream os;
        os << "<spp.Event " << spp::to_string(e.kind) << " t=" << e.t << ">";
        return os.str();
      });

  py::class_<spp::SimulationResult>(m, "SimulationResult")
      .def_property_readonly("status", [](const spp::SimulationResult& r) { return outcome(r.status); })
      .def_property_readonly(
          "t", [](const spp::SimulationResult& r) { return scalars(r, &spp::Sample::t); }, "(N,) sample times")
      .def_property_readonly(
          "x", [](const spp::SimulationResult& r) { return rows(r, &spp::Sample::x); }, "(N, n) positions")
      .def_property_readonly(
          "v", [](const spp::SimulationResult& r) { return rows(r, &spp::Sample::v); }, "(N, n) velocities")
      .def_property_readonly(
          "gap", [](const spp::SimulationResult& r) { return scalars(r, &spp::Sample::gap); }, "(N,) gap w^T x + g0")
      .def_property_readonly(
          "force", [](const spp::SimulationResult& r) { return scalars(r, &spp::Sample::force); },
          "(N,) normal contact force (0 in flight)")
      .def_readonly("events", &spp::SimulationResult::events)
      .def_readonly("impacts", &spp::SimulationResult::impacts)
      .def_readonly("contact_onsets", &spp::SimulationResult::contact_onsets)
      .def_readonly("releases", &spp::SimulationResult::releases)
      .def_readonly("energy_initial", &spp::SimulationResult::energy_initial)
      .def_readonly("energy_final", &spp::SimulationResult::energy_final)
      .def_readonly("impact_energy_loss", &spp::SimulationResult::impact_energy_loss)
      .def("brief_report", &spp::SimulationResult::brief_report)
      .def(py::pickle([](const spp::SimulationResult& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::simulation_result(t); }))
      .def("__repr__",
           [](const spp::SimulationResult& r) { return "<spp.SimulationResult " + r.brief_report() + ">"; });

  OptionsBinding<spp::SimulateOptions>(
      m, "SimulateOptions",
      "Options of simulate (the C++ SimulateOptions, field by field; simulate(system, x0, "
      "v0, duration, options=..., **fields) also takes any field as a keyword)")
      .field("duration", &spp::SimulateOptions::duration, "simulated time T > 0; the last sample is at t = T exactly")
      .field("restitution", &spp::SimulateOptions::restitution,
             "Newton's coefficient e in [0, 1]: normal velocity after = -e * before")
      .field("sample_times", &spp::SimulateOptions::sample_times,
             "samples at these times (sorted, in [0, duration]); empty: samples_per_unit of simulate")
      .field("sample_events", &spp::SimulateOptions::sample_events, "add a sample with the state just after each event")
      .field("max_events", &spp::SimulateOptions::max_events)
      .field("event_rel_tol", &spp::SimulateOptions::event_rel_tol,
             "excursions below zero shallower than this (relative to the phase's amplitude) are not events")
      .field("rest_velocity_rel_tol", &spp::SimulateOptions::rest_velocity_rel_tol,
             "impacts slower than this (relative) are plastic: where chattering ends in lasting contact")
      .cls()
      .def("validate", &spp::SimulateOptions::validate, "Raises ValueError naming the first invalid field.")
      .def("__repr__", [](const py::object& o) { return fields_repr(o, "SimulateOptions"); });
  m.def(
      "simulate",
      [](const spp::System& s, const py::object& x0_arg, const py::object& v0_arg, const py::object& duration_arg,
         const py::object& restitution_arg, const py::object& samples_arg, const py::object& options,
         const py::kwargs& fields) {
        const auto duration = optional_argument<double>(duration_arg, "spp.simulate: argument duration");
        const auto restitution = optional_argument<double>(restitution_arg, "spp.simulate: argument restitution");
        const double samples_per_unit = scalar_argument<double>(samples_arg, "spp.simulate: argument samples_per_unit");
        // (a ragged or 2-D list named with the shape expected, not pybind11's cast failure)
        const Eigen::VectorXd x0 = array_of_numbers(x0_arg, "simulate: x0", 1);
        const Eigen::VectorXd v0 = array_of_numbers(v0_arg, "simulate: v0", 1);
        py::dict rest;
        const RunControl control = take_run_control(fields, rest, false);
        spp::SimulateOptions o = with_fields<spp::SimulateOptions>(options, py::reinterpret_borrow<py::kwargs>(rest),
                                                                   "simulate", "SimulateOptions");
        if (duration) o.duration = *duration;
        if (restitution) o.restitution = *restitution;
        o.validate();
        if (!(samples_per_unit > 0.0))
          detail::invalid("simulate: samples_per_unit must be > 0, got " + std::to_string(samples_per_unit));
        // bounded like trajectory's samples, before the sample times are allocated (1e6 time units at the default
        // 100 per unit were 1e8 samples: a bad_alloc after 83 s, or the machine's memory; found by an attack)
        const long long most = max_samples(s.n());
        const double requested = std::floor(o.duration * samples_per_unit) + 1.0;
        if (o.sample_times.empty() && !(requested <= static_cast<double>(most))) {
          std::ostringstream os;
          os << "simulate: expected duration x samples_per_unit at most " << most << " samples (samples x (2n + 3) at "
             << "most 1e8 values, 800 MB, for n = " << s.n() << "), got duration " << o.duration
             << " x samples_per_unit " << samples_per_unit << " = " << requested
             << " samples: a shorter duration or fewer samples_per_unit";
          detail::invalid(os.str());
        }
        if (o.sample_times.empty()) o.sample_times = spp::uniform_times(o.duration, samples_per_unit);
        // Ctrl-C checked every 256 events or samples: the run stops there and what was simulated is returned
        // (status interrupted, samples and events up to that time) with a RuntimeWarning, as solve keeps what it
        // found (it raised KeyboardInterrupt, losing a long simulation)
        ProgressHook hook(py::none(), "simulate", control.cancel);
        o.progress = [&hook] { return hook.keep_going(); };
        spp::SimulationResult r;
        {
          py::gil_scoped_release release;
          r = spp::simulate(s, x0, v0, o);
        }
        hook.finish();
        std::ostringstream why;
        if (r.status == spp::SimulationStatus::Interrupted)
          why << "simulate interrupted (Ctrl-C): the result holds the samples and events up to t = " << r.end_time
              << " of " << o.duration << " (status interrupted)";
        else
          why << "Ctrl-C came after simulate had finished: the result is complete";
        hook.warn(why.str());
        return r;
      },
      "system"_a, "x0"_a, "v0"_a, "duration"_a = py::none(), "restitution"_a = py::none(), "samples_per_unit"_a = 100.0,
      "options"_a = py::none(),
      (std::string("Exact event-driven simulation from (x0, v0), shapes (n,): simulate(system, x0, v0, duration, "
                   "restitution=0, samples_per_unit=100), or with a SimulateOptions and any field also as a keyword "
                   "(sample_times=[...] replaces the uniform samples). Ctrl-C or cancel=spp.Cancel() stops it: the "
                   "samples and events so far are returned (status interrupted) with a RuntimeWarning.") +
       kThreadRule + " Raises ValueError.")
          .c_str());

  py::class_<spp::SppCheck>(m, "SppCheck")
      .def_property_readonly("t1", [](const spp::SppCheck& c) { return c.spp.t1(); })
      .def_property_readonly("t2", [](const spp::SppCheck& c) { return c.spp.t2(); })
      .def_property_readonly("admissible", [](const spp::SppCheck& c) { return c.spp.admissible(); })
      .def_property_readonly("verdict", [](const spp::SppCheck& c) { return outcome(c.verdict); })
      .def_readonly("consistent", &spp::SppCheck::consistent)
      .def_readonly("return_errors", &spp::SppCheck::return_errors)
      .def_readonly("potential_return_error", &spp::SppCheck::potential_return_error)
      .def_readonly("state_tolerance", &spp::SppCheck::state_tolerance,
                    "this SPP's tolerance on its onset state and potential orbit (from the problem's own error, "
                    "docs/result-files.md, Tolerances)")
      .def_readonly("return_tolerance", &spp::SppCheck::return_tolerance,
                    "this SPP's tolerance on the simulated return after one period")
      .def_readonly("periods_followed", &spp::SppCheck::periods_followed)
      .def_readonly("departure_time", &spp::SppCheck::departure_time)
      .def_readonly("departure", &spp::SppCheck::departure)
      .def_readonly("perturbed_distances", &spp::SppCheck::perturbed_distances)
      .def_readonly("impacts", &spp::SppCheck::impacts, "events of the simulation (over every period)")
      .def_readonly("contact_onsets", &spp::SppCheck::contact_onsets)
      .def_readonly("releases", &spp::SppCheck::releases)
      .def_readonly("growth_per_period", &spp::SppCheck::growth_per_period)
      .def_property_readonly(
          "solution", [](const spp::SppCheck& c) { return c.spp; }, "the SPP checked")
      .def(py::pickle([](const spp::SppCheck& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::spp_check(t); }))
      .def("__repr__", [](const spp::SppCheck& c) {
        std::ostringstream os;
        os << "<spp.SppCheck t1=" << c.spp.t1() << " t2=" << c.spp.t2() << " " << spp::to_string(c.verdict)
           << (c.consistent ? ", consistent" : ", INCONSISTENT") << ", " << c.periods_followed << " periods followed>";
        return os.str();
      });

  py::class_<spp::VerifyResult>(m, "VerifyResult")
      .def_property_readonly("status", [](const spp::VerifyResult& r) { return outcome(r.status); })
      .def_readonly("checks", &spp::VerifyResult::checks)
      .def(
          "to_json", [](const spp::VerifyResult& r) { return spp::verify_json(r); },
          "The verify JSON text, the same text spp verify --json writes (io/verify_file.hpp).")
      .def_readonly("returned", &spp::VerifyResult::returned)
      .def_readonly("left", &spp::VerifyResult::left)
      .def_readonly("inconsistent", &spp::VerifyResult::inconsistent)
      // a property, as every bool of the binding (admissible, stable, consistent): as a method, bool(v.all_consistent)
      // was always True (found by issue 14's attack)
      .def_property_readonly("all_consistent", &spp::VerifyResult::all_consistent,
                             "True when every SPP checked is consistent (inconsistent == 0)")
      .def_readonly("unchecked", &spp::VerifyResult::unchecked,
                    "SPPs not checked (a stopped run, or beyond_simulator_limit)")
      .def_readonly("beyond_simulator_limit", &spp::VerifyResult::beyond_simulator_limit,
                    "SPPs not checked because periods x period passes the simulator's limit (status incomplete)")
      .def_readonly("admissibility_mismatches", &spp::VerifyResult::admissibility_mismatches,
                    "SPPs whose simulation (returns or leaves) is not the solver's admissibility")
      .def_readonly("stability_mismatches", &spp::VerifyResult::stability_mismatches,
                    "SPPs whose claimed stability the Floquet multipliers recomputed from (t1, t2) contradict")
      .def_readonly("state_mismatches", &spp::VerifyResult::state_mismatches,
                    "SPPs whose x0, v0 are not the orbit at (t1, t2)")
      .def_readonly("warnings", &spp::VerifyResult::warnings,
                    "what the verification warns of (the JSON's warnings): SPPs beyond the simulator's limit, a "
                    "perturbation within the simulator's own error, growth above 1 beside a stable verdict")
      .def("brief_report", &spp::VerifyResult::brief_report)
      .def(py::pickle([](const spp::VerifyResult& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::verify_result(t); }))
      .def("__repr__", [](const spp::VerifyResult& r) { return "<spp.VerifyResult " + r.brief_report() + ">"; });

  OptionsBinding<spp::VerifyOptions>(m, "VerifyOptions",
                                     "Options of verify (the C++ VerifyOptions, field by field; verify(system, result, "
                                     "options, **fields) also takes any field as a keyword)")
      .field("periods", &spp::VerifyOptions::periods, "simulated periods (>= 1)")
      .field("perturbation", &spp::VerifyOptions::perturbation,
             "relative size of the perturbation of the mid-flight state; 0: none")
      .field("restitution", &spp::VerifyOptions::restitution,
             "Newton's e for the simulations (matters only once the orbit is left)")
      .field("return_tol", &spp::VerifyOptions::return_tol,
             "an admissible SPP must come back to this relative error after one period")
      .field("follow_tol", &spp::VerifyOptions::follow_tol,
             "later periods count as followed while the return error stays below this")
      .field("potential_return_tol", &spp::VerifyOptions::potential_return_tol,
             "every SPP must come back to this relative error along its potential orbit (events ignored)")
      .field("event_time_tol", &spp::VerifyOptions::event_time_tol,
             "relative to the period: events within it of the expected times match")
      .cls()
      .def("validate", &spp::VerifyOptions::validate, "Raises ValueError naming the first invalid field.")
      .def("__repr__", [](const py::object& o) { return fields_repr(o, "VerifyOptions"); });
  m.def(
      "verify",
      [](const spp::System& s, const py::object& result, const py::object& options, const py::kwargs& fields) {
        py::dict rest;
        const RunControl control = take_run_control(fields, rest, false);
        spp::VerifyOptions o = with_fields<spp::VerifyOptions>(options, py::reinterpret_borrow<py::kwargs>(rest),
                                                               "verify", "VerifyOptions");
        o.validate();
        if (!py::isinstance<spp::SolveResult>(result))
          detail::invalid("verify: result must be a SolveResult (of solve() or load_result()), got " +
                          std::string(py::str(py::type::of(result).attr("__name__"))));
        const spp::SolveResult& r = result.cast<const spp::SolveResult&>();
        // a result knows the system it was solved for (solve(), load_result()): verifying it against another one
        // would blame the solver for the caller's mix-up
        if (py::hasattr(result, "system") && py::isinstance<spp::System>(result.attr("system")) &&
            !spp::same_system(result.attr("system").cast<const spp::System&>(), s))
          detail::invalid(
              "verify: the result was solved for another system than the one given (result.system): "
              "expected the system of the result, got another");
        // Ctrl-C checked before each SPP and every 256 events: the SPPs checked before it are returned (unchecked
        // counts the others) with a RuntimeWarning, as solve keeps what it found (it raised KeyboardInterrupt)
        ProgressHook hook(py::none(), "verify", control.cancel);
        o.progress = [&hook] { return hook.keep_going(); };
        spp::VerifyResult v;
        {
          py::gil_scoped_release release;
          v = spp::verify(s, r.solutions, o);
        }
        hook.finish();
        hook.warn(v.unchecked > 0 ? "verify interrupted (Ctrl-C): " + std::to_string(v.checks.size()) +
                                        " SPP(s) checked, " + std::to_string(v.unchecked) +
                                        " not (the result's unchecked); the counts and status are those of the "
                                        "checked ones"
                                  : std::string("Ctrl-C came after verify had finished: the result is complete"));
        return v;
      },
      "system"_a, "result"_a, "options"_a = py::none(),
      (std::string("Re-simulates every solution of a solve() result: verify(system, result, periods=3, "
                   "perturbation=1e-6, ...), "
                   "or with a VerifyOptions and any field also as a keyword. Ctrl-C or cancel=spp.Cancel() stops "
                   "it: the SPPs checked so far are returned (unchecked > 0 counts the others) with a "
                   "RuntimeWarning.") +
       kThreadRule + " Raises ValueError (also for a result solved for another system than `system`).")
          .c_str());
}

}  // namespace spp::python
