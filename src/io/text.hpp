#pragma once
// Helpers of the io files (private): user text quoted in messages, numbers written to round-trip.

#include <iomanip>
#include <sstream>
#include <string>

#include "spp/detail/invalid.hpp"

namespace spp::io {

using detail::invalid;

/// User text quoted in an error message: at most n characters of it, control characters escaped (\0, \t, \xNN): the
/// message reaches the user as a C string (what()), and a NUL inside a Matrix Market line cut it short there, file
/// and line lost (found by an independent attack).
inline std::string shorten(const std::string& t, size_t n = 40) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < t.size() && i < n; ++i) {
    const auto c = static_cast<unsigned char>(t[i]);
    if (c == 0)
      out += "\\0";
    else if (c == '\t')
      out += "\\t";
    else if (c == '\r')
      out += "\\r";
    else if (c < 0x20 || c == 0x7f)
      out += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
    else
      out += t[i];
  }
  return t.size() > n ? out + "..." : out;
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
