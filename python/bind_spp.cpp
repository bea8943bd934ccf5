// pybind11 bindings: the C++ concepts under the same names. numpy arrays in and out (Eigen <-> numpy through
// pybind11/eigen.h); std::invalid_argument becomes ValueError with the C++ message.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <iomanip>
#include <optional>
#include <sstream>

#include "spp/continuation/continuation.hpp"
#include "spp/core/generators.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/root_map.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/simulator.hpp"
#include "spp/simulation/verify.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

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

// Result statuses and kinds as Python enums (spp._outcome.Outcome: str subclasses) whose members are the C++
// to_string names: one mechanism for every result enum, its members taken from C++ so that they cannot drift.
template <class E>
py::handle& outcome_class() {
  static py::handle cls;  // owned by the module (m.attr), never freed before it
  return cls;
}
template <class E>
void bind_outcome(py::module_& m, const char* name, std::initializer_list<E> values, const char* doc) {
  py::list members;
  for (const E v : values) members.append(py::make_tuple(spp::to_string(v), spp::to_string(v)));
  py::object cls = py::module_::import("spp._outcome").attr("Outcome")(name, members, "module"_a = "spp");
  cls.attr("__doc__") = doc;
  m.attr(name) = cls;
  outcome_class<E>() = cls;
}
template <class E>
py::object outcome(E v) {
  return outcome_class<E>()(spp::to_string(v));
}

// The options (or their defaults) with the keyword arguments set on them, field by field: one mechanism for every
// function that takes an Options struct. An unknown keyword is refused with the list of fields; the list is the bound
// attributes (not the dunders nor validate), so it cannot drift from the binding.
template <class Options>
Options with_fields(const py::object& options, const py::kwargs& fields, const char* where, const char* type_name) {
  py::object o = options.is_none() ? py::cast(Options{}) : py::cast(options.cast<Options>());
  std::vector<std::string> known;
  for (const py::handle a : py::module_::import("builtins").attr("dir")(o)) {
    const std::string n = py::str(a);
    if (n.rfind("_", 0) != 0 && n != "validate") known.push_back(n);
  }
  for (const auto& [key, value] : fields) {
    const std::string name = py::str(key);
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const std::string& n : known) list += (list.empty() ? "" : ", ") + n;
      throw std::invalid_argument(std::string(where) + ": unknown option \"" + name + "\" (" + type_name +
                                  " fields: " + list + ")");
    }
    py::setattr(o, key, value);
  }
  return o.cast<Options>();
}

// "<spp.Name field=value ...>" of the bound fields (those of with_fields), for the options' __repr__.
std::string fields_repr(const py::object& o, const char* type_name) {
  std::string out = std::string("<spp.") + type_name;
  for (const py::handle a : py::module_::import("builtins").attr("dir")(o)) {
    const std::string n = py::str(a);
    if (n.rfind("_", 0) == 0 || n == "validate") continue;
    out += " " + n + "=" + py::repr(o.attr(a)).cast<std::string>();
  }
  return out + ">";
}

// A complex array is refused, naming `what` (pybind11's conversion to double, and numpy's asarray(dtype=float64), keep
// the real part with a mere ComplexWarning: found by an independent review).
void require_real(const py::object& a, const std::string& what) {
  const py::module_ np = py::module_::import("numpy");
  if (np.attr("iscomplexobj")(a).cast<bool>())
    throw std::invalid_argument(what + " must be real, got a complex array (dtype " +
                                py::str(np.attr("asarray")(a).attr("dtype")).cast<std::string>() + ")");
}

}  // namespace

