#include "spp/stability/floquet.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "search/polish.hpp"
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
// forming_norm (if given): |F2|_F |Pi|_F, the size of the product whose rounding the estimate of floquet() bounds.
Eigen::MatrixXd coupled_monodromy(const ModalForm& md, const Orbit& orbit, double* forming_norm = nullptr) {
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
  if (forming_norm != nullptr) *forming_norm = F2.norm() * Pi.norm();
  // flight: a rotation of angle omega_k tf in each (p_k, q'_k)
  Eigen::MatrixXd mono(2 * m, 2 * m);
  for (int k = 0; k < m; ++k) {
    const double c = std::cos(W(k) * tf), s = std::sin(W(k) * tf);
    mono.row(k) = c * F2Pi.row(k) + s * F2Pi.row(m + k);
    mono.row(m + k) = -s * F2Pi.row(k) + c * F2Pi.row(m + k);
  }
  return mono;
}

// The onset state y0 (= the energy gradient there) and the flow direction f = y0' (flight and contact fields agree),
// in energy-scaled modal coordinates.
std::pair<Eigen::VectorXd, Eigen::VectorXd> onset_state_and_flow(const ModalForm& md, const Orbit& orbit) {
  const int m = md.m();
  const Eigen::VectorXd& W = md.omega();
  Eigen::VectorXd y0(2 * m), f(2 * m);
  y0 << orbit.p0, orbit.p0dot.cwiseQuotient(W);
  f << orbit.p0dot, -(W.cwiseProduct(orbit.p0));
  return {y0, f};
}

// The map Mono induces on y0^perp / span(f, k1, k2), of size 2m - 4: the spectrum of Mono without its structural
// multipliers 1, 1 (f, and the left eigenvector y0) and 0, 0 (k1 = (z, 0), k2 = (0, u): the kernel of Pi, which lies
// in y0^perp: y0 . k1 = z^T p0 = 0 is the SPP's equation, y0 . k2 = u^T q0' its zero normal velocity). Mono maps
// y0^perp into itself (grad E is a left eigenvector) and span(f, k1, k2) into span(f); with Q an orthonormal basis of
// {y0, f, k1, k2}^perp, for y in span Q, Mono y = Q (Q^T Mono y) + (a vector of span(f, k1, k2)), so the induced map
// is Q^T Mono Q. (Without k1, k2 the two zeros came out as rounding noise, 2e-16 to 7e-16: on a 2-dof system, where
// nothing else remains, that noise was reported as the spectral radius.)
Eigen::MatrixXd reduced_monodromy(const ModalForm& md, const Orbit& orbit, const Eigen::MatrixXd& mono) {
  const int m = md.m();
  const auto [y0, f] = onset_state_and_flow(md, orbit);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2 * m, 4);
  B.col(0) = y0 / y0.norm();
  B.col(1) = f / f.norm();
  B.col(2).head(m) = md.z() / md.z().norm();
  B.col(3).tail(m) = md.u() / md.u().norm();
  const Eigen::MatrixXd Qfull = Eigen::HouseholderQR<Eigen::MatrixXd>(B).householderQ();
  const Eigen::MatrixXd Q = Qfull.rightCols(2 * m - 4);
  return Q.transpose() * mono * Q;
}

// The coupled modes' largest modulus but the structural multipliers, without eigenvectors or bound (m > 2); NaN if
// the eigensolver fails.
double coupled_radius(const ModalForm& md, const Orbit& orbit) {
  const Eigen::EigenSolver<Eigen::MatrixXd> es(reduced_monodromy(md, orbit, coupled_monodromy(md, orbit)), false);
  if (es.info() != Eigen::Success) return std::numeric_limits<double>::quiet_NaN();
  return es.eigenvalues().cwiseAbs().maxCoeff();
}

