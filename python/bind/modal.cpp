// Python bindings, modal/: which equations (Symmetry) and the modal frequencies.
#include "spp/modal/modal.hpp"

#include <iomanip>
#include <sstream>

#include "common.hpp"

namespace spp::python {

void bind_modal(py::module_& m) {
  py::enum_<spp::Symmetry>(m, "Symmetry",
                           "Which equations: the SPPs (axial) or the point-symmetric potential SPPs "
                           "of det T2 = 0 (point, paper §6.2)")
      .value("axial", spp::Symmetry::Axial)
      .value("point", spp::Symmetry::Point);
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
}

}  // namespace spp::python
