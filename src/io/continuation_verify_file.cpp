#include <array>
#include <cmath>
#include <limits>
#include <numbers>

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
  // null: not computed (NaN) or unbounded (infinite), read back as NaN
  j["spectral_radius_error"] = std::isfinite(p.spectral_radius_error) ? json(p.spectral_radius_error) : json(nullptr);
  return j;
}

BranchPoint point_from_json(const Reader& o, const std::string& parameter) {
  BranchPoint p;
  p.mu = o.number(parameter.c_str());
  p.t1 = o.number("t1");
  p.t2 = o.number("t2");
  p.period = o.number("period");
  p.closure = o.number("closure");
  p.energy = o.number("energy");
  p.x0 = o.vector("x0");
  p.v0 = o.vector("v0");
  p.margin = o.number("margin");  // null: NaN
  p.admissible = o.boolean("admissible");
  // (absent from files written before stability was computed along branches)
  p.spectral_radius = o.o.contains("spectral_radius") ? o.number("spectral_radius")
                                                      : std::numeric_limits<double>::quiet_NaN();
  // (absent from files written before it was computed)
  p.spectral_radius_error = o.o.contains("spectral_radius_error") ? o.number("spectral_radius_error")
                                                                  : std::numeric_limits<double>::quiet_NaN();
  return p;
}

template <class E, size_t N>
E named(const Reader& o, const char* field, const std::array<E, N>& all) {
  const std::string v = o.text(field);
  std::string list;
  for (const E k : all) {
    if (v == to_string(k)) return k;
    list += std::string(list.empty() ? "" : ", ") + to_string(k);
  }
  invalid(o.where + ": field \"" + field + "\" must be one of " + list + ", got \"" + v.substr(0, 40) + "\"");
}

// A stability event's crossing: absent from files written before it (then None); a real crossing has one real
// multiplier of the right sign, a pair two conjugate ones, the angle in [0, pi].
void crossing_from_json(const Reader& o, BranchEvent& e) {
  if (!o.o.contains("crossing")) return;
  if (e.kind != BranchEventKind::StabilityLost && e.kind != BranchEventKind::StabilityGained)
    invalid(o.where + ": field \"crossing\" belongs to stability events only, got it on a " + to_string(e.kind) +
            " event");
  e.crossing =
      named(o, "crossing",
            std::array{MultiplierCrossing::PlusOne, MultiplierCrossing::MinusOne, MultiplierCrossing::ComplexPair});
  const json& zs = o.at("crossing_multipliers");
  const std::string zw = o.where + ": field \"crossing_multipliers\"";
  if (!zs.is_array()) invalid(zw + " must be a list of [re, im] pairs, got " + describe(zs));
  for (size_t k = 0; k < zs.size(); ++k) {
    if (!zs[k].is_array() || zs[k].size() != 2 || !zs[k][0].is_number() || !zs[k][1].is_number())
      invalid(zw + "[" + std::to_string(k) + "] must be [re, im], got " + describe(zs[k]));
    e.crossing_multipliers.emplace_back(zs[k][0].get<double>(), zs[k][1].get<double>());
  }
  e.crossing_angle = o.number("crossing_angle");
  const auto& z = e.crossing_multipliers;
  const bool pair = e.crossing == MultiplierCrossing::ComplexPair;
  const bool ok = pair ? z.size() == 2 && z[0].imag() > 0.0 && z[1] == std::conj(z[0])
                       : z.size() == 1 && z[0].imag() == 0.0 &&
                             (e.crossing == MultiplierCrossing::PlusOne) == (z[0].real() > 0.0);
  if (!ok)
    invalid(zw + " must be " + (pair ? "a conjugate pair (positive imaginary part first)" : "one real multiplier") +
            " of the sign that field \"crossing\" \"" + to_string(e.crossing) + "\" names, got " +
            std::to_string(z.size()) + " value(s)");
  if (!(std::abs(e.crossing_angle - std::abs(std::arg(z[0]))) <= 1e-15 * std::numbers::pi))
    invalid(o.where + ": field \"crossing_angle\" must be |arg| of the crossing multiplier, " +
            num(std::abs(std::arg(z[0]))) + ", got " + num(e.crossing_angle));
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
      if (e.crossing != MultiplierCrossing::None) {  // stability events: which multiplier crosses, and where
        je["crossing"] = to_string(e.crossing);
        json zs = json::array();
        for (const auto& z : e.crossing_multipliers) zs.push_back({z.real(), z.imag()});
        je["crossing_multipliers"] = zs;
        je["crossing_angle"] = e.crossing_angle;
      }
      jb["events"].push_back(je);
    }
    branches.push_back(jb);
  }
  j["branches"] = branches;
  return j;
}

