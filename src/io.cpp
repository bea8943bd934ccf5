#include "spp/io.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_set>
#include <vector>

namespace spp {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
[[noreturn]] void fail(const std::string& s) {
  throw std::invalid_argument(s);
}

// User text quoted in an error message: at most n characters of it.
std::string shorten(const std::string& t, size_t n = 40) {
  return t.size() > n ? t.substr(0, n) + "..." : t;
}

// A value named in an error message, never echoed whole: nested or long input (a 100 000-deep array) is described,
// not dumped (json::dump recurses: a stack overflow).
std::string describe(const json& v) {
  if (v.is_array()) return "a list (" + std::to_string(v.size()) + " entries)";
  if (v.is_object()) return "an object (" + std::to_string(v.size()) + " fields)";
  if (v.is_string()) {
    const std::string& t = v.get_ref<const std::string&>();
    return "the string \"" + shorten(t) + "\"";
  }
  return v.dump();  // a number, boolean or null: short
}

// Fields a system file may hold; any other is named (a misspelt "G0" must not be silently ignored).
void check_fields(const json& j, std::initializer_list<const char*> known, const std::string& where,
                  std::initializer_list<const char*> also = {}) {
  for (const auto& [k, _] : j.items()) {
    bool ok = false;
    for (const char* f : known) ok = ok || k == f;
    for (const char* f : also) ok = ok || k == f;
    if (!ok) {
      std::string list;
      for (const char* f : known) list += std::string(list.empty() ? "" : ", ") + f;
      fail(where + ": unknown field \"" + shorten(k) + "\" (expected: " + list + ")");
    }
  }
}

std::string num(double v) {
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}

Eigen::MatrixXd matrix_field(const json& j, const char* key, const std::string& where, const std::string& dir) {
  if (!j.contains(key)) fail(where + ": missing field \"" + key + "\"");
  const json& v = j.at(key);
  if (v.is_object()) {
    if (!v.contains("matrix_market") || !v.at("matrix_market").is_string())
      fail(where + ": field \"" + key + "\" must be a list of rows or {\"matrix_market\": \"file.mtx\"}");
    fs::path p = v.at("matrix_market").get<std::string>();
    if (p.is_relative()) p = fs::path(dir) / p;
    try {
      return read_matrix_market(p.string());
    } catch (const std::invalid_argument& e) {
      fail(where + ": field \"" + key + "\": " + e.what());
    }
  }
  if (!v.is_array() || v.empty())
    fail(where + ": field \"" + key + "\" must be a non-empty list of rows, got " + std::string(v.type_name()));
  const size_t rows = v.size();
  if (!v[0].is_array()) fail(where + ": field \"" + key + "\" row 0 must be a list of numbers");
  const size_t cols = v[0].size();
  Eigen::MatrixXd A(rows, cols);
  for (size_t i = 0; i < rows; ++i) {
    if (!v[i].is_array() || v[i].size() != cols) {
      std::ostringstream os;
      os << where << ": field \"" << key << "\" row " << i << " must have " << cols << " entries like row 0, got "
         << (v[i].is_array() ? std::to_string(v[i].size()) + " entries" : std::string(v[i].type_name()));
      fail(os.str());
    }
    for (size_t c = 0; c < cols; ++c) {
      if (!v[i][c].is_number()) {
        std::ostringstream os;
        os << where << ": field \"" << key << "\"[" << i << "][" << c << "] must be a number, got " << describe(v[i][c]);
        fail(os.str());
      }
      A(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) = v[i][c].get<double>();
    }
  }
  return A;
}

Eigen::VectorXd vector_field(const json& j, const char* key, const std::string& where) {
  if (!j.contains(key)) fail(where + ": missing field \"" + key + "\"");
  const json& jw = j.at(key);
  if (!jw.is_array() || jw.empty()) fail(where + ": field \"" + key + "\" must be a non-empty list of numbers");
  Eigen::VectorXd w(static_cast<Eigen::Index>(jw.size()));
  for (size_t i = 0; i < jw.size(); ++i) {
    if (!jw[i].is_number())
      fail(where + ": field \"" + key + "\"[" + std::to_string(i) + "] must be a number, got " + describe(jw[i]));
    w(static_cast<Eigen::Index>(i)) = jw[i].get<double>();
  }
  return w;
}

double g0_field(const json& j, const std::string& where) {
  if (!j.contains("g0")) fail(where + ": missing field \"g0\" (the gap at rest)");
  if (!j.at("g0").is_number()) fail(where + ": field \"g0\" must be a number, got " + describe(j.at("g0")));
  return j.at("g0").get<double>();
}

std::string name_field(const json& j) {
  return j.contains("name") && j.at("name").is_string() ? j.at("name").get<std::string>() : "";
}
}  // namespace

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot open \"" + path + "\" for reading");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

System system_from_json(const json& j, const std::string& where, const std::string& dir) {
  if (!j.is_object()) fail(where + ": expected a JSON object with fields M, K, w, g0");
  // (a result's "system" also carries what result_to_json adds)
  check_fields(j, {"name", "description", "M", "K", "w", "g0"}, where, {"n", "w_normalized", "w_input_norm"});
  Eigen::MatrixXd M = matrix_field(j, "M", where, dir);
  Eigen::MatrixXd K = matrix_field(j, "K", where, dir);
  Eigen::VectorXd w = vector_field(j, "w", where);
  const double g0 = g0_field(j, where);
  try {
    return System(std::move(M), std::move(K), std::move(w), g0, name_field(j));
  } catch (const std::invalid_argument& e) {
    fail(where + ": " + e.what());
  }
}

