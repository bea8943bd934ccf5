#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

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

// What a branch point claims that its system at the parameter value refutes in O(n^2): x0, v0 of the system's n
// dofs, x0 on the obstacle w(mu)^T x0 + g0 = 0 (g0 != 0) and the energy 1/2 v0^T M(mu) v0 + 1/2 x0^T K(mu) x0, each to
// kStateAgreement of its scale (the continuation writes them to rounding). Empty when it agrees. Shared by the writer
// (another system's result, Python's to_json(system=other), is refused as SolveResult's is) and the reader (an edited
// embedded system or point). A point whose orbit is undefined (x0 not finite) is checked for its size only.
std::string point_mismatch(const ParametricSystem& s, const BranchPoint& p) {
  // 1e-8 refused spp's own files of ill-conditioned systems (cond M 1e10: energies agree to 1.2e-8; found by an
  // attack); an edit of the state or of the system at the 1e-6 level still shows
  constexpr double kStateAgreement = 1e-6;
  if (p.x0.size() != s.n() || p.v0.size() != s.n())
    return "expected x0 and v0 of the system's " + std::to_string(s.n()) + " dofs, got " + std::to_string(p.x0.size()) +
           " and " + std::to_string(p.v0.size());
  if (!p.x0.allFinite() || !p.v0.allFinite()) return "";
  // (an empty part does not depend on the parameter)
  const Eigen::VectorXd w = s.w_mu().size() ? Eigen::VectorXd(s.w_constant() + p.mu * s.w_mu()) : s.w_constant();
  const Eigen::MatrixXd M = s.M_mu().size() ? Eigen::MatrixXd(s.M_constant() + p.mu * s.M_mu()) : s.M_constant();
  const Eigen::MatrixXd K = s.K_mu().size() ? Eigen::MatrixXd(s.K_constant() + p.mu * s.K_mu()) : s.K_constant();
  // (g0 = 0: eq. 5.2 leaves the scale free and the orbit reaches the obstacle only at a gap closure, closure 0)
  const double gap = w.dot(p.x0) + s.g0();
  if (s.g0() != 0.0 && !(std::abs(gap) <= kStateAgreement * (w.norm() * p.x0.norm() + std::abs(s.g0()))))
    return "x0 is not on the obstacle of the system at " + s.parameter().name + " = " + num(p.mu) + " (gap " +
           num(gap) + ", expected 0)";
  const double e = 0.5 * p.v0.dot(M * p.v0) + 0.5 * p.x0.dot(K * p.x0);
  if (!(std::abs(p.energy - e) <= kStateAgreement * e))
    return "field \"energy\" is " + num(p.energy) + " but 1/2 v0^T M v0 + 1/2 x0^T K x0 of the system at " +
           s.parameter().name + " = " + num(p.mu) + " is " + num(e) + ": expected " + num(e) + ", got " + num(p.energy);
  return "";
}