// The part of the coupled radius' error that comes from the SPP's location (found by issue 14's attack: near a fold
// of a branch the SPP equations are ill-conditioned; the polished (t1, t2) of the chain at k5 = 0.9410560159612414
// was 7.1e-11 off the SPP of the same double matrices, and rho there 1.7e-11 off, 11.7 times the rounding bound, with
// the wrong verdict). In the unknowns x = (t1 / T0, t2 / T0, a), T0 = t1 + t2 (the times relative, so that the estimate
// does not depend on the unit of time) and |a| = 1, the computed x is x* + J^-1 r to first order, r the equations'
// value at x (polish's F, at least the rounding of evaluating them: at the SPP itself they do not round to 0). The
// error is largest along J's smallest right singular vector v: |r| / sigma_min. rho moves along v by the difference
// quotient over that distance (over kLocationStep at least: below it the quotient would be rounding).
double radius_location_error(const EquationSet& eq, const Orbit& orbit, double rho) {
  constexpr double kLocationStep = 1e-7;
  const ModalForm& md = eq.modal();
  const int m = md.m();
  const double T0 = orbit.t1 + orbit.t2, eps = std::numeric_limits<double>::epsilon();
  const Eigen::VectorXd a = orbit.a.normalized();
  Eigen::VectorXd F;
  Eigen::MatrixXd Js;
  search::spp_equations(eq, orbit.t1, orbit.t2, a, F, Js);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m + 2, m + 2);
  J.topRows(m + 1) = Js;
  J.topLeftCorner(m + 1, 2) *= T0;
  J.block(m + 1, 2, 1, m) = a.transpose();  // a's scale is fixed: da . a = 0
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
  const double sigma = svd.singularValues()(m + 1);
  // at least the rounding of evaluating N a and z^T p0 at the SPP and of the SPP's own coordinates: the dimension
  // times eps times |J| (|a| = 1)
  const double floor = (m + 2.0) * eps * J.norm();
  // The modal form's own error (ModalForm::data_error(), from the conditioning of M): the equations are those of a
  // system whose omega_k^2 are off by up to frequency_error() relative and u by data_error(). A relative error of a
  // frequency acts on its mode as one of time, and the times' columns of J are scaled by T0: the equations of the true
  // system differ by about that relative error times |J| (issue 14's attack: the chain as x = T y, cond T 1e3, had its
  // SPPs 1e-11 to 4e-10 off in t, and rho off by up to 50 times the bound).
  const double data_r = (md.frequency_error() + md.data_error()) * J.norm();
  const double r = std::max(F.norm(), floor) + data_r;
  const double distance = r / sigma;
  if (!(distance < 1.0)) return std::numeric_limits<double>::infinity();  // (sigma 0 or NaN included)
  const double h = std::max(distance, kLocationStep);
  // How fast rho moves: along J's smallest right singular vector v (where a fold puts the error) and along each time
  // (where the data's error puts it, away from folds), the largest of the difference quotients.
  // (without a data error, J's smallest direction only: the location error is the equations' rounding, largest there)
  Eigen::MatrixXd dirs = Eigen::MatrixXd::Zero(m + 2, md.data_error() > 0.0 ? 3 : 1);
  dirs.col(0) = svd.matrixV().col(m + 1);
  if (dirs.cols() > 1) dirs(0, 1) = dirs(1, 2) = 1.0;
  double rate = 0.0;
  for (Eigen::Index k = 0; k < dirs.cols(); ++k) {
    const Eigen::VectorXd v = dirs.col(k);
    for (const double sign : {1.0, -1.0}) {
      const double t1 = orbit.t1 + sign * h * T0 * v(0), t2 = orbit.t2 + sign * h * T0 * v(1);
      const Eigen::VectorXd ah = a + sign * h * v.tail(m);
      if (!(t1 > 0.0 && t2 > 0.0) || !gap_can_close(eq, t1, ah)) return std::numeric_limits<double>::infinity();
      rate = std::max(rate, std::abs(coupled_radius(md, make_orbit(eq, t1, t2, ah)) - rho) / h);
    }
  }
  return std::isnan(rate) ? std::numeric_limits<double>::infinity() : rate * distance;
}

bool by_modulus(const std::complex<double>& a, const std::complex<double>& b) {
  const double ma = std::abs(a), mb = std::abs(b);
  if (ma != mb) return ma < mb;
  return std::arg(a) < std::arg(b);
}