System load_system(const std::string& path) {
  const json j = read_json_file(path);
  if (declares_parameter(j))
    fail(path + ": declares the parameter \"" + j.at("parameter").value("name", std::string("?")) +
         "\" (a parametric system): use spp continue, or spp solve --at VALUE (or with g0 = 0 spp solve alone)");
  const std::string dir = fs::path(path).parent_path().string();
  return system_from_json(j, path, dir.empty() ? "." : dir);
}

bool declares_parameter(const json& j) {
  return j.is_object() && j.contains("parameter");
}

namespace {

// {"constant": A, "<name>": B} -> (A, B); a plain value -> (value, empty).
template <typename Read>
auto affine_field(const json& j, const char* key, const std::string& name, const std::string& where, Read read) {
  using T = decltype(read(j, key));
  if (!j.contains(key)) fail(where + ": missing field \"" + key + "\"");
  const json& v = j.at(key);
  if (v.is_object() && v.contains("constant")) {
    for (const auto& [k, _] : v.items())
      if (k != "constant" && k != name)
        fail(where + ": field \"" + key + "\" has a part \"" + k + "\": expected only \"constant\" and \"" + name +
             "\" (the declared parameter)");
    T c = read(v, "constant");
    T m = v.contains(name) ? read(v, name.c_str()) : T();
    return std::make_pair(std::move(c), std::move(m));
  }
  return std::make_pair(read(j, key), T());
}

}  // namespace

ParametricSystem parametric_system_from_json(const json& j, const std::string& where, const std::string& dir) {
  if (!j.is_object()) fail(where + ": expected a JSON object with fields M, K, w, g0, parameter");
  if (!j.contains("parameter"))
    fail(where + ": no field \"parameter\" (e.g. \"parameter\": {\"name\": \"k2\", \"min\": 1, \"max\": 10})");
  const json& p = j.at("parameter");
  if (!p.is_object() || !p.contains("name") || !p.at("name").is_string() || p.at("name").get<std::string>().empty())
    fail(where + ": field \"parameter\" must be {\"name\": \"...\", \"min\": number, \"max\": number}");
  check_fields(j, {"name", "description", "M", "K", "w", "g0", "parameter"}, where);
  check_fields(p, {"name", "min", "max"}, where + ": field \"parameter\"");
  Parameter par;
  par.name = p.at("name").get<std::string>();
  for (const char* k : {"min", "max"})
    if (!p.contains(k) || !p.at(k).is_number())
      fail(where + ": field \"parameter\" needs the number \"" + std::string(k) + "\"");
  par.min = p.at("min").get<double>();
  par.max = p.at("max").get<double>();
  if (par.name == "constant") fail(where + ": the parameter cannot be named \"constant\"");
  auto mat = [&](const json& o, const char* k) { return matrix_field(o, k, where, dir); };
  auto vec = [&](const json& o, const char* k) { return vector_field(o, k, where); };
  auto [M0, M1] = affine_field(j, "M", par.name, where, mat);
  auto [K0, K1] = affine_field(j, "K", par.name, where, mat);
  auto [w0, w1] = affine_field(j, "w", par.name, where, vec);
  const double g0 = g0_field(j, where);
  try {
    return ParametricSystem(std::move(M0), std::move(M1), std::move(K0), std::move(K1), std::move(w0), std::move(w1),
                            g0, par, name_field(j));
  } catch (const std::invalid_argument& e) {
    fail(where + ": " + e.what());
  }
}

ParametricSystem load_parametric_system(const std::string& path) {
  const json j = read_json_file(path);
  const std::string dir = fs::path(path).parent_path().string();
  return parametric_system_from_json(j, path, dir.empty() ? "." : dir);
}

namespace {
json matrix_json(const Eigen::MatrixXd& A) {
  json rows = json::array();
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    json r = json::array();
    for (Eigen::Index c = 0; c < A.cols(); ++c) r.push_back(A(i, c));
    rows.push_back(r);
  }
  return rows;
}
json vector_json(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}
}  // namespace

json system_to_json(const System& s) {
  const auto mat = matrix_json;
  json j;
  j["name"] = s.name();
  j["M"] = mat(s.M());
  j["K"] = mat(s.K());
  j["w"] = std::vector<double>(s.w().data(), s.w().data() + s.w().size());
  j["g0"] = s.g0();
  return j;
}

namespace {
// Whole-token number parsing ("1.5xyz" is not 1.5). Written here: std::from_chars for double is not in g++ 12's
// libstdc++ for every target, and strtod with an end check is the portable equivalent.
bool parse_number(const std::string& token, double& v) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && errno != ERANGE && std::isfinite(v);
}
bool parse_index(const std::string& token, long& v) {
  double d = 0;
  if (!parse_number(token, d) || d != std::floor(d) || std::abs(d) > 9e15) return false;
  v = static_cast<long>(d);
  return true;
}
std::vector<std::string> tokens(const std::string& line) {
  std::istringstream ss(line);
  std::vector<std::string> t;
  for (std::string w; ss >> w;) t.push_back(w);
  return t;
}
// Dense storage the reader may allocate (entries): larger sizes are refused with their size, not std::bad_alloc.
constexpr double kMaxDenseEntries = 4e8;  // 3.2 GB of doubles
}  // namespace