// A point's own values: the parameter in its range (to rounding), t1, t2 > 0 and finite, period 2 (t1 + t2), energy
// finite >= 0, spectral radius >= 0 or null; then point_mismatch. Each read silently before (t1 -3, t1 null, k2
// beyond its range, x0 of length 1, a negative energy: issue 11 attack).
void check_point(const Reader& o, const ParametricSystem& s, const BranchPoint& p, bool state_claimed = true) {
  const Parameter& par = s.parameter();
  const double slack = kSameToRounding * std::max({1.0, std::abs(par.min), std::abs(par.max)});
  if (!(p.mu >= par.min - slack && p.mu <= par.max + slack))
    invalid(o.where + ": field \"" + par.name + "\": expected a value in the parameter's range [" + num(par.min) +
            ", " + num(par.max) + "], got " + num(p.mu));
  if (!(p.t1 > 0.0 && p.t2 > 0.0 && std::isfinite(p.t1) && std::isfinite(p.t2)))
    invalid(o.where + ": fields \"t1\" and \"t2\": expected positive finite numbers, got " + num(p.t1) + " and " +
            num(p.t2));
  if (!(std::abs(p.period - 2.0 * (p.t1 + p.t2)) <= kSameToRounding * 2.0 * (p.t1 + p.t2)))
    invalid(o.where + ": field \"period\": expected 2 (t1 + t2) = " + num(2.0 * (p.t1 + p.t2)) + ", got " +
            num(p.period));
  if (!(p.energy >= 0.0 && std::isfinite(p.energy)))
    invalid(o.where + ": field \"energy\": expected a finite number >= 0, got " + num(p.energy));
  if (!(std::isnan(p.spectral_radius) || (p.spectral_radius >= 0.0 && std::isfinite(p.spectral_radius))))
    invalid(o.where + ": field \"spectral_radius\": expected a finite number >= 0 or null, got " +
            num(p.spectral_radius));
  if (!state_claimed) return;
  if (const std::string why = point_mismatch(s, p); !why.empty()) invalid(o.where + ": " + why);
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
  // the result must be this system's (as result_to_json: Python's to_json(system=other) wrote another system's
  // file; issue 11 attack)
  for (size_t b = 0; b < r.branches.size(); ++b) {
    std::vector<const BranchPoint*> points;
    for (const BranchPoint& q : r.branches[b].points) points.push_back(&q);
    // (a gap closure's point is the normalised direction of an orbit whose amplitude diverges, x0 off the obstacle:
    // checking it refused every continuation through a gap closure at g0 != 0; found by an attack)
    for (const BranchEvent& e : r.branches[b].events)
      if (e.kind != BranchEventKind::GapClosure) points.push_back(&e.at);
    for (size_t i = 0; i < points.size(); ++i)
      if (const std::string why = point_mismatch(s, *points[i]); !why.empty())
        invalid("continuation_to_json: branch " + std::to_string(b) + ", point " + std::to_string(i) +
                " (its points, then its events): " + why + ": the result is another system's");
  }
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
  // what continuation_to_json writes and nothing else, as the solve-result reader (an unknown field was dropped)
  check_fields(j, {"system", "symmetry", "window", "warnings", "status", "stats", "branches"}, where);
  if (!r.at("window").is_object())
    invalid(where + ": field \"window\" must be an object with t1_min, t1_max, t2_min, t2_max, got " +
            describe(r.at("window")));
  check_fields(r.at("window"), {"t1_min", "t1_max", "t2_min", "t2_max"}, where + ": field \"window\"");
  if (!r.at("stats").is_object())
    invalid(where + ": field \"stats\" must be an object of counts, got " + describe(r.at("stats")));
  check_fields(r.at("stats"),
               {"seed_spps", "incomplete_seed_solves", "stalled_branches", "unlisted_crossings", "seed_crossings",
                "corrector_solves", "seconds"},
               where + ": field \"stats\"");
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
  for (const auto& [lo_key, hi_key] : {std::make_pair("t1_min", "t1_max"), std::make_pair("t2_min", "t2_max")}) {
    const double lo = win.number(lo_key), hi = win.number(hi_key);
    if (!(lo >= 0.0 && lo < hi && std::isfinite(hi)))
      invalid(where + ": field \"window\": expected 0 <= " + lo_key + " < " + hi_key + " < inf, got " + lo_key + " = " +
              num(lo) + " and " + hi_key + " = " + num(hi));
  }
  if (!(res.seconds >= 0.0))
    invalid(where + ": field \"stats\": field \"seconds\" must be >= 0, got " + num(res.seconds));
  // continue_branches' status: "success" exactly when no seed solve was incomplete, no branch stalled and every seed
  // crossing was listed (and then it writes no warning); "success" beside stalled_branches 3 or a warning was read
  if (res.status == ContinuationStatus::Success && (res.incomplete_seed_solves != 0 || res.stalled_branches != 0 ||
                                                    res.unlisted_crossings != 0 || !res.warnings.empty()))
    invalid(where + ": field \"status\" is \"success\" but the file has " + std::to_string(res.incomplete_seed_solves) +
            " incomplete seed solves, " + std::to_string(res.stalled_branches) + " stalled branches, " +
            std::to_string(res.unlisted_crossings) + " unlisted crossings and " + std::to_string(res.warnings.size()) +
            " warnings: expected none of them, or status \"incomplete\"");
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
        // clang-format off
        check_fields(a[i], {par.c_str(), "t1", "t2", "period", "closure", "energy", "x0", "v0", "margin",
                            "admissible", "spectral_radius", "spectral_radius_error"}, o.where,
                     {"event", "detail", "crossing", "crossing_multipliers", "crossing_angle"});
        // clang-format on
        if (list[0] == 'p') {
          if (a[i].contains("event")) invalid(o.where + ": field \"event\" belongs to \"events\", got it on a point");
          br.points.push_back(point_from_json(o, par));
          check_point(o, s, br.points.back());
          continue;
        }
        BranchEvent e;
        e.at = point_from_json(o, par);
        e.kind = named(o, "event", kinds);
        check_point(o, s, e.at, e.kind != BranchEventKind::GapClosure);
        e.detail = o.text("detail");
        crossing_from_json(o, e);
        br.events.push_back(std::move(e));
      }
    }
    check_fields(bs[b], {"points", "events"}, bw);
    // one branch listed twice (continue_branches traces each once: a seed crossing on a traced branch is matched,
    // not traced again); a duplicated branch was read as two (issue 11 attack)
    for (size_t k = 0; k < res.branches.size(); ++k) {
      const std::vector<BranchPoint>& q = res.branches[k].points;
      const auto same = [](const BranchPoint& x, const BranchPoint& y) {
        return x.mu == y.mu && x.t1 == y.t1 && x.t2 == y.t2;
      };
      if (!q.empty() && q.size() == br.points.size() && same(q.front(), br.points.front()) &&
          same(q.back(), br.points.back()))
        invalid(bw + ": expected each branch once, got the points of \"branches\"[" + std::to_string(k) + "] again");
    }
    res.branches.push_back(std::move(br));
  }
  long stalled_events = 0;
  for (const Branch& b : res.branches)
    for (const BranchEvent& e : b.events) stalled_events += e.kind == BranchEventKind::Stalled;
  if (stalled_events != res.stalled_branches)
    invalid(where + ": field \"stats\": field \"stalled_branches\" counts the \"stalled\" events of the branches, " +
            std::to_string(stalled_events) + ": expected " + std::to_string(stalled_events) + ", got " +
            std::to_string(res.stalled_branches));
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
    o["state_tolerance"] = c.state_tolerance;  // the tolerances it was checked with (docs/result-files.md)
    o["return_tolerance"] = c.return_tolerance;
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
  out["unchecked"] = r.unchecked;  // a stopped run's SPPs not checked (status interrupted), and those beyond:
  if (r.beyond_simulator_limit > 0) out["beyond_simulator_limit"] = r.beyond_simulator_limit;  // (status incomplete)
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
