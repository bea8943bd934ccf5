// Python bindings, stability/: the monodromy of an SPP (its multipliers are Solution fields).
#include <iomanip>
#include <sstream>

#include "common.hpp"
#include "spp/search/solver.hpp"
#include "spp/stability/floquet.hpp"

namespace spp::python {

void bind_stability(py::module_& m) {
  bind_outcome<spp::StabilityVerdict>(m, "StabilityVerdict",
               "Solution.stability_verdict (docs/stability.md)");
  m.def(
      "monodromy",
      [](const spp::System& s, const py::object& t1_arg, const py::object& t2_arg) {
        const double t1 = scalar_argument<double>(t1_arg, "spp.monodromy: argument t1"),
                     t2 = scalar_argument<double>(t2_arg, "spp.monodromy: argument t2");
        const spp::ModalForm md(s);
        spp::SolveOptions o;
        o.compute_return_error = false;
        o.compute_stability = false;
        const spp::SolutionAt at = spp::solution_at(s, md, t1, t2, o);
        if (!at.found) throw py::value_error("monodromy: " + at.brief_report());
        const spp::Solution& sol = at.solution;
        return py::make_tuple(spp::monodromy(md, sol.orbit), sol.orbit.x0, sol.orbit.v0, sol.period());
      },
      "system"_a, "t1"_a, "t2"_a,
      "The linearised one-period map of the SPP at (t1, t2) (polished there first) under Newton's impact law, e < 1: "
      "(Mono, x0, v0, period), Mono (2n, 2n) acting on (dx, dv) from just before the contact onset (x0, v0) "
      "(docs/stability.md). Raises ValueError when no SPP is within 1e-3 (t1 + t2) of the point.");
}

}  // namespace spp::python