Eigen::MatrixXd read_matrix_market(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail("cannot open Matrix Market file \"" + path + "\"");
  std::string line;
  if (!std::getline(in, line) || line.rfind("%%MatrixMarket", 0) != 0)
    fail(path + ": line 1 must start with %%MatrixMarket");
  std::istringstream hs(line);
  std::string banner, object, format, field, symmetry;
  hs >> banner >> object >> format >> field >> symmetry;
  for (auto* s : {&object, &format, &field, &symmetry})
    for (auto& ch : *s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (object != "matrix") fail(path + ": expected object \"matrix\", got \"" + shorten(object) + "\"");
  if (format != "coordinate" && format != "array")
    fail(path + ": expected format coordinate or array, got \"" + shorten(format) + "\"");
  if (field != "real" && field != "integer" && field != "double")
    fail(path + ": expected field real or integer, got \"" + shorten(field) + "\"");
  if (symmetry != "general" && symmetry != "symmetric")
    fail(path + ": expected symmetry general or symmetric, got \"" + shorten(symmetry) + "\"");
  int lineno = 1;
  auto next_data_line = [&](std::string& l) {  // skips comments and blank lines
    while (std::getline(in, l)) {
      ++lineno;
      if (!tokens(l).empty() && l[l.find_first_not_of(" \t\r\v\f")] != '%') return true;
    }
    return false;
  };
  auto where = [&] { return path + ":" + std::to_string(lineno); };
  auto shown = [](const std::string& l) { return shorten(l, 60); };
  if (!next_data_line(line)) fail(path + ": no size line");
  const std::vector<std::string> size = tokens(line);
  long rows = 0, cols = 0, nnz = 0;
  const bool coordinate = format == "coordinate";
  if (size.size() != (coordinate ? 3u : 2u) || !parse_index(size[0], rows) || !parse_index(size[1], cols) ||
      (coordinate && !parse_index(size[2], nnz)) || rows <= 0 || cols <= 0 || nnz < 0)
    fail(where() + ": bad size line \"" + shown(line) + "\" (expected rows cols" + (coordinate ? " entries" : "") +
         ")");
  if (static_cast<double>(rows) * static_cast<double>(cols) > kMaxDenseEntries)
    fail(where() + ": a " + std::to_string(rows) + " x " + std::to_string(cols) +
         " matrix is too large to hold densely (limit " + num(kMaxDenseEntries) + " entries)");
  const bool sym = symmetry == "symmetric";
  if (sym && rows != cols) fail(where() + ": a symmetric matrix must be square, got " + size[0] + " x " + size[1]);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, cols);
  if (coordinate) {
    // Duplicate entries are summed (the format's convention, as scipy.io.mmread); a symmetric file stores one
    // triangle: an entry given in both triangles is refused.
    Eigen::Matrix<signed char, Eigen::Dynamic, Eigen::Dynamic> side;
    if (sym) side = Eigen::Matrix<signed char, Eigen::Dynamic, Eigen::Dynamic>::Zero(rows, cols);
    for (long e = 0; e < nnz; ++e) {
      if (!next_data_line(line))
        fail(path + ": expected " + std::to_string(nnz) + " entries (size line), got " + std::to_string(e));
      const std::vector<std::string> t = tokens(line);
      long i = 0, j = 0;
      double v = 0;
      if (t.size() != 3 || !parse_index(t[0], i) || !parse_index(t[1], j) || !parse_number(t[2], v) || i < 1 ||
          i > rows || j < 1 || j > cols)
        fail(where() + ": bad entry \"" + shown(line) + "\" (expected row col value, 1 <= row <= " +
             std::to_string(rows) + ", 1 <= col <= " + std::to_string(cols) + ")");
      if (sym && i != j) {
        const long lo = std::min(i, j) - 1, hi = std::max(i, j) - 1;
        const signed char s = i > j ? 1 : 2;
        if (side(hi, lo) != 0 && side(hi, lo) != s)
          fail(where() + ": entry (" + std::to_string(i) + ", " + std::to_string(j) +
               ") of a symmetric file: its mirror was given too (store one triangle)");
        side(hi, lo) = s;
        A(hi, lo) += v;
        A(lo, hi) += v;
      } else {
        A(i - 1, j - 1) += v;
      }
    }
    if (next_data_line(line))
      fail(where() + ": more entries than the " + std::to_string(nnz) + " the size line declares: \"" + shown(line) +
           "\"");
  } else {
    std::vector<std::string> pending;
    size_t next = 0;
    for (long j = 0; j < cols; ++j)
      for (long i = sym ? j : 0; i < rows; ++i) {
        while (next == pending.size()) {
          if (!next_data_line(line))
            fail(path + ": array data ended early at entry (" + std::to_string(i + 1) + ", " + std::to_string(j + 1) +
                 ")");
          pending = tokens(line);
          next = 0;
        }
        double v = 0;
        if (!parse_number(pending[next++], v))
          fail(where() + ": entry (" + std::to_string(i + 1) + ", " + std::to_string(j + 1) + ") is not a number: \"" +
               shown(pending[next - 1]) + "\"");
        A(i, j) = v;
        if (sym) A(j, i) = v;
      }
    if (next != pending.size() || next_data_line(line))
      fail(where() + ": more values than the " + std::to_string(sym ? rows * (rows + 1) / 2 : rows * cols) +
           " the size line declares");
  }
  return A;
}

