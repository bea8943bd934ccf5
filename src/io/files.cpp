#include "spp/io/files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cstring>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "io/text.hpp"

namespace spp {

namespace fs = std::filesystem;
using io::invalid;

void check_path_has_no_nul(const std::string& path, const std::string& what) {
  // a path is handed to the system as a C string, which ends at the first NUL: "a.json\0junk" would open a.json
  if (const size_t at = path.find('\0'); at != std::string::npos)
    invalid(what + ": expected a file path without NUL bytes, got a NUL at byte " + std::to_string(at) + " of \"" +
            io::shorten(path.substr(0, at), io::kQuotedPathChars) + "...\"");
}

std::string read_file(const std::string& path) {
  check_path_has_no_nul(path, "cannot read a file");
  // Only a regular file has a size known before reading it: a device (/dev/zero), a pipe or a directory would be read
  // until memory ran out (found by an independent attack: `spp solve /dev/zero` reached 2.9 GB in 3 s).
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  const std::string shown = io::shorten(path, io::kQuotedPathChars);
  if (!fs::exists(st))
    invalid("cannot open \"" + shown + "\" for reading: expected an existing file, got no such file");
  if (fs::is_directory(st)) invalid("\"" + shown + "\" is a directory, not a file: expected a file, got a directory");
  if (!fs::is_regular_file(st))
    invalid("\"" + shown + "\" is not a regular file: expected a file on disk, got a device, a pipe or a socket");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) invalid("cannot open \"" + shown + "\" for reading");
  if (size > kMaxInputFileBytes)
    invalid("\"" + shown + "\": expected an input file of at most " + std::to_string(kMaxInputFileBytes) + " bytes (" +
            kMaxInputFileReason + "), got " + std::to_string(size) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) invalid("cannot open \"" + shown + "\" for reading");
  // read at most the limit and one byte more: a file that grew since its size was taken is still bounded
  std::string text(static_cast<size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<size_t>(in.gcount()));
  for (char buf[4096]; in.read(buf, sizeof buf) || in.gcount() > 0;) {
    text.append(buf, static_cast<size_t>(in.gcount()));
    if (text.size() > kMaxInputFileBytes)
      invalid("\"" + shown + "\" grew past the " + std::to_string(kMaxInputFileBytes) +
              " bytes an input file of spp may have while it was read");
  }
  return text;
}

std::string output_file(const std::string& path, const std::string& what) {
  check_path_has_no_nul(path, what);
  const std::string shown = io::shorten(path, io::kQuotedPathChars);
  auto refuse_system_dirs = [&](const std::string& p) {
    for (const char* system_dir : {"/dev/", "/proc/"})
      if (p.rfind(system_dir, 0) == 0)
        invalid(what + ": \"" + shown + "\" is under " + std::string(system_dir, std::strlen(system_dir) - 1) +
                " (a device or a process's file, such as a redirected /dev/stdout): expected an output file; write "
                "it to a file, then copy it where it must go");
  };
  std::error_code ec;
  refuse_system_dirs(fs::absolute(fs::path(path), ec).lexically_normal().string());
  fs::path target(path);
  if (fs::is_symlink(fs::symlink_status(target, ec))) {
    target = fs::canonical(target, ec);
    if (ec) invalid(what + ": \"" + shown + "\" is a symbolic link to a missing file: give the file's own path");
    refuse_system_dirs(target.string());
  }
  // NAME_MAX of the usual file systems (ext4, xfs, btrfs, tmpfs): a longer name fails only at the final rename
  constexpr size_t kMaxFileName = 255;
  const std::string name = target.filename().string();
  if (name.size() > kMaxFileName)
    invalid(what + ": the file name \"" + io::shorten(name, 60) + "\": expected at most the " +
            std::to_string(kMaxFileName) + " bytes a file system allows, got " + std::to_string(name.size()) +
            " bytes");
  return target.string();
}

void write_file_atomic(const std::string& given, const std::string& content) {
  const std::string path = output_file(given, "cannot write \"" + io::shorten(given, io::kQuotedPathChars) + "\"");
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir))
    invalid("cannot write \"" + path + "\": expected an existing directory, got \"" + dir.string() +
            "\", which does not exist");
  // the rename below replaces whatever is at path: a directory entry of another kind (a device such as /dev/null, a
  // pipe, a directory) is refused rather than replaced by a regular file
  std::error_code st_ec;
  const fs::file_status st = fs::status(target, st_ec);
  if (fs::exists(st) && !fs::is_regular_file(st))
    invalid("cannot write \"" + path +
            "\": it exists and is not a regular file: expected a file (or no file), got a "
            "directory or a device");
  // a short name (the target's may be up to 255 bytes), unique to this process and call; the salt tells apart
  // processes of one MPI run on two hosts that share a pid and write into one shared directory (a sweep's items)
  static std::atomic<unsigned> calls{0};
  static const unsigned salt = std::random_device{}();
  const fs::path tmp = dir / (".tmp.spp." + std::to_string(::getpid()) + "." + std::to_string(salt) + "." +
                              std::to_string(calls++));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) invalid("cannot write \"" + path + "\": cannot create a temporary file in \"" + dir.string() + "\"");
    out << content;
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      invalid("cannot write \"" + path + "\": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    invalid("cannot write \"" + path + "\": rename failed");
  }
}
void check_writable_directory(const std::string& dir, const std::string& what) {
  const fs::path d = dir.empty() ? fs::path(".") : fs::path(dir);
  const std::string shown = io::shorten(d.string(), io::kQuotedPathChars);
  std::error_code ec;
  const fs::file_status st = fs::status(d, ec);
  if (!fs::exists(st)) {
    // a regular file further up the path (a/file/b): say so rather than "does not exist"
    for (fs::path up = d.parent_path(); !up.empty() && up != up.root_path(); up = up.parent_path())
      if (fs::exists(up, ec) && !fs::is_directory(up, ec))
        invalid(what + ": the directory \"" + shown + "\" cannot exist: \"" +
                io::shorten(up.string(), io::kQuotedPathChars) + "\" on its path is a file, not a directory");
    invalid(what + ": the directory \"" + shown + "\" does not exist (create it first)");
  }
  if (!fs::is_directory(st))
    invalid(what + ": \"" + shown + "\" is not a directory (it is a file): expected a directory to write in");
  // a probe file, created exclusively (several processes of one MPI run may probe the same directory) and removed
  static std::atomic<unsigned> counter{0};
  static const unsigned salt = std::random_device{}();  // MPI ranks on two hosts may share a pid
  const fs::path probe = d / (".spp_write_probe." + std::to_string(::getpid()) + "." + std::to_string(salt) + "." +
                              std::to_string(counter++));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0)
    invalid(what + ": cannot write in the directory \"" + shown +
            "\" (a file cannot be created there: read-only, or no permission); nothing was written");
  ::close(fd);
  fs::remove(probe, ec);
}

}  // namespace spp
