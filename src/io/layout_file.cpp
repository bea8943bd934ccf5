#include "spp/io/layout_file.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "io/json.hpp"

namespace spp {

FeLayout read_fe_layout(const std::string& path, long model_dofs) {
  const io::json j = io::read_json_file(path);
  const std::string where = io::shorten(path, io::kQuotedPathChars);
  if (!j.is_object()) io::invalid(where + ": expected a JSON object (a layout file), got " + io::describe(j));
  io::check_fields(j, {"dofs", "coordinates", "directions", "basis", "model_dofs"}, where);
  FeLayout l;
  const io::Reader r{j, where};
  if (j.contains("model_dofs")) {
    l.model_dofs = r.count("model_dofs");
    if (l.model_dofs != model_dofs)
      io::invalid(where + ": field \"model_dofs\": expected the layout of this model of " + std::to_string(model_dofs) +
                  " dofs, got the layout of a model of " + std::to_string(l.model_dofs));
  }
  const Eigen::VectorXd dofs = r.vector("dofs");
  if (dofs.size() == 0) io::invalid(where + ": field \"dofs\": expected at least one dof, got none");
  std::set<long> seen;
  for (Eigen::Index i = 0; i < dofs.size(); ++i) {
    const double d = dofs(i);
    if (!(d >= 0 && d < static_cast<double>(model_dofs) && d == std::floor(d)))
      io::invalid(where + ": field \"dofs\"[" + std::to_string(i) + "]: expected a whole number from 0 to " +
                  std::to_string(model_dofs - 1) + " (0-based dofs of the model), got " + io::num(d));
    if (!seen.insert(static_cast<long>(d)).second)
      io::invalid(where + ": field \"dofs\"[" + std::to_string(i) + "]: expected each dof once, got dof " +
                  io::num(d) + " again");
    l.dofs.push_back(static_cast<long>(d));
  }
  const auto rows_of = [&](const char* key, Eigen::Index lo, Eigen::Index hi) {
    Eigen::MatrixXd A = io::matrix_field(j, key, where, std::filesystem::path(path).parent_path().string());
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
    if (l.directions.row(i).norm() == 0)
      io::invalid(where + ": field \"directions\"[" + std::to_string(i) + "]: expected a direction, got zero");
  if (j.contains("basis")) l.basis = rows_of("basis", 1, std::numeric_limits<Eigen::Index>::max());
  return l;
}

std::string fe_layout_json(const FeLayout& layout) {
  io::json j;
  j["dofs"] = layout.dofs;
  j["coordinates"] = io::matrix_json(layout.coordinates);
  j["directions"] = io::matrix_json(layout.directions);
  if (layout.basis.size() > 0) j["basis"] = io::matrix_json(layout.basis);
  if (layout.model_dofs > 0) j["model_dofs"] = layout.model_dofs;
  return j.dump(-1) + "\n";
}

FeLayout sample_fe_layout(const FeLayout& layout, long max_rows) {
  const long n = static_cast<long>(layout.dofs.size());
  if (n <= max_rows) return layout;
  std::vector<Eigen::Index> keep;
  for (long k = 0; k < max_rows; ++k) keep.push_back((k * (n - 1)) / (max_rows - 1));
  FeLayout s;
  s.model_dofs = layout.model_dofs;
  for (const Eigen::Index r : keep) s.dofs.push_back(layout.dofs[static_cast<size_t>(r)]);
  s.coordinates = layout.coordinates(keep, Eigen::all);
  s.directions = layout.directions(keep, Eigen::all);
  if (layout.basis.size() > 0) s.basis = layout.basis(keep, Eigen::all);
  return s;
}

}  // namespace spp