json result_to_json(const System& s, const SolveResult& r) {
  json j;
  auto vec = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  j["system"] = system_to_json(s);
  j["system"]["n"] = s.n();
  j["system"]["w_normalized"] = s.w_input_norm() != 1.0;
  j["system"]["w_input_norm"] = s.w_input_norm();
  j["window"] = {{"t1_min", r.t1_min}, {"t1_max", r.t1_max}, {"t2_min", r.t2_min}, {"t2_max", r.t2_max}};
  j["status"] = to_string(r.status);
  j["symmetry"] = to_string(r.symmetry);
  j["warnings"] = r.warnings;
  j["stats"] = {{"flight_pole_lines", r.stats.flight_pole_lines},
                {"contact_pole_lines", r.stats.contact_pole_lines},
                {"rectangles", r.stats.rectangles},
                {"curve_pieces", r.stats.curve_pieces},
                {"roots", r.stats.roots},
                {"evaluations", r.stats.evaluations},
                {"strip_pairs", r.stats.strip_pairs},
                {"certified_steps", r.stats.certified_steps},
                {"heuristic_steps", r.stats.heuristic_steps},
                {"uncertified_steps", r.stats.uncertified_steps},
                {"uncertified_corners", r.stats.uncertified_corners},
                {"unpaired_crossings", r.stats.unpaired_crossings},
                {"unresolved_pieces", r.stats.unresolved_pieces},
                {"unpolished_roots", r.stats.unpolished_roots},
                {"decoupled_modes", r.decoupled_modes},
                {"repeated_frequency_groups", r.repeated_groups},
                {"seconds", r.stats.seconds}};
  json unc = json::array();
  for (const UncertifiedRegion& u : r.uncertified)
    unc.push_back({{"t1_lo", u.t1_lo}, {"t1_hi", u.t1_hi}, {"t2_lo", u.t2_lo}, {"t2_hi", u.t2_hi}, {"cause", u.cause}});
  j["uncertified"] = unc;
  json sols = json::array();
  for (const Solution& x : r.solutions) {
    json o = {{"t1", x.t1},
              {"t2", x.t2},
              {"period", x.period},
              {"admissible", x.admissible},
              {"min_gap", x.min_gap},
              {"min_force", x.min_force},
              {"x0", vec(x.orbit.x0)},
              {"v0", vec(x.orbit.v0)},
              {"energy", x.energy},
              {"residual", x.residual},
              {"return_error", x.return_error},
              {"mid_flight_gap", x.admissibility.mid_flight_gap},
              {"mid_contact_force", x.admissibility.mid_contact_force},
              {"onset_force_rate", x.admissibility.onset_force_rate},
              {"admissibility_certified", x.admissibility.certified},
              {"admissibility_ends_ok", x.admissibility.ends_ok},
              {"flags", x.flags},
              // the orbit in modal coordinates (modal form §2), so that load_result rebuilds the same Solution
              {"orbit", {{"a", vec(x.orbit.a)},
                         {"c", vec(x.orbit.c)},
                         {"p0", vec(x.orbit.p0)},
                         {"p0dot", vec(x.orbit.p0dot)},
                         {"closure_ratio", x.orbit.closure_ratio},
                         {"energy", x.orbit.energy}}}};
    if (x.orbit.symmetry == Symmetry::Point) o["obstacle_velocity"] = x.orbit.obstacle_velocity;
    sols.push_back(o);
  }
  j["solutions"] = sols;
  return j;
}

json read_json_file(const std::string& path) {
  const std::string text = read_file(path);
  // Duplicate keys are refused (nlohmann keeps the last one silently): one set of keys per open object.
  std::vector<std::unordered_set<std::string>> keys;
  std::string duplicate;
  const json::parser_callback_t seen = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start) keys.emplace_back();
    if (event == json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
    if (event == json::parse_event_t::key && !keys.empty() && duplicate.empty()) {
      const std::string k = parsed.get<std::string>();
      if (!keys.back().insert(k).second) duplicate = shorten(k);
    }
    return true;
  };
  json j;
  try {
    j = json::parse(text, seen);
  } catch (const json::exception& e) {
    fail(path + ": malformed JSON: " + e.what());
  }
  if (!duplicate.empty()) fail(path + ": the key \"" + duplicate + "\" appears twice in one object");
  return j;
}

System result_system(const json& r, const std::string& where) {
  if (!r.is_object() || !r.contains("system") || !r.contains("solutions"))
    fail(where + ": expected a result of spp solve (fields \"system\" and \"solutions\")");
  if (!r.at("system").contains("M") || !r.at("system").contains("K"))
    fail(where + ": field \"system\" has no \"M\" and \"K\" (a result from an older spp): run spp solve again");
  return system_from_json(r.at("system"), where + ": field \"system\"");
}

