#include "spp/orbit/orbit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "spp/detail/cosine_sum.hpp"
#include "spp/detail/invalid.hpp"

namespace spp {

namespace {
/// An end derivative of the gap or force within this fraction of its bound (sum |amp| f^k) is taken as zero and the
/// next one decides (ends_ok): far above the rounding of the sums (~m eps), far below any derivative that matters.
constexpr double kEndDerivativeZero = 1e-7;
/// Golden-section refinement of a sampled minimum stops at this fraction of the interval: rounding level of s.
constexpr double kGoldenTol = 1e-15;
/// admissibility_margin samples each phase at this many points per half-period of its fastest term (within
/// [kMarginSamplesMin, kMarginSamplesMax]) before refining the three lowest: the margin's minimum moves by O(h^2)
/// between samples, so a sign change of the margin is not stepped over at the resolution the events are located.
constexpr double kMarginSamplesPerHalfPeriod = 40.0;
constexpr int kMarginSamplesMin = 200, kMarginSamplesMax = 200000;
/// Samples per phase of the point-symmetric orbits' min_gap and min_force: a report, not a proof (their verdict is
/// structural).
constexpr int kAdmissibilitySamples = 2000;

// p, p' after time t of the contact phase from (p0, p0dot), computed in the G basis (O(m^2)).
void contact_flow(const ModalForm& md, double t, const Eigen::VectorXd& p0, const Eigen::VectorXd& p0dot,
                  Eigen::VectorXd& p, Eigen::VectorXd& pdot) {
  const Eigen::VectorXd y = md.G().transpose() * p0, yd = md.G().transpose() * p0dot;
  const Eigen::ArrayXd& dd = md.d().array();
  Eigen::ArrayXd cs = (dd * t).cos(), sc(dd.size()), ms = dd * (dd * t).sin();
  for (Eigen::Index j = 0; j < dd.size(); ++j) sc(j) = dd(j) > 0 ? std::sin(dd(j) * t) / dd(j) : t;
  p = md.G() * (cs * y.array() + sc * yd.array()).matrix();
  pdot = md.G() * (-ms * y.array() + cs * yd.array()).matrix();
}

void flight_flow(const ModalForm& md, double t, const Eigen::VectorXd& p0, const Eigen::VectorXd& p0dot,
                 Eigen::VectorXd& p, Eigen::VectorXd& pdot) {
  const Eigen::ArrayXd& w = md.omega().array();
  p = ((w * t).cos() * p0.array() + (w * t).sin() / w * p0dot.array()).matrix();
  pdot = (-w * (w * t).sin() * p0.array() + (w * t).cos() * p0dot.array()).matrix();
}

OrbitState state_in_basis(const ModalForm& md, const Orbit& o, double t);
}  // namespace

namespace {
// Every field of the orbit from the null vector a of N, given the factor that scales it.
Orbit scaled_orbit(const EquationSet& eq, double t1, double t2, const Eigen::VectorXd& a_in, double scale) {
  const ModalForm& md = eq.modal();
  Orbit o;
  o.t1 = t1;
  o.t2 = t2;
  o.symmetry = eq.symmetry();
  const Eigen::ArrayXd& w = md.omega().array();
  const Eigen::VectorXd q0 = (eq.onset_position(t1, a_in).array() / w).matrix();
  o.closure_ratio = q0.norm() > 0 ? std::abs(md.u().dot(q0)) / q0.norm() : 0.0;
  o.a = scale * a_in;
  o.p0 = eq.onset_position(t1, o.a);
  o.p0dot = eq.onset_velocity(t1, o.a);  // axial: p'(0) = -W tan(W t1) p0, pole-free
  Eigen::VectorXd cd;
  contact_flow(md, t2, o.p0, o.p0dot, o.c, cd);  // point symmetry: c = p(t2) = 0
  o.x0 = md.Phi() * (o.p0.array() / w).matrix();
  o.v0 = md.Phi() * (o.p0dot.array() / w).matrix();
  o.energy = 0.5 * (o.p0dot.array() / w).matrix().squaredNorm() + 0.5 * o.p0.squaredNorm();
  if (eq.moving_obstacle()) o.obstacle_velocity = md.beta() * md.u().dot((o.p0dot.array() / w).matrix());
  return o;
}
}  // namespace

bool gap_can_close(const EquationSet& eq, double t1, const Eigen::VectorXd& a) {
  const ModalForm& md = eq.modal();
  return md.u().dot((eq.onset_position(t1, a).array() / md.omega().array()).matrix()) != 0.0;
}

Orbit make_orbit(const EquationSet& eq, double t1, double t2, const Eigen::VectorXd& a_in) {
  const ModalForm& md = eq.modal();
  if (md.g0() == 0.0)
    detail::invalid("orbit: g0 = 0, the scale of the initial conditions (eq. 5.2) is undefined");
  const double r = md.u().dot((eq.onset_position(t1, a_in).array() / md.omega().array()).matrix());
  if (r == 0.0) detail::invalid("orbit: u^T W^-1 p0 = 0, the gap cannot close (eq. 5.2)");
  return scaled_orbit(eq, t1, t2, a_in, -md.g0() / (md.beta() * r));  // eq. (5.2): w^T x0 = -g0
}

Admissibility sample_point_admissibility(const ModalForm& md, const Orbit& orbit) {
  const Orbit o = in_modal_basis(md, orbit, "sample_point_admissibility");
  Admissibility adm;
  const int samples = kAdmissibilitySamples;
  adm.min_gap = std::numeric_limits<double>::infinity();
  adm.min_force = std::numeric_limits<double>::infinity();
  double max_force = -std::numeric_limits<double>::infinity();
  for (int i = 0; i <= samples; ++i) {
    const OrbitState c = state_in_basis(md, o, 2.0 * o.t2 * i / samples);
    adm.min_force = std::min(adm.min_force, c.force);
    max_force = std::max(max_force, c.force);
    const OrbitState f = state_in_basis(md, o, 2.0 * o.t2 + 2.0 * o.t1 * i / samples);
    // flight gap against the obstacle where it stands at onset (it moves during contact only)
    adm.min_gap = std::min(adm.min_gap, f.gap);
  }
  adm.mid_flight_gap = state_in_basis(md, o, 2.0 * o.t2 + o.t1).gap;
  adm.mid_contact_force = state_in_basis(md, o, o.t2).force;
  adm.ends_ok = false;
  adm.admissible = adm.min_force >= 0.0 && max_force <= 0.0;  // only if the force vanishes at every sample
  adm.certified = !adm.admissible;  // "never admissible" is structural (an odd force); the converse only sampled
  return adm;
}

Orbit make_unit_energy_orbit(const EquationSet& eq, double t1, double t2, const Eigen::VectorXd& a) {
  const Orbit one = scaled_orbit(eq, t1, t2, a, 1.0);
  if (!(one.energy > 0.0)) detail::invalid("orbit: zero null vector, no orbit to scale");
  // The sign that makes the force >= 0 at mid-contact (axial) or at t2 / 2 (point: zero at t2).
  const double sign = state_in_basis(eq.modal(), one, eq.force_probe(t2)).force >= 0.0 ? 1.0 : -1.0;
  return scaled_orbit(eq, t1, t2, a, sign / std::sqrt(one.energy));
}

namespace {
// orbit_state for an orbit known to be in md's basis (the internal loops: no O(n m) check per sample).
OrbitState state_in_basis(const ModalForm& md, const Orbit& o, double t) {
  Eigen::VectorXd p, pd;
  OrbitState s;
  if (t <= 2.0 * o.t2) {
    contact_flow(md, t, o.p0, o.p0dot, p, pd);
    s.force = md.z().dot(p) / md.beta();  // eq. (2.7) in modal form
  } else {
    flight_flow(md, t - o.period(), o.p0, o.p0dot, p, pd);
    s.force = 0.0;
  }
  const Eigen::ArrayXd& w = md.omega().array();
  const Eigen::VectorXd q = (p.array() / w).matrix();
  s.x = md.Phi() * q;
  s.v = md.Phi() * (pd.array() / w).matrix();
  s.gap = md.beta() * md.u().dot(q) + md.g0();
  return s;
}
}  // namespace

OrbitState orbit_state(const ModalForm& md, const Orbit& o, double t) {
  return state_in_basis(md, in_modal_basis(md, o, "orbit_state"), t);
}

namespace {
// Gap in flight about its axis t = -t1:  g(-t1 + tau) = g0 + sum beta u_k a_k / omega_k cos(omega_k tau).
detail::CosineSum flight_gap(const ModalForm& md, const Orbit& o) {
  detail::CosineSum gap;
  gap.c0 = md.g0();
  gap.freq = md.omega();
  gap.amp = (md.beta() * md.u().array() * o.a.array() / md.omega().array()).matrix();
  return gap;
}

// Force in contact about its axis t = t2:  lambda(t2 + tau) = sum (G^T z)_j (G^T c)_j / beta cos(d_j tau).
detail::CosineSum contact_force(const ModalForm& md, const Orbit& o) {
  detail::CosineSum force;
  force.freq = md.d();
  force.amp = ((md.G().transpose() * md.z()).array() * (md.G().transpose() * o.c).array() / md.beta()).matrix();
  return force;
}
}  // namespace

Admissibility check_admissibility(const ModalForm& md, const Orbit& orbit, double rel_tol) {
  const Orbit o = in_modal_basis(md, orbit, "check_admissibility");
  Admissibility adm;
  const detail::CosineSum gap = flight_gap(md, o), force = contact_force(md, o);

  const double gscale = std::abs(gap.c0) + gap.amp.cwiseAbs().sum();
  const double fscale = force.amp.cwiseAbs().sum();
  const double gtol = rel_tol * gscale, ftol = rel_tol * fscale;
  const auto gmin = detail::minimize(gap, 0.0, o.t1, gtol);
  const auto fmin = detail::minimize(force, 0.0, o.t2, ftol);
  adm.min_gap = gmin.value;
  adm.min_force = fmin.value;
  adm.certified = gmin.certified && fmin.certified;
  adm.mid_flight_gap = gap.value(0.0);
  adm.mid_contact_force = force.value(0.0);

  // Ends: gap(t1 - s) ~ -g'''(t1) s^3/6 + g''''(t1) s^4/24 (g, g', g'' vanish by construction);
  // force(t2 - s) ~ -f'(t2) s + f''(t2) s^2/2.
  const double zrel = kEndDerivativeZero;
  const double g3 = gap.derivative(o.t1, 3), g4 = gap.derivative(o.t1, 4);
  const double f1 = force.derivative(o.t2, 1), f2 = force.derivative(o.t2, 2);
  const bool gap_end = g3 < -zrel * gap.bound(3) || (std::abs(g3) <= zrel * gap.bound(3) && g4 >= -zrel * gap.bound(4));
  const bool force_end =
      f1 < -zrel * force.bound(1) || (std::abs(f1) <= zrel * force.bound(1) && f2 >= -zrel * force.bound(2));
  adm.onset_force_rate = -f1;
  adm.ends_ok = gap_end && force_end;
  adm.admissible = adm.ends_ok && gmin.lower_bound >= -gtol && fmin.lower_bound >= -ftol;
  return adm;
}

namespace {
// (cos x - 1 + x^2/2) / x^3, (sin x - x) / x^3, (cos x - 1) / x and sin x / x without cancellation near 0.
double cos_m2_x3(double x) {
  if (std::abs(x) > 0.5) return (std::cos(x) - 1.0 + 0.5 * x * x) / (x * x * x);
  const double x2 = x * x;  // x/24 - x^3/720 + x^5/40320 - x^7/3628800 + x^9/479001600
  return x * (1.0 / 24 - x2 * (1.0 / 720 - x2 * (1.0 / 40320 - x2 * (1.0 / 3628800 - x2 / 479001600.0))));
}
double sin_m1_x3(double x) {
  if (std::abs(x) > 0.5) return (std::sin(x) - x) / (x * x * x);
  const double x2 = x * x;  // -1/6 + x^2/120 - x^4/5040 + x^6/362880 - x^8/39916800
  return -1.0 / 6 + x2 * (1.0 / 120 - x2 * (1.0 / 5040 - x2 * (1.0 / 362880 - x2 / 39916800.0)));
}
double cos_m1_x(double x) {
  if (std::abs(x) > 0.5) return (std::cos(x) - 1.0) / x;
  const double x2 = x * x;
  return -x * (0.5 - x2 * (1.0 / 24 - x2 * (1.0 / 720 - x2 * (1.0 / 40320 - x2 / 3628800.0))));
}
double sinc(double x) {
  if (std::abs(x) > 0.5) return std::sin(x) / x;
  const double x2 = x * x;
  return 1.0 - x2 * (1.0 / 6 - x2 * (1.0 / 120 - x2 * (1.0 / 5040 - x2 / 362880.0)));
}

// Minimum over s in [0, len] of f: samples fine enough for the fastest term, then golden-section refinement
// around the three best samples.
template <typename F>
double sampled_minimum(const F& f, double len, double fastest) {
  const int samples = std::clamp(static_cast<int>(kMarginSamplesPerHalfPeriod * fastest * len / std::numbers::pi),
                                 kMarginSamplesMin, kMarginSamplesMax);
  const double h = len / samples;
  std::vector<std::pair<double, int>> v;
  v.reserve(samples + 1);
  for (int i = 0; i <= samples; ++i) v.emplace_back(f(i * h), i);
  std::partial_sort(v.begin(), v.begin() + 3, v.end());
  double best = v[0].first;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int k = 0; k < 3; ++k) {
    double a = std::max(0.0, (v[k].second - 1) * h), b = std::min(len, (v[k].second + 1) * h);
    double c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
    for (int it = 0; it < 60 && b - a > kGoldenTol * len; ++it) {
      if (fc < fd) {
        b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
      } else {
        a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
      }
    }
    best = std::min({best, fc, fd});
  }
  return best;
}
}  // namespace

