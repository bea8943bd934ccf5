#pragma once
// A broken invariant of spp itself, never a caller's mistake nor a numerical outcome: e.g. LAPACK's symmetric
// eigensolvers not converging on the finite, symmetric, positive definite matrices that System's validation
// guarantees. Thrown as std::logic_error so that no caller mistakes it for a status; the CLI exits 1 with the message,
// Python raises RuntimeError.

#include <stdexcept>
#include <string>

namespace spp::detail {

[[noreturn]] inline void internal_error(const std::string& what) {
  throw std::logic_error("internal error (a defect of spp: please report it with the input): " + what);
}

}  // namespace spp::detail