std::vector<SppCandidate> result_candidates(const json& r, const std::string& where) {
  if (!r.is_object() || !r.contains("solutions") || !r.at("solutions").is_array())
    fail(where + ": missing field \"solutions\" (expected a result of spp solve)");
  std::vector<SppCandidate> out;
  const json& sols = r.at("solutions");
  for (size_t i = 0; i < sols.size(); ++i) {
    const std::string at = where + ": solutions[" + std::to_string(i) + "]";
    const json& o = sols[i];
    auto number = [&](const char* key) {
      if (!o.is_object() || !o.contains(key) || !o.at(key).is_number())
        fail(at + ": field \"" + key + "\" must be a number");
      return o.at(key).get<double>();
    };
    auto vector = [&](const char* key) {
      if (!o.contains(key) || !o.at(key).is_array()) fail(at + ": field \"" + key + "\" must be a list of numbers");
      const json& a = o.at(key);
      Eigen::VectorXd v(static_cast<Eigen::Index>(a.size()));
      for (size_t k = 0; k < a.size(); ++k) {
        if (!a[k].is_number()) fail(at + ": field \"" + key + "\"[" + std::to_string(k) + "] must be a number");
        v(static_cast<Eigen::Index>(k)) = a[k].get<double>();
      }
      return v;
    };
    SppCandidate c;
    c.t1 = number("t1");
    c.t2 = number("t2");
    c.x0 = vector("x0");
    c.v0 = vector("v0");
    if (!o.contains("admissible") || !o.at("admissible").is_boolean())
      fail(at + ": field \"admissible\" must be true or false");
    c.admissible = o.at("admissible").get<bool>();
    c.energy = o.contains("energy") ? number("energy") : std::numeric_limits<double>::quiet_NaN();
    out.push_back(std::move(c));
  }
  return out;
}

namespace {
// Readers for load_result: each names the field it could not read. Doubles written as null (NaN) read back as NaN.
struct Reader {
  const json& o;
  std::string where;
  const json& at(const char* k) const {
    if (!o.is_object() || !o.contains(k)) fail(where + ": missing field \"" + k + "\"");
    return o.at(k);
  }
  double number(const char* k) const {
    const json& v = at(k);
    if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!v.is_number()) fail(where + ": field \"" + k + "\" must be a number, got " + describe(v));
    return v.get<double>();
  }
  long integer(const char* k) const {
    const json& v = at(k);
    if (!v.is_number_integer()) fail(where + ": field \"" + k + "\" must be an integer, got " + describe(v));
    return v.get<long>();
  }
  bool boolean(const char* k) const {
    const json& v = at(k);
    if (!v.is_boolean()) fail(where + ": field \"" + k + "\" must be true or false, got " + describe(v));
    return v.get<bool>();
  }
  std::string text(const char* k) const {
    const json& v = at(k);
    if (!v.is_string()) fail(where + ": field \"" + k + "\" must be a string, got " + describe(v));
    return v.get<std::string>();
  }
  std::vector<std::string> texts(const char* k) const {
    const json& v = at(k);
    std::vector<std::string> out;
    if (!v.is_array()) fail(where + ": field \"" + k + "\" must be a list of strings, got " + describe(v));
    for (const json& e : v) {
      if (!e.is_string()) fail(where + ": field \"" + k + "\" must be a list of strings, got " + describe(e));
      out.push_back(e.get<std::string>());
    }
    return out;
  }
  Eigen::VectorXd vector(const char* k) const {
    const json& v = at(k);
    if (!v.is_array()) fail(where + ": field \"" + k + "\" must be a list of numbers, got " + describe(v));
    Eigen::VectorXd x(static_cast<Eigen::Index>(v.size()));
    for (size_t i = 0; i < v.size(); ++i) {
      if (v[i].is_null()) {
        x(static_cast<Eigen::Index>(i)) = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      if (!v[i].is_number())
        fail(where + ": field \"" + k + "\"[" + std::to_string(i) + "] must be a number, got " + describe(v[i]));
      x(static_cast<Eigen::Index>(i)) = v[i].get<double>();
    }
    return x;
  }
};
}  // namespace