double admissibility_margin(const ModalForm& md, const Orbit& orbit) {
  const Orbit o = in_modal_basis(md, orbit, "admissibility_margin");
  // Gap about the flight's end: g(t1 - s) over the axis form sum A_k cos(w_k tau), tau = t1 - s; the parts that
  // make g, g', g'' at the end (zero by construction, rounding otherwise) are dropped, then divided by (s/t1)^3.
  const detail::CosineSum g = flight_gap(md, o), f = contact_force(md, o);
  const Eigen::ArrayXd &w = g.freq.array(), &A = g.amp.array();
  const Eigen::ArrayXd C = (w * o.t1).cos(), S = (w * o.t1).sin();
  const double gscale = std::abs(g.c0) + A.abs().sum();
  const double t13 = o.t1 * o.t1 * o.t1;
  auto gap = [&](double s) {
    double v = 0.0;
    for (Eigen::Index k = 0; k < w.size(); ++k)
      v += A(k) * w(k) * w(k) * w(k) * (C(k) * cos_m2_x3(w(k) * s) + S(k) * sin_m1_x3(w(k) * s));
    return t13 * v / gscale;
  };
  // Force about the release: lambda(t2 - s) = sum B_j cos(d_j (t2 - s)) minus lambda(t2), divided by s/t2.
  const Eigen::ArrayXd &d = f.freq.array(), &B = f.amp.array();
  const Eigen::ArrayXd Cd = (d * o.t2).cos(), Sd = (d * o.t2).sin();
  const double fscale = B.abs().sum();
  auto force = [&](double s) {
    double v = 0.0;
    for (Eigen::Index j = 0; j < d.size(); ++j)
      v += B(j) * d(j) * (Cd(j) * cos_m1_x(d(j) * s) + Sd(j) * sinc(d(j) * s));
    return o.t2 * v / fscale;
  };
  const double gmin = sampled_minimum(gap, o.t1, w.maxCoeff());
  const double fmin = fscale > 0 ? sampled_minimum(force, o.t2, d.maxCoeff()) : 0.0;
  return std::min(gmin, fmin);
}

