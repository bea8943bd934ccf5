#include "io/json.hpp"

#include <cstdint>
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
  // A UTF-8 byte-order mark opening the text is accepted (nlohmann skips it; editors on Windows write one). A NUL
  // byte anywhere is not: nlohmann's lexer takes it for the end of the input, so "{...}\0garbage" parsed as "{...}"
  // (found by an independent attack). Other trailing text is refused by the parser, its byte offset added.
  if (const size_t at = text.find('\0'); at != std::string::npos)
    invalid(path + ": expected JSON text, got a NUL byte at byte offset " + std::to_string(at) +
            " (a binary file, or text followed by padding?)");
  json j;
  try {
    j = json::parse(text, seen);
  } catch (const json::parse_error& e) {
    invalid(path + ": malformed JSON at byte offset " + std::to_string(e.byte == 0 ? 0 : e.byte - 1) + ": " +
            shorten(e.what(), kMaxParserMessage));
  } catch (const json::exception& e) {
    // nlohmann quotes the offending token whole ("number overflow parsing '1000...'" with 100 000 digits): shortened
    invalid(path + ": malformed JSON: " + shorten(e.what(), kMaxParserMessage));
  } catch (const TooDeep&) {
    invalid(path + ": expected JSON nested at most " + std::to_string(kMaxJsonDepth) +
            " levels deep (lists in lists, objects in objects), got deeper");
  }
  if (!duplicate.empty())
    invalid(path + ": the key \"" + duplicate + "\" appears twice in one object: expected each key once, got it twice");
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

std::string matrix_market_path(const json& v, const char* key, const std::string& where, const std::string& dir) {
  const std::string& given = v.at("matrix_market").get_ref<const std::string&>();
  // a NUL ends a C string: "K.mtx\u0000junk" opened K.mtx silently (found by an independent attack); any control
  // character is refused the same way (no file name of a system is meant to hold one)
  for (size_t i = 0; i < given.size(); ++i) {
    const auto c = static_cast<unsigned char>(given[i]);
    if (c < 0x20 || c == 0x7f)
      invalid(where + ": field \"" + key +
              "\": field \"matrix_market\": expected a file path of printable "
              "characters, got the control character " +
              std::to_string(static_cast<int>(c)) + " at byte " + std::to_string(i) +
              (c == 0 ? " (a NUL byte, which would cut the path short)" : ""));
  }
  if (given.empty())
    invalid(where + ": field \"" + key + "\": field \"matrix_market\": expected a file path, got the empty string");
  fs::path p = given;
  if (p.is_relative()) p = fs::path(dir) / p;
  return p.string();
}

Eigen::MatrixXd matrix_field(const json& j, const char* key, const std::string& where, const std::string& dir,
                             long expected_size) {
  if (!j.contains(key)) invalid(where + ": missing field \"" + key + "\": expected it, got no such field");
  const json& v = j.at(key);
  if (v.is_object()) {
    if (!v.contains("matrix_market") || !v.at("matrix_market").is_string())
      invalid(where + ": field \"" + key + "\" must be a list of rows or {\"matrix_market\": \"file.mtx\"}");
    check_fields(v, {"matrix_market"}, where + ": field \"" + key + "\"");
    const std::string p = matrix_market_path(v, key, where, dir);
    try {
      return read_matrix_market(p, expected_size);
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
  if (!j.contains(key)) invalid(where + ": missing field \"" + key + "\": expected it, got no such field");
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
  if (!o.is_object() || !o.contains(k))
    invalid(where + ": missing field \"" + k + "\": expected it, got no such field");
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
  // nlohmann holds 2^63 .. 2^64 - 1 as unsigned: get<long> wrapped 2^63 to a negative number (found by an independent
  // attack)
  if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<long>::max()))
    invalid(where + ": field \"" + k + "\" must be an integer from " +
            std::to_string(std::numeric_limits<long>::min()) + " to " +
            std::to_string(std::numeric_limits<long>::max()) + ", got " + v.dump());
  return v.get<long>();
}
long Reader::count(const char* k, long max) const {
  const json& v = at(k);
  const std::string rule = "a count, a whole number from 0 to " + std::to_string(max);
  if (!v.is_number_integer()) invalid(where + ": field \"" + k + "\" must be " + rule + ", got " + describe(v));
  const bool in_range = v.is_number_unsigned() ? v.get<std::uint64_t>() <= static_cast<std::uint64_t>(max)
                                               : v.get<std::int64_t>() >= 0 && v.get<std::int64_t>() <= max;
  if (!in_range) invalid(where + ": field \"" + k + "\" must be " + rule + ", got " + v.dump());
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
