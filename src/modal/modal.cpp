#include "spp/modal/modal.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

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
