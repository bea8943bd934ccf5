#include "spp/modes/kipp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "spp/detail/cosine_sum.hpp"
#include "spp/detail/internal_error.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/detail/symmetric_eigen.hpp"
#include "spp/modal/modal.hpp"

namespace spp::modes {

const char* to_string(KippSymmetry s) {
  switch (s) {
    case KippSymmetry::FlightFlight: return "flight-flight";
    case KippSymmetry::FlightImpact: return "flight-impact";
    case KippSymmetry::ImpactImpact: return "impact-impact";
    case KippSymmetry::None: return "none";
  }
  return "?";
}

std::vector<KippSymmetry> symmetries_for(int k) {
  if (k < 1) detail::invalid_option("symmetries_for", "k", k, "at least 1");
  if (k % 2 == 1) return {KippSymmetry::FlightImpact};
  if (k == 2) return {KippSymmetry::FlightFlight};
  return {KippSymmetry::FlightFlight, KippSymmetry::ImpactImpact};
}

int interior_impacts(int k, KippSymmetry s) {
  switch (s) {
    case KippSymmetry::FlightFlight: return k / 2;
    case KippSymmetry::FlightImpact: return (k - 1) / 2;
    case KippSymmetry::ImpactImpact: return (k - 2) / 2;
    case KippSymmetry::None: return k - 1;
  }
  return 0;
}

KippModel::KippModel(const System& system) : system_(system) {
  if (!(system.g0() > 0.0))
    detail::invalid_option("KippModel", "g0", system.g0(),
                           "positive (an obstacle away from the rest position: k-IPP families start at grazing)");
  const detail::SymmetricEigen es = detail::generalized_symmetric_eigen(system.K(), system.M());
  if (!es.ok) detail::internal_error("KippModel: the generalized eigenproblem did not converge");
  Eigen::VectorXd omega = es.values.cwiseMax(0.0).cwiseSqrt();
  Eigen::MatrixXd Phi = es.vectors;
  // A repeated frequency: one mode of its group sees the obstacle, the others none (they start no family). Any
  // basis of the eigenspace was taken before, and each mode with some of w started its own copy of one family,
  // and orbits spread over the group were listed as families of zero-speed impacts (found by an independent attack).
  align_repeated_frequencies(omega, Phi, system.w(), kRepeatedFrequency);
  omega_all_ = omega;
  const Eigen::VectorXd b_all = Phi.transpose() * system.w();
  // The decoupled modes are dropped from the unknowns (class comment), with ModalForm's default threshold.
  constexpr double kDecoupled = 1e-10;
  for (int i = 0; i < system.n(); ++i)
    if (std::abs(b_all(i)) > kDecoupled * b_all.norm()) linear_mode_.push_back(i + 1);
  const int n = static_cast<int>(linear_mode_.size());
  omega_.resize(n);
  b_.resize(n);
  Phi_.resize(system.n(), n);
  for (int i = 0; i < n; ++i) {
    const int j = linear_mode_[static_cast<size_t>(i)] - 1;
    omega_(i) = omega(j);
    b_(i) = b_all(j);
    Phi_.col(i) = Phi.col(j);
  }
  // Orthonormal basis of b^perp: the last n - 1 columns of the Householder Q of b.
  b_reflection_.compute(b_);
  const Eigen::MatrixXd Qfull = b_reflection_.householderQ() * Eigen::MatrixXd::Identity(n, n);
  Q_ = Qfull.rightCols(n - 1);
}

Eigen::MatrixXd KippModel::tangential(const Eigen::MatrixXd& X) const {
  const Eigen::MatrixXd HX = b_reflection_.householderQ().adjoint() * X;  // applied, not formed
  return HX.bottomRows(X.rows() - 1);
}

namespace {

// Flight over time t of the modal state (q, p), with the derivative of every state column (Dq, Dp) carried along.
void flow(const Eigen::VectorXd& omega, double t, Eigen::VectorXd& q, Eigen::VectorXd& p, Eigen::MatrixXd* Dq,
          Eigen::MatrixXd* Dp) {
  const Eigen::ArrayXd c = (omega.array() * t).cos(), s = (omega.array() * t).sin();
  // sin(w t) / w, with its limit t at w = 0 (a rigid mode is refused by System, kept safe anyway)
  Eigen::ArrayXd sw(omega.size());
  for (Eigen::Index i = 0; i < omega.size(); ++i) sw(i) = omega(i) > 0 ? s(i) / omega(i) : t;
  const Eigen::ArrayXd ws = omega.array() * s;
  const Eigen::VectorXd q1 = (c * q.array() + sw * p.array()).matrix();
  const Eigen::VectorXd p1 = (-ws * q.array() + c * p.array()).matrix();
  q = q1;
  p = p1;
  if (Dq) {
    const Eigen::MatrixXd Dq1 = c.matrix().asDiagonal() * *Dq + sw.matrix().asDiagonal() * *Dp;
    const Eigen::MatrixXd Dp1 = (-ws).matrix().asDiagonal() * *Dq + c.matrix().asDiagonal() * *Dp;
    *Dq = Dq1;
    *Dp = Dp1;
  }
}

void reflect(const Eigen::VectorXd& b, Eigen::VectorXd& p, Eigen::MatrixXd* Dp) {
  const double bb = b.squaredNorm();
  p -= (2.0 * b.dot(p) / bb) * b;
  if (Dp) *Dp -= (2.0 / bb) * b * (b.transpose() * *Dp);
}

// The state at A: (q_A, 0) or (q_A, s b/|b|), and its derivative in y.
void start_state(const KippModel& model, const KippShape& shape, const Eigen::VectorXd& y, Eigen::VectorXd& q,
                 Eigen::VectorXd& p, Eigen::MatrixXd& Dq, Eigen::MatrixXd& Dp) {
  const int n = shape.n, N = shape.unknowns();
  q = y.head(n);
  Dq = Eigen::MatrixXd::Zero(n, N);
  Dp = Eigen::MatrixXd::Zero(n, N);
  Dq.leftCols(n).setIdentity();
  if (shape.symmetry == KippSymmetry::ImpactImpact) {
    const Eigen::VectorXd bh = model.b().normalized();
    p = y(n) * bh;
    Dp.col(n) = bh;
  } else if (shape.symmetry == KippSymmetry::None) {
    p = y.segment(n, n);
    Dp.middleCols(n, n).setIdentity();
  } else {
    p = Eigen::VectorXd::Zero(n);
  }
}

}  // namespace

void kipp_residual(const KippModel& model, const KippShape& shape, const Eigen::VectorXd& y, Eigen::VectorXd& F,
                   Eigen::MatrixXd& J) {
  const int n = shape.n, N = shape.unknowns(), m = shape.m(), t0 = shape.first_tau();
  if (n != model.coupled_modes() || y.size() != N) detail::invalid("kipp_residual: expected y of the shape's size");
  F.resize(N - 1);
  J.resize(N - 1, N);
  const Eigen::VectorXd& b = model.b();
  const double g0 = model.g0();
  Eigen::VectorXd q, p;
  Eigen::MatrixXd Dq, Dp;
  start_state(model, shape, y, q, p, Dq, Dp);
  int row = 0;
  if (shape.symmetry == KippSymmetry::ImpactImpact || shape.symmetry == KippSymmetry::None) {  // A on the obstacle
    F(row) = b.dot(q) + g0;
    J.row(row++) = b.transpose() * Dq;
  }
  for (int j = 0; j <= m; ++j) {
    flow(model.omega(), y(t0 + j), q, p, &Dq, &Dp);
    // d/dtau of the flight: (q', p') = (p, -W^2 q) at its end
    Dq.col(t0 + j) += p;
    Dp.col(t0 + j) += (-model.omega().array().square() * q.array()).matrix();
    if (j < m) {  // an interior impact: on the obstacle, then reflected
      F(row) = b.dot(q) + g0;
      J.row(row++) = b.transpose() * Dq;
      reflect(b, p, &Dp);
    }
  }
  if (shape.symmetry == KippSymmetry::None) {  // the k-th impact, then the state back (class comment)
    F(row) = b.dot(q) + g0;
    J.row(row++) = b.transpose() * Dq;
    reflect(b, p, &Dp);
    Dq.leftCols(n) -= Eigen::MatrixXd::Identity(n, n);
    Dp.middleCols(n, n) -= Eigen::MatrixXd::Identity(n, n);
    F.segment(row, n - 1) = model.tangential(q - y.head(n));
    J.middleRows(row, n - 1) = model.tangential(Dq);
    row += n - 1;
    F.segment(row, n - 1) = model.tangential(p - y.segment(n, n));
    J.middleRows(row, n - 1) = model.tangential(Dp);
    row += n - 1;
  } else if (shape.symmetry == KippSymmetry::FlightFlight) {  // B a turning point: p = 0
    F.segment(row, n) = p;
    J.middleRows(row, n) = Dp;
    row += n;
  } else {  // B an impact with normal velocity: on the obstacle, tangential velocity 0
    F(row) = b.dot(q) + g0;
    J.row(row++) = b.transpose() * Dq;
    F.segment(row, n - 1) = model.tangential(p);
    J.middleRows(row, n - 1) = model.tangential(Dp);
    row += n - 1;
  }
  if (row != N - 1) detail::internal_error("kipp_residual: equation count");
}

namespace {

struct ImpactRecord {
  double t = 0.0;
  Eigen::VectorXd q, p_before, p_after;
  bool self_mirror = false;  ///< A or B: its own image under t -> -t
};

}  // namespace

namespace {

// The least period: the smallest shift d (k % d == 0) that maps the impact sequence onto itself; multiplicity k / d.
int multiplicity_of(const std::vector<ImpactRecord>& all, double period, double energy, double omega_max) {
  const int k = static_cast<int>(all.size());
  const double scale = std::sqrt(2.0 * std::max(energy, 1e-300));
  for (int d = 1; d < k; ++d) {
    if (k % d != 0) continue;
    bool same = true;
    for (int i = 0; i < k && same; ++i) {
      const ImpactRecord& a = all[i];
      const ImpactRecord& c = all[(i + d) % k];
      const double dt = std::fmod(c.t - a.t + period, period);
      same = std::abs(dt - period * d / k) <= 1e-8 * period && (a.q - c.q).norm() * omega_max <= 1e-7 * scale &&
             (a.p_after - c.p_after).norm() <= 1e-7 * scale;
    }
    if (same) return k / d;
  }
  return 1;
}

// The admissibility of one flight from (q, p) over tau (docs/modes.md §4): v_out, v_in its end speeds (> 0 towards
// leaving / arriving; only checked at impact ends), min_gap and certified updated.
struct FlightCheck {
  double min_gap = std::numeric_limits<double>::infinity();
  bool certified = true, ends_positive = true;
  int flight = -1;
  double time = 0.0;
  void check(int j, const detail::CosineSum& g, double tau, bool left_impact, double v_out, bool right_impact,
             double v_in, double tol) {
    const double M2 = std::max(g.bound(2), std::numeric_limits<double>::min());
    if ((left_impact && !(v_out > 0)) || (right_impact && !(v_in > 0))) {
      ends_positive = false;
      return;
    }
    const double lo = left_impact ? 0.5 * v_out / M2 : 0.0;
    const double hi = right_impact ? tau - 0.5 * v_in / M2 : tau;
    if (lo < hi) {
      const detail::CosineMinimum mn = detail::minimize(g, lo, hi, tol);
      if (mn.value < min_gap) {
        flight = j;
        time = mn.t;
      }
      min_gap = std::min(min_gap, mn.value);
      certified = certified && mn.certified;
    } else {
      min_gap = std::min(min_gap, g.value(0.5 * (lo + hi)));
    }
  }
};

// kipp_orbit for KippSymmetry::None: the k flights of the whole period from the impact at y.
KippOrbit general_orbit(const KippModel& model, const KippShape& shape, const Eigen::VectorXd& y, double rel_tol) {
  const int n = shape.n, k = shape.k, t0 = shape.first_tau();
  const Eigen::VectorXd& b = model.b();
  const Eigen::VectorXd& omega = model.omega();
  const double g0 = model.g0();
  KippOrbit out;
  Eigen::VectorXd q = y.head(n), p = y.segment(n, n);
  out.energy = 0.5 * (p.squaredNorm() + (omega.array().square() * q.array().square()).sum());
  out.x0 = model.Phi() * q;
  out.v0 = model.Phi() * p;
  std::vector<ImpactRecord> all;
  FlightCheck fc;
  double t = 0.0, min_speed = std::numeric_limits<double>::infinity();
  for (int j = 0; j < k; ++j) {
    const double tau = y(t0 + j);
    const detail::CosineSum g = detail::CosineSum::from_cos_sin(
        g0, (b.array() * q.array()).matrix(), (b.array() * p.array() / omega.array()).matrix(), omega);
    Eigen::VectorXd qe = q, pe = p;
    flow(omega, tau, qe, pe, nullptr, nullptr);
    const double v_out = b.dot(p), v_in = -b.dot(pe);
    min_speed = std::min({min_speed, v_out, v_in});
    fc.check(j, g, tau, true, v_out, true, v_in, rel_tol * g0);
    all.push_back({t, q, Eigen::VectorXd(), p, false});
    t += tau;
    q = qe;
    p = pe;
    out.impact_speeds.push_back(v_in);  // the incoming speed of impact j + 1 (j + 1 = k: the first, at t = 0 again)
    reflect(b, p, nullptr);
  }
  out.period = t;
  // impact i's incoming velocity is the end of flight i - 1 (of flight k - 1 for i = 0)
  std::rotate(out.impact_speeds.rbegin(), out.impact_speeds.rbegin() + 1, out.impact_speeds.rend());
  for (const ImpactRecord& r : all) out.impact_times.push_back(r.t);
  out.gap_certified = fc.certified && fc.ends_positive;
  out.min_flight_gap = fc.ends_positive ? fc.min_gap : 0.0;
  out.min_gap_flight = fc.flight;
  out.min_gap_time = fc.time;
  const double speed_margin = min_speed / (g0 * omega.maxCoeff());
  const double gap_margin = fc.ends_positive ? fc.min_gap / g0 : 0.0;
  out.speed_limited = speed_margin <= gap_margin;
  out.margin = std::min(speed_margin, gap_margin);
  out.multiplicity = multiplicity_of(all, out.period, out.energy, omega.maxCoeff());
  return out;
}

}  // namespace

KippOrbit kipp_orbit(const KippModel& model, const KippShape& shape, const Eigen::VectorXd& y, double rel_tol) {
  if (shape.symmetry == KippSymmetry::None) return general_orbit(model, shape, y, rel_tol);
  const int n = shape.n, m = shape.m(), t0 = shape.first_tau();
  const Eigen::VectorXd& b = model.b();
  const Eigen::VectorXd& omega = model.omega();
  const double g0 = model.g0();
  KippOrbit out;
  double half = 0.0;
  for (int j = 0; j <= m; ++j) half += y(t0 + j);
  out.period = 2.0 * half;

  Eigen::VectorXd q = y.head(n), p = Eigen::VectorXd::Zero(n);
  std::vector<ImpactRecord> half_impacts;  // impacts of the half orbit [0, T/2], A at t = 0
  if (shape.symmetry == KippSymmetry::ImpactImpact) {
    p = y(n) * b.normalized();
    half_impacts.push_back({0.0, q, -p, p, true});
  }
  out.energy = 0.5 * (p.squaredNorm() + (omega.array().square() * q.array().square()).sum());

  // Flights of the half orbit: each a cosine sum of the gap, with impact ends separated from zero (docs/modes.md §4).
  const double speed_scale = g0 * omega.maxCoeff();
  double min_gap = std::numeric_limits<double>::infinity(), min_speed = std::numeric_limits<double>::infinity();
  bool certified = true, ends_positive = true;
  double t = 0.0;
  const bool starts_at_impact = shape.symmetry == KippSymmetry::ImpactImpact;
  for (int j = 0; j <= m; ++j) {
    const double tau = y(t0 + j);
    const detail::CosineSum g = detail::CosineSum::from_cos_sin(
        g0, (b.array() * q.array()).matrix(), (b.array() * p.array() / omega.array()).matrix(), omega);
    const bool left_impact = j > 0 || starts_at_impact;
    const bool right_impact = j < m || shape.symmetry != KippSymmetry::FlightFlight;
    Eigen::VectorXd qe = q, pe = p;
    flow(omega, tau, qe, pe, nullptr, nullptr);
    const double v_out = left_impact ? b.dot(p) : 0.0;    // > 0: leaving the obstacle
    const double v_in = right_impact ? -b.dot(pe) : 0.0;  // > 0: arriving at it
    if (left_impact) min_speed = std::min(min_speed, v_out);
    if (right_impact) min_speed = std::min(min_speed, v_in);
    const double M2 = std::max(g.bound(2), std::numeric_limits<double>::min());
    if ((left_impact && !(v_out > 0)) || (right_impact && !(v_in > 0))) {
      ends_positive = false;
    } else {
      // g' >= v - t M2 near an impact end: g is monotone (and > 0) within v / (2 M2) of it.
      const double lo = left_impact ? 0.5 * v_out / M2 : 0.0;
      const double hi = right_impact ? tau - 0.5 * v_in / M2 : tau;
      if (lo < hi) {
        const detail::CosineMinimum mn = detail::minimize(g, lo, hi, rel_tol * g0);
        if (mn.value < min_gap) {
          out.min_gap_flight = j;
          out.min_gap_time = mn.t;
        }
        min_gap = std::min(min_gap, mn.value);
        certified = certified && mn.certified;
      } else {
        min_gap = std::min(min_gap, g.value(0.5 * (lo + hi)));
      }
    }
    t += tau;
    q = qe;
    p = pe;
    if (right_impact) {
      ImpactRecord r{t, q, p, p, j == m};  // j == m: B, normal velocity, reflected into its opposite
      reflect(b, p, nullptr);
      r.p_after = p;
      half_impacts.push_back(r);
    }
  }
  out.gap_certified = certified && ends_positive;
  out.min_flight_gap = ends_positive ? min_gap : 0.0;
  const double speed_margin = min_speed / speed_scale;
  const double gap_margin = ends_positive ? min_gap / g0 : 0.0;
  out.speed_limited = speed_margin <= gap_margin;
  out.margin = std::min(speed_margin, gap_margin);

  // Whole period: the half orbit's impacts and their mirrors t -> -t (q same, velocities reversed and swapped).
  std::vector<ImpactRecord> all;
  for (const ImpactRecord& r : half_impacts) {
    all.push_back(r);
    if (!r.self_mirror) all.push_back({out.period - r.t, r.q, -r.p_after, -r.p_before});
  }
  std::sort(all.begin(), all.end(), [](const ImpactRecord& a, const ImpactRecord& c) { return a.t < c.t; });
  if (static_cast<int>(all.size()) != shape.k) detail::internal_error("kipp_orbit: impact count");
  const double origin = all.front().t;
  for (const ImpactRecord& r : all) {
    out.impact_times.push_back(r.t - origin);
    out.impact_speeds.push_back(-b.dot(r.p_before));
  }
  out.x0 = model.Phi() * all.front().q;
  out.v0 = model.Phi() * all.front().p_after;

  out.multiplicity = multiplicity_of(all, out.period, out.energy, omega.maxCoeff());
  return out;
}

Eigen::VectorXd grazing_start(const KippModel& model, const KippShape& shape, int coupled) {
  const int n = shape.n;
  if (n != model.coupled_modes()) detail::invalid("grazing_start: expected a shape of the model's coupled modes");
  if (coupled < 0 || coupled >= n)
    detail::invalid_option("grazing_start", "coupled", coupled, "in [0, " + std::to_string(n) + ")");
  if (shape.symmetry == KippSymmetry::None)
    detail::invalid("grazing_start: expected a symmetric shape (symmetries_for), got symmetry none");
  const int mode = coupled;
  const double bj = model.b()(mode);
  const double T = 2.0 * std::acos(-1.0) / model.omega()(mode);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(shape.unknowns());
  const double a = model.g0() / std::abs(bj);
  const int t0 = shape.first_tau(), m = shape.m();
  if (shape.symmetry == KippSymmetry::ImpactImpact) {
    y(mode) = -a * (bj > 0 ? 1.0 : -1.0);  // A on the obstacle: b_j q_j = -g0
    for (int j = 0; j <= m; ++j) y(t0 + j) = T;
  } else {
    y(mode) = a * (bj > 0 ? 1.0 : -1.0);  // A the far turning point: gap 2 g0
    y(t0) = 0.5 * T;                      // to the first touch; then a whole period between touches
    for (int j = 1; j <= m; ++j) y(t0 + j) = T;
    if (shape.symmetry == KippSymmetry::FlightFlight) y(t0 + m) = 0.5 * T;  // B the far turning point again
  }
  return y;
}

Eigen::VectorXd grazing_start_multiple(const KippModel& model, const KippShape& shape, int coupled, int multiple) {
  if (shape.k != 1) detail::invalid_option("grazing_start_multiple", "k", shape.k, "1 (one impact per period)");
  if (multiple < 1) detail::invalid_option("grazing_start_multiple", "multiple", multiple, "at least 1");
  Eigen::VectorXd y = grazing_start(model, shape, coupled);
  const double pi = std::acos(-1.0);
  y(shape.n) = multiple * pi / model.omega()(coupled);
  // B on the obstacle after tau: b_j q_j cos(multiple pi) + g0 = 0
  if (multiple % 2 == 0) y(coupled) = -y(coupled);
  return y;
}

double one_dof_frequency(double g0, double amplitude) {
  if (!(g0 > 0) || !(amplitude >= g0)) detail::invalid_option("one_dof_frequency", "amplitude", amplitude, ">= g0 > 0");
  const double pi = std::acos(-1.0);
  return pi / (pi - std::acos(g0 / amplitude));
}

}  // namespace spp::modes
