#pragma once
// JSON of every io type (private: nlohmann is not part of spp's public headers). Readers name the file and the field
// they cannot read; writers give what the readers read back.

#include <Eigen/Dense>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/text.hpp"
#include "spp/continuation/continuation.hpp"
#include "spp/core/parametric.hpp"
#include "spp/core/system.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/verify.hpp"

namespace spp::io {

using json = nlohmann::json;

/// A value named in an error message, never echoed whole: nested or long input (a 100 000-deep array) is described,
/// not dumped (json::dump recurses: a stack overflow).
std::string describe(const json& v);
/// Refuses any field not in `known` (nor in `also`, accepted silently), naming it and listing `known`.
void check_fields(const json& j, std::initializer_list<const char*> known, const std::string& where,
                  std::initializer_list<const char*> also = {});
void check_fields(const json& j, const std::vector<const char*>& known, const std::string& where,
                  std::initializer_list<const char*> also = {});
/// Parses a JSON file; malformed JSON and a key given twice in one object are refused, naming the file.
json read_json_file(const std::string& path);
/// The same from text; `path` names it in errors.
json parse_json_text(const std::string& text, const std::string& path);

json matrix_json(const Eigen::MatrixXd& A);
json vector_json(const Eigen::VectorXd& v);
/// A field "key" of j: a list of rows (or {"matrix_market": "file.mtx"}, relative to dir) / a list of numbers.
/// expected_size >= 0: a Matrix Market file must declare that size (checked before its n^2 doubles are allocated).
/// The path of {"matrix_market": "file.mtx"} (v, the field `key`), relative to dir; a control character in it (a NUL
/// would cut it short) or an empty path is refused, naming the field.
std::string matrix_market_path(const json& v, const char* key, const std::string& where, const std::string& dir);
Eigen::MatrixXd matrix_field(const json& j, const char* key, const std::string& where, const std::string& dir,
                             long expected_size = -1);
Eigen::VectorXd vector_field(const json& j, const char* key, const std::string& where);

/// Reads the fields of one JSON object, each naming where it is when it cannot. Doubles written as null (NaN) read
/// back as NaN.
struct Reader {
  const json& o;
  std::string where;
  const json& at(const char* k) const;
  double number(const char* k) const;
  long integer(const char* k) const;
  /// A count: a whole number from 0 to max (the range of the field it is read into), refused naming k otherwise.
  long count(const char* k, long max = std::numeric_limits<long>::max()) const;
  bool boolean(const char* k) const;
  std::string text(const char* k) const;
  std::vector<std::string> texts(const char* k) const;
  Eigen::VectorXd vector(const char* k) const;
};

System system_from_json(const json& j, const std::string& where, const std::string& dir = ".");
json system_to_json(const System& system);
/// The system a result file embeds: system_to_json plus "n", "w_normalized", "w_input_norm" (w and g0 stored already
/// divided by |w|); read back to the same System, each of the three checked against M, K, w.
json embedded_system_to_json(const System& system);
System embedded_system_from_json(const json& j, const std::string& where);
bool declares_parameter(const json& j);
ParametricSystem parametric_system_from_json(const json& j, const std::string& where, const std::string& dir = ".");
json parametric_system_to_json(const ParametricSystem& system);

json result_to_json(const System& system, const SolveResult& result);
SolveResult result_from_json(const json& result, const std::string& where);
System result_system(const json& result, const std::string& where);

json continuation_to_json(const ParametricSystem& system, const ContinuationResult& result);
/// What continuation_to_json wrote (every field; `system` is the file's own, continuation_system).
ContinuationResult continuation_from_json(const json& result, const std::string& where, const ParametricSystem& system);
ParametricSystem continuation_system(const json& result, const std::string& where);
json zero_gap_to_json(const ParametricSystem& system, const ContinuationResult& result);
json verify_to_json(const VerifyResult& result);

}  // namespace spp::io
