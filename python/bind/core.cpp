// Python bindings, core/: System, the generators of the paper's examples, ParametricSystem.
#include <iomanip>
#include <sstream>

#include "common.hpp"
#include "spp/core/generators.hpp"
#include "spp/core/parametric.hpp"
#include "spp/core/system.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/io.hpp"

namespace spp::python {

void bind_core(py::module_& m) {
  // (bound here, first: every long call takes it, cancel=)
  py::class_<Cancel>(m, "Cancel",
                     (std::string("A cancel token for a long call (solve, nearest_spp, root_map, continue_branches, "
                                  "continue_branch, verify, modes, trajectory, simulate): c = spp.Cancel(); pass "
                                  "cancel=c; c.cancel() from any thread stops the run where Ctrl-C would, and it "
                                  "returns what it has done, as after Ctrl-C, with a RuntimeWarning saying "
                                  "'(cancelled)'. A cancelled token stops every later run given it at once, until "
                                  "reset().") +
                      kThreadRule)
                         .c_str())
      .def(py::init<>())
      .def(
          "cancel", [](const Cancel& c) { c.flag->store(true); },
          "Stop the runs given this token (safe from any thread; they stop at their next check, within a second).")
      .def(
          "reset", [](const Cancel& c) { c.flag->store(false); }, "Clear the token, for another run.")
      .def_property_readonly(
          "cancelled", [](const Cancel& c) { return c.flag->load(); }, "whether cancel() was called (since reset())")
      .def("__repr__", [](const Cancel& c) {
        return std::string("<spp.Cancel ") + (c.flag->load() ? "cancelled" : "not cancelled") + ">";
      });
  py::class_<spp::System>(m, "System", "M x'' + K x = w lambda, g = w^T x + g0 >= 0 (w stored unit-length)")
      .def(py::init([](const py::object& M, const py::object& K, const py::object& w, const py::object& g0,
                       const std::string& name) {
             // (python/bind/common.hpp: numpy, lists, scipy.sparse; w as (n,), (1, n) or (n, 1))
             return spp::System(matrix_input(M, "System: M"), matrix_input(K, "System: K"),
                                vector_input(w, "System: w"), scalar_argument<double>(g0, "spp.System: argument g0"),
                                name);
           }),
           "M"_a, "K"_a, "w"_a, "g0"_a, "name"_a = "",
           "M, K: (n, n) symmetric positive definite (numpy, lists or scipy.sparse); w: non-zero, (n,), (1, n) or "
           "(n, 1); g0: gap at rest. Raises ValueError.")
      .def_static(
          "from_json",
          [](const std::string& path) {
            require_existing_file(path);
            return spp::load_system(path);
          },
          "path"_a, "Loads a system JSON file (M/K may be Matrix Market).")
      .def(py::pickle(  // (multiprocessing, joblib): the stored M, K, unit w and g0 rebuild the same system
          [](const spp::System& s) { return py::make_tuple(s.M(), s.K(), s.w(), s.g0(), s.name()); },
          [](const py::tuple& t) {
            if (t.size() != 5) detail::invalid("System pickle: expected (M, K, w, g0, name)");
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
      [](int n, const py::object& masses, const py::object& stiffnesses, int contact_dof, bool upper,
         const py::object& g0_arg) {
        const double g0 = scalar_argument<double>(g0_arg, "spp.chain: argument g0");
        // checked here, 0-based as the docstring says (the C++ message is the CLI's, 1-based: "in [1, 5], got 6"
        // for contact_dof=5 confused; found by an independent attack)
        if (n >= 1 && (contact_dof < -1 || contact_dof >= n))
          detail::invalid("chain: contact_dof (0-based) must be in [0, " + std::to_string(n - 1) +
                          "] or -1 (the last), got " + std::to_string(contact_dof));
        // (a ragged or 2-D list named with the shape expected, not pybind11's cast failure)
        return spp::chain(n, vector_of_numbers(masses, "chain: masses"),
                          vector_of_numbers(stiffnesses, "chain: stiffnesses"), contact_dof < 0 ? n - 1 : contact_dof,
                          upper ? spp::ContactSide::Upper : spp::ContactSide::Lower, g0);
      },
      "n"_a, "masses"_a = py::cast(std::vector<double>{1.0}), "stiffnesses"_a = py::cast(std::vector<double>{1.0}),
      "contact_dof"_a = -1, "upper"_a = true, "g0"_a = 1.0,
      "Spring-mass chain fixed at one end (paper §5.2); contact_dof is 0-based (default: the last).");
  m.def(
      "rod_with_slip",
      [](const py::object& a, const py::object& b) {
        return spp::rod_with_slip(scalar_argument<double>(a, "spp.rod_with_slip: argument a"),
                                  scalar_argument<double>(b, "spp.rod_with_slip: argument b"));
      },
      "a"_a = -0.25, "b"_a = 0.25, "4-dof finite-element rod with slip (paper §5.3), obstacle y = a x + b.");
  m.def(
      "two_dof",
      [](const py::object& m1, const py::object& m2, const py::object& k1, const py::object& k2, const py::object& g0) {
        return spp::two_dof(scalar_argument<double>(m1, "spp.two_dof: argument m1"),
                            scalar_argument<double>(m2, "spp.two_dof: argument m2"),
                            scalar_argument<double>(k1, "spp.two_dof: argument k1"),
                            scalar_argument<double>(k2, "spp.two_dof: argument k2"),
                            scalar_argument<double>(g0, "spp.two_dof: argument g0"));
      },
      "m1"_a = 1.0, "m2"_a = 1.0, "k1"_a = 1.0, "k2"_a = 1.0, "g0"_a = 1.0, "2-dof system of paper §2.3.");

  py::class_<spp::ParametricSystem>(m, "ParametricSystem",
                                    "M(mu) = M_constant + mu M_mu, K(mu) likewise, w(mu) likewise, g0 fixed")
      .def(py::init([](const py::object& M0, const py::object& M1, const py::object& K0, const py::object& K1,
                       const py::object& w0, const py::object& w1, const py::object& g0, const std::string& name,
                       const py::object& lo, const py::object& hi, const std::string& label) {
             // the same conversion as System's (scipy.sparse, lists, w as a row or column): ParametricSystem refused
             // what System accepts (found by an independent attack); an empty mu part: independent of mu
             const std::string p = "ParametricSystem: ";
             return spp::ParametricSystem(matrix_input(M0, p + "M_constant"), matrix_input(M1, p + "M_mu", true),
                                          matrix_input(K0, p + "K_constant"), matrix_input(K1, p + "K_mu", true),
                                          vector_input(w0, p + "w_constant"), vector_input(w1, p + "w_mu", true),
                                          scalar_argument<double>(g0, "spp.ParametricSystem: argument g0"),
                                          {name, scalar_argument<double>(lo, "spp.ParametricSystem: argument min"),
                                           scalar_argument<double>(hi, "spp.ParametricSystem: argument max")},
                                          label);
           }),
           "M_constant"_a, "M_mu"_a, "K_constant"_a, "K_mu"_a, "w_constant"_a, "w_mu"_a, "g0"_a, "parameter"_a, "min"_a,
           "max"_a, "name"_a = "",
           "(n, n) parts as System takes them (numpy, lists or scipy.sparse; w parts (n,), (1, n) or (n, 1)); an empty "
           "M_mu, K_mu or w_mu (e.g. np.empty((0, 0))): does not depend on the parameter. Raises ValueError.")
      .def_static(
          "from_json",
          [](const std::string& path) {
            require_existing_file(path);
            return spp::load_parametric_system(path);
          },
          "path"_a, "Loads a system file with \"parameter\".")
      .def(
          "at",
          [](const spp::ParametricSystem& s, const py::object& mu_arg) {
            // a number (ps.at(True) was taken as 1); outside the declared range a RuntimeWarning (it was silent):
            // the system there is validated, but the range is where the file's author vouched for the model
            const double mu = scalar_argument<double>(mu_arg, "spp.ParametricSystem.at: argument mu");
            const spp::Parameter& p = s.parameter();
            if (std::isfinite(mu) && !(mu >= p.min && mu <= p.max)) {
              std::ostringstream os;
              os << std::setprecision(17) << "ParametricSystem.at: " << p.name << " = " << mu
                 << " lies outside the declared range [" << p.min << ", " << p.max
                 << "]: the system there is built and validated, but the range is where the model was declared";
              if (PyErr_WarnEx(PyExc_RuntimeWarning, os.str().c_str(), 1) < 0) throw py::error_already_set();
            }
            return s.at(mu);
          },
          "mu"_a,
          "The System at this parameter value (a RuntimeWarning outside the declared range). Raises ValueError.")
      .def_property_readonly("n", &spp::ParametricSystem::n)
      .def_property_readonly("g0", &spp::ParametricSystem::g0)
      .def_property_readonly("parameter", [](const spp::ParametricSystem& s) { return s.parameter().name; })
      .def_property_readonly(
          "range", [](const spp::ParametricSystem& s) { return py::make_tuple(s.parameter().min, s.parameter().max); })
      .def_property_readonly("name", &spp::ParametricSystem::name)
      .def(py::pickle(  // its parts, as the constructor takes them
          [](const spp::ParametricSystem& s) {
            return py::make_tuple(s.M_constant(), s.M_mu(), s.K_constant(), s.K_mu(), s.w_constant(), s.w_mu(), s.g0(),
                                  s.parameter().name, s.parameter().min, s.parameter().max, s.name());
          },
          [](const py::tuple& t) {
            if (t.size() != 11) detail::invalid("ParametricSystem pickle: expected 11 fields");
            return spp::ParametricSystem(
                t[0].cast<Eigen::MatrixXd>(), t[1].cast<Eigen::MatrixXd>(), t[2].cast<Eigen::MatrixXd>(),
                t[3].cast<Eigen::MatrixXd>(), t[4].cast<Eigen::VectorXd>(), t[5].cast<Eigen::VectorXd>(),
                t[6].cast<double>(), {t[7].cast<std::string>(), t[8].cast<double>(), t[9].cast<double>()},
                t[10].cast<std::string>());
          }))
      .def("__repr__", [](const spp::ParametricSystem& s) {
        std::ostringstream os;
        os << "<spp.ParametricSystem '" << s.name() << "' n=" << s.n() << ", " << s.parameter().name << " in ["
           << s.parameter().min << ", " << s.parameter().max << "]>";
        return os.str();
      });
}

}  // namespace spp::python
