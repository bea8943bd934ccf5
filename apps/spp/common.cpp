#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "command.hpp"

namespace spp::cli {

namespace {
// out and path name one file: the same file (a link, ./x), or the same path not written yet (two outputs of one run)
bool same_file(const std::string& out, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  return (fs::exists(out, ec) && fs::equivalent(out, path, ec)) ||
         fs::weakly_canonical(out, ec) == fs::weakly_canonical(path, ec);
}
}  // namespace

void check_output(const std::string& out, const std::string& opt, const std::vector<std::string>& inputs,
                  const std::vector<NamedOutput>& outputs) {
  namespace fs = std::filesystem;
  if (out.empty()) return;
  std::error_code ec;
  for (const std::string& in : inputs)
    if (!in.empty() && same_file(out, in))
      throw std::invalid_argument(opt + ": \"" + out + "\" is also \"" + in +
                                  "\", a file this run reads (or another output): it would be replaced; write the " +
                                  "output to another file");
  for (const NamedOutput& o : outputs)
    if (!o.path.empty() && same_file(out, o.path))
      throw std::invalid_argument(opt + ": \"" + out + "\" is also the output of " + o.option + " (\"" + o.path +
                                  "\"): two outputs of one run cannot share a file; give each its own");
  // an existing path that is not a regular file (a directory, /dev/null, a pipe) would be replaced by the rename of
  // the atomic write: refused (found by an independent attack: --out /dev/full replaced the device)
  const fs::file_status st = fs::status(out, ec);
  if (fs::exists(st) && !fs::is_regular_file(st))
    throw std::invalid_argument(opt + ": \"" + out + "\" exists and is not a regular file (a directory or a device): " +
                                "write the output to a file");
  const fs::path dir = fs::path(out).parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw std::invalid_argument(opt + ": the directory \"" + dir.string() + "\" of \"" + out + "\" does not exist");
}

namespace {
// An option's text quoted in a message: at most 80 characters of it (an argument may be 128 kB long).
std::string quoted(const std::string& s) {
  return s.size() > 80 ? s.substr(0, 80) + "..." : s;
}
}  // namespace

std::vector<double> parse_list(const std::string& s, const char* opt) {
  std::vector<double> v;
  std::stringstream ss(s);
  std::string item;
  if (!s.empty() && s.back() == ',')  // getline drops an empty last item
    throw std::invalid_argument(std::string(opt) + ": expected comma-separated numbers, got \"" + quoted(s) + "\"");
  while (std::getline(ss, item, ',')) {
    try {
      size_t pos = 0;
      v.push_back(std::stod(item, &pos));
      if (pos != item.size()) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw std::invalid_argument(std::string(opt) + ": expected comma-separated numbers, got \"" + quoted(s) + "\"");
    }
  }
  if (v.empty()) throw std::invalid_argument(std::string(opt) + ": expected at least one number");
  return v;
}

}  // namespace spp::cli
