#include "spp/orbit.hpp"

#include <cmath>
#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>

#include "spp/detail/cosine_sum.hpp"

namespace spp {

namespace {
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
}  // namespace

Orbit make_orbit(const ModalForm& md, double t1, double t2, const Eigen::VectorXd& a_in) {
  if (md.g0() == 0.0)
    throw std::invalid_argument("orbit: g0 = 0, the scale of the initial conditions (eq. 5.2) is undefined");
  Orbit o;
  o.t1 = t1;
  o.t2 = t2;
  const Eigen::ArrayXd& w = md.omega().array();
  Eigen::VectorXd p0 = ((w * t1).cos() * a_in.array()).matrix();
  const Eigen::VectorXd q0 = (p0.array() / w).matrix();
  const double r = md.u().dot(q0);
  o.closure_ratio = q0.norm() > 0 ? std::abs(r) / q0.norm() : 0.0;
  if (r == 0.0) throw std::invalid_argument("orbit: u^T W^-1 p0 = 0, the gap cannot close (eq. 5.2)");
  const double scale = -md.g0() / (md.beta() * r);  // eq. (5.2): w^T x0 = -g0
  o.a = scale * a_in;
  o.p0 = scale * p0;
  o.p0dot = (-w * (w * t1).sin() * o.a.array()).matrix();  // p'(0) = -W tan(W t1) p0, pole-free
  Eigen::VectorXd cd;
  contact_flow(md, t2, o.p0, o.p0dot, o.c, cd);
  o.x0 = md.Phi() * (o.p0.array() / w).matrix();
  o.v0 = md.Phi() * (o.p0dot.array() / w).matrix();
  o.energy = 0.5 * (o.p0dot.array() / w).matrix().squaredNorm() + 0.5 * o.p0.squaredNorm();
  return o;
}

OrbitState orbit_state(const ModalForm& md, const Orbit& o, double t) {
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

Admissibility check_admissibility(const ModalForm& md, const Orbit& o, double rel_tol) {
  Admissibility adm;
  // Gap in flight about its axis t = -t1:  g(-t1 + tau) = g0 + sum beta u_k a_k / omega_k cos(omega_k tau).
  detail::CosineSum gap;
  gap.c0 = md.g0();
  gap.freq = md.omega();
  gap.amp = (md.beta() * md.u().array() * o.a.array() / md.omega().array()).matrix();
  // Force in contact about its axis t = t2:  lambda(t2 + tau) = sum (G^T z)_j (G^T c)_j / beta cos(d_j tau).
  detail::CosineSum force;
  force.freq = md.d();
  force.amp = ((md.G().transpose() * md.z()).array() * (md.G().transpose() * o.c).array() / md.beta()).matrix();

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
  const double zrel = 1e-7;
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

double return_error(const System& sys, const Orbit& o) {
  const int n = sys.n();
  Eigen::VectorXd X0(2 * n);
  X0 << o.x0, o.v0;
  Eigen::MatrixXd A1 = Eigen::MatrixXd::Zero(2 * n, 2 * n), A2 = A1;
  const auto llt = sys.M().llt();
  A1.topRightCorner(n, n).setIdentity();
  A2.topRightCorner(n, n).setIdentity();
  A1.bottomLeftCorner(n, n) = -llt.solve(sys.K());
  A2.bottomLeftCorner(n, n) = -llt.solve(sys.contact_stiffness());
  const Eigen::MatrixXd E2 = (2.0 * o.t2 * A2).exp(), E1 = (2.0 * o.t1 * A1).exp();
  const Eigen::VectorXd XT = E1 * (E2 * X0);
  return (XT - X0).norm() / X0.norm();
}

}  // namespace spp
