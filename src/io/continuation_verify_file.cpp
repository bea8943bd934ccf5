#include <cmath>

#include "io/json.hpp"
#include "spp/io/continuation_file.hpp"
#include "spp/io/verify_file.hpp"

namespace spp::io {

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
  j["spectral_radius"] = std::isfinite(p.spectral_radius) ? json(p.spectral_radius) : json(nullptr);
  return j;
}
}  // namespace

json continuation_to_json(const ParametricSystem& s, const ContinuationResult& r) {
  json j;
  j["system"] = parametric_system_to_json(s);
  j["symmetry"] = to_string(r.symmetry);
  j["window"] = {{"t1_min", r.t1_min}, {"t1_max", r.t1_max}, {"t2_min", r.t2_min}, {"t2_max", r.t2_max}};
  j["warnings"] = r.warnings;
  j["status"] = to_string(r.status);
  j["stats"] = {{"seed_spps", r.seed_spps},
                {"incomplete_seed_solves", r.incomplete_seed_solves},
                {"stalled_branches", r.stalled_branches},
                {"unlisted_crossings", r.unlisted_crossings},
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

json zero_gap_to_json(const ParametricSystem& s, const ContinuationResult& r) {
  json j;
  j["system"] = parametric_system_to_json(s);
  j["window"] = {{"t1_min", r.t1_min}, {"t1_max", r.t1_max}, {"t2_min", r.t2_min}, {"t2_max", r.t2_max}};
  j["status"] = to_string(r.status);
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

json verify_to_json(const VerifyResult& r) {
  json checks = json::array();
  for (const SppCheck& c : r.checks) {
    json o = {{"t1", c.spp.t1()},
              {"t2", c.spp.t2()},
              {"period", c.spp.period()},
              {"admissible", c.spp.admissible()},
              {"verdict", to_string(c.verdict)},
              {"consistent", c.consistent},
              {"return_errors", c.return_errors},
              {"impacts", c.impacts},
              {"contact_onsets", c.contact_onsets},
              {"releases", c.releases}};
    o["periods_followed"] = c.periods_followed;
    if (std::isfinite(c.potential_return_error)) o["potential_return_error"] = c.potential_return_error;
    if (!c.departure.empty()) o["departure"] = {{"t", c.departure_time}, {"what", c.departure}};
    if (!c.perturbed_distances.empty()) {
      o["perturbed_distances"] = c.perturbed_distances;
      o["growth_per_period"] = c.growth_per_period;
    }
    checks.push_back(o);
  }
  return {{"status", to_string(r.status)},  {"checks", checks},
          {"returned", r.returned},         {"left", r.left},
          {"inconsistent", r.inconsistent}, {"all_consistent", r.all_consistent()}};
}

}  // namespace spp::io

namespace spp {

std::string continuation_json(const ParametricSystem& system, const ContinuationResult& result, int indent) {
  return io::continuation_to_json(system, result).dump(indent) + "\n";
}

std::string zero_gap_json(const ParametricSystem& system, const ContinuationResult& result, int indent) {
  return io::zero_gap_to_json(system, result).dump(indent) + "\n";
}

std::string verify_json(const VerifyResult& result, int indent) {
  return io::verify_to_json(result).dump(indent) + "\n";
}

}  // namespace spp
