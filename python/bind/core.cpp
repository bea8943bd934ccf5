// Python bindings, core/: System, the generators of the paper's examples, ParametricSystem.
#include <iomanip>
#include <sstream>

#include "common.hpp"
#include "spp/core/generators.hpp"
#include "spp/core/parametric.hpp"
#include "spp/core/system.hpp"
#include "spp/io.hpp"
#include "spp/detail/invalid.hpp"

namespace spp::python {

void bind_core(py::module_& m) {
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
                 detail::invalid(std::string("System: ") + what + " must be an array of numbers");
               }
               return arr;
             };
             const py::object m = dense(M, "M"), k = dense(K, "K"), v = dense(w, "w");
             for (const auto& [arr, what] : {std::make_pair(m, "M"), std::make_pair(k, "K")})
               if (arr.attr("ndim").cast<int>() != 2)
                 detail::invalid(std::string("System: ") + what + " must be a square matrix, got shape " +
                                             py::str(arr.attr("shape")).cast<std::string>());
             const py::tuple shape = v.attr("shape").cast<py::tuple>();
             const bool vector_like =
                 shape.size() == 1 || (shape.size() == 2 && (shape[0].cast<long>() == 1 || shape[1].cast<long>() == 1));
             if (!vector_like)
               detail::invalid("System: w must be a vector, (n,), (1, n) or (n, 1), got shape " +
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
                 detail::invalid(std::string("ParametricSystem: ") + what +
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
}

}  // namespace spp::python