namespace {
/// Relative mismatch below which an orbit's modal coordinates are taken as those of the modal form in use: the same
/// basis gives x0 = Phi W^-1 p0 to rounding (~m eps); another basis (an eigenvector of the other sign, another
/// rotation of a repeated-frequency group) moves x0 by that mode's part, O(1) of the orbit's scale.
constexpr double kSameBasisTol = 1e-8;

// |Phi W^-1 p0 - x0| + |Phi W^-1 p0dot - v0| / omega_min, relative to |x0| + |v0| / omega_min (a length, like x).
double basis_mismatch(const ModalForm& md, const Eigen::VectorXd& p0, const Eigen::VectorXd& p0dot,
                      const Eigen::VectorXd& x0, const Eigen::VectorXd& v0) {
  const Eigen::ArrayXd& w = md.omega().array();
  const double wmin = w.size() > 0 ? w.minCoeff() : 1.0;
  const double mismatch = (md.Phi() * (p0.array() / w).matrix() - x0).norm() +
                          (md.Phi() * (p0dot.array() / w).matrix() - v0).norm() / wmin;
  const double scale = x0.norm() + v0.norm() / wmin;
  return scale > 0.0 ? mismatch / scale : mismatch;
}
}  // namespace

Orbit in_modal_basis(const ModalForm& md, const Orbit& o, const char* where) {
  if (o.x0.size() != md.n() || o.v0.size() != md.n()) {
    std::ostringstream os;
    os << where << ": expected an orbit of " << md.n() << " dofs, got x0 of " << o.x0.size() << " and v0 of "
       << o.v0.size() << " entries";
    detail::invalid(os.str());
  }
  const bool sizes = o.p0.size() == md.m() && o.p0dot.size() == md.m() && o.a.size() == md.m() &&
                     o.c.size() == md.m();
  if (sizes && basis_mismatch(md, o.p0, o.p0dot, o.x0, o.v0) <= kSameBasisTol) return o;  // this basis: as it is
  // Another basis (or none): x0, v0 do not depend on it. Their coupled-mode coordinates by least squares on the mode
  // shapes (Phi has full column rank), O(n m^2); the flows give a and c from p0, p0dot.
  const Eigen::ArrayXd& w = md.omega().array();
  Eigen::MatrixXd xv(md.n(), 2);
  xv << o.x0, o.v0;
  const Eigen::MatrixXd q = md.Phi().colPivHouseholderQr().solve(xv);
  Orbit r = o;
  r.p0 = (w * q.col(0).array()).matrix();
  r.p0dot = (w * q.col(1).array()).matrix();
  const double mismatch = basis_mismatch(md, r.p0, r.p0dot, o.x0, o.v0);
  if (!(mismatch <= kSameBasisTol)) {
    std::ostringstream os;
    os.precision(3);
    os << where << ": the orbit's x0, v0 are not a motion of this system's modes that see the contact (relative "
       << "residual " << mismatch << " of their projection on them): it is an orbit of another system";
    detail::invalid(os.str());
  }
  const Eigen::VectorXd q0 = q.col(0);
  r.closure_ratio = q0.norm() > 0 ? std::abs(md.u().dot(q0)) / q0.norm() : 0.0;  // as scaled_orbit
  Eigen::VectorXd pd;
  flight_flow(md, -o.t1, r.p0, r.p0dot, r.a, pd);
  contact_flow(md, o.t2, r.p0, r.p0dot, r.c, pd);
  return r;
}

