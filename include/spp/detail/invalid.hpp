#pragma once
// The one way to refuse a caller's mistake (style note, "Errors"): std::invalid_argument, its message naming where,
// what was expected and what was got ("<where>: <field> must be <rule>, got <value>", or "<where>: expected X, got
// Y"). Library, command line and Python binding all throw through these two (tests/style checks that none throws
// std::invalid_argument by hand); never echo unbounded input in the message. Numerical outcomes are statuses, never
// these.

#include <sstream>
#include <stdexcept>
#include <string>

namespace spp::detail {

[[noreturn]] inline void invalid(const std::string& message) {
  throw std::invalid_argument(message);
}

[[noreturn]] inline void invalid_option(const char* where, const std::string& field, double value,
                                        const std::string& rule) {
  std::ostringstream os;
  os << where << ": " << field << " must be " << rule << ", got " << value;
  throw std::invalid_argument(os.str());
}

}  // namespace spp::detail