SolveResult result_from_json(const json& r, const std::string& where) {
  if (!r.is_object()) fail(where + ": expected a result of spp solve (a JSON object)");
  SolveResult res;
  const Reader top{r, where};
  const std::string status = top.text("status");
  if (status == "success")
    res.status = SolveStatus::Success;
  else if (status == "incomplete")
    res.status = SolveStatus::Incomplete;
  else
    fail(where + ": field \"status\" must be \"success\" or \"incomplete\", got \"" + shorten(status) + "\"");
  const std::string sym = top.text("symmetry");
  if (sym != "axial" && sym != "point")
    fail(where + ": field \"symmetry\" must be \"axial\" or \"point\", got \"" + shorten(sym) + "\"");
  res.symmetry = sym == "point" ? Symmetry::Point : Symmetry::Axial;
  res.warnings = top.texts("warnings");
  const Reader win{top.at("window"), where + ": field \"window\""};
  res.t1_min = win.number("t1_min");
  res.t1_max = win.number("t1_max");
  res.t2_min = win.number("t2_min");
  res.t2_max = win.number("t2_max");
  const Reader st{top.at("stats"), where + ": field \"stats\""};
  SolveStats& s = res.stats;
  s.flight_pole_lines = static_cast<int>(st.integer("flight_pole_lines"));
  s.contact_pole_lines = static_cast<int>(st.integer("contact_pole_lines"));
  s.rectangles = st.integer("rectangles");
  s.curve_pieces = st.integer("curve_pieces");
  s.roots = st.integer("roots");
  s.evaluations = st.integer("evaluations");
  s.strip_pairs = st.integer("strip_pairs");
  s.certified_steps = st.integer("certified_steps");
  s.heuristic_steps = st.integer("heuristic_steps");
  s.uncertified_steps = st.integer("uncertified_steps");
  s.uncertified_corners = st.integer("uncertified_corners");
  s.unpaired_crossings = st.integer("unpaired_crossings");
  s.unresolved_pieces = st.integer("unresolved_pieces");
  s.unpolished_roots = st.integer("unpolished_roots");
  s.seconds = st.number("seconds");
  res.decoupled_modes = static_cast<int>(st.integer("decoupled_modes"));
  res.repeated_groups = static_cast<int>(st.integer("repeated_frequency_groups"));
  const json& unc = top.at("uncertified");
  if (!unc.is_array()) fail(where + ": field \"uncertified\" must be a list, got " + describe(unc));
  for (size_t i = 0; i < unc.size(); ++i) {
    const Reader u{unc[i], where + ": field \"uncertified\"[" + std::to_string(i) + "]"};
    res.uncertified.push_back({u.number("t1_lo"), u.number("t1_hi"), u.number("t2_lo"), u.number("t2_hi"), u.text("cause")});
  }
  const json& sols = top.at("solutions");
  if (!sols.is_array()) fail(where + ": field \"solutions\" must be a list, got " + describe(sols));
  for (size_t i = 0; i < sols.size(); ++i) {
    const Reader o{sols[i], where + ": field \"solutions\"[" + std::to_string(i) + "]"};
    Solution x;
    x.t1 = o.number("t1");
    x.t2 = o.number("t2");
    x.period = o.number("period");
    x.admissible = o.boolean("admissible");
    x.min_gap = o.number("min_gap");
    x.min_force = o.number("min_force");
    x.energy = o.number("energy");
    x.residual = o.number("residual");
    x.return_error = o.number("return_error");
    x.flags = o.texts("flags");
    Admissibility& a = x.admissibility;
    a.admissible = x.admissible;
    a.min_gap = x.min_gap;
    a.min_force = x.min_force;
    a.mid_flight_gap = o.number("mid_flight_gap");
    a.mid_contact_force = o.number("mid_contact_force");
    a.onset_force_rate = o.number("onset_force_rate");
    a.certified = o.boolean("admissibility_certified");
    a.ends_ok = o.boolean("admissibility_ends_ok");
    Orbit& b = x.orbit;
    b.t1 = x.t1;
    b.t2 = x.t2;
    b.symmetry = res.symmetry;
    b.x0 = o.vector("x0");
    b.v0 = o.vector("v0");
    const Reader ob{o.at("orbit"), o.where + ": field \"orbit\""};
    b.a = ob.vector("a");
    b.c = ob.vector("c");
    b.p0 = ob.vector("p0");
    b.p0dot = ob.vector("p0dot");
    b.closure_ratio = ob.number("closure_ratio");
    b.energy = ob.number("energy");
    if (res.symmetry == Symmetry::Point) b.obstacle_velocity = o.number("obstacle_velocity");
    res.solutions.push_back(std::move(x));
  }
  return res;
}

SolveResult load_result(const std::string& path) {
  return result_from_json(read_json_file(path), path);
}

std::string result_to_csv(const SolveResult& r) {
  std::ostringstream os;
  os << "t1,t2,period,admissible,min_gap,min_force,energy,residual,return_error";
  const int n = r.solutions.empty() ? 0 : static_cast<int>(r.solutions[0].orbit.x0.size());
  for (int i = 1; i <= n; ++i) os << ",x0_" << i;
  for (int i = 1; i <= n; ++i) os << ",v0_" << i;
  os << "\n";
  for (const Solution& x : r.solutions) {
    os << num(x.t1) << "," << num(x.t2) << "," << num(x.period) << "," << (x.admissible ? 1 : 0) << ","
       << num(x.min_gap) << "," << num(x.min_force) << "," << num(x.energy) << "," << num(x.residual) << ","
       << num(x.return_error);
    for (int i = 0; i < n; ++i) os << "," << num(x.orbit.x0(i));
    for (int i = 0; i < n; ++i) os << "," << num(x.orbit.v0(i));
    os << "\n";
  }
  return os.str();
}

std::string result_table(const SolveResult& r) {
  std::ostringstream os;
  os << std::setw(4) << "#" << std::setw(14) << "t1" << std::setw(14) << "t2" << std::setw(14) << "period"
     << std::setw(12) << "admissible" << std::setw(14) << "min_gap" << std::setw(14) << "min_force"
     << "\n";
  int i = 0;
  for (const Solution& x : r.solutions) {
    os << std::setw(4) << i++ << std::setprecision(8) << std::setw(14) << x.t1 << std::setw(14) << x.t2 << std::setw(14)
       << x.period << std::setw(12) << (x.admissible ? "yes" : "no") << std::setprecision(3) << std::setw(14)
       << x.min_gap << std::setw(14) << x.min_force;
    for (const auto& f : x.flags) os << "  [" << f << "]";
    os << "\n";
  }
  return os.str();
}

