#include "spp/modal/modal.hpp"

#include <algorithm>
#include <array>
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
// rounded: its error is |dK| in the stiffness and |b_exact - B b / 2 - b_rounded| / |b| in u. R is a cancellation
// (~0.05 eps cond(M) omega_max^2 out of terms of ~omega_max^2): in double its own rounding would be as large as what
// it measures. K X and M X are therefore formed to ~2^-63 relative by Ozaki's error-free splitting (exact_product,
// BLAS products of slices whose products are exact in double), R from them in double-double arithmetic; X^T R, B b
// and b need no more than double (X^T R) and long double O(n^2) products, and the rounding of each is bounded
// elementwise and added. Before, every product was long double (O(n^3), unvectorised, one thread): 12.0 s of CPU at
// n = 1000 against 0.5 s for the eigensolve (issue 14's attack).
// Taken only when M~ = D^-1/2 M D^-1/2 (D = diag M) has a condition number above kWellConditionedMass.
constexpr double kWellConditionedMass = 1e2;

// The exact sum hi + lo of a + b (Knuth's TwoSum: no assumption on the magnitudes).
inline void two_sum(double a, double b, double& hi, double& lo) {
  hi = a + b;
  const double bb = hi - a;
  lo = (a - (hi - bb)) + (b - bb);
}

// A B (k the inner dimension) as the double-double hi + lo, with an elementwise bound err on |hi + lo - A B|.
// Ozaki's error-free splitting: each row of A (each column of B) is cut into two slices of s bits, relative to the
// row's (column's) largest entry 2^E <= max < 2^(E+1), and the remainder, |rem| <= 2^(E - 2s). A product of two s-bit
// slices holds integers times one unit below 2^(2s) k <= 2^52 in every partial sum: BLAS computes it exactly in any
// order. The products with a remainder are rounded, by at most gamma_k |slice| |rem|, ~k eps 2^-2s of the whole:
// err bounds them (with the row sums and maxima, a rank-2 outer product) and the double-double sums.
struct ExactProduct {
  Eigen::MatrixXd hi, lo, err;
};
ExactProduct exact_product(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const Eigen::Index k = A.cols();
  const int s = (52 - static_cast<int>(std::ceil(std::log2(std::max<double>(2.0, static_cast<double>(k)))))) / 2;
  // slices[0], slices[1]: s bits each; slices[2]: the remainder. by_rows: A's rows, else B's columns.
  const auto split = [s](const Eigen::MatrixXd& X, bool by_rows, Eigen::VectorXd& top) {
    std::array<Eigen::MatrixXd, 3> sl{X, X, X};
    const Eigen::Index lines = by_rows ? X.rows() : X.cols();
    top.resize(lines);
    for (Eigen::Index i = 0; i < lines; ++i) {
      const double mx = by_rows ? X.row(i).cwiseAbs().maxCoeff() : X.col(i).cwiseAbs().maxCoeff();
      top(i) = mx;
      const int e = mx > 0.0 ? std::ilogb(mx) : 0;
      for (int part = 0; part < 2; ++part) {
        // sigma + a stays in sigma's binade: its ulp 2^(e + 1 - (part + 1) s) is the slice's unit
        const double sigma = 1.5 * std::ldexp(1.0, e + 53 - (part + 1) * s);
        const Eigen::Index len = by_rows ? X.cols() : X.rows();
        for (Eigen::Index j = 0; j < len; ++j) {
          double& rem = by_rows ? sl[2](i, j) : sl[2](j, i);
          double& cut = by_rows ? sl[part](i, j) : sl[part](j, i);
          if (mx == 0.0) {
            cut = 0.0;
            continue;
          }
          const double up = rem + sigma;
          cut = up - sigma;
          rem -= cut;  // exact
        }
      }
    }
    return sl;
  };
  Eigen::VectorXd rowmax, colmax;
  const std::array<Eigen::MatrixXd, 3> a = split(A, true, rowmax), b = split(B, false, colmax);
  ExactProduct out{Eigen::MatrixXd::Zero(A.rows(), B.cols()), Eigen::MatrixXd::Zero(A.rows(), B.cols()),
                   Eigen::MatrixXd()};
  // smallest first: (2,2), (1,2), (2,1), (0,2), (1,1), (2,0), (0,1), (1,0), (0,0)
  for (int level = 4; level >= 0; --level)
    for (int i = 2; i >= 0; --i) {
      const int j = level - i;
      if (j < 0 || j > 2) continue;
      const Eigen::MatrixXd p = detail::product(a[i], false, b[j], false);
      for (Eigen::Index c = 0; c < p.cols(); ++c)
        for (Eigen::Index r = 0; r < p.rows(); ++r) {
          double h, l;
          two_sum(out.hi(r, c), p(r, c), h, l);
          out.hi(r, c) = h;
          out.lo(r, c) += l;
        }
    }
  // |A_i| |B_2| <= 2^(F_j + 1 - 2s) rowsum_i(|A| + 2^(E_i + 1)) (and the mirror): the rounded products, gamma_k each;
  // the double-double's own sums: 9 terms, ~2^-104 of their absolute sum, taken as 16 eps^2 (|A| |B|)'s bound.
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double gamma = 1.01 * static_cast<double>(k) * eps, unit = std::ldexp(1.0, 2 - 2 * s);
  const Eigen::VectorXd rowsum = A.cwiseAbs().rowwise().sum() + static_cast<double>(k) * 2.0 * rowmax;
  const Eigen::VectorXd colsum = B.cwiseAbs().colwise().sum().transpose() + static_cast<double>(k) * 2.0 * colmax;
  out.err = (5.0 * gamma * unit + 16.0 * eps * eps) *
            (rowsum * (2.0 * colmax).transpose() + (2.0 * rowmax) * colsum.transpose());
  return out;
}

