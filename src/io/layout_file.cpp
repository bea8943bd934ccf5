#include "spp/io/layout_file.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "io/json.hpp"

namespace spp {

namespace {
FeLayout layout_of(const io::json& j, const std::string& where, const std::string& dir, long model_dofs) {
  if (!j.is_object()) io::invalid(where + ": expected a JSON object (a layout file), got " + io::describe(j));
  io::check_fields(j, {"dofs", "coordinates", "directions", "basis", "model_dofs", "model_fingerprint"}, where);
  FeLayout l;
  const io::Reader r{j, where};
  if (j.contains("model_dofs")) {
    l.model_dofs = r.count("model_dofs");
    if (l.model_dofs < 1)
      io::invalid(where + ": field \"model_dofs\": expected a positive whole number, got " +
                  std::to_string(l.model_dofs));
    if (model_dofs >= 0 && l.model_dofs != model_dofs)
      io::invalid(where + ": field \"model_dofs\": expected the layout of this model of " + std::to_string(model_dofs) +
                  " dofs, got the layout of a model of " + std::to_string(l.model_dofs));
  }
  if (j.contains("model_fingerprint")) {
    l.fingerprint = r.vector("model_fingerprint");
    if (l.fingerprint.size() != 5 || !l.fingerprint.allFinite())
      io::invalid(where +
                  ": field \"model_fingerprint\": expected 5 finite numbers (spp reduce --layout writes it), "
                  "got " +
                  std::to_string(l.fingerprint.size()));
  }
  // (model_dofs < 0: not known, the file's own bound or none)
  const double bound = model_dofs >= 0 ? static_cast<double>(model_dofs)
                                       : (l.model_dofs > 0 ? static_cast<double>(l.model_dofs)
                                                           : std::numeric_limits<double>::infinity());
  const Eigen::VectorXd dofs = r.vector("dofs");
  if (dofs.size() == 0) io::invalid(where + ": field \"dofs\": expected at least one dof, got none");
  std::set<long> seen;
  for (Eigen::Index i = 0; i < dofs.size(); ++i) {
    const double d = dofs(i);
    if (!(d >= 0 && d < bound && d == std::floor(d)))
      io::invalid(where + ": field \"dofs\"[" + std::to_string(i) + "]: expected a whole number from 0" +
                  (std::isfinite(bound) ? " to " + io::num(bound - 1) : std::string(" up")) +
                  " (0-based dofs of the model), got " + io::num(d));
    if (!seen.insert(static_cast<long>(d)).second)
      io::invalid(where + ": field \"dofs\"[" + std::to_string(i) + "]: expected each dof once, got dof " +
                  io::num(d) + " again");
    l.dofs.push_back(static_cast<long>(d));
  }
  const auto rows_of = [&](const char* key, Eigen::Index lo, Eigen::Index hi) {
    Eigen::MatrixXd A = io::matrix_field(j, key, where, dir);
    if (A.rows() != dofs.size())
      io::invalid(where + ": field \"" + key + "\": expected one row per entry of \"dofs\" (" +
                  std::to_string(dofs.size()) + "), got " + std::to_string(A.rows()));
    if (A.cols() < lo || A.cols() > hi)
      io::invalid(where + ": field \"" + key + "\": expected rows of " + std::to_string(lo) +
                  (hi > lo ? " to " + std::to_string(hi) : "") + " numbers, got " + std::to_string(A.cols()));
    if (!A.allFinite()) io::invalid(where + ": field \"" + key + "\": expected finite numbers, got NaN or inf");
    return A;
  };
  l.coordinates = rows_of("coordinates", 1, 3);
  l.directions = rows_of("directions", l.coordinates.cols(), l.coordinates.cols());
  for (Eigen::Index i = 0; i < l.directions.rows(); ++i)
    if (l.directions.row(i).cwiseAbs().maxCoeff() == 0)  // (not norm(): it underflows to 0 for a direction of 1e-300)
      io::invalid(where + ": field \"directions\"[" + std::to_string(i) + "]: expected a direction, got zero");
  if (j.contains("basis")) l.basis = rows_of("basis", 1, std::numeric_limits<Eigen::Index>::max());
  return l;
}

// The weights of model_fingerprint: cos(1 + k), k the entry's index (row-major for a matrix).
double weight(Eigen::Index k) {
  return std::cos(1.0 + static_cast<double>(k));
}
}  // namespace

FeLayout read_fe_layout(const std::string& path, long model_dofs) {
  return layout_of(io::read_json_file(path), io::shorten(path, io::kQuotedPathChars),
                   std::filesystem::path(path).parent_path().string(), model_dofs);
}

FeLayout parse_fe_layout(const std::string& text, const std::string& where, long model_dofs) {
  return layout_of(io::parse_json_text(text, where), where, ".", model_dofs);
}

Eigen::VectorXd model_fingerprint(const System& system) {
  const long n = system.n();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(5);
  f(0) = static_cast<double>(n);
  for (long i = 0; i < n; ++i) {
    for (long k = 0; k < n; ++k) {
      f(1) += weight(i * n + k) * system.M()(i, k);
      f(2) += weight(i * n + k) * system.K()(i, k);
    }
    f(3) += weight(i) * system.w()(i);
  }
  f(4) = system.g0();
  return f;
}

bool same_fingerprint(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const System& system) {
  if (a.size() != 5 || b.size() != 5 || a(0) != b(0)) return false;
  constexpr double kTol = 1e-9;
  const double scale[] = {system.M().cwiseAbs().sum(), system.K().cwiseAbs().sum(), system.w().cwiseAbs().sum(),
                          std::abs(system.g0())};
  for (int i = 1; i < 5; ++i)
    if (!(std::abs(a(i) - b(i)) <= kTol * std::max(scale[i - 1], std::abs(a(i))))) return false;
  return true;
}

void check_fe_layout(const FeLayout& layout, const System& system, const std::string& layout_where,
                     const std::string& system_where) {
  const long n = system.n();
  const std::string both = layout_where + " is not a layout of " + system_where + ": ";
  if (layout.basis.size() == 0) {
    if (layout.model_dofs > 0 && layout.model_dofs != n)
      io::invalid(both + "expected a layout of a model of " + std::to_string(n) + " dofs, got field \"model_dofs\" " +
                  std::to_string(layout.model_dofs));
    for (size_t r = 0; r < layout.dofs.size(); ++r)
      if (layout.dofs[r] >= n)
        io::invalid(both + "field \"dofs\"[" + std::to_string(r) + "]: expected 0-based dofs of the system (0 to " +
                    std::to_string(n - 1) + "), got " + std::to_string(layout.dofs[r]));
    return;
  }
  if (layout.basis.cols() != n)
    io::invalid(both + "field \"basis\": expected rows of " + std::to_string(n) + " numbers (the system's dofs), got " +
                std::to_string(layout.basis.cols()) + ": the layout of another reduced model");
  if (layout.fingerprint.size() > 0 && !same_fingerprint(layout.fingerprint, model_fingerprint(system), system))
    io::invalid(both +
                "field \"model_fingerprint\": expected the fingerprint of this reduced model (of its M, K, "
                "w, g0), got another's: the layout of another reduced model with as many dofs (spp reduce writes "
                "each reduced model's layout beside it, OUT.layout.json)");
}

std::string fe_layout_json(const FeLayout& layout) {
  io::json j;
  j["dofs"] = layout.dofs;
  j["coordinates"] = io::matrix_json(layout.coordinates);
  j["directions"] = io::matrix_json(layout.directions);
  if (layout.basis.size() > 0) j["basis"] = io::matrix_json(layout.basis);
  if (layout.model_dofs > 0) j["model_dofs"] = layout.model_dofs;
  if (layout.fingerprint.size() > 0) j["model_fingerprint"] = io::vector_json(layout.fingerprint);
  return j.dump(-1) + "\n";
}

FeLayout sample_fe_layout(const FeLayout& layout, long max_rows) {
  const long n = static_cast<long>(layout.dofs.size());
  if (n <= max_rows) return layout;
  std::vector<Eigen::Index> keep;
  for (long k = 0; k < max_rows; ++k) keep.push_back((k * (n - 1)) / (max_rows - 1));
  FeLayout s;
  s.model_dofs = layout.model_dofs;
  s.fingerprint = layout.fingerprint;
  for (const Eigen::Index r : keep) s.dofs.push_back(layout.dofs[static_cast<size_t>(r)]);
  s.coordinates = layout.coordinates(keep, Eigen::all);
  s.directions = layout.directions(keep, Eigen::all);
  if (layout.basis.size() > 0) s.basis = layout.basis(keep, Eigen::all);
  return s;
}

}  // namespace spp
