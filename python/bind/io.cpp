// Python bindings, io/: result files read back.
#include "spp/io.hpp"

#include <iomanip>
#include <sstream>

#include "common.hpp"

namespace spp::python {

py::object result_with_system(const std::string& path) {
  require_existing_file(path);
  spp::ResultFile file = spp::load_result_file(path);  // read and parsed once
  py::object result = py::cast(std::move(file.result));
  result.attr("system") = std::move(file.system);
  return result;
}

void bind_io(py::module_& m) {
  m.def("load_result", &result_with_system, "path"_a,
        "The SolveResult of a result file (spp solve --json, SolveResult.to_json), as C++'s spp::load_result, with its "
        "system as attribute system (the same as SolveResult.from_json). Raises ValueError naming the file and the "
        "field.");
}

}  // namespace spp::python
