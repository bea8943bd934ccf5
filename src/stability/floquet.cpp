#include "spp/stability/floquet.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "spp/detail/invalid.hpp"

namespace spp {
namespace {

// The orbit in md's basis (in_modal_basis), refused unless axially symmetric.
Orbit axial_in_basis(const ModalForm& md, const Orbit& orbit, const char* where) {
  if (orbit.symmetry != Symmetry::Axial)
    detail::invalid(std::string(where) +
                    ": expected an axially symmetric orbit, got a point-symmetric one (its obstacle moves during "
                    "contact: no impact law applies)");
  return in_modal_basis(md, orbit, where);
}

// The monodromy on the coupled modes, in energy-scaled modal coordinates y = (p, q') = (W q, q') (energy |y|^2 / 2;
// the flight flow is a rotation per mode): Mono = F1(2 t1) F2(2 t2) Pi, from just before the onset.
Eigen::MatrixXd coupled_monodromy(const ModalForm& md, const Orbit& orbit) {
  const int m = md.m();
  const Eigen::VectorXd& W = md.omega();
  const Eigen::VectorXd& u = md.u();
  Eigen::MatrixXd Pi = Eigen::MatrixXd::Identity(2 * m, 2 * m);
  // P x -> q: (I - u u^T) q on positions and velocities; on p = W q that is W (I - u u^T) W^-1 = I - z (W^-1 u)^T
  Pi.topLeftCorner(m, m) -= md.z() * u.cwiseQuotient(W).transpose();
  Pi.bottomRightCorner(m, m) -= u * u.transpose();
  const double tc = 2.0 * orbit.t2, tf = 2.0 * orbit.t1;
  const Eigen::MatrixXd C = md.contact_cos(tc), Sn = md.contact_sinc(tc), Ms = md.contact_msin(tc);
  // contact phase p'' = -S p (modal form): p(t) = C p + Sn p'(0), p'(0) = W q'; q'(t) = W^-1 p'(t)
  Eigen::MatrixXd F2(2 * m, 2 * m);
  F2.topLeftCorner(m, m) = C;
  F2.topRightCorner(m, m) = Sn * W.asDiagonal();
  F2.bottomLeftCorner(m, m) = -(W.cwiseInverse().asDiagonal() * Ms);
  F2.bottomRightCorner(m, m) = W.cwiseInverse().asDiagonal() * C * W.asDiagonal();
  const Eigen::MatrixXd F2Pi = F2 * Pi;
  // flight: a rotation of angle omega_k tf in each (p_k, q'_k)
  Eigen::MatrixXd mono(2 * m, 2 * m);
  for (int k = 0; k < m; ++k) {
    const double c = std::cos(W(k) * tf), s = std::sin(W(k) * tf);
    mono.row(k) = c * F2Pi.row(k) + s * F2Pi.row(m + k);
    mono.row(m + k) = -s * F2Pi.row(k) + c * F2Pi.row(m + k);
  }
  return mono;
}

bool by_modulus(const std::complex<double>& a, const std::complex<double>& b) {
  const double ma = std::abs(a), mb = std::abs(b);
  if (ma != mb) return ma < mb;
  return std::arg(a) < std::arg(b);
}

}  // namespace

Floquet floquet(const ModalForm& md, const Orbit& given) {
  const Orbit orbit = axial_in_basis(md, given, "floquet");
  const int m = md.m();
  const Eigen::VectorXd& W = md.omega();
  Floquet res;
  const double T = orbit.period();
  for (Eigen::Index k = 0; k < md.omega_decoupled().size(); ++k) {
    const double th = md.omega_decoupled()(k) * T;  // these modes never see the contact: a rotation
    res.multipliers.emplace_back(std::cos(th), std::sin(th));
    res.multipliers.emplace_back(std::cos(th), -std::sin(th));
  }
  if (m > 0) {
    const Eigen::MatrixXd mono = coupled_monodromy(md, orbit);
    // onset state y0 (= the energy gradient there) and flow direction f = y0' (flight and contact fields agree)
    Eigen::VectorXd y0(2 * m), f(2 * m);
    y0 << orbit.p0, orbit.p0dot.cwiseQuotient(W);
    f << orbit.p0dot, -(W.cwiseProduct(orbit.p0));
    res.structure_residual =
        std::max((mono * f - f).norm() / f.norm(), (mono.transpose() * y0 - y0).norm() / y0.norm());
    // Mono maps y0^perp into itself (grad E is a left eigenvector) and fixes f in it (f . y0 = 0): the map induced on
    // y0^perp / span(f) has the spectrum of Mono without its two 1s. With Q an orthonormal basis of {y0, f}^perp,
    // that map is Q^T Mono Q (for y in span Q: Mono y = Q (Q^T Mono y) + f (f^T Mono y) / |f|^2).
    Eigen::MatrixXd B(2 * m, 2);
    B.col(0) = y0 / y0.norm();
    B.col(1) = f / f.norm();
    const Eigen::MatrixXd Qfull = Eigen::HouseholderQR<Eigen::MatrixXd>(B).householderQ();
    const Eigen::MatrixXd Q = Qfull.rightCols(2 * m - 2);
    res.multipliers.emplace_back(1.0, 0.0);
    res.multipliers.emplace_back(1.0, 0.0);
    if (m > 1) {
      const Eigen::MatrixXd R = Q.transpose() * mono * Q;
      const Eigen::EigenSolver<Eigen::MatrixXd> es(R, false);
      if (es.info() != Eigen::Success) {
        res.multipliers.clear();
        return res;  // NaN radius: not computed
      }
      const Eigen::VectorXcd ev = es.eigenvalues();
      for (Eigen::Index i = 0; i < ev.size(); ++i) res.multipliers.push_back(ev(i));
    }
  }
  // the spectral radius is over everything but the two structural 1s, found before sorting
  double rho = 0.0;
  const size_t structural = md.omega_decoupled().size() * 2;  // the two 1s follow the decoupled pairs
  for (size_t i = 0; i < res.multipliers.size(); ++i)
    if (m == 0 || i < structural || i >= structural + 2) rho = std::max(rho, std::abs(res.multipliers[i]));
  std::sort(res.multipliers.begin(), res.multipliers.end(), by_modulus);
  res.spectral_radius = rho;
  res.margin = 1.0 - rho;
  res.stable = rho < 1.0;
  return res;
}

Eigen::MatrixXd monodromy(const ModalForm& md, const Orbit& given) {
  const Orbit orbit = axial_in_basis(md, given, "monodromy");
  const int m = md.m(), n = md.n(), nd = n - m;
  const double T = orbit.period();
  // y = (p_c, p_d, q'_c, q'_d) -> (x, v): x = Phi W^-1 p_c + Phi_d W_d^-1 p_d, v = Phi q'_c + Phi_d q'_d
  Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  if (m > 0) {
    const Eigen::MatrixXd mc = coupled_monodromy(md, orbit);
    Y.block(0, 0, m, m) = mc.topLeftCorner(m, m);
    Y.block(0, n, m, m) = mc.topRightCorner(m, m);
    Y.block(n, 0, m, m) = mc.bottomLeftCorner(m, m);
    Y.block(n, n, m, m) = mc.bottomRightCorner(m, m);
  }
  for (int k = 0; k < nd; ++k) {
    const double th = md.omega_decoupled()(k) * T, c = std::cos(th), s = std::sin(th);
    Y(m + k, m + k) = c;
    Y(m + k, n + m + k) = s;
    Y(n + m + k, m + k) = -s;
    Y(n + m + k, n + m + k) = c;
  }
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  if (m > 0) {
    S.block(0, 0, n, m) = md.Phi() * md.omega().cwiseInverse().asDiagonal();
    S.block(n, n, n, m) = md.Phi();
  }
  if (nd > 0) {
    S.block(0, m, n, nd) = md.Phi_decoupled() * md.omega_decoupled().cwiseInverse().asDiagonal();
    S.block(n, n + m, n, nd) = md.Phi_decoupled();
  }
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(S);
  return S * Y * lu.inverse();
}

std::string Floquet::brief_report() const {
  std::ostringstream os;
  if (std::isnan(spectral_radius)) return "stability not computed";
  os << (stable ? "stable" : "unstable") << ", spectral radius " << spectral_radius << " (margin " << margin << "), "
     << multipliers.size() << " multipliers";
  return os.str();
}

}  // namespace spp
