// Python bindings, io/: result files read back; finite-element layout files (the C++ reader: one mechanism).
#include "spp/io.hpp"

#include <iomanip>
#include <sstream>

#include "common.hpp"
#include "spp/io/layout_file.hpp"

namespace spp::python {

py::object result_with_system(const std::string& path) {
  require_existing_file(path);
  spp::ResultFile file = spp::load_result_file(path);  // read and parsed once
  py::object result = py::cast(std::move(file.result));
  result.attr("system") = std::move(file.system);
  return result;
}

namespace {
// A layout from a path (str, os.PathLike) or the file's dict (its JSON text, through json.dumps), read by the C++
// reader (io/layout_file.hpp) and checked against `system` (check_fe_layout): its dofs unknown beforehand (a reduced
// model's layout names dofs of the full model).
spp::FeLayout layout_for(const py::object& source, const spp::System& system, const std::string& system_where) {
  const py::module_ os = py::module_::import("os");
  std::string where = "fe_layout";
  spp::FeLayout l;
  if (py::isinstance<py::str>(source) || py::isinstance(source, os.attr("PathLike"))) {
    const std::string path = py::str(os.attr("fspath")(source));
    require_existing_file(path);
    where = path;
    l = spp::read_fe_layout(path, -1);
  } else if (py::isinstance<py::dict>(source)) {
    std::string text;
    try {
      text = py::module_::import("json").attr("dumps")(source, "allow_nan"_a = false).cast<std::string>();
    } catch (const py::error_already_set& e) {
      if (!e.matches(PyExc_TypeError) && !e.matches(PyExc_ValueError)) throw;
      detail::invalid("fe_layout: expected a dict of JSON values (lists of numbers), got one that json cannot write: " +
                      py::str(e.value()).cast<std::string>());
    }
    l = spp::parse_fe_layout(text, where, -1);
  } else {
    detail::invalid("fe_layout: expected a layout (a path, or a dict with dofs, coordinates, directions), got " +
                    std::string(py::str(py::type::of(source).attr("__name__"))));
  }
  spp::check_fe_layout(l, system, where, system_where);
  return l;
}
}  // namespace

void bind_io(py::module_& m) {
  py::class_<spp::FeLayout>(
      m, "FeLayout",
      "A finite-element layout (include/spp/io/layout_file.hpp): dofs (0-based, of the full model), "
      "coordinates and directions (one row per dof, 1 to 3 columns), basis (one row per dof, the reduced model's "
      "dofs columns) or None, model_dofs (0: not given), fingerprint (of the reduced model, spp reduce --layout; None: "
      "not given). FeLayout.read(source, system): from a path or the file's dict, checked against the system it is "
      "drawn over.")
      .def_static(
          "read",
          [](const py::object& source, const spp::System& system, const std::string& system_where) {
            return layout_for(source, system, system_where);
          },
          "source"_a, "system"_a, "system_where"_a = "the system given",
          "The layout of `source` (a path or the file's dict) for `system`: ValueError naming the layout, "
          "`system_where` (e.g. the result file) and what does not match (dofs beyond the system's, basis columns "
          "other than its dofs, or the fingerprint of another reduced model).")
      .def(
          "check",
          [](const spp::FeLayout& l, const spp::System& system, const std::string& system_where) {
            spp::check_fe_layout(l, system, "fe_layout", system_where);
          },
          "system"_a, "system_where"_a = "the system given", "ValueError when the layout is not one of `system`.")
      .def_property_readonly("dofs",
                             [](const spp::FeLayout& l) {
                               return Eigen::Matrix<long, Eigen::Dynamic, 1>::Map(
                                          l.dofs.data(), static_cast<Eigen::Index>(l.dofs.size()))
                                   .eval();
                             })
      .def_readonly("coordinates", &spp::FeLayout::coordinates)
      .def_readonly("directions", &spp::FeLayout::directions)
      .def_property_readonly("basis",
                             [](const spp::FeLayout& l) -> py::object {
                               if (l.basis.size() == 0) return py::none();
                               return py::cast(l.basis);
                             })
      .def_readonly("model_dofs", &spp::FeLayout::model_dofs)
      .def_property_readonly("fingerprint", [](const spp::FeLayout& l) -> py::object {
        if (l.fingerprint.size() == 0) return py::none();
        return py::cast(l.fingerprint);
      });

  m.def("load_result", &result_with_system, "path"_a,
        "The SolveResult of a result file (spp solve --json, SolveResult.to_json), as C++'s spp::load_result, with its "
        "system as attribute system (the same as SolveResult.from_json). Raises ValueError naming the file and the "
        "field.");
}

}  // namespace spp::python