// Returns {data_error, frequency_error} (ModalForm's accessors).
std::pair<double, double> modal_data_error(const System& system, const Eigen::MatrixXd& X, const Eigen::VectorXd& lam) {
  const Eigen::VectorXd s = system.M().diagonal().cwiseSqrt().cwiseInverse();
  const detail::SymmetricEigen me = detail::symmetric_eigen(s.asDiagonal() * system.M() * s.asDiagonal(), false);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!me.ok || !(me.values(0) > 0.0)) return {kInf, kInf};
  const double cond = me.values(me.values.size() - 1) / me.values(0);
  if (cond <= kWellConditionedMass) return {0.0, 0.0};
  const Eigen::Index n = X.rows();
  constexpr double eps = std::numeric_limits<double>::epsilon();
  Eigen::MatrixXd KM(2 * n, n);
  KM << system.K(), system.M();
  const ExactProduct P = exact_product(KM, X);  // rows 0..n-1: K X, rows n..2n-1: M X
  // R = K X - M X diag(lam) in double-double, rounded once; errR bounds its error elementwise
  Eigen::MatrixXd R(n, n), errR(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) {
      const double q = P.hi(n + i, j) * lam(j), qe = std::fma(P.hi(n + i, j), lam(j), -q);  // q + qe exact
      double h, l;
      two_sum(P.hi(i, j), -q, h, l);
      R(i, j) = h + (((l - qe) + P.lo(i, j)) - P.lo(n + i, j) * lam(j));
      errR(i, j) = eps * std::abs(R(i, j)) + P.err(i, j) + std::abs(lam(j)) * P.err(n + i, j) +
                   4.0 * eps * eps * (std::abs(P.hi(i, j)) + std::abs(q));
    }
  // X^T R in double: |fl - exact| <= gamma_n |X|^T |R|
  const Eigen::MatrixXd absX = X.cwiseAbs();
  const double gamma = 1.01 * static_cast<double>(n) * eps;
  const Eigen::MatrixXd XR = detail::product(X, true, R, false);
  const Eigen::MatrixXd XRerr = 1.01 * detail::product(absX, true, errR + gamma * R.cwiseAbs(), false);
  const Eigen::MatrixXd dK = (XR + XR.transpose()) / 2.0, dKerr = (XRerr + XRerr.transpose()) / 2.0;
  // the coupling: b = X^T w and B b = X^T (M (X b)) - b, each product error-free split (O(n^2)), the double-double
  // parts carried; eb, ey, eq, ec bound their errors elementwise
  const Eigen::MatrixXd Xt = X.transpose();
  const ExactProduct Pb = exact_product(Xt, system.w());
  const Eigen::VectorXd bh = Pb.hi.col(0), bl = Pb.lo.col(0), eb = Pb.err.col(0);
  const ExactProduct Py = exact_product(X, bh);
  const Eigen::VectorXd ylo = Py.lo.col(0) + X * bl;
  const Eigen::VectorXd ey = Py.err.col(0) + absX * (eb + 2.0 * gamma * bl.cwiseAbs());
  const ExactProduct Pq = exact_product(system.M(), Py.hi);
  const Eigen::VectorXd qlo = Pq.lo.col(0) + system.M() * ylo;
  const Eigen::VectorXd eq = Pq.err.col(0) + system.M().cwiseAbs() * (ey + 2.0 * gamma * ylo.cwiseAbs());
  const ExactProduct Pc = exact_product(Xt, Pq.hi);
  const Eigen::VectorXd clo = Pc.lo.col(0) + Xt * qlo;
  const Eigen::VectorXd ec = Pc.err.col(0) + absX.transpose() * (eq + 2.0 * gamma * qlo.cwiseAbs());
  const Eigen::VectorXd b_rounded = X.transpose() * system.w();
  Eigen::VectorXd db(n), db_err(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    double h, l;
    two_sum(Pc.hi(i, 0), -bh(i), h, l);  // B b = h + l + clo - bl
    const double Bb = h + ((l + clo(i)) - bl(i));
    const double d = (bh(i) - b_rounded(i)) + bl(i);  // (bh, b_rounded: two roundings of one value, Sterbenz)
    db(i) = d - Bb / 2.0;
    db_err(i) = eb(i) + ec(i) / 2.0 + 4.0 * eps * (std::abs(db(i)) + std::abs(Bb) + std::abs(d)) +
                4.0 * eps * eps * (std::abs(Pc.hi(i, 0)) + std::abs(bh(i)));
  }
  const double bn = bh.norm() * (1.0 - 2.0 * gamma);
  const double stiffness = (dK.norm() + dKerr.norm()) / lam.maxCoeff();
  const double coupling = (db.norm() + db_err.norm()) / bn;
  // Each omega_k^2 is an eigenvalue of diag(lam) + dK: the Rayleigh quotient of e_k moves it by dK_kk, and the rest of
  // the row, of norm rho, by at most rho^2 / delta (Kato-Temple) where delta separates lam_k + dK_kk from the other
  // eigenvalues (each within |dK|_2 of its lam_j, Weyl); by at most rho where that separation is not proved. The row
  // norm alone (before) was 31-42 times the true errors of the chain x = (I + 0.83 superdiag) y, n 100 and 300.
  const double dK2 = dK.norm() + dKerr.norm();  // >= |dK + error|_2
  double frequency = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double diag = std::abs(dK(k, k)) + dKerr(k, k);
    const double rho = std::sqrt(std::max(0.0, dK.row(k).squaredNorm() - dK(k, k) * dK(k, k))) + dKerr.row(k).norm();
    double gap = std::numeric_limits<double>::infinity();
    if (k > 0) gap = std::min(gap, lam(k) - lam(k - 1));
    if (k + 1 < n) gap = std::min(gap, lam(k + 1) - lam(k));
    const double delta = gap - dK2 - diag;
    const double off = delta > dK2 + diag ? std::min(rho, rho * rho / delta) : rho;
    frequency = std::max(frequency, (diag + off) / lam(k));
  }
  // (x2: the first order's neglected B^2)
  return {2.0 * std::max(stiffness, coupling), 2.0 * frequency};
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