ParametricSystem continuation_system(const json& j, const std::string& where) {
  if (!j.is_object() || !j.contains("system") || !j.contains("branches"))
    invalid(where + ": expected a result of spp continue (fields \"system\" and \"branches\")");
  return parametric_system_from_json(j.at("system"), where + ": field \"system\"");
}

ContinuationResult continuation_from_json(const json& j, const std::string& where, const ParametricSystem& s) {
  const Reader r{j, where};
  ContinuationResult res;
  res.parameter = s.parameter();
  const std::string& par = res.parameter.name;
  res.symmetry = named(r, "symmetry", std::array{Symmetry::Axial, Symmetry::Point});
  res.status = named(r, "status", std::array{ContinuationStatus::Success, ContinuationStatus::Incomplete});
  const Reader win{r.at("window"), where + ": field \"window\""};
  res.t1_min = win.number("t1_min");
  res.t1_max = win.number("t1_max");
  res.t2_min = win.number("t2_min");
  res.t2_max = win.number("t2_max");
  res.warnings = r.texts("warnings");
  const Reader st{r.at("stats"), where + ": field \"stats\""};
  res.seed_spps = st.count("seed_spps");
  res.incomplete_seed_solves = st.count("incomplete_seed_solves");
  res.stalled_branches = st.count("stalled_branches");
  res.unlisted_crossings = st.count("unlisted_crossings");
  res.seed_crossings = st.count("seed_crossings");
  res.corrector_solves = st.count("corrector_solves");
  res.seconds = st.number("seconds");
  const json& bs = r.at("branches");
  if (!bs.is_array()) invalid(where + ": field \"branches\" must be a list, got " + describe(bs));
  const auto kinds = std::array{BranchEventKind::LeavesWindow,        BranchEventKind::RangeEnd,
                                BranchEventKind::Fold,                BranchEventKind::AdmissibilityLost,
                                BranchEventKind::AdmissibilityGained, BranchEventKind::GapClosure,
                                BranchEventKind::ClosedLoop,          BranchEventKind::Stalled,
                                BranchEventKind::StabilityLost,       BranchEventKind::StabilityGained};
  for (size_t b = 0; b < bs.size(); ++b) {
    const std::string bw = where + ": field \"branches\"[" + std::to_string(b) + "]";
    const Reader rb{bs[b], bw};
    Branch br;
    for (const char* list : {"points", "events"}) {
      const json& a = rb.at(list);
      if (!a.is_array()) invalid(bw + ": field \"" + list + "\" must be a list, got " + describe(a));
      for (size_t i = 0; i < a.size(); ++i) {
        const Reader o{a[i], bw + ": field \"" + list + "\"[" + std::to_string(i) + "]"};
        if (!a[i].is_object()) invalid(o.where + " must be an object, got " + describe(a[i]));
        if (list[0] == 'p') {
          br.points.push_back(point_from_json(o, par));
          continue;
        }
        BranchEvent e;
        e.at = point_from_json(o, par);
        e.kind = named(o, "event", kinds);
        e.detail = o.text("detail");
        crossing_from_json(o, e);
        br.events.push_back(std::move(e));
      }
    }
    res.branches.push_back(std::move(br));
  }
  return res;
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
  json out = {{"status", to_string(r.status)},  {"checks", checks},
          {"returned", r.returned},         {"left", r.left},
          {"inconsistent", r.inconsistent}, {"all_consistent", r.all_consistent()}};
  // the three kinds of inconsistency, as Python's VerifyResult has them (they were missing here: issue 14's attack)
  out["admissibility_mismatches"] = r.admissibility_mismatches;
  out["stability_mismatches"] = r.stability_mismatches;
  out["state_mismatches"] = r.state_mismatches;
  if (!r.warnings.empty()) out["warnings"] = r.warnings;
  return out;
}

}  // namespace spp::io

namespace spp {

std::string continuation_json(const ParametricSystem& system, const ContinuationResult& result, int indent) {
  return io::continuation_to_json(system, result).dump(indent) + "\n";
}

ContinuationFile load_continuation_file(const std::string& path) {
  const io::json j = io::read_json_file(path);
  ParametricSystem s = io::continuation_system(j, path);
  ContinuationResult r = io::continuation_from_json(j, path, s);
  return {std::move(s), std::move(r)};
}

ContinuationFile parse_continuation_file(const std::string& text, const std::string& where) {
  const io::json j = io::parse_json_text(text, where);
  ParametricSystem s = io::continuation_system(j, where);
  ContinuationResult r = io::continuation_from_json(j, where, s);
  return {std::move(s), std::move(r)};
}

std::string zero_gap_json(const ParametricSystem& system, const ContinuationResult& result, int indent) {
  return io::zero_gap_to_json(system, result).dump(indent) + "\n";
}

std::string verify_json(const VerifyResult& result, int indent) {
  return io::verify_to_json(result).dump(indent) + "\n";
}

}  // namespace spp
