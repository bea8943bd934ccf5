#pragma once
// One way to refuse a bad option: std::invalid_argument with "<where>: <field> must be <rule>, got <value>".

#include <sstream>
#include <stdexcept>
#include <string>

namespace spp::detail {

[[noreturn]] inline void invalid_option(const char* where, const std::string& field, double value,
                                        const std::string& rule) {
  std::ostringstream os;
  os << where << ": " << field << " must be " << rule << ", got " << value;
  throw std::invalid_argument(os.str());
}

}  // namespace spp::detail
