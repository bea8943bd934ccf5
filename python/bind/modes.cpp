// Python bindings, modes/: k-impact periodic orbits (nonsmooth modes, docs/modes.md).
#include <sstream>

#include "common.hpp"
#include "spp/modes/nonsmooth_modes.hpp"
#include "state.hpp"

namespace spp::python {

namespace md = spp::modes;

namespace {

// A Python integer (numpy's too, through operator.index), not a bool, in [lo, hi]: else TypeError (not an integer)
// or ValueError (out of range), with `message` (compared as Python integers: 2**63 was pybind11's RuntimeError).
int index_in(const py::handle& v, int lo, int hi, const std::string& message) {
  const bool is_bool = py::isinstance<py::bool_>(v) || py::isinstance(v, py::module_::import("numpy").attr("bool_"));
  py::object whole;
  if (!is_bool) {
    try {
      whole = py::module_::import("operator").attr("index")(v);
    } catch (const py::error_already_set& e) {
      if (!e.matches(PyExc_TypeError)) throw;
    }
  }
  if (!whole) throw py::type_error(message);
  if (whole < py::int_(lo) || whole > py::int_(hi)) detail::invalid(message);
  return whole.cast<int>();
}

// One k of spp.modes, in [1, kMaxImpactsPerPeriod] (a bool is refused: True was taken as 1).
int one_k(const py::handle& v, const py::object& given) {
  const std::string expected = "k: expected an int from 1 to " + std::to_string(md::kMaxImpactsPerPeriod) +
                               " or a sequence of them (e.g. [1, 2, 3] or range(1, 4)), got ";
  return index_in(v, 1, md::kMaxImpactsPerPeriod, "modes: " + expected + typed_repr(given));
}

// k as documented: one int or a sequence of ints; a string ('1..3', the CLI's form) is no sequence of ints here.
std::vector<int> k_values(const py::object& k) {
  if (py::isinstance<py::str>(k) || py::isinstance<py::bytes>(k) || !py::isinstance<py::sequence>(k))
    return {one_k(k, k)};
  std::vector<int> out;
  for (const py::handle v : k) out.push_back(one_k(v, k));
  return out;
}

// An integer argument in [lo, hi] (multiples), checked as k is.
int whole_in(const char* name, const py::object& v, int lo, int hi) {
  return index_in(v, lo, hi,
                  std::string("modes: ") + name + ": expected an int from " + std::to_string(lo) + " to " +
                      std::to_string(hi) + ", got " + typed_repr(v));
}

}  // namespace

void bind_modes(py::module_& m) {
  bind_outcome<md::ModeEventKind>(m, "ModeEventKind",
               "ModeEvent.kind");
  bind_outcome<md::ModesStatus>(m, "ModesStatus",
               "ModesResult.status: traced (every family found followed to a located end; NOT every k-IPP family: "
               "docs/modes.md §5) or incomplete (a family stalled)");
  // Nonsmooth modes: k-IPP families (docs/modes.md). Kinds and statuses as their C++ to_string names.
  py::class_<md::ModePoint>(m, "ModePoint", "One k-IPP of a family (state just after its first impact)")
      .def_readonly("energy", &md::ModePoint::energy)
      .def_readonly("period", &md::ModePoint::period)
      .def_readonly("frequency", &md::ModePoint::frequency, "2 pi / period")
      .def_readonly("impact_times", &md::ModePoint::impact_times, "k times in [0, period), first 0")
      .def_readonly("x0", &md::ModePoint::x0)
      .def_readonly("v0", &md::ModePoint::v0, "velocity just after the first impact")
      .def_readonly("admissible", &md::ModePoint::admissible)
      .def_readonly("margin", &md::ModePoint::margin)
      .def_readonly("multiplicity", &md::ModePoint::multiplicity, "r > 1: an r-fold repetition of a shorter orbit")
      .def(py::pickle([](const md::ModePoint& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::mode_point(t); }))
      .def("__repr__", [](const md::ModePoint& p) {
        std::ostringstream os;
        os << "<spp.ModePoint energy=" << p.energy << " frequency=" << p.frequency << " period=" << p.period << ", "
           << p.impact_times.size() << " impacts, " << (p.admissible ? "admissible" : "not admissible")
           << (p.multiplicity > 1 ? ", multiplicity " + std::to_string(p.multiplicity) : std::string()) << ">";
        return os.str();
      });
  py::class_<md::ModeEvent>(m, "ModeEvent")
      .def_property_readonly("kind", [](const md::ModeEvent& e) { return outcome(e.kind); })
      .def_readonly("at", &md::ModeEvent::at)
      .def_readonly("detail", &md::ModeEvent::detail)
      .def(py::pickle([](const md::ModeEvent& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::mode_event(t); }))
      .def("__repr__", [](const md::ModeEvent& e) {
        std::ostringstream os;
        os << "<spp.ModeEvent " << md::to_string(e.kind) << " at energy=" << e.at.energy
           << " frequency=" << e.at.frequency << (e.detail.empty() ? "" : ": " + e.detail) << ">";
        return os.str();
      });
  py::class_<md::ModeFamily>(m, "ModeFamily")
      .def_readonly("k", &md::ModeFamily::k)
      .def_property_readonly("symmetry", [](const md::ModeFamily& f) { return std::string(md::to_string(f.symmetry)); })
      .def_property_readonly(
          "mode", [](const md::ModeFamily& f) { return f.mode; },
          "the linear mode of the grazing start, numbered from 1 (lowest frequency), as in C++ and the JSON")
      .def_readonly("multiplicity", &md::ModeFamily::multiplicity)
      .def_readonly("label", &md::ModeFamily::label)
      .def_readonly("points", &md::ModeFamily::points)
      .def_readonly("events", &md::ModeFamily::events)
      .def_property_readonly(
          "arrays",
          [](const md::ModeFamily& f) {
            Eigen::MatrixXd a(static_cast<Eigen::Index>(f.points.size()), 3);
            for (size_t i = 0; i < f.points.size(); ++i)
              a.row(static_cast<Eigen::Index>(i)) << f.points[i].energy, f.points[i].frequency, f.points[i].margin;
            return a;
          },
          "(N, 3): energy, frequency, margin of every point")
      .def(py::pickle([](const md::ModeFamily& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::mode_family(t); }))
      .def("__repr__", [](const md::ModeFamily& f) {
        std::ostringstream os;
        os << "<spp.ModeFamily " << f.label << ": k=" << f.k << " " << md::to_string(f.symmetry) << " mode=" << f.mode
           << " multiplicity=" << f.multiplicity << ", " << f.points.size() << " points, events:";
        for (const md::ModeEvent& e : f.events) os << " " << md::to_string(e.kind);
        if (f.events.empty()) os << " none";
        os << ">";
        return os.str();
      });
  py::class_<md::ModesResult>(m, "ModesResult")
      .def_property_readonly("status", [](const md::ModesResult& r) { return outcome(r.status); })
      .def_readonly("families", &md::ModesResult::families)
      .def_readonly("linear_frequencies", &md::ModesResult::linear_frequencies)
      .def_readonly("corrector_solves", &md::ModesResult::corrector_solves)
      .def_readonly("inadmissible_stretches", &md::ModesResult::inadmissible_stretches,
                    "stretches of inadmissible orbits followed (through_inadmissible)")
      .def_readonly("seconds", &md::ModesResult::seconds)
      .def_readonly("interrupted", &md::ModesResult::interrupted,
                    "Ctrl-C stopped the tracing: the families traced before it (status incomplete)")
      .def("brief_report", &md::ModesResult::brief_report)
      .def(py::pickle([](const md::ModesResult& x) { return state::of(x); },
                      [](const py::tuple& t) { return state::modes_result(t); }))
      .def("__repr__", [](const md::ModesResult& r) {
        const std::string report = r.brief_report();
        const std::string prefix = "spp modes: ";  // (brief_report's, as SolveResult's repr drops "spp: ")
        return "<spp.ModesResult " + (report.rfind(prefix, 0) == 0 ? report.substr(prefix.size()) : report) + ">";
      });
  py::class_<md::ModesProgress>(m, "ModesProgress",
                                "What a running modes reports to its progress callback (modes(..., progress=f)).")
      .def_readonly("k", &md::ModesProgress::k, "impacts per period of the families being traced now")
      .def_readonly("k_last", &md::ModesProgress::k_last, "the largest k traced (every k from 1 to it is traced)")
      .def_readonly("families", &md::ModesProgress::families, "families found so far (every k traced)")
      .def_readonly("steps", &md::ModesProgress::steps, "family points tried so far")
      .def_readonly("seconds", &md::ModesProgress::seconds, "time since modes started")
      .def("line", &md::ModesProgress::line)
      .def("__repr__", [](const md::ModesProgress& p) { return "<spp.ModesProgress " + p.line() + ">"; });
  m.def(
      "modes",
      [](const spp::System& s, const py::object& k, const py::object& energy_max, const py::object& max_step,
         const py::object& branch_points, const py::object& multiples, const py::object& through_inadmissible,
         const py::object& progress, const py::object& seed_period_max, const py::object& cancel) {
        md::ModesOptions o;
        o.k_values = k_values(k);
        o.energy_max = scalar_argument<double>(energy_max, "spp.modes: argument energy_max");
        o.max_step = scalar_argument<double>(max_step, "spp.modes: argument max_step");
        o.branch_points = scalar_argument<bool>(branch_points, "spp.modes: argument branch_points");
        o.period_multiples = whole_in("multiples", multiples, 1, md::kMaxPeriodMultiples);
        o.through_inadmissible =
            scalar_argument<bool>(through_inadmissible, "spp.modes: argument through_inadmissible");
        o.seed_period_max = scalar_argument<double>(seed_period_max, "spp.modes: argument seed_period_max");
        o.validate();
        // Ctrl-C checked before each family point: stopped, the families traced so far are returned (status
        // incomplete, interrupted) with a RuntimeWarning, as solve does; the progress line or callable (solve's
        // ProgressHook) every 0.2 s, as solve reports (the callback runs per point); cancel=spp.Cancel() as Ctrl-C
        ProgressHook hook(progress, "modes", cancel);
        double last = -1.0;
        o.progress = [&hook, &last](const md::ModesProgress& p) {
          if (p.seconds - last < 0.2) return hook.keep_going();
          last = p.seconds;
          return hook(p);
        };
        md::ModesResult r;
        {
          py::gil_scoped_release release;
          r = md::nonsmooth_modes(s, o);
        }
        hook.finish();
        hook.warn(r.interrupted ? std::string("modes interrupted (Ctrl-C): the result holds the families traced before "
                                              "(status incomplete, interrupted True)")
                                : std::string("Ctrl-C came after modes had finished: the result is complete"));
        return r;
      },
      "system"_a, "k"_a, "energy_max"_a, "max_step"_a = 0.05, "branch_points"_a = true, "multiples"_a = 1,
      "through_inadmissible"_a = false, "progress"_a = py::none(), "seed_period_max"_a = 0.0, "cancel"_a = py::none(),
      ("k-IPP families (nonsmooth modes, e = 1, docs/modes.md): modes(system, k=[1, 2, 3], energy_max=5). k: the "
       "impacts per period, an int from 1 to 40 or a sequence of them (list, tuple, range(1, 4)); energy_max: a "
       "number > 0; multiples: J, an int from 1 to 100 (spp modes --multiples J): with k = 1, 1-IPP families also "
       "from each mode's grazing orbit seen with period j times its own, j = 2..J (1: none; docs/modes.md §3); "
       "through_inadmissible: follow each family through its inadmissible orbits to where it is admissible again "
       "(spp modes --through-inadmissible; a new family there, event admissibility_regained). progress=True prints "
       "the progress line on stderr (from 1 s on); progress=f calls f(ModesProgress) every 0.2 s (returning False "
       "stops the tracing, as Ctrl-C). seed_period_max: T > 0 also seeds families from the plane of their two "
       "flight durations, periods up to T (spp modes --seed-period-max; docs/modes.md §3). Ctrl-C or "
       "cancel=spp.Cancel() stops it: the families traced so far are returned (status incomplete, interrupted "
       "True) with a RuntimeWarning." +
       std::string(kThreadRule) +
       " Raises TypeError for another type (a bool, a float, a string such as '1..3', None) and ValueError for a "
       "value out of range.")
          .c_str());
}

}  // namespace spp::python
