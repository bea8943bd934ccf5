#pragma once
// Helpers of the io files (private): user text quoted in messages, numbers written to round-trip.

#include <iomanip>
#include <sstream>
#include <string>

#include "spp/detail/invalid.hpp"

namespace spp::io {

using detail::invalid;

/// User text quoted in an error message: at most n characters of it.
inline std::string shorten(const std::string& t, size_t n = 40) {
  return t.size() > n ? t.substr(0, n) + "..." : t;
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
