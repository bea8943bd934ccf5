#include "io/json.hpp"

#include <filesystem>
#include <limits>
#include <unordered_set>

#include "spp/io/files.hpp"
#include "spp/io/matrix_market.hpp"

namespace spp::io {

namespace fs = std::filesystem;

std::string describe(const json& v) {
  if (v.is_array()) return "a list (" + std::to_string(v.size()) + " entries)";
  if (v.is_object()) return "an object (" + std::to_string(v.size()) + " fields)";
  if (v.is_string()) {
    const std::string& t = v.get_ref<const std::string&>();
    return "the string \"" + shorten(t) + "\"";
  }
  return v.dump();  // a number, boolean or null: short
}

void check_fields(const json& j, std::initializer_list<const char*> known, const std::string& where,
                  std::initializer_list<const char*> also) {
  check_fields(j, std::vector<const char*>(known), where, also);
}

void check_fields(const json& j, const std::vector<const char*>& known, const std::string& where,
                  std::initializer_list<const char*> also) {
  for (const auto& [k, _] : j.items()) {
    bool ok = false;
    for (const char* f : known) ok = ok || k == f;
    for (const char* f : also) ok = ok || k == f;
    if (!ok) {
      std::string list;
      for (const char* f : known) list += std::string(list.empty() ? "" : ", ") + f;
      invalid(where + ": unknown field \"" + shorten(k) + "\" (expected: " + list + ")");
    }
  }
}

json read_json_file(const std::string& path) {
  return parse_json_text(read_file(path), path);
}

namespace {
// Deepest nesting of arrays and objects a file may have. spp's own files nest at most 5 deep (a result's
// solutions[k].orbit.x0); nlohmann parses iteratively, but copying, comparing or dumping a value recurses once per
// level, so a 100 000-deep array (fuzzing) must stop at the parser, not overflow the stack later.
constexpr int kMaxJsonDepth = 64;
// Characters of a parser's message quoted in ours: its position and reason fit, an echoed token is cut.
constexpr size_t kMaxParserMessage = 200;
struct TooDeep {};  // thrown out of the parser callback: stops the parse at the first level too deep
}  // namespace

json parse_json_text(const std::string& text, const std::string& path) {
  // Duplicate keys are refused (nlohmann keeps the last one silently): one set of keys per open object.
  std::vector<std::unordered_set<std::string>> keys;
  std::string duplicate;
  const json::parser_callback_t seen = [&](int depth, json::parse_event_t event, json& parsed) {
    if ((event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) &&
        depth >= kMaxJsonDepth)
      throw TooDeep{};
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
    // nlohmann quotes the offending token whole ("number overflow parsing '1000...'" with 100 000 digits): shortened
    invalid(path + ": malformed JSON: " + shorten(e.what(), kMaxParserMessage));
  } catch (const TooDeep&) {
    invalid(path + ": expected JSON nested at most " + std::to_string(kMaxJsonDepth) +
            " levels deep (lists in lists, objects in objects), got deeper");
  }
  if (!duplicate.empty()) invalid(path + ": the key \"" + duplicate + "\" appears twice in one object");
  return j;
}

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

Eigen::MatrixXd matrix_field(const json& j, const char* key, const std::string& where, const std::string& dir,
                             long expected_size) {
  if (!j.contains(key)) invalid(where + ": missing field \"" + key + "\"");
  const json& v = j.at(key);
  if (v.is_object()) {
    if (!v.contains("matrix_market") || !v.at("matrix_market").is_string())
      invalid(where + ": field \"" + key + "\" must be a list of rows or {\"matrix_market\": \"file.mtx\"}");
    check_fields(v, {"matrix_market"}, where + ": field \"" + key + "\"");
    fs::path p = v.at("matrix_market").get<std::string>();
    if (p.is_relative()) p = fs::path(dir) / p;
    try {
      return read_matrix_market(p.string(), expected_size);
    } catch (const std::invalid_argument& e) {
      invalid(where + ": field \"" + key + "\": " + e.what());
    }
  }
  if (!v.is_array() || v.empty())
    invalid(where + ": field \"" + key + "\" must be a non-empty list of rows, got " + std::string(v.type_name()));
  const size_t rows = v.size();
  if (!v[0].is_array()) invalid(where + ": field \"" + key + "\" row 0 must be a list of numbers");
  const size_t cols = v[0].size();
  Eigen::MatrixXd A(rows, cols);
  for (size_t i = 0; i < rows; ++i) {
    if (!v[i].is_array() || v[i].size() != cols) {
      std::ostringstream os;
      os << where << ": field \"" << key << "\" row " << i << " must have " << cols << " entries like row 0, got "
         << (v[i].is_array() ? std::to_string(v[i].size()) + " entries" : std::string(v[i].type_name()));
      invalid(os.str());
    }
    for (size_t c = 0; c < cols; ++c) {
      if (!v[i][c].is_number()) {
        std::ostringstream os;
        os << where << ": field \"" << key << "\"[" << i << "][" << c << "] must be a number, got "
           << describe(v[i][c]);
        invalid(os.str());
      }
      A(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) = v[i][c].get<double>();
    }
  }
  return A;
}

Eigen::VectorXd vector_field(const json& j, const char* key, const std::string& where) {
  if (!j.contains(key)) invalid(where + ": missing field \"" + key + "\"");
  const json& jw = j.at(key);
  if (!jw.is_array() || jw.empty()) invalid(where + ": field \"" + key + "\" must be a non-empty list of numbers");
  Eigen::VectorXd w(static_cast<Eigen::Index>(jw.size()));
  for (size_t i = 0; i < jw.size(); ++i) {
    if (!jw[i].is_number())
      invalid(where + ": field \"" + key + "\"[" + std::to_string(i) + "] must be a number, got " + describe(jw[i]));
    w(static_cast<Eigen::Index>(i)) = jw[i].get<double>();
  }
  return w;
}

const json& Reader::at(const char* k) const {
  if (!o.is_object() || !o.contains(k)) invalid(where + ": missing field \"" + k + "\"");
  return o.at(k);
}
double Reader::number(const char* k) const {
  const json& v = at(k);
  if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!v.is_number()) invalid(where + ": field \"" + k + "\" must be a number, got " + describe(v));
  return v.get<double>();
}
long Reader::integer(const char* k) const {
  const json& v = at(k);
  if (!v.is_number_integer()) invalid(where + ": field \"" + k + "\" must be an integer, got " + describe(v));
  return v.get<long>();
}
bool Reader::boolean(const char* k) const {
  const json& v = at(k);
  if (!v.is_boolean()) invalid(where + ": field \"" + k + "\" must be true or false, got " + describe(v));
  return v.get<bool>();
}
std::string Reader::text(const char* k) const {
  const json& v = at(k);
  if (!v.is_string()) invalid(where + ": field \"" + k + "\" must be a string, got " + describe(v));
  return v.get<std::string>();
}
std::vector<std::string> Reader::texts(const char* k) const {
  const json& v = at(k);
  std::vector<std::string> out;
  if (!v.is_array()) invalid(where + ": field \"" + k + "\" must be a list of strings, got " + describe(v));
  for (const json& e : v) {
    if (!e.is_string()) invalid(where + ": field \"" + k + "\" must be a list of strings, got " + describe(e));
    out.push_back(e.get<std::string>());
  }
  return out;
}
Eigen::VectorXd Reader::vector(const char* k) const {
  const json& v = at(k);
  if (!v.is_array()) invalid(where + ": field \"" + k + "\" must be a list of numbers, got " + describe(v));
  Eigen::VectorXd x(static_cast<Eigen::Index>(v.size()));
  for (size_t i = 0; i < v.size(); ++i) {
    if (v[i].is_null()) {
      x(static_cast<Eigen::Index>(i)) = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    if (!v[i].is_number())
      invalid(where + ": field \"" + k + "\"[" + std::to_string(i) + "] must be a number, got " + describe(v[i]));
    x(static_cast<Eigen::Index>(i)) = v[i].get<double>();
  }
  return x;
}

}  // namespace spp::io