// Estimated error bound of the largest modulus of R's eigenvalues (ev, right eigenvectors V) when R carries an
// absolute error of 2-norm `eta`. First-order perturbation theory (Wilkinson; Golub & Van Loan §7.2.2): a simple
// eigenvalue lambda_i moves by at most kappa_i |E|_2 + O(|E|^2), kappa_i = |x_i| |y_i| / |y_i^H x_i|, x_i and y_i its
// right and left eigenvectors. The left ones are the rows of V^-1 (R = V D V^-1, so e_i^T V^-1 R = lambda_i e_i^T
// V^-1, and y_i^H x_i = 1): kappa_i = |V e_i| |e_i^T V^-1|. The moduli move by no more than the eigenvalues, so the
// largest modulus rho is off by at most max kappa_i eta over the eigenvalues that could be the largest (|lambda_i| +
// kappa_i eta >= rho). A defective or nearly defective leading eigenvalue (V singular to working precision) gets an
// infinite bound: no verdict near 1 rests on it.
double largest_modulus_error(const Eigen::VectorXcd& ev, const Eigen::MatrixXcd& V, double eta, double rho) {
  const Eigen::FullPivLU<Eigen::MatrixXcd> lu(V);
  if (!lu.isInvertible()) return std::numeric_limits<double>::infinity();
  const Eigen::MatrixXcd Vinv = lu.inverse();
  double err = 0.0;
  for (Eigen::Index i = 0; i < ev.size(); ++i) {
    const double kappa = V.col(i).norm() * Vinv.row(i).norm();
    if (!std::isfinite(kappa)) return std::numeric_limits<double>::infinity();
    if (std::abs(ev(i)) + kappa * eta >= rho) err = std::max(err, kappa * eta);
  }
  return err;
}

}  // namespace

const char* to_string(StabilityVerdict v) {
  switch (v) {
    case StabilityVerdict::NotComputed: return "not_computed";
    case StabilityVerdict::Stable: return "stable";
    case StabilityVerdict::Unstable: return "unstable";
    case StabilityVerdict::Undecided: return "undecided";
    case StabilityVerdict::Neutral: return "neutral";
  }
  return "?";
}

StabilityVerdict stability_verdict(double rho, double error, bool has_decoupled_modes) {
  if (std::isnan(rho) || std::isnan(error)) return StabilityVerdict::NotComputed;
  if (rho - error > 1.0) return StabilityVerdict::Unstable;
  if (rho + error >= 1.0) return StabilityVerdict::Undecided;
  return has_decoupled_modes ? StabilityVerdict::Neutral : StabilityVerdict::Stable;
}