OrbitSamples sample_orbit(const ModalForm& md, const Orbit& orbit, int samples) {
  const Orbit o = in_modal_basis(md, orbit, "sample_orbit");
  OrbitSamples s{Eigen::VectorXd(samples), Eigen::VectorXd(samples), Eigen::VectorXd(samples),
                 Eigen::MatrixXd(samples, md.n()), Eigen::MatrixXd(samples, md.n())};
  const double T = o.period();
  for (int k = 0; k < samples; ++k) {
    s.t(k) = T * k / (samples - 1);
    const OrbitState st = state_in_basis(md, o, s.t(k));
    s.x.row(k) = st.x.transpose();
    s.v.row(k) = st.v.transpose();
    s.gap(k) = st.gap;
    s.force(k) = st.force;
  }
  return s;
}

double return_error(const System& sys, const Orbit& o) {
  const int n = sys.n();
  // State (L^T x, L^T v / w), M = L L^T and w a frequency of the system (sqrt |L^-1 K L^-T|): mass-weighted, so that
  // the relative error does not depend on the units of each dof (x = D x' in raw coordinates gave return errors up
  // to 1e4, or NaN, for exact roots; found by an independent attack), both halves in the same units and the flows'
  // generators balanced (entries ~ w, not 1 and w^2), so that it does not depend on the time scale either (with K
  // scaled by 1e16, the unbalanced form gave 0.5 to 7).
  const Eigen::LLT<Eigen::MatrixXd> llt(sys.M());
  const auto L = llt.matrixL();
  auto weighted = [&](const Eigen::MatrixXd& S) {  // L^-1 S L^-T (the contact stiffness is not symmetric)
    const Eigen::MatrixXd A = L.solve(S);                                // L^-1 S
    return Eigen::MatrixXd(L.solve(A.transpose()).transpose());          // (L^-1 (L^-1 S)^T)^T = L^-1 S L^-T
  };
  const Eigen::MatrixXd Kw = weighted(sys.K()), Kcw = weighted(sys.contact_stiffness());
  const double w = std::sqrt(Kw.norm());
  const Eigen::MatrixXd LT = llt.matrixU();
  Eigen::VectorXd X0(2 * n);
  X0 << LT * o.x0, LT * o.v0 / w;
  Eigen::MatrixXd A1 = Eigen::MatrixXd::Zero(2 * n, 2 * n), A2 = A1;
  A1.topRightCorner(n, n) = w * Eigen::MatrixXd::Identity(n, n);
  A2.topRightCorner(n, n) = w * Eigen::MatrixXd::Identity(n, n);
  A1.bottomLeftCorner(n, n) = -Kw / w;
  A2.bottomLeftCorner(n, n) = -Kcw / w;
  const Eigen::MatrixXd E2 = (2.0 * o.t2 * A2).exp(), E1 = (2.0 * o.t1 * A1).exp();
  const Eigen::VectorXd XT = E1 * (E2 * X0);
  return (XT - X0).norm() / X0.norm();
}

}  // namespace spp
