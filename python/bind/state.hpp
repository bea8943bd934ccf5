#pragma once
// Pickling of the plain-data results (multiprocessing, joblib): each as the tuple of its fields, in declaration order,
// nested for the structs it holds; read back field for field. One pair of functions per struct, used by py::pickle
// in the binding files. (SolveResult pickles as its result file's text, the one type with a JSON reader.)
#include <pybind11/complex.h>

#include <complex>
#include <string>
#include <vector>

#include "common.hpp"
#include "spp/continuation/continuation.hpp"
#include "spp/modes/nonsmooth_modes.hpp"
#include "spp/orbit/solution.hpp"
#include "spp/search/root_map.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/simulator.hpp"
#include "spp/simulation/verify.hpp"

namespace spp::python::state {

// A pickled tuple of the wrong length (another version's, or hand-made) is refused by name.
inline const py::tuple& sized(const py::tuple& t, size_t n, const char* what) {
  if (t.size() != n)
    detail::invalid(std::string(what) + " pickle: expected " + std::to_string(n) + " fields, got " +
                    std::to_string(t.size()));
  return t;
}

inline py::tuple of(const spp::Solution& s) {
  const spp::Orbit& o = s.orbit;
  const spp::Admissibility& a = s.admissibility;
  const spp::Floquet& f = s.floquet;
  return py::make_tuple(py::make_tuple(o.t1, o.t2, o.a, o.c, o.p0, o.p0dot, o.x0, o.v0, o.closure_ratio, o.energy,
                                       static_cast<int>(o.symmetry), o.obstacle_velocity),
                        py::make_tuple(a.admissible, a.min_gap, a.min_force, a.mid_flight_gap, a.mid_contact_force,
                                       a.onset_force_rate, a.ends_ok, a.certified),
                        py::make_tuple(f.multipliers, f.spectral_radius, f.margin, f.stable, f.structure_residual,
                                       f.leading, f.spectral_radius_error, static_cast<int>(f.verdict),
                                       f.location_error),
                        s.residual, s.return_error, s.flags);
}
inline spp::Solution solution(const py::tuple& t) {
  sized(t, 6, "Solution");
  spp::Solution s;
  const py::tuple o = sized(t[0].cast<py::tuple>(), 12, "Solution (orbit)");
  s.orbit.t1 = o[0].cast<double>();
  s.orbit.t2 = o[1].cast<double>();
  s.orbit.a = o[2].cast<Eigen::VectorXd>();
  s.orbit.c = o[3].cast<Eigen::VectorXd>();
  s.orbit.p0 = o[4].cast<Eigen::VectorXd>();
  s.orbit.p0dot = o[5].cast<Eigen::VectorXd>();
  s.orbit.x0 = o[6].cast<Eigen::VectorXd>();
  s.orbit.v0 = o[7].cast<Eigen::VectorXd>();
  s.orbit.closure_ratio = o[8].cast<double>();
  s.orbit.energy = o[9].cast<double>();
  s.orbit.symmetry = static_cast<spp::Symmetry>(o[10].cast<int>());
  s.orbit.obstacle_velocity = o[11].cast<double>();
  const py::tuple a = sized(t[1].cast<py::tuple>(), 8, "Solution (admissibility)");
  s.admissibility.admissible = a[0].cast<bool>();
  s.admissibility.min_gap = a[1].cast<double>();
  s.admissibility.min_force = a[2].cast<double>();
  s.admissibility.mid_flight_gap = a[3].cast<double>();
  s.admissibility.mid_contact_force = a[4].cast<double>();
  s.admissibility.onset_force_rate = a[5].cast<double>();
  s.admissibility.ends_ok = a[6].cast<bool>();
  s.admissibility.certified = a[7].cast<bool>();
  const py::tuple f = sized(t[2].cast<py::tuple>(), 9, "Solution (floquet)");
  s.floquet.multipliers = f[0].cast<std::vector<std::complex<double>>>();
  s.floquet.spectral_radius = f[1].cast<double>();
  s.floquet.margin = f[2].cast<double>();
  s.floquet.stable = f[3].cast<bool>();
  s.floquet.structure_residual = f[4].cast<double>();
  s.floquet.leading = f[5].cast<std::vector<std::complex<double>>>();
  s.floquet.spectral_radius_error = f[6].cast<double>();
  s.floquet.verdict = static_cast<spp::StabilityVerdict>(f[7].cast<int>());
  s.floquet.location_error = f[8].cast<double>();
  s.residual = t[3].cast<double>();
  s.return_error = t[4].cast<double>();
  s.flags = t[5].cast<std::vector<std::string>>();
  return s;
}

inline py::tuple of(const spp::BranchPoint& p) {
  return py::make_tuple(p.mu, p.t1, p.t2, p.period, p.admissible, p.margin, p.closure, p.energy, p.x0, p.v0,
                        p.spectral_radius, p.spectral_radius_error);
}
inline spp::BranchPoint branch_point(const py::tuple& t) {
  sized(t, 12, "BranchPoint");
  spp::BranchPoint p;
  p.mu = t[0].cast<double>();
  p.t1 = t[1].cast<double>();
  p.t2 = t[2].cast<double>();
  p.period = t[3].cast<double>();
  p.admissible = t[4].cast<bool>();
  p.margin = t[5].cast<double>();
  p.closure = t[6].cast<double>();
  p.energy = t[7].cast<double>();
  p.x0 = t[8].cast<Eigen::VectorXd>();
  p.v0 = t[9].cast<Eigen::VectorXd>();
  p.spectral_radius = t[10].cast<double>();
  p.spectral_radius_error = t[11].cast<double>();
  return p;
}
inline py::tuple of(const spp::BranchEvent& e) {
  return py::make_tuple(static_cast<int>(e.kind), of(e.at), e.detail, static_cast<int>(e.crossing),
                        e.crossing_multipliers, e.crossing_angle);
}
inline spp::BranchEvent branch_event(const py::tuple& t) {
  sized(t, 6, "BranchEvent");
  spp::BranchEvent e{static_cast<spp::BranchEventKind>(t[0].cast<int>()), branch_point(t[1].cast<py::tuple>()),
                     t[2].cast<std::string>()};
  e.crossing = static_cast<spp::MultiplierCrossing>(t[3].cast<int>());
  e.crossing_multipliers = t[4].cast<std::vector<std::complex<double>>>();
  e.crossing_angle = t[5].cast<double>();
  return e;
}
inline py::tuple of(const spp::Branch& b) {
  py::list pts, evs;
  for (const spp::BranchPoint& p : b.points) pts.append(of(p));
  for (const spp::BranchEvent& e : b.events) evs.append(of(e));
  return py::make_tuple(pts, evs);
}
inline spp::Branch branch(const py::tuple& t) {
  sized(t, 2, "Branch");
  spp::Branch b;
  for (const py::handle p : t[0]) b.points.push_back(branch_point(p.cast<py::tuple>()));
  for (const py::handle e : t[1]) b.events.push_back(branch_event(e.cast<py::tuple>()));
  return b;
}
inline py::tuple of(const spp::ContinuationResult& r) {
  py::list brs;
  for (const spp::Branch& b : r.branches) brs.append(of(b));
  return py::make_tuple(static_cast<int>(r.status), r.incomplete_seed_solves, r.stalled_branches, r.unlisted_crossings,
                        py::make_tuple(r.parameter.name, r.parameter.min, r.parameter.max),
                        static_cast<int>(r.symmetry), py::make_tuple(r.t1_min, r.t1_max, r.t2_min, r.t2_max), brs,
                        r.warnings, py::make_tuple(r.seed_spps, r.seed_crossings, r.corrector_solves, r.seconds),
                        r.interrupted);
}
inline spp::ContinuationResult continuation_result(const py::tuple& t) {
  sized(t, 11, "ContinuationResult");
  spp::ContinuationResult r;
  r.status = static_cast<spp::ContinuationStatus>(t[0].cast<int>());
  r.incomplete_seed_solves = t[1].cast<long>();
  r.stalled_branches = t[2].cast<long>();
  r.unlisted_crossings = t[3].cast<long>();
  const py::tuple par = sized(t[4].cast<py::tuple>(), 3, "ContinuationResult (parameter)");
  r.parameter = {par[0].cast<std::string>(), par[1].cast<double>(), par[2].cast<double>()};
  r.symmetry = static_cast<spp::Symmetry>(t[5].cast<int>());
  const py::tuple w = sized(t[6].cast<py::tuple>(), 4, "ContinuationResult (window)");
  r.t1_min = w[0].cast<double>();
  r.t1_max = w[1].cast<double>();
  r.t2_min = w[2].cast<double>();
  r.t2_max = w[3].cast<double>();
  for (const py::handle b : t[7]) r.branches.push_back(branch(b.cast<py::tuple>()));
  r.warnings = t[8].cast<std::vector<std::string>>();
  const py::tuple c = sized(t[9].cast<py::tuple>(), 4, "ContinuationResult (counts)");
  r.seed_spps = c[0].cast<long>();
  r.seed_crossings = c[1].cast<long>();
  r.corrector_solves = c[2].cast<long>();
  r.seconds = c[3].cast<double>();
  r.interrupted = t[10].cast<bool>();
  return r;
}

inline py::tuple of(const spp::Event& e) {
  return py::make_tuple(e.t, static_cast<int>(e.kind), e.x, e.v_before, e.v_after, e.normal_velocity_before,
                        e.normal_velocity_after, e.force);
}
inline spp::Event event(const py::tuple& t) {
  sized(t, 8, "Event");
  spp::Event e;
  e.t = t[0].cast<double>();
  e.kind = static_cast<spp::EventKind>(t[1].cast<int>());
  e.x = t[2].cast<Eigen::VectorXd>();
  e.v_before = t[3].cast<Eigen::VectorXd>();
  e.v_after = t[4].cast<Eigen::VectorXd>();
  e.normal_velocity_before = t[5].cast<double>();
  e.normal_velocity_after = t[6].cast<double>();
  e.force = t[7].cast<double>();
  return e;
}
inline py::tuple of(const spp::SimulationResult& r) {
  py::list samples, events;
  for (const spp::Sample& s : r.samples) samples.append(py::make_tuple(s.t, s.x, s.v, s.gap, s.force, s.in_contact));
  for (const spp::Event& e : r.events) events.append(of(e));
  return py::make_tuple(
      static_cast<int>(r.status), samples, events, py::make_tuple(r.impacts, r.contact_onsets, r.releases),
      py::make_tuple(r.energy_initial, r.energy_final, r.impact_energy_loss, r.end_time), r.in_contact_at_end);
}
inline spp::SimulationResult simulation_result(const py::tuple& t) {
  sized(t, 6, "SimulationResult");
  spp::SimulationResult r;
  r.status = static_cast<spp::SimulationStatus>(t[0].cast<int>());
  for (const py::handle h : t[1]) {
    const py::tuple s = sized(h.cast<py::tuple>(), 6, "SimulationResult (sample)");
    spp::Sample smp;
    smp.t = s[0].cast<double>();
    smp.x = s[1].cast<Eigen::VectorXd>();
    smp.v = s[2].cast<Eigen::VectorXd>();
    smp.gap = s[3].cast<double>();
    smp.force = s[4].cast<double>();
    smp.in_contact = s[5].cast<bool>();
    r.samples.push_back(std::move(smp));
  }
  for (const py::handle e : t[2]) r.events.push_back(event(e.cast<py::tuple>()));
  const py::tuple c = sized(t[3].cast<py::tuple>(), 3, "SimulationResult (counts)");
  r.impacts = c[0].cast<long>();
  r.contact_onsets = c[1].cast<long>();
  r.releases = c[2].cast<long>();
  const py::tuple e = sized(t[4].cast<py::tuple>(), 4, "SimulationResult (energies)");
  r.energy_initial = e[0].cast<double>();
  r.energy_final = e[1].cast<double>();
  r.impact_energy_loss = e[2].cast<double>();
  r.end_time = e[3].cast<double>();
  r.in_contact_at_end = t[5].cast<bool>();
  return r;
}

inline py::tuple of(const spp::SppCheck& c) {
  return py::make_tuple(of(c.spp), static_cast<int>(c.verdict), c.consistent, c.return_errors, c.potential_return_error,
                        c.periods_followed, c.departure_time, c.departure,
                        py::make_tuple(c.impacts, c.contact_onsets, c.releases), c.perturbed_distances,
                        c.growth_per_period, py::make_tuple(c.state_tolerance, c.return_tolerance));
}
inline spp::SppCheck spp_check(const py::tuple& t) {
  sized(t, 12, "SppCheck");
  spp::SppCheck c;
  c.spp = solution(t[0].cast<py::tuple>());
  c.verdict = static_cast<spp::Verdict>(t[1].cast<int>());
  c.consistent = t[2].cast<bool>();
  c.return_errors = t[3].cast<std::vector<double>>();
  c.potential_return_error = t[4].cast<double>();
  c.periods_followed = t[5].cast<int>();
  c.departure_time = t[6].cast<double>();
  c.departure = t[7].cast<std::string>();
  const py::tuple n = sized(t[8].cast<py::tuple>(), 3, "SppCheck (counts)");
  c.impacts = n[0].cast<long>();
  c.contact_onsets = n[1].cast<long>();
  c.releases = n[2].cast<long>();
  c.perturbed_distances = t[9].cast<std::vector<double>>();
  c.growth_per_period = t[10].cast<double>();
  const py::tuple tol = sized(t[11].cast<py::tuple>(), 2, "SppCheck (tolerances)");
  c.state_tolerance = tol[0].cast<double>();
  c.return_tolerance = tol[1].cast<double>();
  return c;
}
inline py::tuple of(const spp::VerifyResult& r) {
  py::list checks;
  for (const spp::SppCheck& c : r.checks) checks.append(of(c));
  return py::make_tuple(static_cast<int>(r.status), checks, r.returned, r.left, r.inconsistent, r.unchecked,
                        r.admissibility_mismatches, r.stability_mismatches, r.state_mismatches,
                        r.beyond_simulator_limit, r.warnings);
}
inline spp::VerifyResult verify_result(const py::tuple& t) {
  sized(t, 11, "VerifyResult");
  spp::VerifyResult r;
  r.status = static_cast<spp::VerifyStatus>(t[0].cast<int>());
  for (const py::handle c : t[1]) r.checks.push_back(spp_check(c.cast<py::tuple>()));
  r.returned = t[2].cast<int>();
  r.left = t[3].cast<int>();
  r.inconsistent = t[4].cast<int>();
  r.unchecked = t[5].cast<long>();
  r.admissibility_mismatches = t[6].cast<int>();
  r.stability_mismatches = t[7].cast<int>();
  r.state_mismatches = t[8].cast<int>();
  r.beyond_simulator_limit = t[9].cast<long>();
  r.warnings = t[10].cast<std::vector<std::string>>();
  return r;
}

inline py::tuple of(const spp::NearestSpp& r) {
  return py::make_tuple(r.found, of(r.solution), static_cast<int>(r.search_status),
                        py::make_tuple(r.t1_lo, r.t1_hi, r.t2_lo, r.t2_hi), r.candidates);
}
inline spp::NearestSpp nearest_spp(const py::tuple& t) {
  sized(t, 5, "NearestSpp");
  spp::NearestSpp r;
  r.found = t[0].cast<bool>();
  r.solution = solution(t[1].cast<py::tuple>());
  r.search_status = static_cast<spp::SolveStatus>(t[2].cast<int>());
  const py::tuple w = sized(t[3].cast<py::tuple>(), 4, "NearestSpp (window)");
  r.t1_lo = w[0].cast<double>();
  r.t1_hi = w[1].cast<double>();
  r.t2_lo = w[2].cast<double>();
  r.t2_hi = w[3].cast<double>();
  r.candidates = t[4].cast<long>();
  return r;
}

inline py::tuple of(const spp::RootMapCell& c) {
  return py::make_tuple(c.t1, c.t2, c.symmetric, c.onset);
}
inline spp::RootMapCell root_map_cell(const py::tuple& t) {
  sized(t, 4, "RootMapCell");
  return {t[0].cast<Eigen::VectorXd>(), t[1].cast<Eigen::VectorXd>(), t[2].cast<Eigen::MatrixXd>(),
          t[3].cast<Eigen::MatrixXd>()};
}
inline py::tuple of(const spp::RootMap& r) {
  py::list cells;
  for (const spp::RootMapCell& c : r.cells) cells.append(of(c));
  return py::make_tuple(r.flight_poles, r.contact_poles, cells, r.evaluations, r.unsampled_cells);
}
inline spp::RootMap root_map(const py::tuple& t) {
  sized(t, 5, "RootMap");
  spp::RootMap r;
  r.flight_poles = t[0].cast<std::vector<double>>();
  r.contact_poles = t[1].cast<std::vector<double>>();
  for (const py::handle c : t[2]) r.cells.push_back(root_map_cell(c.cast<py::tuple>()));
  r.evaluations = t[3].cast<long>();
  r.unsampled_cells = t[4].cast<long>();
  return r;
}

// Nonsmooth modes (modes/nonsmooth_modes.hpp): no JSON reader exists for them (spp modes writes its file only), so
// they pickle field by field like the other plain-data results, y (the continuation's unknowns) included.
inline py::tuple of(const spp::modes::ModePoint& p) {
  return py::make_tuple(p.energy, p.period, p.frequency, p.impact_times, p.x0, p.v0, p.admissible, p.margin,
                        p.multiplicity, p.y);
}
inline spp::modes::ModePoint mode_point(const py::tuple& t) {
  sized(t, 10, "ModePoint");
  spp::modes::ModePoint p;
  p.energy = t[0].cast<double>();
  p.period = t[1].cast<double>();
  p.frequency = t[2].cast<double>();
  p.impact_times = t[3].cast<std::vector<double>>();
  p.x0 = t[4].cast<Eigen::VectorXd>();
  p.v0 = t[5].cast<Eigen::VectorXd>();
  p.admissible = t[6].cast<bool>();
  p.margin = t[7].cast<double>();
  p.multiplicity = t[8].cast<int>();
  p.y = t[9].cast<Eigen::VectorXd>();
  return p;
}
inline py::tuple of(const spp::modes::ModeEvent& e) {
  return py::make_tuple(static_cast<int>(e.kind), of(e.at), e.detail);
}
inline spp::modes::ModeEvent mode_event(const py::tuple& t) {
  sized(t, 3, "ModeEvent");
  return {static_cast<spp::modes::ModeEventKind>(t[0].cast<int>()), mode_point(t[1].cast<py::tuple>()),
          t[2].cast<std::string>()};
}
inline py::tuple of(const spp::modes::ModeFamily& f) {
  py::list pts, evs;
  for (const spp::modes::ModePoint& p : f.points) pts.append(of(p));
  for (const spp::modes::ModeEvent& e : f.events) evs.append(of(e));
  return py::make_tuple(f.k, static_cast<int>(f.symmetry), f.mode, f.multiplicity, f.label, pts, evs);
}
inline spp::modes::ModeFamily mode_family(const py::tuple& t) {
  sized(t, 7, "ModeFamily");
  spp::modes::ModeFamily f;
  f.k = t[0].cast<int>();
  f.symmetry = static_cast<spp::modes::KippSymmetry>(t[1].cast<int>());
  f.mode = t[2].cast<int>();
  f.multiplicity = t[3].cast<int>();
  f.label = t[4].cast<std::string>();
  for (const py::handle p : t[5]) f.points.push_back(mode_point(p.cast<py::tuple>()));
  for (const py::handle e : t[6]) f.events.push_back(mode_event(e.cast<py::tuple>()));
  return f;
}
inline py::tuple of(const spp::modes::ModesResult& r) {
  py::list fams;
  for (const spp::modes::ModeFamily& f : r.families) fams.append(of(f));
  return py::make_tuple(static_cast<int>(r.status), fams, r.linear_frequencies,
                        py::make_tuple(r.corrector_solves, r.stalled_families, r.seconds, r.inadmissible_stretches),
                        r.interrupted);
}
inline spp::modes::ModesResult modes_result(const py::tuple& t) {
  sized(t, 5, "ModesResult");
  spp::modes::ModesResult r;
  r.status = static_cast<spp::modes::ModesStatus>(t[0].cast<int>());
  for (const py::handle f : t[1]) r.families.push_back(mode_family(f.cast<py::tuple>()));
  r.linear_frequencies = t[2].cast<Eigen::VectorXd>();
  const py::tuple c = sized(t[3].cast<py::tuple>(), 4, "ModesResult (counts)");
  r.corrector_solves = c[0].cast<long>();
  r.stalled_families = c[1].cast<long>();
  r.seconds = c[2].cast<double>();
  r.inadmissible_stretches = c[3].cast<long>();
  r.interrupted = t[4].cast<bool>();
  return r;
}

}  // namespace spp::python::state
