// Python bindings, orbit/: Solution, and one period of an SPP (trajectory).
#include "spp/orbit/orbit.hpp"

#include <iomanip>
#include <sstream>

#include "common.hpp"
#include "state.hpp"
#include "spp/orbit/solution.hpp"
#include "spp/search/solver.hpp"
#include "spp/detail/invalid.hpp"

namespace spp::python {

namespace {
// spp::sample_orbit's samples (the same times T k / (samples - 1), the same states), computed here one by one so that
// Ctrl-C is checked between them: every kSamplesPerCheck samples, or every one for large systems, about every 1e6
// flops (well under a millisecond; a sample costs ~ m^2 + n m). Cut short when it is pressed: the samples computed
// (the first rows) are returned, the count in `done`.
// With `times` (not empty), the samples are at those times instead (from contact onset, any real: the orbit is
// periodic, each is taken modulo the period), e.g. an animation's frame times, exact between the uniform samples.
spp::OrbitSamples sampled(const spp::ModalForm& md, const spp::Orbit& orbit, int samples, ProgressHook& hook, int& done,
                          const Eigen::VectorXd& times) {
  constexpr double kFlopsPerCheck = 1e6;
  constexpr double kSamplesPerCheck = 1024;
  const double per_sample = static_cast<double>(md.m()) * static_cast<double>(md.m() + md.n()) + 1.0;
  const int every = static_cast<int>(std::clamp(kFlopsPerCheck / per_sample, 1.0, kSamplesPerCheck));
  spp::OrbitSamples s{Eigen::VectorXd(samples), Eigen::VectorXd(samples), Eigen::VectorXd(samples),
                      Eigen::MatrixXd(samples, md.n()), Eigen::MatrixXd(samples, md.n())};
  const double T = orbit.period();
  done = 0;
  for (int k = 0; k < samples; ++k) {
    if (k % every == 0 && !hook.keep_going()) break;
    done = k + 1;
    s.t(k) = times.size() > 0 ? times(k) : T * k / (samples - 1);
    const spp::OrbitState st =
        spp::orbit_state(md, orbit, times.size() > 0 ? s.t(k) - T * std::floor(s.t(k) / T) : s.t(k));
    s.x.row(k) = st.x.transpose();
    s.v.row(k) = st.v.transpose();
    s.gap(k) = st.gap;
    s.force(k) = st.force;
  }
  return s;
}
}  // namespace

void bind_orbit(py::module_& m) {
  py::class_<spp::Solution>(m, "Solution", "One potential SPP")
      .def_property_readonly("t1", &spp::Solution::t1, "flight half-duration")
      .def_property_readonly("t2", &spp::Solution::t2, "contact half-duration")
      .def_property_readonly("period", &spp::Solution::period, "2 (t1 + t2)")
      .def_property_readonly("admissible", &spp::Solution::admissible)
      .def_property_readonly("min_gap", &spp::Solution::min_gap, "smallest gap over the flight")
      .def_property_readonly("min_force", &spp::Solution::min_force, "smallest contact force over the contact phase")
      .def_property_readonly("energy", &spp::Solution::energy)
      .def_readonly("residual", &spp::Solution::residual)
      .def_readonly("return_error", &spp::Solution::return_error)
      .def_readonly("flags", &spp::Solution::flags)
      .def_property_readonly(
          "obstacle_velocity", [](const spp::Solution& s) { return s.orbit.obstacle_velocity; },
          "point symmetry: normal velocity of the obstacle during contact (g0 / t2); 0 for SPPs")
      .def_property_readonly(
          "floquet_multipliers",
          [](const spp::Solution& s) {
            return Eigen::VectorXcd(Eigen::Map<const Eigen::VectorXcd>(
                s.floquet.multipliers.data(), static_cast<Eigen::Index>(s.floquet.multipliers.size())));
          },
          "(2n,) complex Floquet multipliers under Newton's impact law, e < 1, sorted by modulus (docs/stability.md); "
          "empty when not computed (point symmetry)")
      .def_property_readonly(
          "spectral_radius", [](const spp::Solution& s) { return s.floquet.spectral_radius; },
          "largest |multiplier| but the two structural 1s (NaN: not computed)")
      .def_property_readonly(
          "stability_margin", [](const spp::Solution& s) { return s.floquet.margin; }, "1 - spectral_radius")
      .def_property_readonly(
          "spectral_radius_error", [](const spp::Solution& s) { return s.floquet.spectral_radius_error; },
          "estimated error bound of spectral_radius: rounding, and the SPP's location error (spectral_radius_"
          "location_error; inf: defective leading multiplier or no bound on the location; NaN: not computed or read "
          "from a file written before it)")
      .def_property_readonly(
          "spectral_radius_location_error", [](const spp::Solution& s) { return s.floquet.location_error; },
          "the part of spectral_radius_error from the SPP's location error (large near a fold of a branch, "
          "docs/stability.md; 0 for solutions read from a result file)")
      .def_property_readonly(
          "stability_verdict", [](const spp::Solution& s) { return outcome(s.floquet.verdict); },
          "StabilityVerdict: stable / unstable when |spectral_radius - 1| exceeds spectral_radius_error, undecided "
          "when not, neutral when modes that never see the contact put multipliers on the unit circle")
      .def_property_readonly(
          "leading_multipliers",
          [](const spp::Solution& s) {
            return Eigen::VectorXcd(Eigen::Map<const Eigen::VectorXcd>(
                s.floquet.leading.data(), static_cast<Eigen::Index>(s.floquet.leading.size())));
          },
          "the coupled modes' multiplier of largest modulus (one real, or a conjugate pair); not in result files")
      .def_property_readonly("stable", &spp::Solution::stable,
                             "admissible and stability_verdict stable (proved up to the rounding bound)")
      .def_property_readonly(
          "x0", [](const spp::Solution& s) { return s.orbit.x0; }, "(n,) state at contact onset")
      .def_property_readonly(
          "v0", [](const spp::Solution& s) { return s.orbit.v0; }, "(n,)")
      .def(py::pickle([](const spp::Solution& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::solution(t); }))
      .def("__repr__", [](const spp::Solution& s) {
        return "<spp.Solution t1=" + std::to_string(s.t1()) + " t2=" + std::to_string(s.t2()) +
               (s.admissible() ? " admissible>" : " not admissible>");
      });

  m.def(
      "trajectory",
      [](const spp::System& s, const py::object& t1_arg, const py::object& t2_arg, const py::object& samples_arg,
         const py::object& cancel, const py::object& times_arg) {
        const double t1 = scalar_argument<double>(t1_arg, "spp.trajectory: argument t1"),
                     t2 = scalar_argument<double>(t2_arg, "spp.trajectory: argument t2");
        Eigen::VectorXd times;
        if (!times_arg.is_none()) {
          times = array_of_numbers(times_arg, "trajectory: times", 1);
          if (times.size() == 0 || !times.allFinite())
            detail::invalid("trajectory: times must be a non-empty vector of finite numbers, got " +
                            std::to_string(times.size()) + " value(s)" + (times.allFinite() ? "" : " not all finite"));
          if (times.size() > max_samples(s.n()))
            detail::invalid("trajectory: expected at most " + std::to_string(max_samples(s.n())) +
                            " times (samples x (2n + 3) at most 1e8 values), got " + std::to_string(times.size()));
        }
        // taken as any Python integer (an int parameter made samples=10**12 a signature mismatch, "incompatible
        // function arguments"; found by an independent attack): its range is said instead
        if (py::isinstance<py::bool_>(samples_arg))
          throw py::type_error("trajectory: samples must be an int, got " + typed_repr(samples_arg));
        py::object whole;
        try {
          whole = py::module_::import("operator").attr("index")(samples_arg);
        } catch (const py::error_already_set& e) {
          if (!e.matches(PyExc_TypeError)) throw;
          throw py::type_error("trajectory: samples must be an int, got " + typed_repr(samples_arg));
        }
        // the samples' arrays are allocated at once: bounded like spp trajectory's CSV (kMaxSampleValues)
        const long long most = max_samples(s.n());
        if (whole < py::int_(2) || whole > py::int_(most)) {
          std::string shown = py::repr(whole).cast<std::string>();
          if (shown.size() > 60) shown = shown.substr(0, 60) + "...";
          detail::invalid("trajectory: samples must be from 2 to " + std::to_string(most) +
                          " (samples x (2n + 3) at most 1e8 values, 800 MB, for n = " + std::to_string(s.n()) +
                          "), got " + shown + ": out of range");
        }
        const int samples = times.size() > 0 ? static_cast<int>(times.size()) : whole.cast<int>();
        // Ctrl-C checked while sampling (a million samples of a large system take seconds; it was not checked at
        // all, found by an independent attack) and after each stage. During the sampling, the samples computed so
        // far are returned (interrupted True, a RuntimeWarning), as solve keeps what it found; before it (the modal
        // form, Newton) there is nothing to keep: KeyboardInterrupt.
        ProgressHook hook(py::none(), "trajectory", cancel);
        spp::SolutionAt at;
        spp::OrbitSamples os;
        int done = 0;
        bool before_sampling = false;
        {
          py::gil_scoped_release release;
          const spp::ModalForm md(s);
          spp::SolveOptions o;
          o.compute_return_error = false;
          if (hook.keep_going()) at = spp::solution_at(s, md, t1, t2, o);
          before_sampling = !hook.keep_going();
          if (at.found && !before_sampling) os = sampled(md, at.solution.orbit, samples, hook, done, times);
        }
        // Ctrl-C before the sampling: nothing to keep, KeyboardInterrupt. A cancelled token (another thread's
        // cancel()) returns no samples instead, as every call taking cancel= returns (a KeyboardInterrupt raised in a
        // worker thread reached the main thread through Future.result(); found by the attack on issue 13)
        if (before_sampling && !hook.cancelled) hook.raise_if_interrupted();
        hook.finish();
        if (before_sampling && !at.found) {
          hook.warn("trajectory interrupted (Ctrl-C) before the SPP was polished: no samples (interrupted True)");
          const double nan = std::numeric_limits<double>::quiet_NaN();
          return py::dict("t"_a = Eigen::VectorXd(0), "x"_a = Eigen::MatrixXd(0, s.n()),
                          "v"_a = Eigen::MatrixXd(0, s.n()), "gap"_a = Eigen::VectorXd(0),
                          "force"_a = Eigen::VectorXd(0), "t1"_a = t1, "t2"_a = t2, "period"_a = nan,
                          "admissible"_a = py::none(), "interrupted"_a = true);
        }
        if (!at.found) throw py::value_error("trajectory: " + at.brief_report());
        const bool cut = done < samples;
        hook.warn(cut ? "trajectory interrupted (Ctrl-C): " + std::to_string(done) + " of " + std::to_string(samples) +
                            " samples, from t = 0 (interrupted True)"
                      : std::string("Ctrl-C came after trajectory had finished: the samples are complete"));
        const spp::Solution& sol = at.solution;
        return py::dict("t"_a = Eigen::VectorXd(os.t.head(done)), "x"_a = Eigen::MatrixXd(os.x.topRows(done)),
                        "v"_a = Eigen::MatrixXd(os.v.topRows(done)), "gap"_a = Eigen::VectorXd(os.gap.head(done)),
                        "force"_a = Eigen::VectorXd(os.force.head(done)), "t1"_a = sol.t1(), "t2"_a = sol.t2(),
                        "period"_a = sol.orbit.period(), "admissible"_a = sol.admissible(), "interrupted"_a = cut);
      },
      "system"_a, "t1"_a, "t2"_a, "samples"_a = 1001, "cancel"_a = py::none(), "times"_a = py::none(),
      ("One period of the SPP at (t1, t2) (polished there first), from its own equations, as spp trajectory writes it: "
       "dict of t (N,) from contact onset, x, v (N, n), gap, force (N,), and the polished t1, t2, period, "
       "admissible, and interrupted (Ctrl-C during the sampling: the samples so far, with a RuntimeWarning; before it, "
       "KeyboardInterrupt; cancel=spp.Cancel() cancelled before it: no samples, and when the SPP was not polished "
       "yet the given t1, t2, period nan and admissible None). Unlike simulate, it follows an inadmissible SPP too (the potential orbit, gap < 0 "
       "somewhere). "
       "times=[...]: the rows at those times instead (from contact onset, any real, taken modulo the period; "
       "samples is then ignored), exact at any time (an animation's frames). cancel=spp.Cancel() stops it as Ctrl-C "
       "does." +
       std::string(kThreadRule) + " Raises ValueError when no SPP is within 1e-3 (t1 + t2) of the point.")
          .c_str());
}

}  // namespace spp::python
