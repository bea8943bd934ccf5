#pragma once
// Whole files: every writer of spp goes through write_file_atomic (a temporary file renamed over the target), so that
// a failure never leaves a half-written output.

#include <string>

namespace spp {

/// The file's bytes. Throws std::invalid_argument naming the file when it cannot be opened.
std::string read_file(const std::string& path);
/// Writes `content` to a temporary file in the target's directory and renames it over `path`. Throws
/// std::invalid_argument naming the file (missing directory, write or rename failure); the target is then untouched.
void write_file_atomic(const std::string& path, const std::string& content);

}  // namespace spp
