#include "spp/io/files.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/text.hpp"

namespace spp {

namespace fs = std::filesystem;
using io::invalid;

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) invalid("\"" + path + "\" is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) invalid("cannot open \"" + path + "\" for reading");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
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
}  // namespace spp