std::string trajectory_csv(const ModalForm& md, const Orbit& o, int samples) {
  std::ostringstream os;
  const int n = md.n();
  os << "t";
  for (int i = 1; i <= n; ++i) os << ",x" << i;
  for (int i = 1; i <= n; ++i) os << ",v" << i;
  os << ",gap,force\n";
  const double T = o.period();
  for (int k = 0; k < samples; ++k) {
    const double t = T * k / (samples - 1);
    const OrbitState st = orbit_state(md, o, t);
    os << num(t);
    for (int i = 0; i < n; ++i) os << "," << num(st.x(i));
    for (int i = 0; i < n; ++i) os << "," << num(st.v(i));
    os << "," << num(st.gap) << "," << num(st.force) << "\n";
  }
  return os.str();
}

namespace {
// ",x1..xn,v1..vn" and the matching values: the state columns shared by every CSV of states.
void state_columns(std::ostringstream& os, Eigen::Index n) {
  for (Eigen::Index i = 1; i <= n; ++i) os << ",x" << i;
  for (Eigen::Index i = 1; i <= n; ++i) os << ",v" << i;
}
void state_values(std::ostringstream& os, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < x.size(); ++i) os << "," << num(x(i));
  for (Eigen::Index i = 0; i < v.size(); ++i) os << "," << num(v(i));
}
}  // namespace

std::string simulation_csv(const SimulationResult& r) {
  std::ostringstream os;
  os << "t";
  state_columns(os, r.samples.empty() ? 0 : r.samples[0].x.size());
  os << ",gap,force,contact\n";
  for (const Sample& s : r.samples) {
    os << num(s.t);
    state_values(os, s.x, s.v);
    os << "," << num(s.gap) << "," << num(s.force) << "," << (s.in_contact ? 1 : 0) << "\n";
  }
  return os.str();
}

std::string events_csv(const SimulationResult& r) {
  std::ostringstream os;
  os << "t,event,normal_velocity_before,normal_velocity_after,force";
  state_columns(os, r.samples.empty() ? 0 : r.samples[0].x.size());
  os << "\n";
  for (const Event& e : r.events) {
    os << num(e.t) << "," << to_string(e.kind) << "," << num(e.normal_velocity_before) << ","
       << num(e.normal_velocity_after) << "," << num(e.force);
    state_values(os, e.x, e.v_after);
    os << "\n";
  }
  return os.str();
}

json verify_to_json(const VerifyResult& r) {
  json checks = json::array();
  for (const SppCheck& c : r.checks) {
    json o = {{"t1", c.candidate.t1},
              {"t2", c.candidate.t2},
              {"period", c.candidate.period()},
              {"admissible", c.candidate.admissible},
              {"verdict", to_string(c.verdict)},
              {"consistent", c.consistent},
              {"return_errors", c.return_errors},
              {"impacts", c.impacts},
              {"contact_onsets", c.contact_onsets},
              {"releases", c.releases}};
    o["periods_followed"] = c.periods_followed;
    if (!c.departure.empty()) o["departure"] = {{"t", c.departure_time}, {"what", c.departure}};
    if (!c.perturbed_distances.empty()) {
      o["perturbed_distances"] = c.perturbed_distances;
      o["growth_per_period"] = c.growth_per_period;
    }
    checks.push_back(o);
  }
  return {{"checks", checks},
          {"returned", r.returned},
          {"left", r.left},
          {"inconsistent", r.inconsistent},
          {"all_consistent", r.all_consistent()}};
}

std::string verify_table(const VerifyResult& r) {
  std::ostringstream os;
  const bool perturbed =
      std::any_of(r.checks.begin(), r.checks.end(), [](const SppCheck& c) { return !c.perturbed_distances.empty(); });
  const int periods = r.checks.empty() ? 0 : static_cast<int>(r.checks[0].return_errors.size());
  os << std::setw(4) << "#" << std::setw(13) << "t1" << std::setw(13) << "t2" << std::setw(12) << "admissible"
     << std::setw(14) << "return_err" << std::setw(9) << "verdict";
  if (periods > 1) os << std::setw(10) << "followed" << std::setw(14) << "err_last";
  if (perturbed) os << std::setw(12) << "growth/T";
  os << "  note\n";
  int i = 0;
  for (const SppCheck& c : r.checks) {
    os << std::setw(4) << i++ << std::setprecision(8) << std::setw(13) << c.candidate.t1 << std::setw(13)
       << c.candidate.t2 << std::setw(12) << (c.candidate.admissible ? "yes" : "no") << std::setprecision(3)
       << std::setw(14) << (c.return_errors.empty() ? 0.0 : c.return_errors[0]) << std::setw(9) << to_string(c.verdict);
    if (periods > 1)
      os << std::setw(10) << (std::to_string(c.periods_followed) + "/" + std::to_string(periods)) << std::setw(14)
         << c.return_errors.back();
    if (perturbed) {
      if (c.perturbed_distances.empty())
        os << std::setw(12) << "-";
      else
        os << std::setprecision(6) << std::setw(12) << c.growth_per_period;
    }
    const bool departs = c.verdict == Verdict::Leaves || c.periods_followed < periods;
    os << "  " << (c.consistent ? "" : "INCONSISTENT with the solver: ")
       << (departs ? (c.verdict == Verdict::Returns ? "later: " : "") + c.departure : "") << "\n";
  }
  return os.str();
}

void write_file_atomic(const std::string& path, const std::string& content) {
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) fail("cannot write \"" + path + "\": directory \"" + dir.string() + "\" does not exist");
  const fs::path tmp = dir / (".tmp." + target.filename().string() + "." + std::to_string(::getpid()));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail("cannot write \"" + path + "\": cannot create a temporary file in \"" + dir.string() + "\"");
    out << content;
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      fail("cannot write \"" + path + "\": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    fail("cannot write \"" + path + "\": rename failed");
  }
}

