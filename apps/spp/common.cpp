#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "command.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/io/files.hpp"

namespace spp::cli {

namespace {
std::string quoted_path(const std::string& s) {
  return s.size() > 512 ? s.substr(0, 512) + "..." : s;
}
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
  // the file written: through a symbolic link; nothing under /dev or /proc; a name a file system takes (files.hpp)
  const std::string target = output_file(out, opt);
  std::error_code ec;
  for (const std::string& in : inputs)
    if (!in.empty() && same_file(target, in))
      detail::invalid(opt + ": \"" + out + "\" is also \"" + in +
                                  "\", a file this run reads (or another output): it would be replaced; write the " +
                                  "output to another file");
  for (const NamedOutput& o : outputs)
    if (!o.path.empty() && same_file(target, o.path))
      detail::invalid(opt + ": \"" + out + "\" is also the output of " + o.option + " (\"" + o.path +
                                  "\"): two outputs of one run cannot share a file; give each its own");
  // an existing path that is not a regular file (a directory, /dev/null, a pipe) would be replaced by the rename of
  // the atomic write: refused (found by an independent attack: --out /dev/full replaced the device)
  const fs::file_status st = fs::status(target, ec);
  if (fs::exists(st) && !fs::is_regular_file(st))
    detail::invalid(opt + ": \"" + out + "\" exists and is not a regular file (a directory or a device): " +
                                "write the output to a file");
  // its directory: there and writable, checked by writing a probe file before any work (a read-only directory was
  // found only when the output was written, after the solve; found by an independent attack)
  check_writable_directory(fs::path(target).parent_path().string(), opt + " \"" + quoted_path(out) + "\"");
}

namespace {
// An option's text quoted in a message: at most 80 characters of it (an argument may be 128 kB long).
std::string quoted(const std::string& s) {
  return s.size() > 80 ? s.substr(0, 80) + "..." : s;
}
}  // namespace

std::optional<double> parse_number(const std::string& item) {
  // std::from_chars: decimal only ("0x10" and "0x1p-3" are not numbers here, as std::stod took them), no locale,
  // "inf" and "nan" read (and refused where they are no values by the callers' checks)
  double x = 0.0;
  const char* begin = item.data();
  const char* end = item.data() + item.size();
  if (begin != end && *begin == '+' && begin + 1 != end && begin[1] != '-') ++begin;  // "+3" (from_chars takes no +)
  const auto [ptr, ec] = std::from_chars(begin, end, x);
  if (ec != std::errc() || ptr != end || begin == end) return std::nullopt;  // "1.5xyz" is not 1.5; 1e400 no double
  return x;
}

std::string number_problem(const std::string& text) {
  if (parse_number(text)) return "";
  double x = 0.0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (begin != end && *begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, x);
  if (ec == std::errc::result_out_of_range && ptr == end)
    return "expected a number within the range of a double (magnitude 2.2e-308 to 1.8e308, or 0), got \"" +
           quoted(text) + "\"";
  return "expected a decimal number (as 2, 0.5 or 1e-3), got \"" + quoted(text) + "\"";
}

CLI::Validator whole_number(double min, double max) {
  std::ostringstream range;
  range << "a whole number from " << min << " to " << max;
  return CLI::Validator(
      [min, max, want = range.str()](std::string& text) -> std::string {
        const std::optional<double> x = parse_number(text);
        if (!x || !(*x >= min && *x <= max) || std::floor(*x) != *x)
          return "expected " + want + " (1e7 and 10000000 both read), got \"" + cli::quoted(text) + "\"";
        text = std::to_string(static_cast<long long>(*x));  // what CLI11 then reads into the integer
        return "";
      },
      "COUNT");
}

std::vector<double> parse_list(const std::string& s, const char* opt) {
  std::vector<double> v;
  std::stringstream ss(s);
  std::string item;
  if (!s.empty() && s.back() == ',')  // getline drops an empty last item
    detail::invalid(std::string(opt) + ": expected comma-separated numbers, got \"" + quoted(s) + "\"");
  while (std::getline(ss, item, ',')) {
    const std::optional<double> x = parse_number(item);
    if (!x) detail::invalid(std::string(opt) + ": expected comma-separated numbers, got \"" + quoted(s) + "\"");
    v.push_back(*x);
  }
  if (v.empty()) detail::invalid(std::string(opt) + ": expected at least one number");
  return v;
}

ProgressLine::ProgressLine(bool quiet) : tty_(!quiet && isatty(STDERR_FILENO) != 0) {}

void ProgressLine::show(const std::string& line, double seconds, bool stopping) {
  if (!tty_ || seconds < 1.0) return;
  const std::string text = "  " + line + (stopping ? " (stopping)" : "") + "   ";
  std::fprintf(stderr, "\r%s", text.c_str());
  std::fflush(stderr);
  width_ = std::max(width_, static_cast<int>(text.size()));
  shown_ = true;
}

void ProgressLine::clear() {
  if (shown_) std::fprintf(stderr, "\r%*s\r", width_, "");
  std::fflush(stderr);
}

}  // namespace spp::cli
