// The _spp extension module: one binding file per area of the library (python/bind/<area>.cpp), the C++ concepts under
// the same names. numpy arrays in and out (Eigen <-> numpy through pybind11/eigen.h); std::invalid_argument becomes
// ValueError with the C++ message (decoded with backslashreplace: never lost).
#include "common.hpp"

namespace {

// Every C++ exception as pybind11 maps it (std::invalid_argument: ValueError, std::bad_alloc: MemoryError, ...), its
// message decoded with backslashreplace: pybind11 decodes what() as strict UTF-8, and a message holding a byte that is
// not (a Latin-1 file name, a Matrix Market line with \xff) became an empty ValueError(), file and field lost (found
// by an independent attack). io::shorten escapes such bytes at the source; this keeps any other message whole.
void translate_keeping_the_message(std::exception_ptr p) {
  namespace py = pybind11;
  if (!p) return;
  try {
    std::rethrow_exception(p);
  } catch (py::error_already_set&) {
    throw;  // (a Python exception already: pybind11 restores it)
  } catch (const std::exception& e) {
    py::detail::translate_exception(p);
    const std::string what = e.what();
    if (what.empty() || !PyErr_Occurred()) return;
    PyObject *type = nullptr, *value = nullptr, *trace = nullptr;
    PyErr_Fetch(&type, &value, &trace);
    PyErr_NormalizeException(&type, &value, &trace);
    PyObject* args = value != nullptr ? PyObject_GetAttrString(value, "args") : nullptr;
    const bool lost = args != nullptr && PyTuple_Check(args) && PyTuple_Size(args) == 0;
    Py_XDECREF(args);
    if (!lost) {
      PyErr_Restore(type, value, trace);
      return;
    }
    Py_XDECREF(value);
    Py_XDECREF(trace);
    PyObject* text = PyUnicode_DecodeUTF8(what.data(), static_cast<Py_ssize_t>(what.size()), "backslashreplace");
    if (text == nullptr) {  // (backslashreplace decodes any bytes: not reached)
      Py_XDECREF(type);
      return;
    }
    PyErr_SetObject(type, text);
    Py_DECREF(text);
    Py_XDECREF(type);
  }
}

}  // namespace

PYBIND11_MODULE(_spp, m) {
  pybind11::register_local_exception_translator(translate_keeping_the_message);
  m.doc() = "spp: periodic orbits with one lasting contact phase (SPPs) of vibro-impact systems";
  m.attr("__version__") = SPP_VERSION;
  spp::python::bind_core(m);
  spp::python::bind_modal(m);
  spp::python::bind_orbit(m);
  spp::python::bind_search(m);
  spp::python::bind_stability(m);
  spp::python::bind_simulation(m);
  spp::python::bind_continuation(m);
  spp::python::bind_io(m);
  spp::python::bind_modes(m);
  spp::python::bind_distributed(m);
}
