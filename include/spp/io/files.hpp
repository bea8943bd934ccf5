#pragma once
// Whole files: every writer of spp goes through write_file_atomic (a temporary file renamed over the target), so that
// a failure never leaves a half-written output.
// Cost: one read or one write of the whole file (plus a rename), memory the file's size.

#include <cstdint>
#include <string>

namespace spp {

/// Largest input file (system, result, continuation file) read whole: 1 GiB. A dense system of 5000 dofs (M and K,
/// 5e7 numbers of ~20 characters) is ~1 GB of JSON text, and parsing holds the text and its tree at once (~3x);
/// larger models are given as Matrix Market files and reduced first (spp reduce). Named in the refusal.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{1} << 30;
inline constexpr const char* kMaxInputFileReason =
    "1 GiB: a dense 5000-dof system; give a larger model as Matrix Market files and reduce it with spp reduce";

/// Refuses, starting with `what`, a path holding a NUL byte: the system reads a path as a C string, which the NUL
/// would cut short (a different file opened silently).
void check_path_has_no_nul(const std::string& path, const std::string& what);
/// The bytes of a regular file of at most kMaxInputFileBytes. Throws std::invalid_argument naming the file when it
/// cannot be opened, is not a regular file (a device such as /dev/zero, a pipe) or is larger.
std::string read_file(const std::string& path);
/// The file an output path names: `path` itself, or the file a symbolic link there points to (written through, not
/// replaced: a rename over the link replaced it, /dev/stdout included, found by an independent attack). Refuses,
/// naming `what` (e.g. "--json"), a dangling link, a path under /dev or /proc (devices and a process's files: a
/// redirected /dev/stdout is no output file), and a file name longer than the file system's 255 bytes.
std::string output_file(const std::string& path, const std::string& what);
/// Writes `content` to a temporary file in the target's directory and renames it over output_file(path). Throws
/// std::invalid_argument naming the file (missing directory, write or rename failure); the target is then untouched.
void write_file_atomic(const std::string& path, const std::string& content);
/// Checks before any work that files can be written in directory `dir` ("" is the working directory): creates a
/// temporary file there and removes it. Throws std::invalid_argument starting with `what` (e.g. "--json") when `dir`
/// does not exist, is not a directory (a regular file on the path), or a file cannot be created in it (read-only).
void check_writable_directory(const std::string& dir, const std::string& what);

}  // namespace spp
