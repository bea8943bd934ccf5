#include "spp/io/system_file.hpp"

#include <cmath>
#include <filesystem>

#include "io/json.hpp"
#include "spp/core/names.hpp"
#include "spp/io/files.hpp"
#include "spp/io/matrix_market.hpp"

namespace spp::io {

namespace fs = std::filesystem;

namespace {
// Longest "description" a system file may hold, in bytes: a paragraph or a few (the name's limit is kMaxNameBytes,
// core/names.hpp). Documented in the README.
constexpr size_t kMaxDescriptionBytes = 65536;

void check_description(const std::string& description, const std::string& where) {
  check_text(description, where, kMaxDescriptionBytes, /*line_breaks=*/true, "a description is a few paragraphs");
}

double g0_field(const json& j, const std::string& where) {
  if (!j.contains("g0"))
    invalid(where + ": missing field \"g0\": expected the gap at rest, a number, got no such field");
  if (!j.at("g0").is_number()) invalid(where + ": field \"g0\" must be a number, got " + describe(j.at("g0")));
  return j.at("g0").get<double>();
}

// "name" and "description" are optional strings: any other value is refused, not ignored (a list there was taken
// silently, however deep).
std::string name_field(const json& j, const std::string& where) {
  for (const char* k : {"name", "description"})
    if (j.contains(k) && !j.at(k).is_string())
      invalid(where + ": field \"" + k + "\" must be a string, got " + describe(j.at(k)));
  // the checks of the constructors (core/names.hpp), naming the file; tabs and line breaks kept in the description
  if (j.contains("name")) check_name(j.at("name").get_ref<const std::string&>(), where + ": field \"name\"");
  if (j.contains("description"))
    check_description(j.at("description").get_ref<const std::string&>(), where + ": field \"description\"");
  return j.contains("name") ? j.at("name").get<std::string>() : "";
}

// {"constant": A, "<name>": B} -> (A, B); a plain value -> (value, empty).
template <typename Read>
auto affine_field(const json& j, const char* key, const std::string& name, const std::string& where, Read read) {
  using T = decltype(read(j, key, where));
  if (!j.contains(key)) invalid(where + ": missing field \"" + key + "\": expected it, got no such field");
  const json& v = j.at(key);
  if (v.is_object() && v.contains("constant")) {
    for (const auto& [k, _] : v.items())
      if (k != "constant" && k != name)
        invalid(where + ": field \"" + key + "\" has a part \"" + k + "\": expected only \"constant\" and \"" + name +
                "\" (the declared parameter)");
    const std::string part = where + ": field \"" + key + "\"";  // errors name both, e.g. "K": "k2"[0][1]
    T c = read(v, "constant", part);
    T m = v.contains(name) ? read(v, name.c_str(), part) : T();
    return std::make_pair(std::move(c), std::move(m));
  }
  return std::make_pair(read(j, key, where), T());
}

}  // namespace

namespace {
// A system file's fields, or also a result's embedded system's (embedded_system_to_json) when `embedded`.
System system_fields(const json& j, const std::string& where, const std::string& dir, bool embedded) {
  if (!j.is_object()) invalid(where + ": expected a JSON object with fields M, K, w, g0");
  if (embedded)
    check_fields(j, {"name", "description", "M", "K", "w", "g0", "n", "w_normalized", "w_input_norm"}, where);
  else if (const char* k = j.contains("n")              ? "n"
                           : j.contains("w_input_norm") ? "w_input_norm"
                           : j.contains("w_normalized") ? "w_normalized"
                                                        : nullptr)
    invalid(where + ": field \"" + k +
            "\" belongs to the system a result file embeds, not to a system file "
            "(expected name, description, M, K, w, g0): remove it, or give the result file itself where a result is "
            "taken");
  else
    check_fields(j, {"name", "description", "M", "K", "w", "g0"}, where);
  // w first: its length is n, refused beyond the dense solver's reach before M and K (maybe Matrix Market files of
  // gigabytes) are read
  Eigen::VectorXd w = vector_field(j, "w", where);
  if (w.size() > kMaxDenseDofs)
    invalid(where + ": field \"w\" has " + std::to_string(w.size()) + " entries: a system of more than " +
            std::to_string(kMaxDenseDofs) +
            " dofs is beyond the dense solver (its O(n^3) modal form would take half an hour or more); reduce it "
            "first: spp reduce " +
            where + " --modes m --out REDUCED.json");
  const long n = static_cast<long>(w.size());
  Eigen::MatrixXd M = matrix_field(j, "M", where, dir, n);
  Eigen::MatrixXd K = matrix_field(j, "K", where, dir, n);
  const double g0 = g0_field(j, where);
  std::string name = name_field(j, where);  // (outside the try: its message already names the file)
  try {
    return System(std::move(M), std::move(K), std::move(w), g0, std::move(name));
  } catch (const std::invalid_argument& e) {
    invalid(where + ": " + e.what());
  }
}
}  // namespace

System system_from_json(const json& j, const std::string& where, const std::string& dir) {
  return system_fields(j, where, dir, false);
}

json embedded_system_to_json(const System& s) {
  json j = system_to_json(s);
  j["n"] = s.n();
  j["w_normalized"] = s.w_input_norm() != 1.0;
  j["w_input_norm"] = s.w_input_norm();
  return j;
}

System embedded_system_from_json(const json& j, const std::string& where) {
  const System s = system_fields(j, where, ".", true);
  const Reader js{j, where};
  if (j.contains("n") && js.integer("n") != s.n())
    invalid(where + ": field \"n\" must be the size of M, K and w, " + std::to_string(s.n()) + ", got " +
            std::to_string(js.integer("n")));
  if (!j.contains("w_input_norm")) {
    if (j.contains("w_normalized"))
      invalid(where +
              ": field \"w_normalized\" given without \"w_input_norm\": expected both or neither, got only "
              "\"w_normalized\"");
    return s;
  }
  const double norm = js.number("w_input_norm");
  if (!(norm > 0.0 && std::isfinite(norm)))
    invalid(where + ": field \"w_input_norm\" must be |w| as given, a positive finite number, got " + num(norm));
  if (j.contains("w_normalized") && js.boolean("w_normalized") != (norm != 1.0))
    invalid(where + ": field \"w_normalized\" must be " + (norm != 1.0 ? "true" : "false") +
            " (w_input_norm = " + num(norm) + "), got " + (js.boolean("w_normalized") ? "true" : "false"));
  // w and g0 as stored (already divided by |w|: normalising them again moves them by an ulp), and the input's |w|.
  try {
    return System::normalized(s.M(), s.K(), js.vector("w"), js.number("g0"), norm, s.name());
  } catch (const std::invalid_argument& e) {
    invalid(where + ": " + e.what());
  }
}

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

bool declares_parameter(const json& j) {
  return j.is_object() && j.contains("parameter");
}

ParametricSystem parametric_system_from_json(const json& j, const std::string& where, const std::string& dir) {
  if (!j.is_object()) invalid(where + ": expected a JSON object with fields M, K, w, g0, parameter");
  if (!j.contains("parameter"))
    invalid(where +
            ": no field \"parameter\": expected one (e.g. \"parameter\": {\"name\": \"k2\", \"min\": 1, "
            "\"max\": 10}), got a system without a parameter");
  const json& p = j.at("parameter");
  if (!p.is_object() || !p.contains("name") || !p.at("name").is_string() || p.at("name").get<std::string>().empty())
    invalid(where + ": field \"parameter\" must be {\"name\": \"...\", \"min\": number, \"max\": number}");
  check_fields(j, {"name", "description", "M", "K", "w", "g0", "parameter"}, where);
  check_fields(p, {"name", "min", "max"}, where + ": field \"parameter\"");
  Parameter par;
  par.name = p.at("name").get<std::string>();
  check_name(par.name, where + ": field \"parameter\": field \"name\"");  // (as the constructor checks it)
  for (const char* k : {"min", "max"})
    if (!p.contains(k) || !p.at(k).is_number())
      invalid(where + ": field \"parameter\" needs the number \"" + std::string(k) + "\": expected a number, got " +
              (p.contains(k) ? describe(p.at(k)) : std::string("no such field")));
  par.min = p.at("min").get<double>();
  par.max = p.at("max").get<double>();
  if (par.name == "constant")
    invalid(where +
            ": the parameter cannot be named \"constant\": expected another name (\"constant\" is the key of "
            "the constant parts of M, K and w), got \"constant\"");
  // w first: its length is n, which a Matrix Market file's size line must match before it is read
  auto vec = [&](const json& o, const char* k, const std::string& at) { return vector_field(o, k, at); };
  auto [w0, w1] = affine_field(j, "w", par.name, where, vec);
  const long n = static_cast<long>(w0.size());
  auto mat = [&](const json& o, const char* k, const std::string& at) { return matrix_field(o, k, at, dir, n); };
  auto [M0, M1] = affine_field(j, "M", par.name, where, mat);
  auto [K0, K1] = affine_field(j, "K", par.name, where, mat);
  const double g0 = g0_field(j, where);
  std::string name = name_field(j, where);  // (outside the try: its message already names the file)
  try {
    return ParametricSystem(std::move(M0), std::move(M1), std::move(K0), std::move(K1), std::move(w0), std::move(w1),
                            g0, par, std::move(name));
  } catch (const std::invalid_argument& e) {
    invalid(where + ": " + e.what());
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

}  // namespace spp::io

namespace spp {

namespace {
// The declared parameter's name for a message: "?" when "parameter" is no object with a string "name" (json::value
// threw json::type_error on a number there, not a message naming the field).
std::string parameter_name(const io::json& p) {
  if (!p.is_object() || !p.contains("name") || !p.at("name").is_string()) return "?";
  return io::shorten(p.at("name").get<std::string>());
}
}  // namespace

System load_system(const std::string& path) {
  const io::json j = io::read_json_file(path);
  if (io::declares_parameter(j))
    io::invalid(path + ": declares the parameter \"" + parameter_name(j.at("parameter")) +
                "\" (a parametric system): use spp continue, or spp solve --at VALUE (or with g0 = 0 spp solve alone)");
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return io::system_from_json(j, path, dir.empty() ? "." : dir);
}

ParametricSystem load_parametric_system(const std::string& path) {
  const io::json j = io::read_json_file(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return io::parametric_system_from_json(j, path, dir.empty() ? "." : dir);
}

bool file_declares_parameter(const std::string& path) {
  return io::declares_parameter(io::read_json_file(path));
}

std::vector<std::string> system_file_inputs(const std::string& path) {
  if (path.empty()) return {};
  std::vector<std::string> files = {path};
  const io::json j = io::read_json_file(path);
  if (!j.is_object()) return files;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(path).parent_path();
  auto add = [&](const io::json& v) {  // {"matrix_market": "file.mtx"}, relative to the system file
    if (!v.is_object() || !v.contains("matrix_market") || !v.at("matrix_market").is_string()) return;
    fs::path p = v.at("matrix_market").get<std::string>();
    files.push_back((p.is_relative() ? dir / p : p).string());
  };
  for (const char* key : {"M", "K"}) {
    if (!j.contains(key)) continue;
    add(j.at(key));
    if (j.at(key).is_object())  // the parts of a parametric matrix ({"constant": ..., "k2": ...})
      for (const auto& [_, part] : j.at(key).items()) add(part);
  }
  return files;
}

namespace {
Eigen::SparseMatrix<double> sparse_matrix_field(const io::json& j, const char* key, const std::string& where,
                                                const std::string& dir, long n) {
  if (!j.contains(key)) io::invalid(where + ": missing field \"" + key + "\": expected it, got no such field");
  const io::json& v = j.at(key);
  if (!v.is_object()) return io::matrix_field(j, key, where, dir).sparseView();  // a (small) list of rows
  if (!v.contains("matrix_market") || !v.at("matrix_market").is_string())
    io::invalid(where + ": field \"" + key + "\" must be a list of rows or {\"matrix_market\": \"file.mtx\"}");
  io::check_fields(v, {"matrix_market"}, where + ": field \"" + key + "\"");
  const std::string p = io::matrix_market_path(v, key, where, dir);
  try {
    return read_sparse_matrix_market(p, n);
  } catch (const std::invalid_argument& e) {
    io::invalid(where + ": field \"" + key + "\": " + e.what());
  }
}
}  // namespace

SparseSystem load_sparse_system(const std::string& path) {
  const io::json j = io::read_json_file(path);
  if (io::declares_parameter(j))
    io::invalid(path + ": declares a parameter (a parametric system): spp reduce takes a system without one");
  if (!j.is_object()) io::invalid(path + ": expected a JSON object with fields M, K, w, g0");
  io::check_fields(j, {"name", "description", "M", "K", "w", "g0"}, path);
  const std::string d = std::filesystem::path(path).parent_path().string();
  const std::string dir = d.empty() ? "." : d;
  // w first: its length fixes n, which each Matrix Market file's size line must match before it is read
  Eigen::VectorXd w = io::vector_field(j, "w", path);
  const long n = static_cast<long>(w.size());
  Eigen::SparseMatrix<double> M = sparse_matrix_field(j, "M", path, dir, n);
  Eigen::SparseMatrix<double> K = sparse_matrix_field(j, "K", path, dir, n);
  if (!j.contains("g0"))
    io::invalid(path + ": missing field \"g0\": expected the gap at rest, a number, got no such field");
  if (!j.at("g0").is_number()) io::invalid(path + ": field \"g0\" must be a number, got " + io::describe(j.at("g0")));
  std::string name = io::name_field(j, path);  // (the same checks as a dense system's)
  try {
    return SparseSystem(std::move(M), std::move(K), std::move(w), j.at("g0").get<double>(), name);
  } catch (const std::invalid_argument& e) {
    io::invalid(path + ": " + e.what());
  }
}

std::vector<std::string> sparse_system_matrix_files(const std::string& json_path) {
  namespace fs = std::filesystem;
  const fs::path p(json_path);
  const fs::path stem = p.parent_path() / p.stem();
  return {stem.string() + ".M.mtx", stem.string() + ".K.mtx"};
}

void write_sparse_system(const SparseSystem& system, const std::string& json_path, const std::string& description) {
  namespace fs = std::filesystem;
  io::check_description(description, "write_sparse_system: description");  // (what the reader takes back)
  const std::vector<std::string> files = sparse_system_matrix_files(json_path);
  const std::string comment = system.name() + ", n = " + std::to_string(system.n());
  const std::string m_text = matrix_market_text(system.M(), true, "M of " + comment);
  const std::string k_text = matrix_market_text(system.K(), true, "K of " + comment);
  io::json j;
  j["name"] = system.name();
  if (!description.empty()) j["description"] = description;
  j["M"] = {{"matrix_market", fs::path(files[0]).filename().string()}};
  j["K"] = {{"matrix_market", fs::path(files[1]).filename().string()}};
  j["w"] = io::vector_json(system.w());
  j["g0"] = system.g0();
  const std::string json_text = j.dump(2) + "\n";
  write_file_atomic(files[0], m_text);
  write_file_atomic(files[1], k_text);
  write_file_atomic(json_path, json_text);
}

std::string system_json(const System& system, int indent) {
  return io::system_to_json(system).dump(indent) + "\n";
}

std::string parametric_system_json(const ParametricSystem& system, int indent) {
  return io::parametric_system_to_json(system).dump(indent) + "\n";
}

}  // namespace spp
