#include "spp/modal/modal.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "spp/detail/dense_products.hpp"
#include "spp/detail/internal_error.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/detail/out_of_memory.hpp"
#include "spp/detail/symmetric_eigen.hpp"

namespace spp {

namespace {
// The eigensolver's error on each omega^2 is ~ eps omega_max^2 (backward stable): the slowest omega^2 is resolved to
// kSpectrumDigits relative only if omega_max^2 / omega_min^2 <= kSpectrumDigits / eps (omega ratio ~6.7e4). Beyond,
// the slow modes, which carry the SPPs, are rounding: found by an independent review (a chain with one mass 1e-30
// gave "success, 0 SPPs" in a NaN window; frequencies 0.304, 0.903 for 0.289, 0.898). Refused, not solved.
constexpr double kSpectrumDigits = 1e-6;
// The frequencies themselves (rad per time unit): the admissibility and stability tests use time derivatives of the
// orbit up to ~omega^4 times its amplitude and their products, which overflow or underflow beyond ~1e+-75 per factor
// (masses 1e-250 on a unit chain, omega ~ 1e125, gave its three admissible SPPs as inadmissible with status
// incomplete; masses 1e280 lost all six; found by an independent attack). Refused with the remedy, another time unit.
constexpr double kMaxFrequency = 1e50;
void check_resolved_spectrum(const Eigen::VectorXd& omega2) {  // ascending
  const double lo = omega2(0), hi = omega2(omega2.size() - 1);
  if (lo > 0.0 && std::isfinite(hi) && std::numeric_limits<double>::epsilon() * hi <= kSpectrumDigits * lo) {
    const double max2 = kMaxFrequency * kMaxFrequency;
    if (lo > 0.0 && std::isfinite(hi) && (hi > max2 || lo < 1.0 / max2)) {
      std::ostringstream os;
      os << std::setprecision(3) << "system: its frequencies run from omega_min = " << std::sqrt(lo)
         << " to omega_max = " << std::sqrt(hi) << " rad per time unit, outside [1e-50, 1e50], where the orbits' time "
         << "derivatives stay within double precision: expected the system in another time unit (multiplying M by c^2 "
         << "divides every frequency by c)";
      detail::invalid(os.str());
    }
    return;
  }
  std::ostringstream os;
  if (!(lo > 0.0) || !std::isfinite(hi) || !std::isfinite(lo))
    os << std::setprecision(3) << "system: K v = omega^2 M v gives omega^2 from " << lo << " to " << hi
       << ", not positive and finite: M or K is singular to rounding although each passed the definiteness test (a "
          "near-zero mass or stiffness? check M and K)";
  else
    os << std::setprecision(3) << "system: its frequencies span omega_max / omega_min = "
       << std::sqrt(std::max(hi, 0.0)) / std::sqrt(std::max(lo, 0.0))
       << " (omega_min = " << std::sqrt(std::max(lo, 0.0)) << ", omega_max = " << std::sqrt(std::max(hi, 0.0))
       << "): beyond what double precision resolves (at most "
       << std::sqrt(kSpectrumDigits / std::numeric_limits<double>::epsilon())
       << ", for 6 significant digits of the slowest omega^2). A mode that much stiffer is quasi-static: condense it "
          "out (static condensation), or check M and K (units, a near-zero mass)";
  detail::invalid(os.str());
}

// ModalForm::data_error(): 0 for a well-conditioned mass matrix (the stability bound's own terms cover the
// eigensolvers' backward error there, measured); else measured. The computed modes X (n x n, M-normalised to
// rounding) and omega^2 = lam are exact for the system written in the coordinates x = X q: mass I + B, stiffness
// diag(lam) + A, coupling b = X^T w (a congruence: same multipliers), with B = X^T M X - I, A = X^T K X - diag(lam).
// In M-orthonormal coordinates (I + B)^-1/2 q that is, to first order, the stiffness diag(lam) + dK with
// dK = sym(X^T R), R = K X - M X diag(lam), and the coupling b - B b / 2. The modal form takes diag(lam) and the b it
// rounded: its error is |dK| in the stiffness and |b_exact - B b / 2 - b_rounded| / |b| in u. Both are computed in long
// double (64-bit mantissa): in double their own rounding, ~eps cond(M) omega_max^2, would be as large as what they
// measure (the eigensolver's error is ~0.05 eps cond(M) omega_max^2 on the chain in dense coordinates: cond(M~) 2.6e5
// and 2.6e7 gave 2.7e-12 and 3.3e-10 relative, against an mpmath eigensolve). Cost O(n^3) in long double, only when
// M~ = D^-1/2 M D^-1/2 (D = diag M) has a condition number above kWellConditionedMass.
constexpr double kWellConditionedMass = 1e2;
// Returns {data_error, frequency_error} (ModalForm's accessors).
std::pair<double, double> modal_data_error(const System& system, const Eigen::MatrixXd& X, const Eigen::VectorXd& lam) {
  const Eigen::VectorXd s = system.M().diagonal().cwiseSqrt().cwiseInverse();
  const detail::SymmetricEigen me = detail::symmetric_eigen(s.asDiagonal() * system.M() * s.asDiagonal(), false);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!me.ok || !(me.values(0) > 0.0)) return {kInf, kInf};
  const double cond = me.values(me.values.size() - 1) / me.values(0);
  if (cond <= kWellConditionedMass) return {0.0, 0.0};
  using MatL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  using VecL = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
  const MatL Xl = X.cast<long double>(), Kl = system.K().cast<long double>(), Ml = system.M().cast<long double>();
  const VecL laml = lam.cast<long double>(), wl = system.w().cast<long double>();
  const MatL MX = Ml * Xl;
  const MatL R = Kl * Xl - MX * laml.asDiagonal();
  const MatL XR = Xl.transpose() * R;
  const MatL dK = (XR + XR.transpose()) / 2.0L;
  const MatL B = Xl.transpose() * MX - MatL::Identity(X.cols(), X.cols());
  const VecL b = Xl.transpose() * wl;
  const Eigen::VectorXd b_rounded = X.transpose() * system.w();
  const VecL db = b - B * b / 2.0L - b_rounded.cast<long double>();
  const double stiffness = static_cast<double>(dK.norm()) / lam.maxCoeff();
  const double coupling = static_cast<double>(db.norm() / b.norm());
  // (and the long double rounding of both, ~n eps_ld cond(M~), and the first order's neglected B^2: x2)
  double frequency = 0.0;  // each mode's row of dK over its own omega^2
  for (Eigen::Index k = 0; k < dK.rows(); ++k)
    frequency = std::max(frequency, static_cast<double>(dK.row(k).norm()) / lam(k));
  const double floor = 2.0 * X.rows() * std::numeric_limits<long double>::epsilon() * cond;
  return {2.0 * std::max(stiffness, coupling) + floor, 2.0 * frequency + floor};
}
}  // namespace

