#include "spp/io/result_file.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <type_traits>
#include <vector>

#include "io/json.hpp"
#include "search/tolerances.hpp"

namespace spp::io {

namespace {

// Dofs of the system a result embeds (rows of its M), or -1 when it holds none.
long embedded_dofs(const json& r) {
  if (!r.contains("system") || !r.at("system").is_object() || !r.at("system").contains("M")) return -1;
  const json& M = r.at("system").at("M");
  return M.is_array() ? static_cast<long>(M.size()) : -1;
}

// What every SPP of a result must satisfy to be used: positive half-durations, and x0, v0 of the system's size.
void check_solution(const Reader& o, double t1, double t2, const Eigen::VectorXd& x0, const Eigen::VectorXd& v0,
                    long n) {
  if (!(t1 > 0.0 && t2 > 0.0 && std::isfinite(t1) && std::isfinite(t2)))
    invalid(o.where + ": t1 and t2 must be positive and finite, got " + num(t1) + " and " + num(t2));
  if (n >= 0 && (x0.size() != n || v0.size() != n))
    invalid(o.where + ": x0 and v0 must have " + std::to_string(n) + " entries (the system's dofs), got " +
            std::to_string(x0.size()) + " and " + std::to_string(v0.size()));
}

// Every count of a result's "stats" by its key, for f(key, member) on a SolveResult (const or not): the one list
// that result_json writes, check_result checks and result_from_json reads.
template <class Result, class F>
void for_each_count(Result& r, F f) {
  f("flight_pole_lines", r.stats.flight_pole_lines);
  f("contact_pole_lines", r.stats.contact_pole_lines);
  f("rectangles", r.stats.rectangles);
  f("curve_pieces", r.stats.curve_pieces);
  f("roots", r.stats.roots);
  f("evaluations", r.stats.evaluations);
  f("strip_pairs", r.stats.strip_pairs);
  f("certified_steps", r.stats.certified_steps);
  f("heuristic_steps", r.stats.heuristic_steps);
  f("uncertified_steps", r.stats.uncertified_steps);
  f("uncertified_corners", r.stats.uncertified_corners);
  f("unpaired_crossings", r.stats.unpaired_crossings);
  f("unresolved_pieces", r.stats.unresolved_pieces);
  f("unpolished_roots", r.stats.unpolished_roots);
  f("unsearched_cells", r.stats.unsearched_cells);
  f("pole_line_artifacts", r.stats.pole_line_artifacts);
  f("decoupled_modes", r.decoupled_modes);
  f("repeated_frequency_groups", r.repeated_groups);
}

std::vector<const char*> count_keys() {
  std::vector<const char*> keys;
  const SolveResult none;
  for_each_count(none, [&](const char* key, const auto&) { keys.push_back(key); });
  return keys;
}

// The stability verdict of a solution with multipliers, and its error bound. Files written before the bound have
// neither: their verdict is the old one, spectral_radius < 1 (error NaN: unknown). Otherwise the verdict must be
// the one the radius and the bound give (stability_verdict; "neutral" only with the decoupled modes' radius 1).
void read_verdict(const Reader& o, Floquet& f) {
  const bool has_error = o.o.contains("spectral_radius_error"), has_verdict = o.o.contains("stability_verdict");
  if (has_error != has_verdict)
    invalid(o.where + ": fields \"spectral_radius_error\" and \"stability_verdict\" go together, got only " +
            (has_error ? "the first" : "the second"));
  if (!has_verdict) {
    f.spectral_radius_error = f.location_error = std::numeric_limits<double>::quiet_NaN();
    f.verdict = f.spectral_radius < 1.0 ? StabilityVerdict::Stable : StabilityVerdict::Unstable;
    return;
  }
  const json& e = o.at("spectral_radius_error");
  if (e.is_null())
    f.spectral_radius_error = std::numeric_limits<double>::infinity();
  else if (e.is_number() && e.get<double>() >= 0.0 && std::isfinite(e.get<double>()))
    f.spectral_radius_error = e.get<double>();
  else
    invalid(o.where + ": field \"spectral_radius_error\" must be a number >= 0 or null (unbounded), got " +
            describe(e));
  const std::string v = o.text("stability_verdict");
  const StabilityVerdict all[] = {StabilityVerdict::Stable, StabilityVerdict::Unstable, StabilityVerdict::Undecided,
                                  StabilityVerdict::Neutral};
  const auto it = std::find_if(std::begin(all), std::end(all), [&](StabilityVerdict k) { return v == to_string(k); });
  if (it == std::end(all))
    invalid(o.where + ": field \"stability_verdict\" must be one of stable, unstable, undecided, neutral, got \"" +
            v.substr(0, 40) + "\"");
  f.verdict = *it;
  // the location part of the bound (files written before it have none: NaN, not recorded), at most the bound
  if (o.o.contains("spectral_radius_location_error")) {
    const json& l = o.at("spectral_radius_location_error");
    const bool ok = l.is_null() ? !std::isfinite(f.spectral_radius_error)
                                : l.is_number() && l.get<double>() >= 0.0 && l.get<double>() <= f.spectral_radius_error;
    if (!ok)
      invalid(o.where + ": field \"spectral_radius_location_error\": expected a number from 0 to spectral_radius_error " +
              "(" + num(f.spectral_radius_error) + "), or null with an unbounded spectral_radius_error, got " +
              describe(l));
    f.location_error = l.is_null() ? std::numeric_limits<double>::infinity() : l.get<double>();
  } else {
    f.location_error = std::numeric_limits<double>::quiet_NaN();
  }
  const double rho = f.spectral_radius, err = f.spectral_radius_error;
  const bool consistent = f.verdict == StabilityVerdict::Neutral ? rho == 1.0
                                                                  : f.verdict == stability_verdict(rho, err, false);
  if (!consistent)
    invalid(o.where + ": field \"stability_verdict\" is \"" + v + "\" but spectral_radius " + num(rho) + " +- " +
            num(err) + " gives \"" + to_string(stability_verdict(rho, err, false)) +
            "\" (\"neutral\" needs spectral_radius 1 exactly): expected the verdict they give, got another");
}

// One SPP's values that no solve leaves undefined (written as null they would read as NaN, found by an independent
// review) and its flags (one of kSolutionFlags each).
void check_solution_values(const json& o, const std::string& at) {
  for (const char* k : {"min_gap", "min_force", "energy", "residual", "mid_flight_gap", "mid_contact_force"})
    if (o.contains(k) && !(o.at(k).is_number() && std::isfinite(o.at(k).get<double>())))
      invalid(at + ": field \"" + k + "\": expected a finite number, got " + describe(o.at(k)));
  // -1: not computed (SolveOptions::compute_return_error off); otherwise a relative error, finite and >= 0. A
  // return_error of -5 or null was read as written (issue 11 attack).
  if (o.contains("return_error") &&
      !(o.at("return_error").is_number() &&
        (o.at("return_error").get<double>() == -1.0 ||
         (o.at("return_error").get<double>() >= 0.0 && std::isfinite(o.at("return_error").get<double>())))))
    invalid(at + ": field \"return_error\": expected a finite number >= 0, or -1 (not computed), got " +
            describe(o.at("return_error")));
  for (const char* k : {"energy", "residual"})  // (a sum of squares, a norm)
    if (o.contains(k) && o.at(k).is_number() && o.at(k).get<double>() < 0.0)
      invalid(at + ": field \"" + k + "\": expected a number >= 0, got " + describe(o.at(k)));
  // the solver lists an SPP only once Newton converged (polish: residual below search::kConvergedResidual); a
  // residual of 0.5 was read as an SPP (found by an independent attack)
  if (o.contains("residual") && o.at("residual").is_number() &&
      !(o.at("residual").get<double>() < search::kConvergedResidual))
    invalid(at + ": field \"residual\": expected a number below " + num(search::kConvergedResidual) +
            " (the residual below which the solver accepts a root as an SPP), got " + describe(o.at("residual")));
  for (const char* k : {"x0", "v0"}) {
    if (!o.contains(k) || !o.at(k).is_array()) continue;  // (the reader names a missing or malformed vector)
    const json& v = o.at(k);
    for (size_t i = 0; i < v.size(); ++i)
      if (!(v[i].is_number() && std::isfinite(v[i].get<double>())))
        invalid(at + ": field \"" + k + "\"[" + std::to_string(i) + "]: expected a finite number, got " +
                describe(v[i]));
  }
  // minima over a phase are at most the phase's middle value; an admissible SPP's are >= 0 up to the tolerance of
  // its certified test (orbit.cpp check_admissibility: rel_tol of the gap's or force's amplitude; kAdmissibleSlack is
  // far above it). An admissible SPP with min_gap -0.5 was read silently (found by an independent attack).
  auto value = [&](const char* k) {
    return o.contains(k) && o.at(k).is_number() ? o.at(k).get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  constexpr double kAdmissibleSlack = 1e-6;
  for (const auto& [min_key, mid_key] : {std::make_pair("min_gap", "mid_flight_gap"),
                                         std::make_pair("min_force", "mid_contact_force")}) {
    const double lo = value(min_key), mid = value(mid_key);
    if (lo > mid + kSameToRounding * std::abs(mid))
      invalid(at + ": field \"" + min_key + "\" " + num(lo) + " exceeds field \"" + mid_key + "\" " + num(mid) +
              ": a minimum over the phase is at most its middle value: expected at most " + num(mid) + ", got " +
              num(lo));
    if (o.contains("admissible") && o.at("admissible") == true && lo < -kAdmissibleSlack * std::abs(mid))
      invalid(at + ": field \"admissible\" is true but field \"" + min_key + "\" is " + num(lo) +
              ": expected >= 0 (to " + num(kAdmissibleSlack) + " of \"" + mid_key + "\"), or admissible false");
  }
  if (o.contains("floquet_multipliers") && o.at("floquet_multipliers").is_array()) {  // sorted by modulus
    double last = 0.0;
    const json& mu = o.at("floquet_multipliers");
    for (size_t i = 0; i < mu.size(); ++i) {
      if (!mu[i].is_array() || mu[i].size() != 2 || !mu[i][0].is_number() || !mu[i][1].is_number()) continue;
      const double r = std::hypot(mu[i][0].get<double>(), mu[i][1].get<double>());
      if (r < last * (1.0 - kSameToRounding))
        invalid(at + ": field \"floquet_multipliers\"[" + std::to_string(i) + "] has modulus " + num(r) +
                ", less than the one before it (" + num(last) + "): expected them sorted by modulus");
      last = std::max(last, r);
    }
  }
  if (o.contains("flags") && o.at("flags").is_array())
    for (size_t i = 0; i < o.at("flags").size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (o.at("flags")[i] == o.at("flags")[j])
          invalid(at + ": field \"flags\"[" + std::to_string(i) + "]: " + describe(o.at("flags")[i]) +
                  " is listed twice: expected each flag once, got it twice");
  if (o.contains("flags") && o.at("flags").is_array())
    for (size_t i = 0; i < o.at("flags").size(); ++i) {
      const json& f = o.at("flags")[i];
      const bool known = f.is_string() && std::any_of(kSolutionFlags.begin(), kSolutionFlags.end(), [&](const char* k) {
                           return f.get<std::string>() == k;
                         });
      if (!known) {
        std::string list;
        for (const char* k : kSolutionFlags) list += std::string(list.empty() ? "" : ", ") + k;
        invalid(at + ": field \"flags\"[" + std::to_string(i) + "]: expected one of " + list + ", got " +
                describe(f));
      }
    }
}

// An SPP's onset state is on the obstacle to rounding; a relative gap beyond this means another system's SPP.
constexpr double kOnObstacle = 1e-8;

// The orbit block (modal coordinates of one SPP, orbit/orbit.hpp): a, c, p0, p0dot of one length m, the modes that
// see the contact (1 <= m <= n), a closure ratio in [0, 1] and the SPP's energy (the same number as its "energy").
// Each read silently before (found by an independent attack).
void check_orbit_block(const Reader& ob, const Orbit& b, long n, double energy, double solution_energy) {
  const Eigen::Index m = b.p0.size();
  if (m < 1 || (n >= 0 && m > n) || b.a.size() != m || b.c.size() != m || b.p0dot.size() != m)
    invalid(ob.where + ": expected a, c, p0, p0dot of one length between 1 and the system's " +
            (n >= 0 ? std::to_string(n) : std::string("n")) + " dofs, got " + std::to_string(b.a.size()) + ", " +
            std::to_string(b.c.size()) + ", " + std::to_string(m) + " and " + std::to_string(b.p0dot.size()));
  for (const auto& [key, v] : {std::pair<const char*, const Eigen::VectorXd*>{"a", &b.a}, {"c", &b.c},
                               {"p0", &b.p0}, {"p0dot", &b.p0dot}})
    if (!v->allFinite()) invalid(ob.where + ": field \"" + key + "\": expected finite numbers");
  if (!(b.closure_ratio >= 0.0 && b.closure_ratio <= 1.0 + kSameToRounding))
    invalid(ob.where + ": field \"closure_ratio\": expected a number in [0, 1], got " + num(b.closure_ratio));
  if (!(std::abs(energy - solution_energy) <= kSameToRounding * std::abs(solution_energy)))
    invalid(ob.where + ": field \"energy\" must be the SPP's \"energy\" " + num(solution_energy) + ", got " +
            num(energy));
}

// The stability fields (stability/floquet.hpp): 2n multipliers; spectral_radius their largest modulus once the two
// structural 1s are set aside, >= 0; stability_margin = 1 - spectral_radius. A radius beside an empty list, or a margin
// that contradicts it, was read silently before (found by an independent attack).
void check_floquet(const Reader& o, const Floquet& f, long n) {
  const std::string at = o.where + ": field \"floquet_multipliers\"";
  if (n >= 0 && static_cast<long>(f.multipliers.size()) != 2 * n)
    invalid(at + ": expected 2n = " + std::to_string(2 * n) + " multipliers (the system's " + std::to_string(n) +
            " dofs), got " + std::to_string(f.multipliers.size()));
  for (const auto& z : f.multipliers)
    if (!std::isfinite(z.real()) || !std::isfinite(z.imag())) invalid(at + ": expected finite numbers");
  if (!(f.spectral_radius >= 0.0 && std::isfinite(f.spectral_radius)))
    invalid(o.where + ": field \"spectral_radius\": expected a finite number >= 0, got " + num(f.spectral_radius));
  std::vector<std::complex<double>> rest = f.multipliers;  // set aside the two closest to 1
  for (int k = 0; k < 2 && !rest.empty(); ++k)
    rest.erase(std::min_element(rest.begin(), rest.end(), [](const auto& p, const auto& q) {
      return std::abs(p - 1.0) < std::abs(q - 1.0);
    }));
  double rho = 0.0;
  for (const auto& z : rest) rho = std::max(rho, std::abs(z));
  const double tol = kSameToRounding * std::max(1.0, rho);
  if (!(std::abs(rho - f.spectral_radius) <= tol))
    invalid(o.where + ": field \"spectral_radius\" must be the largest modulus of \"floquet_multipliers\" but the "
                      "two structural 1s, " + num(rho) + ", got " + num(f.spectral_radius));
  if (!(std::abs(f.margin - (1.0 - f.spectral_radius)) <= tol))
    invalid(o.where + ": field \"stability_margin\" must be 1 - spectral_radius = " + num(1.0 - f.spectral_radius) +
            ", got " + num(f.margin));
}

// The leading multipliers (Floquet::leading) from the file's list: the one whose modulus is spectral_radius (a
// positive imaginary part first) and its conjugate when complex. They were left empty, so Python's
// Solution.leading_multipliers read [] after load_result (found by the attack of issue 14). Not for a neutral verdict
// (the radius is then the decoupled modes' 1, not a coupled multiplier's) nor with fewer than three multipliers.
std::vector<std::complex<double>> leading_of(const Floquet& f) {
  if (f.verdict == StabilityVerdict::Neutral || f.multipliers.size() < 3) return {};
  const std::complex<double>* best = nullptr;
  for (const auto& z : f.multipliers) {
    const double d = std::abs(std::abs(z) - f.spectral_radius), db = best ? std::abs(std::abs(*best) - f.spectral_radius) : 0.0;
    if (best == nullptr || d < db || (d == db && z.imag() > best->imag())) best = &z;
  }
  std::vector<std::complex<double>> lead{*best};
  if (best->imag() != 0.0) lead.push_back(std::conj(*best));
  return lead;
}

// What the solver's status means (search/solver.cpp, finalize: "success" exactly when no warning and no uncertified
// region), checked across fields: "success" beside a count of unproved work, a warning or an SPP whose
// admissibility is not certified; "incomplete" with neither warning nor region; fewer roots than SPPs listed (an
// admissible_only solve lists fewer, never more); an SPP outside the window. Each read silently before (found by an
// independent review).
void check_consistency(const json& r, const std::string& where) {
  const bool has_status = r.contains("status") && r.at("status").is_string();
  const std::string status = has_status ? r.at("status").get<std::string>() : "";
  const json none = json::array();
  const json& warnings = r.contains("warnings") && r.at("warnings").is_array() ? r.at("warnings") : none;
  const json& unc = r.contains("uncertified") && r.at("uncertified").is_array() ? r.at("uncertified") : none;
  const json& sols = r.contains("solutions") && r.at("solutions").is_array() ? r.at("solutions") : none;
  const bool has_stats = r.contains("stats") && r.at("stats").is_object();
  if (status == "success") {
    if (!warnings.empty())
      invalid(where + ": field \"status\" is \"success\" but field \"warnings\" has " +
              std::to_string(warnings.size()) + " entr" + (warnings.size() == 1 ? "y" : "ies") +
              ": a search with warnings is \"incomplete\": expected status \"incomplete\", got \"success\"");
    if (has_stats)
      for (const char* k : {"uncertified_steps", "uncertified_corners", "unpaired_crossings", "unresolved_pieces",
                            "unpolished_roots", "unsearched_cells"})
        if (r.at("stats").contains(k) && r.at("stats").at(k).is_number_integer() &&
            r.at("stats").at(k).get<long>() != 0)
          invalid(where + ": field \"status\" is \"success\" but field \"stats\".\"" + k + "\" is " +
                  std::to_string(r.at("stats").at(k).get<long>()) + ": expected 0, or status \"incomplete\"");
    for (size_t i = 0; i < sols.size(); ++i)
      if (sols[i].is_object() && sols[i].contains("admissibility_certified") &&
          sols[i].at("admissibility_certified") == false)
        invalid(where + ": field \"status\" is \"success\" but field \"solutions\"[" + std::to_string(i) +
                "] has \"admissibility_certified\": false: expected true, or status \"incomplete\"");
  } else if (status == "incomplete" && warnings.empty() && unc.empty()) {
    invalid(where + ": field \"status\" is \"incomplete\" but neither \"warnings\" nor \"uncertified\" says why: "
            "expected at least one of them non-empty, or status \"success\"");
  }
  if (has_stats && !sols.empty())  // every SPP lies on a traced curve piece of a rectangle, found by evaluations
    for (const char* k : {"rectangles", "curve_pieces", "evaluations"})
      if (r.at("stats").contains(k) && r.at("stats").at(k).is_number_integer() && r.at("stats").at(k).get<long>() < 1)
        invalid(where + ": field \"stats\".\"" + k + "\" is " + std::to_string(r.at("stats").at(k).get<long>()) +
                " beside " + std::to_string(sols.size()) + " SPP(s) in \"solutions\": expected at least 1");
  if (has_stats && r.at("stats").contains("roots") && r.at("stats").at("roots").is_number_integer()) {
    const long roots = r.at("stats").at("roots").get<long>(), listed = static_cast<long>(sols.size());
    if (roots < listed)
      invalid(where + ": field \"stats\".\"roots\" must count at least the " + std::to_string(listed) +
              " SPP(s) listed in \"solutions\", got " + std::to_string(roots));
    // solve() lists every root it counts (finalize), unless admissible_only drops the non-admissible ones: a file
    // that lists a non-admissible SPP was solved without it and lists them all. One SPP deleted from such a file
    // read as a complete "success" (found by an independent attack).
    const auto inadmissible = std::find_if(sols.begin(), sols.end(), [](const json& o) {
      return o.is_object() && o.contains("admissible") && o.at("admissible") == false;
    });
    if (roots != listed && inadmissible != sols.end())
      invalid(where + ": field \"stats\".\"roots\" is " + std::to_string(roots) + " but field \"solutions\" lists " +
              std::to_string(listed) + " SPP(s), among them the non-admissible \"solutions\"[" +
              std::to_string(inadmissible - sols.begin()) +
              "]: a solve that keeps non-admissible SPPs (admissible_only off) lists every root it counts: expected " +
              std::to_string(roots) + " SPP(s) listed, got " + std::to_string(listed) + " (an SPP deleted?)");
  }
  if (!r.contains("window") || !r.at("window").is_object()) return;
  const Reader win{r.at("window"), where + ": field \"window\""};
  // (a root within rounding of an edge is kept on it: search::kOnEdgeUlps)
  auto outside = [](double t, double lo, double hi) {
    const double slack = kSameToRounding * hi;
    return !(t >= lo - slack && t <= hi + slack);
  };
  double last_period = 0.0;  // solve() lists its SPPs by period
  // solve() keeps one SPP per root: two within search::kSameRoot of the window's size (its own deduplication,
  // solver.cpp polish_candidates) are one SPP listed twice. A duplicated SPP, with roots + 1, was read as two (issue 11
  // attack). Sorted by period, a copy sits among the SPPs of the same period: O(SPPs) for distinct periods.
  const double same_root = search::kSameRoot * (win.number("t1_max") + win.number("t2_max"));
  auto time_of = [](const json& o, const char* k) {
    return o.is_object() && o.contains(k) && o.at(k).is_number() ? o.at(k).get<double>()
                                                                 : std::numeric_limits<double>::quiet_NaN();
  };
  for (size_t i = 0; i < sols.size(); ++i)
    for (size_t j = i; j-- > 0;) {
      const double d1 = time_of(sols[i], "t1") - time_of(sols[j], "t1"),
                   d2 = time_of(sols[i], "t2") - time_of(sols[j], "t2");
      // periods apart (sorted; |d1 + d2| <= sqrt(2) same_root for a copy): no earlier one is as close
      if (!(std::abs(d1 + d2) <= 2.0 * same_root)) break;
      if (std::hypot(d1, d2) <= same_root)
        invalid(where + ": field \"solutions\"[" + std::to_string(i) + "] is at (t1, t2) = (" +
                num(time_of(sols[i], "t1")) + ", " + num(time_of(sols[i], "t2")) + "), the place of \"solutions\"[" +
                std::to_string(j) + "] (within " + num(same_root) +
                ", where spp solve keeps one root): expected each SPP listed once, got one twice");
    }
  for (size_t i = 0; i < sols.size(); ++i) {
    const json& o = sols[i];
    if (o.is_object() && o.contains("period") && o.at("period").is_number()) {
      const double period = o.at("period").get<double>();
      if (period < last_period)
        invalid(where + ": field \"solutions\"[" + std::to_string(i) + "] has period " + num(period) +
                ", less than the one before it (" + num(last_period) + "): expected the SPPs sorted by period, as "
                "spp solve writes them");
      last_period = period;
    }
    if (!o.is_object() || !o.contains("t1") || !o.contains("t2") || !o.at("t1").is_number() ||
        !o.at("t2").is_number())
      continue;  // (named by the reader)
    const double t1 = o.at("t1").get<double>(), t2 = o.at("t2").get<double>();
    if (!(t1 > 0.0 && t2 > 0.0)) continue;  // (named by check_solution)
    if (outside(t1, win.number("t1_min"), win.number("t1_max")) ||
        outside(t2, win.number("t2_min"), win.number("t2_max")))
      invalid(where + ": field \"solutions\"[" + std::to_string(i) + "] at (t1, t2) = (" + num(t1) + ", " + num(t2) +
              ") is outside the field \"window\" (" + num(win.number("t1_min")) + ", " + num(win.number("t1_max")) +
              "] x (" + num(win.number("t2_min")) + ", " + num(win.number("t2_max")) +
              "]: expected an SPP of the window, got one outside it");
  }
}

// What result_to_json writes and nothing else: an unknown field is refused, not ignored (a misspelt field was read as
// absent), and so is a value that contradicts another (a period other than 2 (t1 + t2), "success" beside uncertified
// regions, an empty window, a negative count; all read silently before, found by an independent review). Fields
// missing are left to the readers, which name them.
void check_result(const json& r, const std::string& where) {
  // the g0 = 0 solve's file (gap closures along a parameter, paper §6.1) is another kind of result: said so, not
  // "unknown field" (found by an independent attack)
  if (r.contains("normalization"))
    invalid(where + ": this is the result of a g0 = 0 solve (SPPs at gap closures along the parameter, paper §6.1), "
                    "not of a solve at g0 != 0: expected the result of spp solve on a system with g0 != 0 (its "
                    "solutions are read with Python's json, or followed with spp continue)");
  check_fields(r, {"system", "window", "status", "symmetry", "warnings", "stats", "uncertified", "solutions"}, where);
  if (r.contains("window")) {
    const std::string at = where + ": field \"window\"";
    if (!r.at("window").is_object())
      invalid(at + " must be an object with t1_min, t1_max, t2_min, t2_max, got " + describe(r.at("window")));
    check_fields(r.at("window"), {"t1_min", "t1_max", "t2_min", "t2_max"}, at);
    const Reader win{r.at("window"), at};
    for (const auto& [lo_key, hi_key] : {std::make_pair("t1_min", "t1_max"), std::make_pair("t2_min", "t2_max")}) {
      const double lo = win.number(lo_key), hi = win.number(hi_key);
      // (solve() reports the lower ends it searched from, filled in and raised to the axis bands: never 0)
      if (!(lo > 0.0 && lo < hi && std::isfinite(hi)))
        invalid(at + ": expected 0 < " + lo_key + " < " + hi_key + " < inf, got " + lo_key + " = " + num(lo) + " and " +
                hi_key + " = " + num(hi));
    }
  }
  if (r.contains("stats")) {
    const std::string at = where + ": field \"stats\"";
    const json& st = r.at("stats");
    if (!st.is_object()) invalid(at + " must be an object of counts, got " + describe(st));
    const std::vector<const char*> counts = count_keys();
    check_fields(st, counts, at, {"seconds"});
    const Reader sr{st, at};
    // each count within the range of the field it is read into (an int or a long of SolveResult)
    SolveResult none;
    for_each_count(none, [&](const char* k, const auto& count) {
      if (st.contains(k)) sr.count(k, std::numeric_limits<std::remove_cvref_t<decltype(count)>>::max());
    });
    if (st.contains("seconds") && !(sr.number("seconds") >= 0.0))
      invalid(at + ": field \"seconds\" must be >= 0, got " + num(sr.number("seconds")));
  }
  if (r.contains("uncertified") && r.at("uncertified").is_array()) {
    const json& unc = r.at("uncertified");
    for (size_t i = 0; i < unc.size(); ++i) {
      const std::string at = where + ": field \"uncertified\"[" + std::to_string(i) + "]";
      if (!unc[i].is_object()) invalid(at + " must be an object, got " + describe(unc[i]));
      check_fields(unc[i], {"t1_lo", "t1_hi", "t2_lo", "t2_hi", "cause"}, at);
      const Reader u{unc[i], at};
      const std::string cause = u.text("cause");
      bool known = false;
      std::string list;
      for (const char* c : kUncertifiedCauses) {
        known = known || cause == c;
        list += std::string(list.empty() ? "" : ", ") + c;
      }
      if (!known) invalid(at + ": field \"cause\" must be one of " + list + ", got \"" + shorten(cause) + "\"");
      if (!(u.number("t1_lo") <= u.number("t1_hi") && u.number("t2_lo") <= u.number("t2_hi")))
        invalid(at + ": expected t1_lo <= t1_hi and t2_lo <= t2_hi, got (" + num(u.number("t1_lo")) + ", " +
                num(u.number("t1_hi")) + ") and (" + num(u.number("t2_lo")) + ", " + num(u.number("t2_hi")) + ")");
    }
    if (!unc.empty() && r.contains("status") && r.at("status") == "success")
      invalid(where + ": field \"status\" is \"success\" but field \"uncertified\" lists " +
              std::to_string(unc.size()) +
              " region(s): a search with uncertified regions is \"incomplete\": "
              "expected status \"incomplete\", got \"success\"");
  }
  if (r.contains("solutions") && r.at("solutions").is_array()) {
    const json& sols = r.at("solutions");
    for (size_t i = 0; i < sols.size(); ++i) {
      const std::string at = where + ": field \"solutions\"[" + std::to_string(i) + "]";
      const json& o = sols[i];
      if (!o.is_object()) invalid(at + " must be an object, got " + describe(o));
      // (the last seven: stability/floquet.hpp, absent from files written before it; the last two from files written
      // before the verdict's error bound)
      // clang-format off
      check_fields(o, {"t1", "t2", "period", "admissible", "min_gap", "min_force", "x0", "v0", "energy", "residual",
                       "return_error", "mid_flight_gap", "mid_contact_force", "onset_force_rate",
                       "admissibility_certified", "admissibility_ends_ok", "flags", "orbit", "obstacle_velocity",
                       "floquet_multipliers", "spectral_radius", "stability_margin", "stable",
                       "floquet_structure_residual", "spectral_radius_error", "spectral_radius_location_error",
                       "stability_verdict"}, at);
      // clang-format on
      if (o.contains("orbit")) {
        if (!o.at("orbit").is_object())
          invalid(at + ": field \"orbit\" must be an object, got " + describe(o.at("orbit")));
        check_fields(o.at("orbit"), {"a", "c", "p0", "p0dot", "closure_ratio", "energy"}, at + ": field \"orbit\"");
      }
      check_solution_values(o, at);
      if (o.contains("period") && o.contains("t1") && o.contains("t2")) {
        const Reader so{o, at};
        const double t1 = so.number("t1"), t2 = so.number("t2"), period = so.number("period");
        const double expected = 2.0 * (t1 + t2);  // one flight and one contact phase, each 2 t_i (eq. 2.4)
        // (t1, t2 not positive and finite: refused by check_solution, naming them)
        if (t1 > 0.0 && t2 > 0.0 && std::isfinite(expected) &&
            !(std::abs(period - expected) <= kSameToRounding * expected))
          invalid(at + ": field \"period\" must be 2 (t1 + t2) = " + num(expected) + ", got " + num(period));
      }
    }
  }
  check_consistency(r, where);
}

}  // namespace

json result_to_json(const System& s, const SolveResult& r) {
  // the result must be this system's: a file that embeds one system beside another's SPPs would read back as nonsense
  // (Python's to_json(system) wrote one, found by an independent attack). Each SPP's x0 has the system's size and,
  // when axial, starts on this system's obstacle (gap 0 to rounding), O(n) per SPP.
  for (size_t i = 0; i < r.solutions.size(); ++i) {
    const Orbit& o = r.solutions[i].orbit;
    const std::string at = "result_to_json: solution " + std::to_string(i);
    if (o.x0.size() != s.n() || o.v0.size() != s.n())
      invalid(at + ": expected x0 and v0 of the system's " + std::to_string(s.n()) + " dofs, got " +
              std::to_string(o.x0.size()) + " and " + std::to_string(o.v0.size()) +
              ": the result is another system's");
    const double gap = s.w().dot(o.x0) + s.g0();
    if (o.symmetry == Symmetry::Axial && !(std::abs(gap) <= kOnObstacle * (s.w().norm() * o.x0.norm() + std::abs(s.g0()))))
      invalid(at + ": its x0 is not on this system's obstacle (gap " + num(gap) + ", expected 0): the result is "
                   "another system's");
  }
  json j;
  auto vec = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  j["system"] = embedded_system_to_json(s);
  j["window"] = {{"t1_min", r.t1_min}, {"t1_max", r.t1_max}, {"t2_min", r.t2_min}, {"t2_max", r.t2_max}};
  j["status"] = to_string(r.status);
  j["symmetry"] = to_string(r.symmetry);
  j["warnings"] = r.warnings;
  json stats = json::object();
  for_each_count(r, [&](const char* key, const auto& count) { stats[key] = count; });
  stats["seconds"] = r.stats.seconds;
  j["stats"] = stats;
  json unc = json::array();
  for (const UncertifiedRegion& u : r.uncertified)
    unc.push_back({{"t1_lo", u.t1_lo}, {"t1_hi", u.t1_hi}, {"t2_lo", u.t2_lo}, {"t2_hi", u.t2_hi}, {"cause", u.cause}});
  j["uncertified"] = unc;
  json sols = json::array();
  for (const Solution& x : r.solutions) {
    json o = {{"t1", x.t1()},
              {"t2", x.t2()},
              {"period", x.period()},
              {"admissible", x.admissible()},
              {"min_gap", x.min_gap()},
              {"min_force", x.min_force()},
              {"x0", vec(x.orbit.x0)},
              {"v0", vec(x.orbit.v0)},
              {"energy", x.energy()},
              {"residual", x.residual},
              {"return_error", x.return_error},
              {"mid_flight_gap", x.admissibility.mid_flight_gap},
              {"mid_contact_force", x.admissibility.mid_contact_force},
              {"onset_force_rate", x.admissibility.onset_force_rate},
              {"admissibility_certified", x.admissibility.certified},
              {"admissibility_ends_ok", x.admissibility.ends_ok},
              {"flags", x.flags}};
    // the orbit in modal coordinates (modal form §2), so that load_result rebuilds the same Solution; absent when it
    // was read from a file without them (in_modal_basis rebuilds them from x0, v0)
    if (x.orbit.p0.size() > 0)
      o["orbit"] = {{"a", vec(x.orbit.a)},
                    {"c", vec(x.orbit.c)},
                    {"p0", vec(x.orbit.p0)},
                    {"p0dot", vec(x.orbit.p0dot)},
                    {"closure_ratio", x.orbit.closure_ratio},
                    {"energy", x.orbit.energy}};
    if (x.orbit.symmetry == Symmetry::Point) o["obstacle_velocity"] = x.orbit.obstacle_velocity;
    if (!std::isnan(x.floquet.spectral_radius)) {  // stability/floquet.hpp; absent when not computed
      json mu = json::array();
      for (const auto& z : x.floquet.multipliers) mu.push_back({z.real(), z.imag()});
      o["floquet_multipliers"] = mu;
      o["spectral_radius"] = x.floquet.spectral_radius;
      o["stability_margin"] = x.floquet.margin;
      o["stable"] = x.stable();
      o["floquet_structure_residual"] = x.floquet.structure_residual;
      // null: unbounded (a defective leading multiplier); NaN is not JSON
      const double err = x.floquet.spectral_radius_error;
      o["spectral_radius_error"] = std::isfinite(err) ? json(err) : json(nullptr);
      const double loc = x.floquet.location_error;  // the part of err from the SPP's location (floquet.hpp)
      o["spectral_radius_location_error"] = std::isfinite(loc) ? json(loc) : json(nullptr);
      o["stability_verdict"] = to_string(x.floquet.verdict);
    }
    sols.push_back(o);
  }
  j["solutions"] = sols;
  return j;
}

SolveResult result_from_json(const json& r, const std::string& where) {
  if (!r.is_object() || !r.contains("system") || !r.contains("solutions"))
    invalid(where + ": expected a result of spp solve (fields \"system\" and \"solutions\")");
  check_result(r, where);
  SolveResult res;
  const Reader top{r, where};
  const std::string status = top.text("status");
  if (status == "success")
    res.status = SolveStatus::Success;
  else if (status == "incomplete")
    res.status = SolveStatus::Incomplete;
  else
    invalid(where + ": field \"status\" must be \"success\" or \"incomplete\", got \"" + shorten(status) + "\"");
  const std::string sym = top.text("symmetry");
  if (sym != "axial" && sym != "point")
    invalid(where + ": field \"symmetry\" must be \"axial\" or \"point\", got \"" + shorten(sym) + "\"");
  res.symmetry = sym == "point" ? Symmetry::Point : Symmetry::Axial;
  res.warnings = top.texts("warnings");
  const Reader win{top.at("window"), where + ": field \"window\""};
  res.t1_min = win.number("t1_min");
  res.t1_max = win.number("t1_max");
  res.t2_min = win.number("t2_min");
  res.t2_max = win.number("t2_max");
  const Reader st{top.at("stats"), where + ": field \"stats\""};
  for_each_count(res, [&](const char* key, auto& count) {
    using Count = std::remove_reference_t<decltype(count)>;
    const bool older = std::string(key) == "unsearched_cells" && !st.o.contains(key);  // before the field existed
    count = older ? Count{0} : static_cast<Count>(st.count(key, std::numeric_limits<Count>::max()));
  });
  res.stats.seconds = st.number("seconds");
  const json& unc = top.at("uncertified");
  if (!unc.is_array()) invalid(where + ": field \"uncertified\" must be a list, got " + describe(unc));
  for (size_t i = 0; i < unc.size(); ++i) {
    const Reader u{unc[i], where + ": field \"uncertified\"[" + std::to_string(i) + "]"};
    res.uncertified.push_back(
        {u.number("t1_lo"), u.number("t1_hi"), u.number("t2_lo"), u.number("t2_hi"), u.text("cause")});
  }
  const json& sols = top.at("solutions");
  const long n = embedded_dofs(r);
  if (!sols.is_array()) invalid(where + ": field \"solutions\" must be a list, got " + describe(sols));
  for (size_t i = 0; i < sols.size(); ++i) {
    const Reader o{sols[i], where + ": field \"solutions\"[" + std::to_string(i) + "]"};
    Solution x;
    x.residual = o.number("residual");
    x.return_error = o.number("return_error");
    x.flags = o.texts("flags");
    Admissibility& a = x.admissibility;
    a.admissible = o.boolean("admissible");
    a.min_gap = o.number("min_gap");
    a.min_force = o.number("min_force");
    a.mid_flight_gap = o.number("mid_flight_gap");
    a.mid_contact_force = o.number("mid_contact_force");
    a.onset_force_rate = o.number("onset_force_rate");
    a.certified = o.boolean("admissibility_certified");
    a.ends_ok = o.boolean("admissibility_ends_ok");
    Orbit& b = x.orbit;
    b.t1 = o.number("t1");
    b.t2 = o.number("t2");
    b.symmetry = res.symmetry;
    b.x0 = o.vector("x0");
    b.v0 = o.vector("v0");
    check_solution(o, b.t1, b.t2, b.x0, b.v0, n);
    if (o.o.contains("orbit")) {
      const Reader ob{o.at("orbit"), o.where + ": field \"orbit\""};
      b.a = ob.vector("a");
      b.c = ob.vector("c");
      b.p0 = ob.vector("p0");
      b.p0dot = ob.vector("p0dot");
      b.closure_ratio = ob.number("closure_ratio");
      b.energy = ob.number("energy");
      check_orbit_block(ob, b, n, x.energy(), o.number("energy"));
    } else {  // files written before the orbit block: in_modal_basis rebuilds the modal coordinates from x0, v0
      b.closure_ratio = std::numeric_limits<double>::quiet_NaN();
      b.energy = o.number("energy");
    }
    // What the symmetry's equation set gives each SPP (solve() writes it so): a point-symmetric SPP has an obstacle
    // velocity, the flag "point_symmetric" and no multipliers (floquet() is axial only); an axial one none of them.
    // An axial result relabelled "point" read as 7 admissible point-symmetric SPPs (issue 11 attack).
    const bool point = res.symmetry == Symmetry::Point;
    const bool flagged = std::find(x.flags.begin(), x.flags.end(), "point_symmetric") != x.flags.end();
    if (point != flagged || point != o.o.contains("obstacle_velocity") ||
        (point && o.o.contains("floquet_multipliers")))
      invalid(o.where + ": field \"symmetry\" is \"" + sym + "\": expected " +
              (point ? "the flag \"point_symmetric\", a field \"obstacle_velocity\" and no \"floquet_multipliers\""
                     : "neither the flag \"point_symmetric\" nor a field \"obstacle_velocity\"") +
              " (what spp solve writes for that symmetry), got " + (flagged ? "the flag, " : "no flag, ") +
              (o.o.contains("obstacle_velocity") ? "obstacle_velocity" : "no obstacle_velocity") +
              (o.o.contains("floquet_multipliers") ? " and multipliers" : " and no multipliers"));
    if (point) b.obstacle_velocity = o.number("obstacle_velocity");
    if (!o.o.contains("floquet_multipliers")) {  // files written before stability was computed have none of it
      // (a file with its multipliers deleted but "stable": true passed spp verify, which checks the multipliers given)
      for (const char* key : {"spectral_radius", "stability_margin", "stable", "floquet_structure_residual",
                              "spectral_radius_error", "spectral_radius_location_error", "stability_verdict"})
        if (o.o.contains(key))
          invalid(o.where + ": field \"" + key +
                  "\" without \"floquet_multipliers\": expected the stability fields together, got this one alone");
    }
    if (o.o.contains("floquet_multipliers")) {  // files written before stability was computed have none
      const json& mu = o.at("floquet_multipliers");
      const std::string mw = o.where + ": field \"floquet_multipliers\"";
      if (!mu.is_array()) invalid(mw + " must be a list of [re, im] pairs, got " + describe(mu));
      for (size_t k = 0; k < mu.size(); ++k) {
        if (!mu[k].is_array() || mu[k].size() != 2 || !mu[k][0].is_number() || !mu[k][1].is_number())
          invalid(mw + "[" + std::to_string(k) + "] must be [re, im], got " + describe(mu[k]));
        x.floquet.multipliers.emplace_back(mu[k][0].get<double>(), mu[k][1].get<double>());
      }
      x.floquet.spectral_radius = o.number("spectral_radius");
      x.floquet.margin = o.number("stability_margin");
      x.floquet.structure_residual = o.number("floquet_structure_residual");
      check_floquet(o, x.floquet, n);
      read_verdict(o, x.floquet);
      x.floquet.leading = leading_of(x.floquet);
      x.floquet.stable = x.floquet.verdict == StabilityVerdict::Stable;
      if (o.boolean("stable") != x.stable())
        invalid(o.where + ": field \"stable\" must be admissible and stability_verdict \"stable\" (files without a "
                "verdict: spectral_radius < 1), got " + (o.boolean("stable") ? "true" : "false"));
    }
    res.solutions.push_back(std::move(x));
  }
  return res;
}

System result_system(const json& r, const std::string& where) {
  if (!r.is_object() || !r.contains("system") || !r.contains("solutions"))
    invalid(where + ": expected a result of spp solve (fields \"system\" and \"solutions\")");
  check_result(r, where);
  if (!r.at("system").contains("M") || !r.at("system").contains("K"))
    invalid(where +
            ": field \"system\" has no \"M\" and \"K\" (a result from an older spp): expected the system "
            "with its matrices, got none; run spp solve again");
  System s = embedded_system_from_json(r.at("system"), where + ": field \"system\"");
  if (s.g0() == 0.0)  // spp solve refuses g0 = 0 (its SPPs need one more unknown): no result of it has one
    invalid(where + ": field \"system\": field \"g0\" is 0, which no result of spp solve has (a g0 = 0 system is "
                    "solved along a parameter): expected the g0 of the system that was solved");
  return s;
}

}  // namespace spp::io

namespace spp {

std::string result_json(const System& system, const SolveResult& result, int indent) {
  return io::result_to_json(system, result).dump(indent) + "\n";
}

namespace {
// What the file's SPPs claim that its own system refutes in O(n^2) each: an energy other than
// 1/2 v0^T M v0 + 1/2 x0^T K x0 (a doubled energy was read as written; issue 11 attack). The modal energy solve()
// writes agrees with it to rounding (~1e-15 relative); kEnergyAgreement leaves room for ill-conditioned M, K (1e-8
// refused spp's own file of chain5 written as x = T y with cond M 1.1e10: 1.2e-8; found by an attack).
void check_against_system(const System& s, const SolveResult& r, const std::string& where) {
  constexpr double kEnergyAgreement = 1e-6;
  for (size_t i = 0; i < r.solutions.size(); ++i) {
    const Orbit& o = r.solutions[i].orbit;
    const double e = 0.5 * o.v0.dot(s.M() * o.v0) + 0.5 * o.x0.dot(s.K() * o.x0);
    if (!(std::abs(o.energy - e) <= kEnergyAgreement * e))
      io::invalid(where + ": field \"solutions\"[" + std::to_string(i) + "]: field \"energy\" is " + io::num(o.energy) +
                  " but 1/2 v0^T M v0 + 1/2 x0^T K x0 with the file's system is " + io::num(e) + ": expected " +
                  io::num(e) + ", got " + io::num(o.energy));
  }
}

ResultFile read_result_file(const io::json& j, const std::string& where) {
  ResultFile f{io::result_system(j, where), io::result_from_json(j, where)};
  check_against_system(f.system, f.result, where);
  return f;
}
}  // namespace

ResultFile load_result_file(const std::string& path) {
  return read_result_file(io::read_json_file(path), path);
}

ResultFile parse_result_file(const std::string& text, const std::string& where) {
  return read_result_file(io::parse_json_text(text, where), where);
}

SolveResult load_result(const std::string& path) {
  return load_result_file(path).result;
}

SolveResult parse_result(const std::string& text, const std::string& where) {
  return parse_result_file(text, where).result;
}

System load_result_system(const std::string& path) {
  return io::result_system(io::read_json_file(path), path);
}


}  // namespace spp