Floquet floquet(const ModalForm& md, const Orbit& given) {
  const Orbit orbit = axial_in_basis(md, given, "floquet");
  const int m = md.m();
  const Eigen::VectorXd& W = md.omega();
  Floquet res;
  const double T = orbit.period();
  const bool decoupled = md.omega_decoupled().size() > 0;
  for (Eigen::Index k = 0; k < md.omega_decoupled().size(); ++k) {
    const double th = md.omega_decoupled()(k) * T;  // these modes never see the contact: a rotation
    res.multipliers.emplace_back(std::cos(th), std::sin(th));
    res.multipliers.emplace_back(std::cos(th), -std::sin(th));
  }
  double rho = 0.0, rho_error = 0.0;  // of the coupled modes' multipliers but the two structural 1s
  if (m > 0) {
    double forming_norm = 0.0;
    const Eigen::MatrixXd mono = coupled_monodromy(md, orbit, &forming_norm);
    const auto [y0, f] = onset_state_and_flow(md, orbit);
    res.structure_residual =
        std::max((mono * f - f).norm() / f.norm(), (mono.transpose() * y0 - y0).norm() / y0.norm());
    res.multipliers.emplace_back(1.0, 0.0);
    res.multipliers.emplace_back(1.0, 0.0);
    if (m > 1) {  // the two zeros of the onset's projection, exact (reduced_monodromy)
      res.multipliers.emplace_back(0.0, 0.0);
      res.multipliers.emplace_back(0.0, 0.0);
    }
    if (m > 2) {
      const Eigen::MatrixXd R = reduced_monodromy(md, orbit, mono);
      const Eigen::EigenSolver<Eigen::MatrixXd> es(R, true);
      if (es.info() != Eigen::Success) {
        res.multipliers.clear();
        return res;  // NaN radius: not computed
      }
      const Eigen::VectorXcd ev = es.eigenvalues();
      Eigen::Index top = 0;
      for (Eigen::Index i = 0; i < ev.size(); ++i) {
        res.multipliers.push_back(ev(i));
        if (std::abs(ev(i)) > std::abs(ev(top)) || (std::abs(ev(i)) == std::abs(ev(top)) && ev(i).imag() > 0))
          top = i;
      }
      rho = std::abs(ev(top));
      res.leading.push_back(ev(top));
      if (ev(top).imag() != 0.0) res.leading.push_back(std::conj(ev(top)));  // real Schur form: exact pairs
      // Backward error of R, estimated (absolute, 2-norm): (a) the computed monodromy's own error, at least what
      // the structure residual shows (an exact Mono fixes f and y0 exactly; the orbit's error shows there too) and
      // at least the rounding of forming F1 F2 Pi (unit roundoff times the dimension times |F2| |Pi|, F1 being a
      // rotation); (b) the reduction Q^T Mono Q and the QR algorithm, backward stable: dimension times eps |R|.
      const double eps = std::numeric_limits<double>::epsilon(), dim = 2.0 * m;
      // (c) the modal form's own error: its eigensolvers are backward stable, so omega_k^2 and the contact phase's
      // d_j^2 are exact for data off by ~dim eps omega_max^2 (absolute). In energy-scaled coordinates the flows'
      // generators then carry an error of ~dim eps omega_max^2 / omega_min, felt for 2 t1 + 2 t2: the slow modes
      // see it most (issue 14's attack: n = 4 with frequencies 0.028 to 29 had errors 16 times the bound without it).
      const double omega_max = std::max(W.maxCoeff(), md.omega_decoupled().size() > 0
                                                          ? md.omega_decoupled().maxCoeff()
                                                          : 0.0);
      // With an ill-conditioned M the modal form's error is larger (ModalForm::data_error(), found by issue 14's
      // attack): the stiffness off by data_error omega_max^2 and u by data_error; u enters the contact phase's
      // S = W^2 - z z^T through z = W u (|dS| <= 2 omega_max^2 |du|) and the projection Pi (|dPi| <= 2 |du| omega_max /
      // omega_min in these coordinates).
      const double de = md.data_error(), ratio = omega_max / W.minCoeff();
      const double modal_eta =
          2.0 * (orbit.t1 + orbit.t2) * (dim * eps + 3.0 * de) * omega_max * ratio + 2.0 * de * ratio * forming_norm;
      const double eta =
          std::max(res.structure_residual, dim * eps * forming_norm) + dim * eps * R.norm() + modal_eta;
      // (a NaN residual, from a degenerate orbit with f = 0, bounds nothing: unbounded, hence undecided near 1)
      rho_error = std::isnan(eta) ? std::numeric_limits<double>::infinity()
                                  : largest_modulus_error(ev, es.eigenvectors(), eta, rho);
    }
  }
  std::sort(res.multipliers.begin(), res.multipliers.end(), by_modulus);
  // the decoupled modes' multipliers have modulus 1 exactly (cos^2 + sin^2 rounds to 1 +- eps: not taken from them)
  res.spectral_radius = decoupled ? std::max(rho, 1.0) : rho;
  res.spectral_radius_error = rho_error;
  res.margin = 1.0 - res.spectral_radius;
  res.verdict = stability_verdict(rho, rho_error, decoupled);
  res.stable = res.verdict == StabilityVerdict::Stable;
  return res;
}

Floquet floquet(const EquationSet& eq, const Orbit& given) {
  if (eq.symmetry() != Symmetry::Axial)
    detail::invalid("floquet: expected the axial equation set, got the " + std::string(to_string(eq.symmetry())) +
                    " one");
  const ModalForm& md = eq.modal();
  Floquet res = floquet(md, given);
  if (res.leading.empty()) return res;  // nothing located decides (m <= 2: no multiplier but the structural ones)
  const double rho = std::abs(res.leading.front());
  res.location_error = radius_location_error(eq, in_modal_basis(md, given, "floquet"), rho);
  res.spectral_radius_error += res.location_error;
  res.verdict = stability_verdict(rho, res.spectral_radius_error, md.omega_decoupled().size() > 0);
  res.stable = res.verdict == StabilityVerdict::Stable;
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
  os << to_string(verdict) << ", spectral radius " << spectral_radius << " +- " << std::setprecision(2)
     << spectral_radius_error << std::setprecision(6) << " (margin " << margin << "), " << multipliers.size()
     << " multipliers";
  if (verdict == StabilityVerdict::Neutral) os << " (modes that never see the contact lie on the unit circle)";
  return os.str();
}

}  // namespace spp