int align_repeated_frequencies(Eigen::VectorXd& omega, Eigen::MatrixXd& Phi, const Eigen::VectorXd& w,
                               double repeat_tol) {
  const int n = static_cast<int>(omega.size());
  int groups = 0;
  for (int i = 0; i < n;) {
    int j = i + 1;
    while (j < n && omega(j) - omega(i) <= repeat_tol * omega(j)) ++j;
    if (j - i > 1) {
      // a Householder reflection of the group's shapes taking c = V^T w onto e1 |c|
      Eigen::MatrixXd V = Phi.middleCols(i, j - i);
      Eigen::VectorXd c = V.transpose() * w;
      if (c.norm() > 0.0) {
        Eigen::VectorXd e = Eigen::VectorXd::Zero(j - i);
        e(0) = c.norm();
        Eigen::VectorXd v = c - e;
        constexpr double kAligned = 1e-14;  // c already along e1 to rounding: the reflection would be noise
        if (v.norm() > kAligned * c.norm()) {
          v.normalize();
          Eigen::MatrixXd Hh = Eigen::MatrixXd::Identity(j - i, j - i) - 2.0 * v * v.transpose();
          Phi.middleCols(i, j - i) = V * Hh;
        }
      }
      omega.segment(i, j - i).setConstant(omega.segment(i, j - i).mean());
      ++groups;
    }
    i = j;
  }
  return groups;
}

