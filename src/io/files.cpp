#include "spp/io/files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "io/text.hpp"

namespace spp {

namespace fs = std::filesystem;
using io::invalid;

std::string read_file(const std::string& path) {
  // Only a regular file has a size known before reading it: a device (/dev/zero), a pipe or a directory would be read
  // until memory ran out (found by an independent attack: `spp solve /dev/zero` reached 2.9 GB in 3 s).
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  const std::string shown = io::shorten(path, io::kQuotedPathChars);
  if (!fs::exists(st)) invalid("cannot open \"" + shown + "\" for reading: no such file");
  if (fs::is_directory(st)) invalid("\"" + shown + "\" is a directory, not a file");
  if (!fs::is_regular_file(st))
    invalid("\"" + shown + "\" is not a regular file (a device, a pipe or a socket): expected a file on disk");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) invalid("cannot open \"" + shown + "\" for reading");
  if (size > kMaxInputFileBytes)
    invalid("\"" + shown + "\" has " + std::to_string(size) + " bytes, more than the " +
            std::to_string(kMaxInputFileBytes) + " an input file of spp may have (" + kMaxInputFileReason + ")");
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

void write_file_atomic(const std::string& path, const std::string& content) {
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir))
    invalid("cannot write \"" + path + "\": directory \"" + dir.string() + "\" does not exist");
  // the rename below replaces whatever is at path: a directory entry of another kind (a device such as /dev/null, a
  // pipe, a directory) is refused rather than replaced by a regular file
  std::error_code st_ec;
  const fs::file_status st = fs::status(target, st_ec);
  if (fs::exists(st) && !fs::is_regular_file(st))
    invalid("cannot write \"" + path + "\": it exists and is not a regular file (a directory or a device)");
  const fs::path tmp = dir / (".tmp." + target.filename().string() + "." + std::to_string(::getpid()));
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
