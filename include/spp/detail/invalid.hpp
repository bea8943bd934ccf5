#pragma once
// One way to refuse a caller's mistake: std::invalid_argument, its message naming what is wrong and where
// ("<where>: <field> must be <rule>, got <value>"). Numerical outcomes are statuses, never these.

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