// (a function-try-block: the eigensolvers' n x n workspaces are what runs out first for a large n)
ModalForm::ModalForm(const System& system, double decoupling_tol, double repeat_tol) try : n_(system.n()) {
  detail::SymmetricEigen ges = detail::generalized_symmetric_eigen(system.K(), system.M());
  if (!ges.ok) detail::internal_error("modal form: the generalized eigenproblem K v = omega^2 M v did not converge");
  check_resolved_spectrum(ges.values);
  Eigen::VectorXd omega_all = ges.values.cwiseMax(0.0).cwiseSqrt();
  std::tie(data_error_, frequency_error_) = modal_data_error(system, ges.vectors, ges.values);
  Eigen::MatrixXd Phi_all = std::move(ges.vectors);  // M-normalised
  const Eigen::VectorXd& w = system.w();

  repeated_groups_ = align_repeated_frequencies(omega_all, Phi_all, w, repeat_tol);
  const int n = n_;

  Eigen::VectorXd b = Phi_all.transpose() * w;  // |b|^2 = w^T M^{-1} w
  beta_ = b.norm();
  g0_ = system.g0();
  std::vector<int> act, dec;
  for (int k = 0; k < n; ++k) (std::abs(b(k)) > decoupling_tol * beta_ ? act : dec).push_back(k);

  const int m = static_cast<int>(act.size());
  omega_.resize(m);
  u_.resize(m);
  Phi_.resize(n, m);
  for (int k = 0; k < m; ++k) {
    omega_(k) = omega_all(act[k]);
    u_(k) = b(act[k]) / beta_;
    Phi_.col(k) = Phi_all.col(act[k]);
  }
  u_.normalize();
  omega_dec_.resize(static_cast<Eigen::Index>(dec.size()));
  Phi_dec_.resize(n, static_cast<Eigen::Index>(dec.size()));
  for (size_t k = 0; k < dec.size(); ++k) {
    omega_dec_(static_cast<Eigen::Index>(k)) = omega_all(dec[k]);
    Phi_dec_.col(static_cast<Eigen::Index>(k)) = Phi_all.col(dec[k]);
  }

  // Contact phase: S = W^2 - z z^T, PSD with a single zero eigenvalue (eigenvector W^{-1} u).
  z_ = omega_.cwiseProduct(u_);
  Eigen::MatrixXd S = Eigen::MatrixXd(omega_.array().square().matrix().asDiagonal()) - z_ * z_.transpose();
  detail::SymmetricEigen es = detail::symmetric_eigen(S);
  if (!es.ok) detail::internal_error("modal form: the contact-phase eigenproblem of S = W^2 - z z^T did not converge");
  d_ = es.values.cwiseMax(0.0).cwiseSqrt();
  G_ = std::move(es.vectors);
  if (m > 0) {
    d_(0) = 0.0;  // exact: the constrained direction
    Eigen::VectorXd g = u_.cwiseQuotient(omega_).normalized();
    if (g.dot(G_.col(0)) < 0) g = -g;
    G_.col(0) = g;
  }
} catch (const std::bad_alloc&) {
  const double n = static_cast<double>(system.n());
  throw detail::OutOfMemory("out of memory: the modal form of n = " + std::to_string(system.n()) +
                            " dofs (a few eigenvector matrices, each " + detail::dense_size(n, n) + ")");
}

const char* to_string(Symmetry s) {
  return s == Symmetry::Axial ? "axial" : "point";
}

std::optional<Symmetry> symmetry_named(std::string_view name) {
  for (const Symmetry s : {Symmetry::Axial, Symmetry::Point})
    if (name == to_string(s)) return s;
  return std::nullopt;
}

Eigen::MatrixXd ModalForm::contact_cos(double t) const {
  const Eigen::VectorXd e = (d_.array() * t).cos().matrix();
  return detail::congruence(G_, e);
}

