#include "spp/io/csv.hpp"

#include <sstream>

#include "io/text.hpp"

namespace spp {

using io::invalid;
using io::num;

namespace {
// A yes/no column as true/false: pandas.read_csv reads such a column as bool (1/0 read as int64; found by an
// independent attack), numpy and the csv module read the text as it is, and R's read.csv as logical.
const char* yes_no(bool b) {
  return b ? "true" : "false";
}
}  // namespace

std::string result_to_csv(const SolveResult& r) {
  std::ostringstream os;
  os << "t1,t2,period,admissible,min_gap,min_force,energy,residual,return_error,spectral_radius,stable,"
        "spectral_radius_error,stability_verdict";
  const int n = r.solutions.empty() ? 0 : static_cast<int>(r.solutions[0].orbit.x0.size());
  for (int i = 1; i <= n; ++i) os << ",x0_" << i;
  for (int i = 1; i <= n; ++i) os << ",v0_" << i;
  os << "\n";
  for (const Solution& x : r.solutions) {
    os << num(x.t1()) << "," << num(x.t2()) << "," << num(x.period()) << "," << yes_no(x.admissible()) << ","
       << num(x.min_gap()) << "," << num(x.min_force()) << "," << num(x.energy()) << "," << num(x.residual) << ","
       << num(x.return_error) << "," << num(x.floquet.spectral_radius) << "," << yes_no(x.stable()) << ","
       << num(x.floquet.spectral_radius_error) << "," << to_string(x.floquet.verdict);
    for (int i = 0; i < n; ++i) os << "," << num(x.orbit.x0(i));
    for (int i = 0; i < n; ++i) os << "," << num(x.orbit.v0(i));
    os << "\n";
  }
  return os.str();
}

void check_trajectory_csv_size(long samples, long n, const std::string& what) {
  const double values = static_cast<double>(samples) * (2.0 * static_cast<double>(n) + 3.0);
  if (samples < 2 || values > kMaxCsvValues) {
    std::ostringstream os;
    os << what << ": expected 2 to " << static_cast<long>(kMaxCsvValues / (2.0 * static_cast<double>(n) + 3.0))
       << " samples for a " << n << "-dof system (at most " << kMaxCsvValues << " values, samples x (2n + 3), in one "
       << "CSV, ~0.5 GB of text), got " << samples;
    invalid(os.str());
  }
}

std::string trajectory_csv(const ModalForm& md, const Orbit& o, int samples) {
  check_trajectory_csv_size(samples, md.n(), "trajectory_csv: samples");
  std::ostringstream os;
  const int n = md.n();
  os << "t";
  for (int i = 1; i <= n; ++i) os << ",x" << i;
  for (int i = 1; i <= n; ++i) os << ",v" << i;
  os << ",gap,force\n";
  const OrbitSamples s = sample_orbit(md, o, samples);
  for (int k = 0; k < samples; ++k) {
    os << num(s.t(k));
    for (int i = 0; i < n; ++i) os << "," << num(s.x(k, i));
    for (int i = 0; i < n; ++i) os << "," << num(s.v(k, i));
    os << "," << num(s.gap(k)) << "," << num(s.force(k)) << "\n";
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
    os << "," << num(s.gap) << "," << num(s.force) << "," << yes_no(s.in_contact) << "\n";
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

}  // namespace spp
