#include "spp/io/matrix_market.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <tuple>
#include <vector>

#include "io/text.hpp"
#include "spp/detail/out_of_memory.hpp"
#include "spp/io/files.hpp"

namespace spp {

using io::invalid;
using io::num;
using io::shorten;

namespace {
// Whole-token number parsing ("1.5xyz" is not 1.5). Written here: std::from_chars for double is not in g++ 12's
// libstdc++ for every target, and strtod with an end check is the portable equivalent.
bool parse_number(const std::string& token, double& v) {
  // decimal only: strtod also reads hexadecimal ("0x1p3" = 8), which Matrix Market does not have
  if (token.empty() || token.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && errno != ERANGE && std::isfinite(v);
}
// An index or count is a whole number written as one (the format's integers: "5.0" or "5e0" is refused, as scipy's
// mmread refuses it; an index read through a double accepted both, found by an independent attack).
bool parse_index(const std::string& token, long& v) {
  const char* b = token.data();
  const char* e = b + token.size();
  if (b != e && *b == '+') ++b;  // (from_chars takes no '+')
  const auto [end, ec] = std::from_chars(b, e, v);
  return ec == std::errc() && end == e && b != e;
}
std::vector<std::string> tokens(const std::string& line) {
  std::istringstream ss(line);
  std::vector<std::string> t;
  for (std::string w; ss >> w;) t.push_back(w);
  return t;
}
// Dense storage the reader may allocate (entries): larger sizes are refused with their size, not std::bad_alloc.
constexpr double kMaxDenseEntries = 4e8;  // 3.2 GB of doubles

// Longest line of a Matrix Market file: a data line holds two indices and a value (< 80 characters), an array line a
// few values; only a comment could be longer. A file without newlines (/dev/zero, a binary file) is refused at this
// many characters instead of being read into one string until memory runs out (found by an independent attack).
constexpr size_t kMaxLineBytes = size_t{1} << 20;  // 1 MiB

// std::getline with a cap of kMaxLineBytes: false at the end of the file, refused past the cap.
bool read_line(std::istream& in, std::string& line, const std::string& path, int lineno) {
  line.clear();
  std::streambuf* sb = in.rdbuf();
  for (;;) {
    int c = 0;
    try {
      c = sb->sbumpc();
    } catch (const std::exception& e) {  // (a read error: /proc/self/mem gave libstdc++'s bare filebuf message)
      invalid("cannot read Matrix Market file \"" + shorten(path, io::kQuotedPathChars) + "\" at line " +
              std::to_string(lineno) + ": " + shorten(e.what(), 200) + ": expected a readable file");
    }
    if (c == std::char_traits<char>::eof()) {
      in.setstate(std::ios::eofbit);
      return !line.empty();
    }
    if (c == '\n') return true;
    if (line.size() >= kMaxLineBytes)
      invalid(path + ":" + std::to_string(lineno) + ": a line longer than " + std::to_string(kMaxLineBytes) +
              " bytes (the limit of a Matrix Market line: a data line is two indices and a value); not a Matrix "
              "Market file?");
    line.push_back(static_cast<char>(c));
  }
}

// The size line against the size the caller knows (w's length), before anything of the declared size is allocated.
void check_size(const std::string& path, long rows, long cols, long expected_size) {
  if (expected_size >= 0 && (rows != expected_size || cols != expected_size))
    invalid(path + ": declares a " + std::to_string(rows) + " x " + std::to_string(cols) + " matrix, expected " +
            std::to_string(expected_size) + " x " + std::to_string(expected_size) + " (the length of w)");
}

// The one parser of both readers: checks the banner and the size line, calls on_size(rows, cols) once, then
// on_entry(i, j, v) (0-based, as stored: one triangle of a symmetric file) for every stored entry. `where` names the
// current line. expected_size >= 0: the size line must declare it (checked before anything else about the size).
template <typename OnSize, typename OnEntry>
void parse_matrix_market(const std::string& path, bool dense, long expected_size, OnSize on_size, OnEntry on_entry) {
  check_path_has_no_nul(path, "cannot read a Matrix Market file");
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
    invalid("Matrix Market file \"" + shorten(path, io::kQuotedPathChars) +
            "\" is not a regular file: expected a file on disk, got a directory, a device or a pipe");
  std::ifstream in(path);
  if (!in) invalid("cannot open Matrix Market file \"" + shorten(path, io::kQuotedPathChars) + "\"");
  std::string line;
  if (!read_line(in, line, path, 1) || line.rfind("%%MatrixMarket", 0) != 0)
    invalid(path + ": line 1 must start with %%MatrixMarket, got \"" + shorten(line, 60) + "\"");
  std::istringstream hs(line);
  std::string banner, object, format, field, symmetry, extra;
  hs >> banner >> object >> format >> field >> symmetry >> extra;
  // the banner is exactly five tokens: a sixth ("... symmetric extra") was ignored, so a header of another variant
  // of the format read as this one (found by an independent attack)
  if (!extra.empty())
    invalid(path +
            ":1: expected the header \"%%MatrixMarket matrix <format> <field> <symmetry>\" (five words), "
            "got the extra word \"" +
            shorten(extra) + "\" after them");
  for (auto* s : {&object, &format, &field, &symmetry})
    for (auto& ch : *s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (object != "matrix") invalid(path + ":1: expected object \"matrix\", got \"" + shorten(object) + "\"");
  if (format != "coordinate" && format != "array")
    invalid(path + ":1: expected format coordinate or array, got \"" + shorten(format) + "\"");
  if (field != "real" && field != "integer" && field != "double")
    invalid(path + ":1: expected field real or integer, got \"" + shorten(field) + "\"");
  if (symmetry != "general" && symmetry != "symmetric")
    invalid(path + ":1: expected symmetry general or symmetric, got \"" + shorten(symmetry) + "\"");
  int lineno = 1;
  auto next_data_line = [&](std::string& l) {  // skips comments and blank lines
    while (read_line(in, l, path, lineno + 1)) {
      ++lineno;
      if (!tokens(l).empty() && l[l.find_first_not_of(" \t\r\v\f")] != '%') return true;
    }
    return false;
  };
  auto where = [&] { return path + ":" + std::to_string(lineno); };
  auto shown = [](const std::string& l) { return shorten(l, 60); };
  if (!next_data_line(line)) invalid(path + ": expected a size line after the header, got the end of the file");
  const std::vector<std::string> size = tokens(line);
  long rows = 0, cols = 0, nnz = 0;
  const bool coordinate = format == "coordinate";
  if (size.size() != (coordinate ? 3u : 2u) || !parse_index(size[0], rows) || !parse_index(size[1], cols) ||
      (coordinate && !parse_index(size[2], nnz)) || rows <= 0 || cols <= 0 || nnz < 0)
    invalid(where() + ": bad size line \"" + shown(line) + "\" (expected rows cols" + (coordinate ? " entries" : "") +
            ")");
  check_size(path, rows, cols, expected_size);
  if (dense && static_cast<double>(rows) * static_cast<double>(cols) > kMaxDenseEntries)
    invalid(where() + ": expected a matrix of at most " + num(kMaxDenseEntries) +
            " entries to hold densely (a large sparse model is reduced first: spp reduce), got a " +
            std::to_string(rows) + " x " + std::to_string(cols) + " matrix, too large");
  if (!dense && rows > std::numeric_limits<int>::max() / 2)
    invalid(where() + ": expected at most " + std::to_string(std::numeric_limits<int>::max() / 2) +
            " rows (a sparse matrix with int indices), got " + std::to_string(rows) + " rows");
  const bool sym = symmetry == "symmetric";
  if (sym && rows != cols) invalid(where() + ": a symmetric matrix must be square, got " + size[0] + " x " + size[1]);
  on_size(rows, cols, sym, where);
  if (coordinate) {
    for (long e = 0; e < nnz; ++e) {
      if (!next_data_line(line))
        invalid(path + ": expected " + std::to_string(nnz) + " entries (size line), got " + std::to_string(e));
      const std::vector<std::string> t = tokens(line);
      long i = 0, j = 0;
      double v = 0;
      if (t.size() != 3 || !parse_index(t[0], i) || !parse_index(t[1], j) || !parse_number(t[2], v) || i < 1 ||
          i > rows || j < 1 || j > cols)
        invalid(where() + ": bad entry \"" + shown(line) + "\" (expected row col value, 1 <= row <= " +
                std::to_string(rows) + ", 1 <= col <= " + std::to_string(cols) + ")");
      on_entry(i - 1, j - 1, v, where);
    }
    if (next_data_line(line))
      invalid(where() + ": expected the " + std::to_string(nnz) +
              " entries the size line declares, got more entries than the " + std::to_string(nnz) + ": \"" +
              shown(line) + "\"");
  } else {
    std::vector<std::string> pending;
    size_t next = 0;
    for (long j = 0; j < cols; ++j)
      for (long i = sym ? j : 0; i < rows; ++i) {
        while (next == pending.size()) {
          if (!next_data_line(line))
            invalid(path +
                    ": expected the values the size line declares, got the end of the file (array data ended "
                    "early at entry (" +
                    std::to_string(i + 1) + ", " + std::to_string(j + 1) + "))");
          pending = tokens(line);
          next = 0;
        }
        double v = 0;
        if (!parse_number(pending[next++], v))
          invalid(where() + ": entry (" + std::to_string(i + 1) + ", " + std::to_string(j + 1) +
                  ") is not a number: expected a decimal number, got \"" + shown(pending[next - 1]) + "\"");
        on_entry(i, j, v, where);
      }
    if (next != pending.size() || next_data_line(line))
      invalid(where() + ": expected the " + std::to_string(sym ? rows * (rows + 1) / 2 : rows * cols) +
              " values the size line declares, got more values than the " +
              std::to_string(sym ? rows * (rows + 1) / 2 : rows * cols));
  }
}

std::string mirror_given(long i, long j) {
  return "entry (" + std::to_string(i + 1) + ", " + std::to_string(j + 1) +
         ") of a symmetric file: its mirror was given too (expected one triangle stored, got both)";
}

}  // namespace

Eigen::MatrixXd read_matrix_market(const std::string& path, long expected_size) {
  Eigen::MatrixXd A;
  // Duplicate entries are summed (the format's convention, as scipy.io.mmread); a symmetric file stores one
  // triangle: an entry given in both triangles is refused.
  Eigen::Matrix<signed char, Eigen::Dynamic, Eigen::Dynamic> side;
  bool sym = false;
  parse_matrix_market(
      path, true, expected_size,
      [&](long rows, long cols, bool symmetric, const auto& where) {
        sym = symmetric;
        detail::naming_allocation(
            where() + ": " + detail::dense_size(static_cast<double>(rows), static_cast<double>(cols)), [&] {
              A = Eigen::MatrixXd::Zero(rows, cols);
              if (sym) side = Eigen::Matrix<signed char, Eigen::Dynamic, Eigen::Dynamic>::Zero(rows, cols);
            });
      },
      [&](long i, long j, double v, const auto& where) {
        if (sym && i != j) {
          const long lo = std::min(i, j), hi = std::max(i, j);
          const signed char s = i > j ? 1 : 2;
          if (side(hi, lo) != 0 && side(hi, lo) != s) invalid(where() + ": " + mirror_given(i, j));
          side(hi, lo) = s;
          A(hi, lo) += v;
          A(lo, hi) += v;
        } else {
          A(i, j) += v;
        }
      });
  return A;
}

Eigen::SparseMatrix<double> read_sparse_matrix_market(const std::string& path, long expected_size) {
  std::vector<Eigen::Triplet<double>> entries;
  // (lower index, upper index, which triangle) of every off-diagonal entry of a symmetric file: one triangle only
  std::vector<std::tuple<long, long, signed char>> sides;
  bool sym = false;
  long rows = 0, cols = 0;
  parse_matrix_market(
      path, false, expected_size,
      [&](long r, long c, bool symmetric, const auto&) {
        rows = r;
        cols = c;
        sym = symmetric;
      },
      [&](long i, long j, double v, const auto&) {
        if (v == 0.0) return;  // (array files list the zeros too)
        entries.emplace_back(static_cast<int>(i), static_cast<int>(j), v);
        if (sym && i != j) {
          entries.emplace_back(static_cast<int>(j), static_cast<int>(i), v);
          sides.emplace_back(std::min(i, j), std::max(i, j), i > j ? 1 : 2);
        }
      });
  std::sort(sides.begin(), sides.end());
  for (size_t k = 1; k < sides.size(); ++k)
    if (std::get<0>(sides[k]) == std::get<0>(sides[k - 1]) && std::get<1>(sides[k]) == std::get<1>(sides[k - 1]) &&
        std::get<2>(sides[k]) != std::get<2>(sides[k - 1]))
      invalid(path + ": " + mirror_given(std::get<1>(sides[k]), std::get<0>(sides[k])));
  Eigen::SparseMatrix<double> A(rows, cols);
  A.setFromTriplets(entries.begin(), entries.end());  // duplicates summed
  return A;
}

std::string matrix_market_text(const Eigen::SparseMatrix<double>& A, bool symmetric, const std::string& comment) {
  Eigen::SparseMatrix<double> stored = A;
  if (symmetric) stored = A.triangularView<Eigen::Lower>();
  stored.prune(0.0);
  std::string out =
      std::string("%%MatrixMarket matrix coordinate real ") + (symmetric ? "symmetric" : "general") + "\n";
  if (!comment.empty()) out += "% " + comment + "\n";
  out += std::to_string(A.rows()) + " " + std::to_string(A.cols()) + " " + std::to_string(stored.nonZeros()) + "\n";
  char buf[64];
  for (int k = 0; k < stored.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(stored, k); it; ++it) {
      std::snprintf(buf, sizeof buf, "%ld %ld %.17g\n", static_cast<long>(it.row()) + 1,
                    static_cast<long>(it.col()) + 1, it.value());
      out += buf;
    }
  return out;
}

}  // namespace spp