PYBIND11_MODULE(_spp, m) {
  m.doc() = "spp: periodic orbits with one lasting contact phase (SPPs) of vibro-impact systems";
  m.attr("__version__") = SPP_VERSION;
  bind_outcome(m, "SolveStatus", {spp::SolveStatus::NotRun, spp::SolveStatus::Success, spp::SolveStatus::Incomplete},
               "SolveResult.status (and NearestSpp.search_status): success (every check of completeness passed) or "
               "incomplete (SolveResult.uncertified says where and why)");
  bind_outcome(m, "SimulationStatus",
               {spp::SimulationStatus::NotRun, spp::SimulationStatus::Success, spp::SimulationStatus::EventLimit,
                spp::SimulationStatus::Stalled},
               "SimulationResult.status");
  bind_outcome(m, "EventKind", {spp::EventKind::Impact, spp::EventKind::ContactOnset, spp::EventKind::Release},
               "Event.kind");
  bind_outcome(m, "VerifyStatus", {spp::VerifyStatus::Success, spp::VerifyStatus::Inconsistent},
               "VerifyResult.status: inconsistent when a simulation disagrees with the solver's admissibility");
  bind_outcome(m, "Verdict", {spp::Verdict::Returns, spp::Verdict::Leaves}, "SppCheck.verdict");
  bind_outcome(m, "ContinuationStatus", {spp::ContinuationStatus::Success, spp::ContinuationStatus::Incomplete},
               "ContinuationResult.status");
  bind_outcome(m, "BranchEventKind",
               {spp::BranchEventKind::LeavesWindow, spp::BranchEventKind::RangeEnd, spp::BranchEventKind::Fold,
                spp::BranchEventKind::AdmissibilityLost, spp::BranchEventKind::AdmissibilityGained,
                spp::BranchEventKind::GapClosure, spp::BranchEventKind::ClosedLoop, spp::BranchEventKind::Stalled,
                spp::BranchEventKind::StabilityLost, spp::BranchEventKind::StabilityGained},
               "BranchEvent.kind");

  py::class_<spp::System>(m, "System", "M x'' + K x = w lambda, g = w^T x + g0 >= 0 (w stored unit-length)")
      .def(py::init([](const py::object& M, const py::object& K, const py::object& w, double g0,
                       const std::string& name) {
             // numpy arrays, nested lists, scipy.sparse matrices (densified: the solver is dense), and w as (n,),
             // (1, n) or (n, 1): each converted here, with the argument named when it cannot be
             const py::module_ np = py::module_::import("numpy");
             auto dense = [&](const py::object& a, const char* what) {
               py::object d = py::hasattr(a, "toarray") ? a.attr("toarray")() : a;
               require_real(d, std::string("System: ") + what);
               py::object arr;
               try {
                 arr = np.attr("asarray")(d, "dtype"_a = "float64");
               } catch (const py::error_already_set&) {
                 throw std::invalid_argument(std::string("System: ") + what + " must be an array of numbers");
               }
               return arr;
             };
             const py::object m = dense(M, "M"), k = dense(K, "K"), v = dense(w, "w");
             for (const auto& [arr, what] : {std::make_pair(m, "M"), std::make_pair(k, "K")})
               if (arr.attr("ndim").cast<int>() != 2)
                 throw std::invalid_argument(std::string("System: ") + what + " must be a square matrix, got shape " +
                                             py::str(arr.attr("shape")).cast<std::string>());
             const py::tuple shape = v.attr("shape").cast<py::tuple>();
             const bool vector_like =
                 shape.size() == 1 || (shape.size() == 2 && (shape[0].cast<long>() == 1 || shape[1].cast<long>() == 1));
             if (!vector_like)
               throw std::invalid_argument("System: w must be a vector, (n,), (1, n) or (n, 1), got shape " +
                                           py::str(py::object(shape)).cast<std::string>());
             return spp::System(m.cast<Eigen::MatrixXd>(), k.cast<Eigen::MatrixXd>(),
                                v.attr("ravel")().cast<Eigen::VectorXd>(), g0, name);
           }),
           "M"_a, "K"_a, "w"_a, "g0"_a, "name"_a = "",
           "M, K: (n, n) symmetric positive definite (numpy, lists or scipy.sparse); w: non-zero, (n,), (1, n) or "
           "(n, 1); g0: gap at rest. Raises ValueError.")
      .def_static("from_json", &spp::load_system, "path"_a, "Loads a system JSON file (M/K may be Matrix Market).")
      .def(py::pickle(  // (multiprocessing, joblib): the stored M, K, unit w and g0 rebuild the same system
          [](const spp::System& s) { return py::make_tuple(s.M(), s.K(), s.w(), s.g0(), s.name()); },
          [](const py::tuple& t) {
            if (t.size() != 5) throw std::invalid_argument("System pickle: expected (M, K, w, g0, name)");
            return spp::System(t[0].cast<Eigen::MatrixXd>(), t[1].cast<Eigen::MatrixXd>(), t[2].cast<Eigen::VectorXd>(),
                               t[3].cast<double>(), t[4].cast<std::string>());
          }))
      .def_property_readonly("n", &spp::System::n)
      .def_property_readonly("M", &spp::System::M, "(n, n) mass matrix")
      .def_property_readonly("K", &spp::System::K, "(n, n) stiffness matrix")
      .def_property_readonly("w", &spp::System::w, "(n,) unit contact direction")
      .def_property_readonly("g0", &spp::System::g0)
      .def_property_readonly("name", &spp::System::name)
      .def("gap", &spp::System::gap, "x"_a, "w^T x + g0 for x of shape (n,)")
      .def("contact_stiffness", &spp::System::contact_stiffness, "K~ of eq. (2.4), (n, n)")
      .def("__repr__",
           [](const spp::System& s) { return "<spp.System '" + s.name() + "' n=" + std::to_string(s.n()) + ">"; });

  m.def(
      "chain",
      [](int n, std::vector<double> masses, std::vector<double> stiffnesses, int contact_dof, bool upper, double g0) {
        return spp::chain(n, masses, stiffnesses, contact_dof < 0 ? n - 1 : contact_dof,
                          upper ? spp::ContactSide::Upper : spp::ContactSide::Lower, g0);
      },
      "n"_a, "masses"_a = std::vector<double>{1.0}, "stiffnesses"_a = std::vector<double>{1.0}, "contact_dof"_a = -1,
      "upper"_a = true, "g0"_a = 1.0,
      "Spring-mass chain fixed at one end (paper §5.2); contact_dof is 0-based (default: the last).");
  m.def("rod_with_slip", &spp::rod_with_slip, "a"_a = -0.25, "b"_a = 0.25,
        "4-dof finite-element rod with slip (paper §5.3), obstacle y = a x + b.");
  m.def("two_dof", &spp::two_dof, "m1"_a = 1.0, "m2"_a = 1.0, "k1"_a = 1.0, "k2"_a = 1.0, "g0"_a = 1.0,
        "2-dof system of paper §2.3.");

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
      .def_property_readonly("stable", &spp::Solution::stable, "admissible and spectral_radius < 1")
      .def_property_readonly(
          "x0", [](const spp::Solution& s) { return s.orbit.x0; }, "(n,) state at contact onset")
      .def_property_readonly(
          "v0", [](const spp::Solution& s) { return s.orbit.v0; }, "(n,)")
      .def("__repr__", [](const spp::Solution& s) {
        return "<spp.Solution t1=" + std::to_string(s.t1()) + " t2=" + std::to_string(s.t2()) +
               (s.admissible() ? " admissible>" : " not admissible>");
      });

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
          "to_json", [](const spp::SolveResult& r, const spp::System& s) { return spp::result_json(s, r, -1); },
          "system"_a, "The result JSON text, as spp solve --json writes it.")
      .def(
          "to_dataframe",
          [](const spp::SolveResult& r) {
            py::module_ pd;
            try {
              pd = py::module_::import("pandas");
            } catch (const py::error_already_set&) {
              throw py::import_error("to_dataframe needs pandas (Debian: apt-get install python3-pandas)");
            }
            py::list t1, t2, period, admissible, min_gap, min_force, energy, residual, return_error, flags;
            for (const spp::Solution& x : r.solutions) {
              t1.append(x.t1());
              t2.append(x.t2());
              period.append(x.period());
              admissible.append(x.admissible());
              min_gap.append(x.min_gap());
              min_force.append(x.min_force());
              energy.append(x.energy());
              residual.append(x.residual);
              return_error.append(x.return_error);
              std::string f;
              for (const std::string& s : x.flags) f += (f.empty() ? "" : ",") + s;
              flags.append(f);
            }
            return pd.attr("DataFrame")(
                py::dict("t1"_a = t1, "t2"_a = t2, "period"_a = period, "admissible"_a = admissible,
                         "min_gap"_a = min_gap, "min_force"_a = min_force, "energy"_a = energy, "residual"_a = residual,
                         "return_error"_a = return_error, "flags"_a = flags));
          },
          "One row per SPP (t1, t2, period, admissible, min_gap, min_force, energy, residual, return_error, flags), in "
          "the result's order (by period); needs pandas.")
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
              throw std::invalid_argument(
                  "SolveResult pickle: its attribute system must be the spp.System it was "
                  "solved for (results of solve() have it)");
            const spp::System sys = self.attr("system").cast<spp::System>();
            const spp::SolveResult& r = self.cast<const spp::SolveResult&>();
            for (const spp::Solution& x : r.solutions)
              if (x.orbit.x0.size() != sys.n())
                throw std::invalid_argument("SolveResult pickle: its system has n = " + std::to_string(sys.n()) +
                                            " dofs, its solutions " + std::to_string(x.orbit.x0.size()));
            return py::make_tuple(spp::result_json(sys, r, -1));
          },
          [](const py::tuple& state) {
            if (state.size() != 1) throw std::invalid_argument("SolveResult pickle: expected one field");
            const std::string text = state[0].cast<std::string>();
            py::dict attrs;
            attrs["system"] = spp::parse_result_system(text, "pickled SolveResult");
            return std::make_pair(spp::parse_result(text, "pickled SolveResult"), attrs);
          }))
      .def_static(
          "from_json",
          [](const std::string& path) {
            spp::System system = spp::load_result_system(path);
            py::object result = py::cast(spp::load_result(path));
            result.attr("system") = std::move(system);
            return result;
          },
          "path"_a,
          "The SolveResult of a result file (spp solve --json, SolveResult.to_json), with its system as attribute "
          "system: the status, solutions, stats, uncertified regions and warnings that were written. Raises "
          "ValueError naming the file and the field.");

  py::enum_<spp::Symmetry>(m, "Symmetry",
                           "Which equations: the SPPs (axial) or the point-symmetric potential SPPs "
                           "of det T2 = 0 (point, paper §6.2)")
      .value("axial", spp::Symmetry::Axial)
      .value("point", spp::Symmetry::Point);
  // The symmetry from the enum or its name ("axial", "point").
  auto symmetry_of = [](const py::object& v) {
    if (py::isinstance<spp::Symmetry>(v)) return v.cast<spp::Symmetry>();
    const std::string name = py::str(v);
    if (const std::optional<spp::Symmetry> s = spp::symmetry_named(name)) return *s;
    throw std::invalid_argument("symmetry must be Symmetry.axial, Symmetry.point, \"axial\" or \"point\", got \"" +
                                name + "\"");
  };
  py::class_<spp::SolveOptions>(m, "SolveOptions",
                                "Options of solve (the C++ SolveOptions, field by field; solve(system, options, "
                                "**fields) also takes any field as a keyword)")
      .def(py::init<>())
      .def_readwrite("t1_max", &spp::SolveOptions::t1_max, "upper end of the flight half-duration window (> 0)")
      .def_readwrite("t2_max", &spp::SolveOptions::t2_max, "upper end of the contact half-duration window (> 0)")
      .def_readwrite("t1_min", &spp::SolveOptions::t1_min, "lower end (0: from the axis)")
      .def_readwrite("t2_min", &spp::SolveOptions::t2_min, "lower end (0: from the axis)")
      .def_readwrite("max_cells", &spp::SolveOptions::max_cells, "refuse windows with more cells than this")
      .def_readwrite("certify_steps", &spp::SolveOptions::certify_steps,
                     "prove every trace step (default True: status success only if all are; False: the midpoint "
                     "check, 3-25x faster, a heuristic, so the status is incomplete)")
      .def_readwrite("pole_margin", &spp::SolveOptions::pole_margin)
      .def_readwrite("max_turn", &spp::SolveOptions::max_turn)
      .def_readwrite("min_step", &spp::SolveOptions::min_step)
      .def_readwrite("admissibility_tol", &spp::SolveOptions::admissibility_tol)
      .def_readwrite("admissible_only", &spp::SolveOptions::admissible_only)
      .def_readwrite("compute_return_error", &spp::SolveOptions::compute_return_error)
      .def_readwrite("compute_stability", &spp::SolveOptions::compute_stability)
      .def_readwrite("threads", &spp::SolveOptions::threads, "worker threads (0: all)")
      .def_property(
          "symmetry", [](const spp::SolveOptions& o) { return o.symmetry; },
          [symmetry_of](spp::SolveOptions& o, const py::object& v) { o.symmetry = symmetry_of(v); },
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
        // progress is not a SolveOptions field (a callable): taken out of the keywords first
        py::dict rest;
        py::object progress = py::none();
        for (const auto& [key, value] : fields) {
          if (py::str(key).cast<std::string>() == "progress")
            progress = py::reinterpret_borrow<py::object>(value);
          else
            rest[key] = value;
        }
        spp::SolveOptions o = solve_options(options, py::reinterpret_borrow<py::kwargs>(rest), "solve");
        o.validate();
        // a callable is called; anything else is taken for its truth (True, numpy.True_: the text line)
        const bool call = PyCallable_Check(progress.ptr()) != 0;
        auto truth = [](const py::object& v) {
          const int t = PyObject_IsTrue(v.ptr());
          if (t < 0) throw py::error_already_set();
          return t != 0;
        };
        const bool text = !call && truth(progress);
        bool interrupted = false, shown = false;
        // Called from this thread every 0.2 s (spp::SolveOptions::progress): Ctrl-C (KeyboardInterrupt) stops the
        // search and keeps what was found; the user's callable may stop it too (by returning False) or raise.
        o.progress = [&](const spp::SolveProgress& p) {
          const py::gil_scoped_acquire gil;
          if (PyErr_CheckSignals() != 0) {
            if (!PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) throw py::error_already_set();
            PyErr_Clear();
            interrupted = true;
            return false;
          }
          if (text && p.seconds >= 1.0) {
            py::module_::import("sys").attr("stderr").attr("write")("\r  " + p.line() + "   ");
            shown = true;
          }
          if (!call) return true;
          const py::object r = progress(p);
          return r.is_none() || truth(r);  // None continues; otherwise the value's truth
        };
        spp::SolveResult r;
        {
          py::gil_scoped_release release;
          r = spp::solve(s, o);
        }
        if (shown) py::module_::import("sys").attr("stderr").attr("write")("\n");
        // a Ctrl-C that came after the last report (while the roots were polished): the result is complete, so it
        // is returned, not lost to a KeyboardInterrupt at the next line
        bool late = false;
        if (PyErr_CheckSignals() != 0) {
          if (!PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) throw py::error_already_set();
          PyErr_Clear();
          late = !interrupted;
          interrupted = true;
        }
        const std::string message =
            late && r.stats.unsearched_cells == 0
                ? std::string("Ctrl-C came after the search had finished: the result is complete")
                : "solve interrupted (Ctrl-C): " + std::to_string(r.stats.unsearched_cells) +
                      " cell(s) not searched; the result holds what was found before (status incomplete)";
        if (interrupted && PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) < 0)
          throw py::error_already_set();  // warnings turned into errors
        py::object result = py::cast(std::move(r));
        result.attr("system") = s;
        return result;
      },
      "system"_a, "options"_a = py::none(),
      "Every SPP with t1 in (t1_min, t1_max], t2 in (t2_min, t2_max]: solve(system, t1_max=12, t2_max=12), or "
      "solve(system, SolveOptions) with any field also given as a keyword (symmetry=\"point\": the point-symmetric "
      "potential SPPs of paper §6.2; certify_steps=False: the faster midpoint check, a heuristic, status incomplete). "
      "progress=True prints the cells traced on "
      "stderr; progress=f calls f(SolveProgress) every 0.2 s (returning False stops the search). Ctrl-C stops it "
      "too: the result then holds what was found (status incomplete, stats['unsearched_cells'] > 0) and a "
      "RuntimeWarning says so. Raises ValueError.");

  m.def(
      "trajectory",
      [](const spp::System& s, double t1, double t2, int samples) {
        if (samples < 2)
          throw std::invalid_argument("trajectory: samples must be >= 2, got " + std::to_string(samples));
        const spp::ModalForm md(s);
        spp::SolveOptions o;
        o.compute_return_error = false;
        spp::Solution sol;
        {
          py::gil_scoped_release release;
          sol = spp::solution_at(s, md, t1, t2, o);
        }
        spp::OrbitSamples os = spp::sample_orbit(md, sol.orbit, samples);
        return py::dict("t"_a = std::move(os.t), "x"_a = std::move(os.x), "v"_a = std::move(os.v),
                        "gap"_a = std::move(os.gap), "force"_a = std::move(os.force), "t1"_a = sol.t1(), "t2"_a = sol.t2(),
                        "period"_a = sol.orbit.period(), "admissible"_a = sol.admissible());
      },
      "system"_a, "t1"_a, "t2"_a, "samples"_a = 1001,
      "One period of the SPP at (t1, t2) (polished there first), from its own equations, as spp trajectory writes it: "
      "dict of t (N,) from contact onset, x, v (N, n), gap, force (N,), and the polished t1, t2, period, "
      "admissible. Unlike simulate, it follows an inadmissible SPP too (the potential orbit, gap < 0 somewhere). "
      "Raises ValueError when no SPP is within 1e-3 (t1 + t2) of the point.");
  m.def(
      "monodromy",
      [](const spp::System& s, double t1, double t2) {
        const spp::ModalForm md(s);
        spp::SolveOptions o;
        o.compute_return_error = false;
        o.compute_stability = false;
        const spp::Solution sol = spp::solution_at(s, md, t1, t2, o);
        return py::make_tuple(spp::monodromy(md, sol.orbit), sol.orbit.x0, sol.orbit.v0, sol.period());
      },
      "system"_a, "t1"_a, "t2"_a,
      "The linearised one-period map of the SPP at (t1, t2) (polished there first) under Newton's impact law, e < 1: "
      "(Mono, x0, v0, period), Mono (2n, 2n) acting on (dx, dv) from just before the contact onset (x0, v0) "
      "(docs/stability.md). Raises ValueError when no SPP is within 1e-3 (t1 + t2) of the point.");
  m.def(
      "fundamental_box", [](const spp::System& s) { return spp::fundamental_box(spp::ModalForm(s)); }, "system"_a,
      "(t1_max, t2_max) of the fundamental box: t1 <= pi / omega_1 (slowest free-flight mode that sees the contact), "
      "t2 <= pi / d_1 (slowest contact-phase oscillation): t1, t2 = fundamental_box(s); solve(s, t1_max=t1, "
      "t2_max=t2).");
  m.def(
      "modal_frequencies",
      [](const spp::System& s) {
        const spp::ModalForm md(s);
        return py::dict("flight"_a = md.omega(), "contact"_a = md.d(), "decoupled"_a = md.omega_decoupled());
      },
      "system"_a,
      "The frequencies that place the pole lines of every window: flight (free-flight modes that see the contact, "
      "ascending; poles of tan at t1 = (k + 1/2) pi / omega), contact (contact-phase frequencies, the first 0: the "
      "constrained direction; poles at t2 = (k + 1/2) pi / d) and decoupled (modes that never see the contact).");

  py::class_<spp::NearestSpp>(m, "NearestSpp", "Result of nearest_spp: the SPP nearest to a guess")
      .def_readonly("found", &spp::NearestSpp::found)
      .def_readonly("solution", &spp::NearestSpp::solution)
      .def_property_readonly("search_status", [](const spp::NearestSpp& r) { return outcome(r.search_status); })
      .def_readonly("candidates", &spp::NearestSpp::candidates, "SPPs in the window searched")
      .def_property_readonly(
          "window", [](const spp::NearestSpp& r) { return py::make_tuple(r.t1_lo, r.t1_hi, r.t2_lo, r.t2_hi); });
  m.def(
      "nearest_spp",
      [solve_options](const spp::System& s, double t1, double t2, double radius, const py::object& options,
                      const py::kwargs& fields) {
        const spp::SolveOptions o = solve_options(options, fields, "nearest_spp");
        py::gil_scoped_release release;
        return spp::nearest_spp(s, t1, t2, radius, o);
      },
      "system"_a, "t1"_a, "t2"_a, "radius"_a = 0.05, "options"_a = py::none(),
      "The SPP nearest to a guess (t1, t2), e.g. read off the root map: the complete solver on the window "
      "(t1 (1 - radius), t1 (1 + radius)] x (t2 (1 - radius), t2 (1 + radius)], then the nearest root. "
      "found is False when that window holds none. Raises ValueError.");

  py::class_<spp::Event>(m, "Event")
      .def_readonly("t", &spp::Event::t)
      .def_property_readonly("kind", [](const spp::Event& e) { return outcome(e.kind); })
      .def_readonly("x", &spp::Event::x)
      .def_readonly("v_before", &spp::Event::v_before)
      .def_readonly("v_after", &spp::Event::v_after)
      .def_readonly("normal_velocity_before", &spp::Event::normal_velocity_before)
      .def_readonly("normal_velocity_after", &spp::Event::normal_velocity_after)
      .def_readonly("force", &spp::Event::force);

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
      .def("brief_report", &spp::SimulationResult::brief_report);

  py::class_<spp::SimulateOptions>(m, "SimulateOptions",
                                   "Options of simulate (the C++ SimulateOptions, field by field; simulate(system, x0, "
                                   "v0, duration, options=..., **fields) also takes any field as a keyword)")
      .def(py::init<>())
      .def_readwrite("duration", &spp::SimulateOptions::duration,
                     "simulated time T > 0; the last sample is at t = T exactly")
      .def_readwrite("restitution", &spp::SimulateOptions::restitution,
                     "Newton's coefficient e in [0, 1]: normal velocity after = -e * before")
      .def_readwrite("sample_times", &spp::SimulateOptions::sample_times,
                     "samples at these times (sorted, in [0, duration]); empty: samples_per_unit of simulate")
      .def_readwrite("sample_events", &spp::SimulateOptions::sample_events,
                     "add a sample with the state just after each event")
      .def_readwrite("max_events", &spp::SimulateOptions::max_events)
      .def_readwrite("event_rel_tol", &spp::SimulateOptions::event_rel_tol,
                     "excursions below zero shallower than this (relative to the phase's amplitude) are not events")
      .def_readwrite("rest_velocity_rel_tol", &spp::SimulateOptions::rest_velocity_rel_tol,
                     "impacts slower than this (relative) are plastic: where chattering ends in lasting contact")
      .def("validate", &spp::SimulateOptions::validate, "Raises ValueError naming the first invalid field.")
      .def("__repr__", [](const py::object& o) { return fields_repr(o, "SimulateOptions"); });
  m.def(
      "simulate",
      [](const spp::System& s, const Eigen::VectorXd& x0, const Eigen::VectorXd& v0, std::optional<double> duration,
         std::optional<double> restitution, double samples_per_unit, const py::object& options,
         const py::kwargs& fields) {
        spp::SimulateOptions o = with_fields<spp::SimulateOptions>(options, fields, "simulate", "SimulateOptions");
        if (duration) o.duration = *duration;
        if (restitution) o.restitution = *restitution;
        o.validate();
        if (!(samples_per_unit > 0.0))
          throw std::invalid_argument("simulate: samples_per_unit must be > 0, got " +
                                      std::to_string(samples_per_unit));
        if (o.sample_times.empty()) o.sample_times = spp::uniform_times(o.duration, samples_per_unit);
        py::gil_scoped_release release;
        return spp::simulate(s, x0, v0, o);
      },
      "system"_a, "x0"_a, "v0"_a, "duration"_a = py::none(), "restitution"_a = py::none(), "samples_per_unit"_a = 100.0,
      "options"_a = py::none(),
      "Exact event-driven simulation from (x0, v0), shapes (n,): simulate(system, x0, v0, duration, restitution=0, "
      "samples_per_unit=100), or with a SimulateOptions and any field also as a keyword (sample_times=[...] replaces "
      "the uniform samples). Raises ValueError.");

  m.def(
      "load_result",
      [](const std::string& path) {
        spp::System system = spp::load_result_system(path);
        py::object result = py::cast(spp::load_result(path));
        result.attr("system") = std::move(system);
        return result;
      },
      "path"_a,
      "The SolveResult of a result file (spp solve --json, SolveResult.to_json), as C++'s spp::load_result, with its "
      "system as attribute system (the same as SolveResult.from_json). Raises ValueError naming the file and the "
      "field.");

  py::class_<spp::RootMapCell>(m, "RootMapCell", "One rectangle between pole lines, sampled on its own grid")
      .def_readonly("t1", &spp::RootMapCell::t1, "(n1,) ascending")
      .def_readonly("t2", &spp::RootMapCell::t2, "(n2,) ascending")
      .def_readonly("symmetric", &spp::RootMapCell::symmetric,
                    "(n2, n1) sign(det H) min|eig H|: its zero curves are eq. (5.1a)")
      .def_readonly("onset", &spp::RootMapCell::onset,
                    "(n2, n1) the same for P^T H P on z-perp: its zero curves are eq. (5.1b)");
  py::class_<spp::RootMap>(m, "RootMap")
      .def_readonly("flight_poles", &spp::RootMap::flight_poles, "pole lines t1 = (k + 1/2) pi / omega_i")
      .def_readonly("contact_poles", &spp::RootMap::contact_poles, "pole lines t2 = (k + 1/2) pi / d_j")
      .def_readonly("cells", &spp::RootMap::cells)
      .def_readonly("evaluations", &spp::RootMap::evaluations);
  py::class_<spp::RootMapOptions>(m, "RootMapOptions",
                                  "Options of root_map (the C++ RootMapOptions, field by field; root_map(system, "
                                  "t1_max, t2_max, options, **fields) also takes any field as a keyword)")
      .def(py::init<>())
      .def_readwrite("t1_min", &spp::RootMapOptions::t1_min, "lower end of the window in t1 (>= 0)")
      .def_readwrite("t1_max", &spp::RootMapOptions::t1_max, "upper end of the window in t1 (> t1_min)")
      .def_readwrite("t2_min", &spp::RootMapOptions::t2_min, "lower end of the window in t2 (>= 0)")
      .def_readwrite("t2_max", &spp::RootMapOptions::t2_max, "upper end of the window in t2 (> t2_min)")
      .def_readwrite("t1_points", &spp::RootMapOptions::t1_points, "grid points across the window along t1 (>= 16)")
      .def_readwrite("t2_points", &spp::RootMapOptions::t2_points, "grid points across the window along t2 (>= 16)")
      .def_readwrite("min_cell_points", &spp::RootMapOptions::min_cell_points,
                     "at least this many points per cell and axis (>= 2)")
      .def_readwrite("pole_margin", &spp::RootMapOptions::pole_margin,
                     "distance kept from pole lines, relative to the cell width (in [0, 0.25))")
      .def("validate", &spp::RootMapOptions::validate, "Raises ValueError naming the first invalid field.")
      .def("__repr__", [](const py::object& o) { return fields_repr(o, "RootMapOptions"); });
  m.def(
      "root_map",
      [](const spp::System& s, std::optional<double> t1_max, std::optional<double> t2_max, const py::object& options,
         const py::kwargs& fields) {
        spp::RootMapOptions o = with_fields<spp::RootMapOptions>(options, fields, "root_map", "RootMapOptions");
        if (t1_max) o.t1_max = *t1_max;
        if (t2_max) o.t2_max = *t2_max;
        o.validate();
        py::gil_scoped_release release;
        return spp::root_map(s, o);
      },
      "system"_a, "t1_max"_a = py::none(), "t2_max"_a = py::none(), "options"_a = py::none(),
      "Both conditions of the SPP equations sampled cell by cell over the window (root maps, Fig. 4): "
      "root_map(system, t1_max, t2_max, t1_points=400, ...) or root_map(system, options=RootMapOptions) with any "
      "field also as a keyword. Raises ValueError.");

  py::class_<spp::ParametricSystem>(m, "ParametricSystem",
                                    "M(mu) = M_constant + mu M_mu, K(mu) likewise, w(mu) likewise, g0 fixed")
      .def(py::init([](const py::object& M0, const py::object& M1, const py::object& K0, const py::object& K1,
                       const py::object& w0, const py::object& w1, double g0, const std::string& name, double lo,
                       double hi, const std::string& label) {
             const std::pair<const py::object*, const char*> parts[] = {{&M0, "M_constant"}, {&M1, "M_mu"},
                                                                        {&K0, "K_constant"}, {&K1, "K_mu"},
                                                                        {&w0, "w_constant"}, {&w1, "w_mu"}};
             for (const auto& [a, what] : parts) require_real(*a, std::string("ParametricSystem: ") + what);
             auto as = [](const py::object& a, const char* what, auto shape) {
               try {
                 return a.cast<decltype(shape)>();
               } catch (const py::cast_error&) {
                 throw std::invalid_argument(std::string("ParametricSystem: ") + what +
                                             " must be an array of numbers, got " +
                                             py::str(py::type::of(a)).cast<std::string>());
               }
             };
             return spp::ParametricSystem(as(M0, "M_constant", Eigen::MatrixXd()), as(M1, "M_mu", Eigen::MatrixXd()),
                                          as(K0, "K_constant", Eigen::MatrixXd()), as(K1, "K_mu", Eigen::MatrixXd()),
                                          as(w0, "w_constant", Eigen::VectorXd()), as(w1, "w_mu", Eigen::VectorXd()),
                                          g0, {name, lo, hi}, label);
           }),
           "M_constant"_a, "M_mu"_a, "K_constant"_a, "K_mu"_a, "w_constant"_a, "w_mu"_a, "g0"_a, "parameter"_a, "min"_a,
           "max"_a, "name"_a = "",
           "(n, n) parts (an empty (0, 0) array: does not depend on the parameter); raises ValueError.")
      .def_static("from_json", &spp::load_parametric_system, "path"_a, "Loads a system file with \"parameter\".")
      .def("at", &spp::ParametricSystem::at, "mu"_a, "The System at this parameter value.")
      .def_property_readonly("n", &spp::ParametricSystem::n)
      .def_property_readonly("g0", &spp::ParametricSystem::g0)
      .def_property_readonly("parameter", [](const spp::ParametricSystem& s) { return s.parameter().name; })
      .def_property_readonly(
          "range", [](const spp::ParametricSystem& s) { return py::make_tuple(s.parameter().min, s.parameter().max); });
  py::class_<spp::BranchPoint>(m, "BranchPoint")
      .def_readonly("mu", &spp::BranchPoint::mu)
      .def_readonly("t1", &spp::BranchPoint::t1)
      .def_readonly("t2", &spp::BranchPoint::t2)
      .def_readonly("period", &spp::BranchPoint::period)
      .def_readonly("admissible", &spp::BranchPoint::admissible)
      .def_readonly("margin", &spp::BranchPoint::margin, "admissibility margin (NaN where meaningless)")
      .def_readonly("spectral_radius", &spp::BranchPoint::spectral_radius,
                    "largest |Floquet multiplier| but the two structural 1s (NaN where not computed)")
      .def_readonly("closure", &spp::BranchPoint::closure)
      .def_readonly("energy", &spp::BranchPoint::energy)
      .def_readonly("x0", &spp::BranchPoint::x0)
      .def_readonly("v0", &spp::BranchPoint::v0);
  py::class_<spp::BranchEvent>(m, "BranchEvent")
      .def_property_readonly("kind", [](const spp::BranchEvent& e) { return outcome(e.kind); })
      .def_readonly("at", &spp::BranchEvent::at)
      .def_readonly("detail", &spp::BranchEvent::detail);
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
          "(N, 4): mu, t1, t2, margin of every point");
  py::class_<spp::ContinuationResult>(m, "ContinuationResult")
      .def_property_readonly("status", [](const spp::ContinuationResult& r) { return outcome(r.status); })
      .def_readonly("incomplete_seed_solves", &spp::ContinuationResult::incomplete_seed_solves)
      .def_readonly("stalled_branches", &spp::ContinuationResult::stalled_branches)
      .def_readonly("unlisted_crossings", &spp::ContinuationResult::unlisted_crossings)
      .def_readonly("branches", &spp::ContinuationResult::branches)
      .def_readonly("warnings", &spp::ContinuationResult::warnings)
      .def("brief_report", &spp::ContinuationResult::brief_report)
      .def(
          "gap_closures", [](const spp::ContinuationResult& r) { return spp::gap_closures(r); },
          "GapClosure events sorted by mu: with g0 = 0, the SPPs of paper §6.1");
  py::class_<spp::ContinueOptions>(m, "ContinueOptions",
                                   "Options of continue_branches (the C++ ContinueOptions, field by field; "
                                   "continue_branches(system, t1_max, t2_max, options, **fields) also takes any field "
                                   "as a keyword)")
      .def(py::init<>())
      .def_readwrite("t1_max", &spp::ContinueOptions::t1_max, "upper end of the window in t1 (> 0)")
      .def_readwrite("t2_max", &spp::ContinueOptions::t2_max, "upper end of the window in t2 (> 0)")
      .def_readwrite("t1_min", &spp::ContinueOptions::t1_min, "lower end (0: as solve)")
      .def_readwrite("t2_min", &spp::ContinueOptions::t2_min, "lower end (0: as solve)")
      .def_readwrite("seeds", &spp::ContinueOptions::seeds,
                     "parameter values (min, max and evenly between) where solve seeds branches")
      .def_readwrite("max_step", &spp::ContinueOptions::max_step,
                     "largest step, in arclength of (t1/t1_max, t2/t2_max, mu/(max - min))")
      .def_readwrite("min_step", &spp::ContinueOptions::min_step,
                     "a branch whose step falls below this stops with a \"stalled\" event")
      .def_readwrite("max_turn", &spp::ContinueOptions::max_turn, "largest angle (rad) between successive tangents")
      .def_readwrite("max_points", &spp::ContinueOptions::max_points, "per branch and direction")
      .def_readwrite("locate_tol", &spp::ContinueOptions::locate_tol,
                     "events located to this, in the same scaled arclength")
      .def_readwrite("threads", &spp::ContinueOptions::threads, "for the seeding solves (0: all)")
      .def_property(
          "symmetry", [](const spp::ContinueOptions& o) { return o.symmetry; },
          [symmetry_of](spp::ContinueOptions& o, const py::object& v) { o.symmetry = symmetry_of(v); },
          "Symmetry.axial (default) or Symmetry.point (or their names)")
      .def("validate", &spp::ContinueOptions::validate, "Raises ValueError naming the first invalid field.")
      .def("__repr__", [](const py::object& o) { return fields_repr(o, "ContinueOptions"); });
  m.def(
      "continue_branches",
      [](const spp::ParametricSystem& s, std::optional<double> t1_max, std::optional<double> t2_max,
         const py::object& options, const py::kwargs& fields) {
        spp::ContinueOptions o =
            with_fields<spp::ContinueOptions>(options, fields, "continue_branches", "ContinueOptions");
        if (t1_max) o.t1_max = *t1_max;
        if (t2_max) o.t2_max = *t2_max;
        o.validate();
        py::gil_scoped_release release;
        return spp::continue_branches(s, o);
      },
      "system"_a, "t1_max"_a = py::none(), "t2_max"_a = py::none(), "options"_a = py::none(),
      "Every SPP of the window followed over the parameter's range: continue_branches(system, t1_max=3, t2_max=1, "
      "seeds=9, ...), or with a ContinueOptions and any field also as a keyword. Raises ValueError.");

  py::class_<spp::SppCheck>(m, "SppCheck")
      .def_property_readonly("t1", [](const spp::SppCheck& c) { return c.spp.t1(); })
      .def_property_readonly("t2", [](const spp::SppCheck& c) { return c.spp.t2(); })
      .def_property_readonly("admissible", [](const spp::SppCheck& c) { return c.spp.admissible(); })
      .def_property_readonly("verdict", [](const spp::SppCheck& c) { return outcome(c.verdict); })
      .def_readonly("consistent", &spp::SppCheck::consistent)
      .def_readonly("return_errors", &spp::SppCheck::return_errors)
      .def_readonly("periods_followed", &spp::SppCheck::periods_followed)
      .def_readonly("departure_time", &spp::SppCheck::departure_time)
      .def_readonly("departure", &spp::SppCheck::departure)
      .def_readonly("perturbed_distances", &spp::SppCheck::perturbed_distances)
      .def_readonly("growth_per_period", &spp::SppCheck::growth_per_period);

  py::class_<spp::VerifyResult>(m, "VerifyResult")
      .def_property_readonly("status", [](const spp::VerifyResult& r) { return outcome(r.status); })
      .def_readonly("checks", &spp::VerifyResult::checks)
      .def_readonly("returned", &spp::VerifyResult::returned)
      .def_readonly("left", &spp::VerifyResult::left)
      .def_readonly("inconsistent", &spp::VerifyResult::inconsistent)
      .def("all_consistent", &spp::VerifyResult::all_consistent)
      .def("brief_report", &spp::VerifyResult::brief_report);

  py::class_<spp::VerifyOptions>(m, "VerifyOptions",
                                 "Options of verify (the C++ VerifyOptions, field by field; verify(system, result, "
                                 "options, **fields) also takes any field as a keyword)")
      .def(py::init<>())
      .def_readwrite("periods", &spp::VerifyOptions::periods, "simulated periods (>= 1)")
      .def_readwrite("perturbation", &spp::VerifyOptions::perturbation,
                     "relative size of the perturbation of the mid-flight state; 0: none")
      .def_readwrite("restitution", &spp::VerifyOptions::restitution,
                     "Newton's e for the simulations (matters only once the orbit is left)")
      .def_readwrite("return_tol", &spp::VerifyOptions::return_tol,
                     "an admissible SPP must come back to this relative error after one period")
      .def_readwrite("follow_tol", &spp::VerifyOptions::follow_tol,
                     "later periods count as followed while the return error stays below this")
      .def_readwrite("event_time_tol", &spp::VerifyOptions::event_time_tol,
                     "relative to the period: events within it of the expected times match")
      .def("validate", &spp::VerifyOptions::validate, "Raises ValueError naming the first invalid field.")
      .def("__repr__", [](const py::object& o) { return fields_repr(o, "VerifyOptions"); });
  m.def(
      "verify",
      [](const spp::System& s, const spp::SolveResult& r, const py::object& options, const py::kwargs& fields) {
        const spp::VerifyOptions o = with_fields<spp::VerifyOptions>(options, fields, "verify", "VerifyOptions");
        o.validate();
        py::gil_scoped_release release;
        return spp::verify(s, r.solutions, o);
      },
      "system"_a, "result"_a, "options"_a = py::none(),
      "Re-simulates every solution of a solve() result: verify(system, result, periods=3, perturbation=1e-6, ...), "
      "or with a VerifyOptions and any field also as a keyword. Raises ValueError.");
}
