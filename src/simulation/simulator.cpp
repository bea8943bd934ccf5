#include "spp/simulation/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "spp/detail/cosine_sum.hpp"
#include "spp/detail/internal_error.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/detail/symmetric_eigen.hpp"

namespace spp {

namespace {

// Modes of M y'' + K y = 0 restricted to the range of the orthonormal basis T (n x m).
Simulator::Phase make_phase(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, const Eigen::MatrixXd& T) {
  Simulator::Phase p;
  const Eigen::Index m = T.cols();
  if (m == 0) {
    p.omega.resize(0);
    p.Phi.resize(T.rows(), 0);
    return p;
  }
  const Eigen::MatrixXd Mr = T.transpose() * M * T, Kr = T.transpose() * K * T;
  const detail::SymmetricEigen es = detail::generalized_symmetric_eigen(Kr, Mr);  // Psi^T Mr Psi = I
  if (!es.ok) detail::internal_error("simulator: the generalized eigenproblem of a phase did not converge");
  p.omega = es.values.cwiseMax(0.0).cwiseSqrt();
  p.Phi = T * es.vectors;
  return p;
}

struct PhaseState {  // modal coordinates of one phase started from (x, v)
  Eigen::VectorXd q, qd;
};

PhaseState modal_state(const Simulator::Phase& p, const Eigen::MatrixXd& M, const Eigen::VectorXd& x,
                       const Eigen::VectorXd& v) {
  return {p.Phi.transpose() * (M * (x - p.x_s)), p.Phi.transpose() * (M * v)};
}

// The phase's watched quantity (gap or force) along the flow from s: offset + sum_k weights_k q_k(t), with
// q_k(t) = q_k cos(w_k t) + (qd_k / w_k) sin(w_k t).
detail::CosineSum watched(const Simulator::Phase& p, const PhaseState& s) {
  Eigen::VectorXd b(s.qd.size());
  for (Eigen::Index k = 0; k < b.size(); ++k) b(k) = p.omega(k) > 0.0 ? s.qd(k) / p.omega(k) : 0.0;
  return detail::CosineSum::from_cos_sin(p.offset, p.weights.cwiseProduct(s.q), p.weights.cwiseProduct(b), p.omega);
}

void state_at(const Simulator::Phase& p, const PhaseState& s, double t, Eigen::VectorXd& x, Eigen::VectorXd& v) {
  const Eigen::ArrayXd c = (p.omega.array() * t).cos(), sn = (p.omega.array() * t).sin();
  Eigen::VectorXd q(s.q.size()), qd(s.q.size());
  for (Eigen::Index k = 0; k < q.size(); ++k) {
    const double w = p.omega(k);
    q(k) = s.q(k) * c(k) + (w > 0.0 ? s.qd(k) / w * sn(k) : s.qd(k) * t);
    qd(k) = -s.q(k) * w * sn(k) + s.qd(k) * c(k);
  }
  x = p.x_s + p.Phi * q;
  v = p.Phi * qd;
}

// A touchdown with zero velocity and acceleration (how an SPP's contact begins) is a triple root of the gap,
// located by a crossing only to ~(tol / |g'''|)^(1/3); g'' has a simple root there: Newton on it finds the
// point where gap, velocity and acceleration vanish together, kept only if the gap is still within tolerance.
double tangent_touchdown(const detail::CosineSum& gap, double s, double tol) {
  double r = s;
  for (int it = 0; it < 4; ++it) {
    const double g3 = gap.derivative(r, 3);
    if (g3 == 0.0) return s;
    r -= gap.derivative(r, 2) / g3;
  }
  const double g3 = std::abs(gap.derivative(r, 3));
  const double window = 10.0 * std::cbrt(6.0 * tol / g3);
  const double v_tol = std::sqrt(8.0 * tol * gap.bound(2));
  if (r >= 0.0 && std::abs(r - s) <= window && std::abs(gap.value(r)) <= tol && std::abs(gap.derivative(r, 1)) <= v_tol)
    return r;
  return s;
}

}  // namespace

void SimulateOptions::validate() const {
  auto bad = [](const std::string& field, double value, const std::string& rule) {
    detail::invalid_option("simulate", field, value, rule);
  };
  if (!(std::isfinite(duration) && duration > 0.0)) bad("duration", duration, "finite and > 0");
  if (!(restitution >= 0.0 && restitution <= 1.0)) bad("restitution", restitution, "in [0, 1]");
  if (!(event_rel_tol > 0.0 && event_rel_tol < 1e-3)) bad("event_rel_tol", event_rel_tol, "in (0, 1e-3)");
  if (!(rest_velocity_rel_tol > 0.0 && rest_velocity_rel_tol < 1e-2))
    bad("rest_velocity_rel_tol", rest_velocity_rel_tol, "in (0, 1e-2)");
  if (max_events < 1) bad("max_events", static_cast<double>(max_events), ">= 1");
  for (size_t i = 0; i < sample_times.size(); ++i) {
    const double t = sample_times[i];
    if (!(std::isfinite(t) && t >= 0.0 && t <= duration))
      bad("sample_times[" + std::to_string(i) + "]", t, "in [0, duration]");
    if (i > 0 && t < sample_times[i - 1]) bad("sample_times[" + std::to_string(i) + "]", t, "sorted (non-decreasing)");
  }
}

std::vector<double> uniform_times(double duration, double per_unit) {
  if (!(per_unit >= 0.0 && std::isfinite(per_unit))) {
    std::ostringstream os;
    os << "simulate: samples per unit time must be finite and >= 0, got " << per_unit;
    detail::invalid(os.str());
  }
  std::vector<double> t;
  if (per_unit == 0.0 || !(duration > 0.0)) return t;
  const double count = std::floor(duration * per_unit);
  if (count > 1e8) {
    std::ostringstream os;
    os << "simulate: " << count << " samples requested (duration " << duration << " x " << per_unit
       << " per unit time); at most 1e8: expected at most 1e8 samples, got " << count;
    detail::invalid(os.str());
  }
  t.reserve(static_cast<size_t>(count) + 1);
  for (long k = 0; k <= static_cast<long>(count); ++k) t.push_back(static_cast<double>(k) / per_unit);
  return t;
}

const char* to_string(EventKind kind) {
  switch (kind) {
    case EventKind::Impact: return "impact";
    case EventKind::ContactOnset: return "contact_onset";
    case EventKind::Release: return "release";
  }
  return "unknown";
}

const char* to_string(SimulationStatus status) {
  switch (status) {
    case SimulationStatus::NotRun: return "not_run";
    case SimulationStatus::Success: return "success";
    case SimulationStatus::EventLimit: return "event_limit";
    case SimulationStatus::Stalled: return "stalled";
    case SimulationStatus::Interrupted: return "interrupted";
  }
  return "unknown";
}

std::string SimulationResult::brief_report() const {
  std::ostringstream os;
  os.precision(10);
  os << "simulation " << to_string(status) << ": t = " << end_time << ", " << impacts << " impacts, " << contact_onsets
     << " contact onsets, " << releases << " releases; energy " << energy_initial << " -> " << energy_final
     << " (impact loss " << impact_energy_loss << ")";
  return os.str();
}

Simulator::Simulator(const System& system) : system_(system) {
  const Eigen::MatrixXd& M = system_.M();
  const Eigen::MatrixXd& K = system_.K();
  const Eigen::VectorXd& w = system_.w();
  const Eigen::Index n = system_.n();
  M_llt_.compute(M);
  const Eigen::LLT<Eigen::MatrixXd> Kllt(K);
  Minv_w_ = M_llt_.solve(w);
  w_Minv_w_ = w.dot(Minv_w_);

  flight_ = make_phase(M, K, Eigen::MatrixXd::Identity(n, n));
  flight_.x_s = Eigen::VectorXd::Zero(n);

  // Contact: x = x_s + T y with T an orthonormal basis of w-perp (Householder), x_s the constrained equilibrium
  // (minimum of x^T K x / 2 on w^T x = -g0).
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(w);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
  contact_ = make_phase(M, K, Q.rightCols(n - 1));
  const Eigen::VectorXd Kinv_w = Kllt.solve(w);
  contact_.x_s = -system_.g0() / w.dot(Kinv_w) * Kinv_w;
  normal_motion_ = Kinv_w / w.dot(Kinv_w);
  // force from w^T x'' = 0: lambda = w^T M^-1 K x / (w^T M^-1 w)
  force_row_ = (K * Minv_w_).transpose() / w_Minv_w_;
  flight_.offset = system_.g0();  // gap = g0 + w^T Phi q
  flight_.weights = (w.transpose() * flight_.Phi).transpose();
  contact_.offset = force_row_.dot(contact_.x_s);  // force = force_row (x_s + Phi q)
  contact_.weights = (force_row_ * contact_.Phi).transpose();
}

std::pair<Eigen::VectorXd, Eigen::VectorXd> Simulator::follow_contact_then_flight(const Eigen::VectorXd& x0,
                                                                                 const Eigen::VectorXd& v0,
                                                                                 double contact_time,
                                                                                 double flight_time) const {
  if (x0.size() != system_.n() || v0.size() != system_.n() || !(contact_time >= 0.0) || !(flight_time >= 0.0) ||
      !std::isfinite(contact_time) || !std::isfinite(flight_time)) {
    std::ostringstream os;
    os << "follow_contact_then_flight: expected x0 and v0 of size " << system_.n()
       << " and finite durations >= 0, got sizes " << x0.size() << " and " << v0.size() << ", durations " << contact_time
       << " and " << flight_time;
    detail::invalid(os.str());
  }
  // K normal_motion_ is parallel to w, so (c + s t) normal_motion_ is a motion of the contact flow (no acceleration)
  // with w^T x = c + s t: the normal position and velocity at the start, carried along; the rest, normal to w, moves
  // in the contact modes. (The normal velocity was projected away: a point-symmetric SPP, whose obstacle moves, could
  // not be followed, and verify did not check its x0, v0; issue 11 finding.)
  const double c = system_.w().dot(x0) + system_.g0(), s = system_.w().dot(v0);
  const Eigen::VectorXd z0 = x0 - c * normal_motion_, zd0 = v0 - s * normal_motion_;
  Eigen::VectorXd x, v;
  state_at(contact_, modal_state(contact_, system_.M(), z0, zd0), contact_time, x, v);
  x += (c + s * contact_time) * normal_motion_;
  v += s * normal_motion_;
  Eigen::VectorXd xf, vf;
  state_at(flight_, modal_state(flight_, system_.M(), x, v), flight_time, xf, vf);
  return {xf, vf};
}

// The event search steps through every period of the fastest mode (detail::first_crossing_below_zero; measured 2.4 us
// per period on the paper's chain without events, so 1e8 periods take ~4 min): --duration 1e300 without an event
// never ended (issue 11 attack). Refused beyond kMaxPeriods of the fastest mode of either phase (README, spp simulate;
// verify's --periods 100000 of an SPP stays below it unless its period spans over 1000 of them: verify reports such an
// SPP as not checked).
double Simulator::max_duration() const {
  constexpr double kMaxPeriods = 1e8;
  const double omega_max = std::max(flight_.omega.size() ? flight_.omega.maxCoeff() : 0.0,
                                    contact_.omega.size() ? contact_.omega.maxCoeff() : 0.0);
  return omega_max > 0.0 ? kMaxPeriods * 2.0 * M_PI / omega_max : std::numeric_limits<double>::infinity();
}

double Simulator::energy(const Eigen::VectorXd& x, const Eigen::VectorXd& v) const {
  return 0.5 * v.dot(system_.M() * v) + 0.5 * x.dot(system_.K() * x);
}

SimulationResult Simulator::run(const Eigen::VectorXd& x0, const Eigen::VectorXd& v0,
                                const SimulateOptions& opt) const {
  opt.validate();
  const Eigen::Index n = system_.n();
  if (x0.size() != n || v0.size() != n) {
    std::ostringstream os;
    os << "simulate: expected x0 and v0 of size " << n << " (the system's dofs), got " << x0.size() << " and "
       << v0.size();
    detail::invalid(os.str());
  }
  if (!x0.allFinite() || !v0.allFinite()) detail::invalid("simulate: x0 and v0 must be finite numbers");
  // Event finding squares modal amplitudes and multiplies them by powers of omega: a state whose energy is near the
  // overflow threshold gave an energy of inf, NaN bounds and an endless event loop (found by an independent review:
  // x0 = 1e308 spun forever, 1e300 ended "success" with energy -nan). Refused well before.
  constexpr double kMaxEnergy = 1e250;
  if (const double e0 = energy(x0, v0); !(e0 <= kMaxEnergy)) {
    std::ostringstream os;
    os << "simulate: the initial state's energy 1/2 v0^T M v0 + 1/2 x0^T K x0 is " << e0 << ": beyond " << kMaxEnergy
       << ", where the event computations overflow (change the units of x, M or K)";
    detail::invalid(os.str());
  }
  if (const double longest = max_duration(); opt.duration > longest) {  // (max_duration says why)
    std::ostringstream rule;
    rule << "at most " << longest << " (1e8 periods of the fastest mode: the event search steps through each)";
    detail::invalid_option("simulate", "duration", opt.duration, rule.str());
  }
  const Eigen::MatrixXd& M = system_.M();
  const Eigen::VectorXd& w = system_.w();
  const double e = opt.restitution;

  SimulationResult res;
  Eigen::VectorXd x = x0, v = v0;
  double t = 0.0;
  bool contact = false;
  size_t next_sample = 0;
  while (next_sample < opt.sample_times.size() && opt.sample_times[next_sample] <= 0.0) ++next_sample;

  auto push_sample = [&](double ts, const Eigen::VectorXd& xs, const Eigen::VectorXd& vs, bool in_contact) {
    if (!res.samples.empty() && res.samples.back().t == ts) res.samples.pop_back();  // keep the later state
    Sample s;
    s.t = ts;
    s.x = xs;
    s.v = vs;
    s.gap = system_.gap(xs);
    s.force = in_contact ? force_row_.dot(xs) : 0.0;
    s.in_contact = in_contact;
    res.samples.push_back(std::move(s));
  };
  // Removes the normal velocity (and, for contact, the gap) along M^-1 w: the M-orthogonal projection.
  auto project_velocity = [&](Eigen::VectorXd& vv) { vv -= (w.dot(vv) / w_Minv_w_) * Minv_w_; };
  auto project_position = [&](Eigen::VectorXd& xx) { xx -= (system_.gap(xx) / w_Minv_w_) * Minv_w_; };

  auto tolerance = [&](const detail::CosineSum& f, int k) {
    return opt.event_rel_tol * ((k == 0 ? std::abs(f.c0) : 0.0) + f.bound(k));
  };

  // On the obstacle with zero normal velocity: lasting contact iff the force the constraint needs is
  // non-negative, decided by its first derivative that is not negligible (lambda, lambda', lambda''), with the
  // tolerance of the contact phase's own event search (so that the two never contradict each other).
  auto needs_contact = [&](const Eigen::VectorXd& xx, const Eigen::VectorXd& vv) {
    const detail::CosineSum f = watched(contact_, modal_state(contact_, M, xx, vv));
    for (int k = 0; k <= 2; ++k) {
      const double d = f.derivative(0.0, k);
      if (std::abs(d) > tolerance(f, k)) return d > 0.0;
    }
    return true;  // at rest on the obstacle to every order we can see: contact holds
  };

  auto record = [&](EventKind kind, const Eigen::VectorXd& vb, const Eigen::VectorXd& va, double force) {
    Event ev;
    ev.t = t;
    ev.kind = kind;
    ev.x = x;
    ev.v_before = vb;
    ev.v_after = va;
    ev.normal_velocity_before = w.dot(vb);
    ev.normal_velocity_after = w.dot(va);
    ev.force = force;
    res.events.push_back(std::move(ev));
    if (kind == EventKind::Impact) ++res.impacts;
    if (kind == EventKind::ContactOnset) ++res.contact_onsets;
    if (kind == EventKind::Release) ++res.releases;
  };

  // Gap reached zero in flight (or the start is on the obstacle): impact, then contact or flight. A bounce
  // slower than v_rest is plastic: either below the velocity tolerance, or so low (height v^2 / (2 |g''|)
  // within a few event tolerances) that its end could not be told from its start.
  auto touchdown = [&](const detail::CosineSum& gap, double gap_tol, bool stalled) {
    const double vn = w.dot(v);
    const double v_rest = std::max(opt.rest_velocity_rel_tol * gap.bound(1), std::sqrt(8.0 * gap_tol * gap.bound(2)));
    if (vn > v_rest && !stalled) return;  // leaving the obstacle
    const Eigen::VectorXd vb = v;
    if (vn < -v_rest) {
      const double vn_after = -e * vn;
      v -= ((1.0 + e) * vn / w_Minv_w_) * Minv_w_;
      if (vn_after > v_rest && !stalled) {
        res.impact_energy_loss += 0.5 * (1.0 - e * e) * vn * vn / w_Minv_w_;
        record(EventKind::Impact, vb, v, 0.0);
        return;
      }
    }
    project_velocity(v);  // too slow to bounce: the accumulation of impacts ends here, plastically
    res.impact_energy_loss += 0.5 * vn * vn / w_Minv_w_;
    if (vn < -v_rest) record(EventKind::Impact, vb, v, 0.0);
    if (needs_contact(x, v)) {
      project_position(x);
      record(EventKind::ContactOnset, vb, v, force_row_.dot(x));
      contact = true;
    } else if (stalled) {
      // leaving the obstacle from rest, but found again at once: a rounding penetration below the gap's tolerance
      // (a long run from v5 = 2 on chain5 looped here at t = 206422.89; found by an independent attack). On the
      // obstacle exactly, its positive acceleration takes it away.
      project_position(x);
    }
  };

  // initial state
  {
    const double g = system_.gap(x);
    constexpr double kInitialGapTol = 1e-9;  // penetration within ~5e6 eps of the gap's scale: on the obstacle
    // (or within 100 event tolerances, when that is larger: verify's, for a state known to less than 1e-11, whose onset
    // it checks to 100 times its error; issue 11)
    constexpr double kStartMargin = 100.0;
    const double gtol =
        std::max(kInitialGapTol, kStartMargin * opt.event_rel_tol) * (std::abs(system_.g0()) + x.norm());
    if (g < -gtol) {
      std::ostringstream os;
      os << "simulate: the initial state penetrates the obstacle: gap w^T x0 + g0 = " << g
         << " < 0: expected a gap >= 0 at the start, got " << g;
      detail::invalid(os.str());
    }
    res.energy_initial = energy(x, v);
    push_sample(0.0, x, v, false);
    if (g <= gtol) {
      const detail::CosineSum f = watched(flight_, modal_state(flight_, M, x, v));
      touchdown(f, tolerance(f, 0), false);
      if (contact) push_sample(0.0, x, v, true);  // replaces the sample before the onset
    }
  }

  res.status = SimulationStatus::Success;
  int stalled_events = 0;                 // consecutive events without time passing
  constexpr int kMaxStalledEvents = 100;  // zero-time events in a row: an event sequence at one instant
  // is a few (impact, onset, release); 100 is a loop that time cannot leave
  constexpr long kProgressEvery = 256;  // events or samples between two calls of opt.progress
  long steps_since_progress = 0;
  while (t < opt.duration) {
    if (opt.progress && steps_since_progress >= kProgressEvery) {
      steps_since_progress = 0;
      if (!opt.progress()) {
        res.status = SimulationStatus::Interrupted;
        break;
      }
    }
    ++steps_since_progress;
    if (static_cast<long>(res.events.size()) >= opt.max_events) {
      res.status = SimulationStatus::EventLimit;
      break;
    }
    if (stalled_events > kMaxStalledEvents) {
      res.status = SimulationStatus::Stalled;
      break;
    }
    const Phase& ph = contact ? contact_ : flight_;
    const PhaseState ps = modal_state(ph, M, x, v);
    const detail::CosineSum f = watched(ph, ps);  // must stay >= 0 in this phase
    const double f_tol = tolerance(f, 0);
    const double remaining = opt.duration - t;
    const detail::Crossing cr = detail::first_crossing_below_zero(f, 0.0, remaining, f_tol);
    const double s_end = cr.found ? (contact ? cr.t : tangent_touchdown(f, cr.t, f_tol)) : remaining;
    const double t_end = cr.found ? std::min(t + s_end, opt.duration) : opt.duration;
    Eigen::VectorXd xs, vs;
    bool stopped = false;
    for (; next_sample < opt.sample_times.size() && opt.sample_times[next_sample] < t_end; ++next_sample) {
      if (opt.progress && ++steps_since_progress >= kProgressEvery) {  // (a long flight sampled densely)
        steps_since_progress = 0;
        if (!opt.progress()) {
          stopped = true;
          break;
        }
      }
      const double ts = opt.sample_times[next_sample];
      state_at(ph, ps, ts - t, xs, vs);
      push_sample(ts, xs, vs, contact);
    }
    if (stopped) {  // the state where sampling stopped: the samples end there
      res.status = SimulationStatus::Interrupted;
      const double ts = next_sample > 0 ? std::max(t, opt.sample_times[next_sample - 1]) : t;
      state_at(ph, ps, ts - t, x, v);
      t = ts;
      break;
    }
    state_at(ph, ps, s_end, x, v);
    // time passed in the phase's own clock (s_end), not in t: past t ~ 1e5 an event sequence a few 1e-11 apart
    // leaves t + s_end == t, and a long run stopped as "stalled" at t = 206422.89 (found by an independent attack)
    stalled_events = s_end > 0.0 ? 0 : stalled_events + 1;
    t = t_end;
    if (!cr.found) break;
    if (contact) {
      project_velocity(v);  // rounding only: the contact flow keeps w^T v = 0
      record(EventKind::Release, v, v, 0.0);
      contact = false;
    } else {
      touchdown(f, f_tol, s_end <= 0.0);  // stalled: no time passed since the last event
    }
    if (opt.sample_events) push_sample(t, x, v, contact);
  }
  res.end_time = t;
  push_sample(t, x, v, contact);
  res.in_contact_at_end = contact;
  res.energy_final = energy(x, v);
  return res;
}

SimulationResult simulate(const System& system, const Eigen::VectorXd& x0, const Eigen::VectorXd& v0,
                          const SimulateOptions& options) {
  return Simulator(system).run(x0, v0, options);
}

}  // namespace spp
