// The _spp extension module: one binding file per area of the library (python/bind/<area>.cpp), the C++ concepts under
// the same names. numpy arrays in and out (Eigen <-> numpy through pybind11/eigen.h); std::invalid_argument becomes
// ValueError with the C++ message.
#include "common.hpp"

PYBIND11_MODULE(_spp, m) {
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
