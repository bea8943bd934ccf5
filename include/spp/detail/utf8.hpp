#pragma once
// UTF-8 in messages and names: the length of the well-formed sequence at a byte, one rule for the text quoted in an
// error message (io::shorten escapes what is not UTF-8, so that every message is valid UTF-8: Python decodes it) and
// for the names a system carries (check_text refuses them, so that nothing is built that a JSON file cannot hold).

#include <cstddef>
#include <string>

namespace spp::detail {

/// Bytes of the well-formed UTF-8 sequence starting at t[i] (1 to 4; RFC 3629: no overlong form, no surrogate, at most
/// U+10FFFF), or 0 when the byte there starts none (a Latin-1 byte, a stray continuation byte, a sequence cut short).
/// O(1).
inline std::size_t utf8_sequence(const std::string& t, std::size_t i) {
  const auto b = [&](std::size_t k) { return i + k < t.size() ? static_cast<unsigned char>(t[i + k]) : 0u; };
  const unsigned c = b(0);
  const auto cont = [&](std::size_t k, unsigned lo = 0x80, unsigned hi = 0xbf) { return b(k) >= lo && b(k) <= hi; };
  if (c < 0x80) return 1;
  if (c >= 0xc2 && c <= 0xdf) return cont(1) ? 2 : 0;
  if (c == 0xe0) return cont(1, 0xa0) && cont(2) ? 3 : 0;        // (no overlong form)
  if (c == 0xed) return cont(1, 0x80, 0x9f) && cont(2) ? 3 : 0;  // (no surrogate)
  if (c >= 0xe1 && c <= 0xef) return cont(1) && cont(2) ? 3 : 0;
  if (c == 0xf0) return cont(1, 0x90) && cont(2) && cont(3) ? 4 : 0;        // (no overlong form)
  if (c == 0xf4) return cont(1, 0x80, 0x8f) && cont(2) && cont(3) ? 4 : 0;  // (at most U+10FFFF)
  if (c >= 0xf1 && c <= 0xf3) return cont(1) && cont(2) && cont(3) ? 4 : 0;
  return 0;
}

/// Whether the sequence of `length` bytes at t[i] is a C1 control character (U+0080 to U+009F: C2 80 to C2 9F), a
/// control as much as the C0 ones (U+009B is the terminal's CSI).
inline bool utf8_c1_control(const std::string& t, std::size_t i, std::size_t length) {
  return length == 2 && static_cast<unsigned char>(t[i]) == 0xc2 && static_cast<unsigned char>(t[i + 1]) <= 0x9f;
}

}  // namespace spp::detail
