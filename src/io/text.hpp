#pragma once
// Helpers of the io files (private): user text quoted in messages, numbers written to round-trip.

#include <iomanip>
#include <sstream>
#include <string>

#include "spp/detail/invalid.hpp"
#include "spp/detail/utf8.hpp"

namespace spp::io {

using detail::invalid;

/// User text quoted in an error message: at most n characters of it, control characters escaped (\t, \r, \xNN; C1
/// controls too) and so is every byte that is not UTF-8 (\xff): the message reaches the user as a C string (what()),
/// and a NUL inside a Matrix Market line cut it short there, file and line lost; Python decodes it as UTF-8, and a
/// Latin-1 byte made it an empty ValueError (both found by independent attacks). A NUL is \x00, not \0 (which, before a
/// digit, read like an octal escape). Never cuts inside a character: the result is valid UTF-8.
inline std::string shorten(const std::string& t, size_t n = 40) {
  static const char* const kHex = "0123456789abcdef";
  const auto hex = [](unsigned char c) { return std::string("\\x") + kHex[c >> 4] + kHex[c & 15]; };
  std::string out;
  size_t i = 0;
  for (size_t shown = 0; i < t.size() && shown < n; ++shown) {
    const auto c = static_cast<unsigned char>(t[i]);
    const size_t len = detail::utf8_sequence(t, i);
    if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (len == 0 || c < 0x20 || c == 0x7f) {
      out += hex(c);
    } else if (detail::utf8_c1_control(t, i, len)) {
      out += hex(c) + hex(static_cast<unsigned char>(t[i + 1]));
    } else {
      out.append(t, i, len);
    }
    i += len == 0 ? 1 : len;
  }
  return i < t.size() ? out + "..." : out;
}

/// Characters of a file path quoted in an error message: a real path fits (PATH_MAX is 4096, paths are far shorter in
/// practice), text passed where a path was expected (a whole JSON result, 100 kB) is cut.
inline constexpr size_t kQuotedPathChars = 512;

/// A double with 17 significant digits (reads back to the same value).
inline std::string num(double v) {
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}

}  // namespace spp::io
