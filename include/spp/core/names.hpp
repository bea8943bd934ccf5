#pragma once
// The names a system carries (its own, its parameter's) and a system file's description: one check, used by the
// constructors (System, SparseSystem, ParametricSystem) and by the readers of system and result files, so that nothing
// is built that a file cannot hold (spp.System(name=5000 characters) wrote a result file that load_result refused;
// found by an independent attack).

#include <cstddef>
#include <string>

namespace spp {

/// Longest name a system (dense, sparse, parametric) or its parameter may carry, in bytes: a name is a title (tables,
/// figure titles, the result files that embed it); a 100 MB name was read whole and copied into every output (found by
/// an independent attack). Documented in the README.
inline constexpr std::size_t kMaxNameBytes = 4096;

/// Refuses (std::invalid_argument "<where>: expected ..., got ...") a name longer than kMaxNameBytes or holding a
/// control character, C0 or C1 (a NUL cut the name short in every table and figure title), or bytes that are not
/// UTF-8 (no JSON file can hold them). O(length).
void check_name(const std::string& name, const std::string& where);

/// The same for a text of at most max_bytes whose tabs and line breaks are kept when line_breaks (a description);
/// `kind` says what the text is, in the refusal of a long one ("a name is a title"). O(length).
void check_text(const std::string& text, const std::string& where, std::size_t max_bytes, bool line_breaks,
                const char* kind);

}  // namespace spp