Eigen::MatrixXd ModalForm::contact_sinc(double t) const {
  Eigen::VectorXd e(d_.size());
  for (Eigen::Index j = 0; j < d_.size(); ++j) e(j) = d_(j) > 0 ? std::sin(d_(j) * t) / d_(j) : t;
  return detail::congruence(G_, e);
}

Eigen::MatrixXd ModalForm::contact_msin(double t) const {
  const Eigen::VectorXd e = (d_.array() * (d_.array() * t).sin()).matrix();
  return detail::congruence(G_, e);
}

namespace {
// Index range j in [first, last] of the poles (j + 1/2) pi / f inside (lo, hi), as doubles (they may be huge).
std::pair<double, double> pole_index_range(double f, double lo, double hi) {
  double first = std::max(0.0, std::ceil(lo * f / std::numbers::pi - 0.5));
  double last = std::ceil(hi * f / std::numbers::pi - 0.5) - 1.0;  // (last + 1/2) pi / f < hi
  return {first, last};
}
// Beyond 2^52 consecutive indices j, j + 1 are no longer distinct pole positions in double precision.
constexpr double kLargestPoleIndex = 4503599627370496.0;
// Poles of two frequencies closer than this (relative) are one pole line: ~5e3 eps, above the
// rounding of (j + 1/2) pi / f for the largest indices used, so a repeated frequency does not give two lines.
constexpr double kSamePole = 1e-12;
}  // namespace

double count_tangent_poles(const Eigen::VectorXd& freqs, double lo, double hi) {
  double count = 0.0;
  for (Eigen::Index k = 0; k < freqs.size(); ++k) {
    if (!(freqs(k) > 0)) continue;
    const auto [first, last] = pole_index_range(freqs(k), lo, hi);
    count += std::max(0.0, last - first + 1.0);
  }
  return count;
}

std::vector<double> tangent_poles(const Eigen::VectorXd& freqs, double lo, double hi, double max_count) {
  const double count = count_tangent_poles(freqs, lo, hi);
  if (count > max_count) {
    std::ostringstream os;
    os << "window (" << lo << ", " << hi << ") holds " << count << " pole lines (more than " << max_count
       << "): narrow the window";
    detail::invalid(os.str());
  }
  std::vector<double> poles;
  poles.reserve(static_cast<size_t>(count));
  for (Eigen::Index k = 0; k < freqs.size(); ++k) {
    const double f = freqs(k);
    if (!(f > 0)) continue;
    const auto [first, last] = pole_index_range(f, lo, hi);
    if (last < first) continue;
    if (last >= kLargestPoleIndex) {
      std::ostringstream os;
      os << "window end " << hi << " is beyond double resolution of the pole lines of frequency " << f
         << " (pole index " << last << " >= 2^52): move the window closer to 0";
      detail::invalid(os.str());
    }
    // integer loop counter: a double counter stops advancing past 2^53
    for (auto j = static_cast<long long>(first); j <= static_cast<long long>(last); ++j) {
      const double t = (static_cast<double>(j) + 0.5) * std::numbers::pi / f;
      if (t > lo && t < hi) poles.push_back(t);
    }
  }
  std::sort(poles.begin(), poles.end());
  std::vector<double> merged;
  for (double t : poles)
    if (merged.empty() || t - merged.back() > kSamePole * t) merged.push_back(t);
  return merged;
}

ModalForm ModalForm::in_time_unit(double rate) const {
  if (!(rate > 0.0 && std::isfinite(rate))) {
    std::ostringstream os;
    os << "ModalForm::in_time_unit: rate must be positive and finite, got " << rate;
    detail::invalid(os.str());
  }
  ModalForm out = *this;
  out.omega_ /= rate;
  out.z_ /= rate;
  out.d_ /= rate;
  out.omega_dec_ /= rate;
  return out;
}

std::vector<double> ModalForm::flight_poles(double lo, double hi) const {
  return tangent_poles(omega_, lo, hi);
}
std::vector<double> ModalForm::contact_poles(double lo, double hi) const {
  return tangent_poles(d_, lo, hi);
}

}  // namespace spp