json parametric_system_to_json(const ParametricSystem& s) {
  const std::string& p = s.parameter().name;
  json j;
  j["name"] = s.name();
  j["parameter"] = {{"name", p}, {"min", s.parameter().min}, {"max", s.parameter().max}};
  j["M"] = {{"constant", matrix_json(s.M_constant())}, {p, matrix_json(s.M_mu())}};
  j["K"] = {{"constant", matrix_json(s.K_constant())}, {p, matrix_json(s.K_mu())}};
  j["w"] = {{"constant", vector_json(s.w_constant())}, {p, vector_json(s.w_mu())}};
  j["g0"] = s.g0();
  return j;
}

namespace {
json point_json(const BranchPoint& p, const std::string& parameter) {
  json j = {{parameter, p.mu},
            {"t1", p.t1},
            {"t2", p.t2},
            {"period", p.period},
            {"closure", p.closure},
            {"energy", p.energy},
            {"x0", vector_json(p.x0)},
            {"v0", vector_json(p.v0)}};
  // NaN is not JSON: the margin is null where it means nothing (g0 = 0 away from a closure, diverging orbit).
  j["margin"] = std::isfinite(p.margin) ? json(p.margin) : json(nullptr);
  j["admissible"] = p.admissible;
  return j;
}
}  // namespace

json continuation_to_json(const ParametricSystem& s, const ContinuationResult& r) {
  json j;
  j["system"] = parametric_system_to_json(s);
  j["symmetry"] = to_string(r.symmetry);
  j["window"] = {{"t1_min", r.t1_min}, {"t1_max", r.t1_max}, {"t2_min", r.t2_min}, {"t2_max", r.t2_max}};
  j["warnings"] = r.warnings;
  j["stats"] = {{"seed_spps", r.seed_spps},
                {"seed_crossings", r.seed_crossings},
                {"corrector_solves", r.corrector_solves},
                {"seconds", r.seconds}};
  const std::string& p = r.parameter.name;
  json branches = json::array();
  for (const Branch& b : r.branches) {
    json jb;
    jb["points"] = json::array();
    for (const BranchPoint& q : b.points) jb["points"].push_back(point_json(q, p));
    jb["events"] = json::array();
    for (const BranchEvent& e : b.events) {
      json je = point_json(e.at, p);
      je["event"] = to_string(e.kind);
      je["detail"] = e.detail;
      jb["events"].push_back(je);
    }
    branches.push_back(jb);
  }
  j["branches"] = branches;
  return j;
}

std::string continuation_table(const ContinuationResult& r) {
  std::ostringstream os;
  os << std::setw(7) << "branch" << std::setw(22) << "event" << std::setw(15) << r.parameter.name << std::setw(13)
     << "t1" << std::setw(13) << "t2" << std::setw(12) << "margin"
     << "  detail\n";
  for (size_t b = 0; b < r.branches.size(); ++b)
    for (const BranchEvent& e : r.branches[b].events)
      os << std::setw(7) << b << std::setw(22) << to_string(e.kind) << std::setw(15) << std::setprecision(10) << e.at.mu
         << std::setw(13) << std::setprecision(7) << e.at.t1 << std::setw(13) << e.at.t2 << std::setw(12)
         << std::setprecision(3) << e.at.margin << "  " << e.detail << "\n";
  return os.str();
}

json zero_gap_to_json(const ParametricSystem& s, const ContinuationResult& r) {
  json j;
  j["system"] = parametric_system_to_json(s);
  j["window"] = {{"t1_min", r.t1_min}, {"t1_max", r.t1_max}, {"t2_min", r.t2_min}, {"t2_max", r.t2_max}};
  j["status"] = r.warnings.empty() ? "success" : "incomplete";
  j["symmetry"] = to_string(r.symmetry);
  j["warnings"] = r.warnings;
  j["normalization"] = "unit energy (g0 = 0: eq. 5.2 leaves the scale free); the sign that makes the force >= 0";
  j["solutions"] = json::array();
  for (const BranchPoint& p : gap_closures(r)) {
    json q = point_json(p, r.parameter.name);
    q.erase(r.parameter.name);
    q.erase("closure");
    q["parameter"] = {{"name", r.parameter.name}, {"value", p.mu}};
    j["solutions"].push_back(q);
  }
  return j;
}

std::string zero_gap_table(const ContinuationResult& r) {
  std::ostringstream os;
  os << std::setw(4) << "#" << std::setw(18) << r.parameter.name << std::setw(15) << "t1" << std::setw(15) << "t2"
     << std::setw(15) << "period" << std::setw(12) << "admissible" << std::setw(12) << "margin\n";
  int k = 0;
  for (const BranchPoint& p : gap_closures(r))
    os << std::setw(4) << k++ << std::setw(18) << std::setprecision(12) << p.mu << std::setw(15) << std::setprecision(9)
       << p.t1 << std::setw(15) << p.t2 << std::setw(15) << p.period << std::setw(12) << (p.admissible ? "yes" : "no")
       << std::setw(12) << std::setprecision(3) << p.margin << "\n";
  return os.str();
}

}  // namespace spp
