#include "spp/core/system.hpp"

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "spp/core/names.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/detail/out_of_memory.hpp"
#include "spp/detail/symmetric_eigen.hpp"
#include "spp/detail/utf8.hpp"

namespace spp {
namespace {

void check_finite(const Eigen::MatrixXd& A, const char* field) {
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = 0; i < A.rows(); ++i)
      if (!std::isfinite(A(i, j))) {
        std::ostringstream os;
        os << "system: " << field << "[" << i << "]";
        if (A.cols() > 1) os << "[" << j << "]";  // (w, a vector, has one index)
        os << " must be finite, got " << A(i, j);
        detail::invalid(os.str());
      }
}

// Symmetric (relative tolerance) and positive definite; symmetrised copy returned.
Eigen::MatrixXd check_spd(const Eigen::MatrixXd& A, const char* field) {
  const double scale = A.cwiseAbs().maxCoeff();
  const double asym = (A - A.transpose()).cwiseAbs().maxCoeff();
  if (asym > kSymmetryTolerance * scale) {
    Eigen::Index i = 0, j = 0;
    (A - A.transpose()).cwiseAbs().maxCoeff(&i, &j);
    std::ostringstream os;  // (17 digits: "K[1][0] = -1 but K[0][1] = -1" hid the difference; an attack)
    os << "system: " << field << " must be symmetric (relative tolerance " << kSymmetryTolerance << "), got " << field
       << "[" << i << "][" << j << "] = " << std::setprecision(17) << A(i, j) << " but " << field << "[" << j << "]["
       << i << "] = " << A(j, i);
    detail::invalid(os.str());
  }
  // (halved before the sum: A + A^T overflowed to inf for entries above 8.99e307, and masses of 1e308 were reported
  // as "the eigenvalues of M did not converge"; found by an independent attack)
  Eigen::MatrixXd S = 0.5 * A + 0.5 * A.transpose();
  // Positive definite, decided on the unit-diagonal congruent matrix D^-1/2 S D^-1/2 (D = diag S): the same answer for
  // the same system in other units per dof (x = diag(1e3, 1, 1e-3) x' scales S by D, not its definiteness), with a
  // margin above rounding (an eigenvalue at the level of rounding is singular).
  for (Eigen::Index i = 0; i < S.rows(); ++i)
    if (!(S(i, i) > 0.0)) {
      std::ostringstream os;
      os << "system: " << field << " must be positive definite, got the diagonal entry " << field << "[" << i << "]["
         << i << "] = " << S(i, i);
      detail::invalid(os.str());
    }
  const Eigen::VectorXd d = S.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd U = d.asDiagonal() * S * d.asDiagonal();
  const detail::SymmetricEigen es = detail::symmetric_eigen(U, /*vectors=*/false);
  if (!es.ok)
    detail::invalid(std::string("system: the eigenvalues of ") + field +
                    " (scaled to a unit diagonal) did not converge");
  const double lmin = es.values.minCoeff();
  const double lmax = es.values.cwiseAbs().maxCoeff();
  if (!(lmin > kDefinitenessMargin * std::numeric_limits<double>::epsilon() * lmax * static_cast<double>(A.rows()))) {
    std::ostringstream os;
    os << "system: " << field << " must be positive definite, got smallest eigenvalue " << lmin << " (largest " << lmax
       << ") of " << field << " scaled to a unit diagonal";
    detail::invalid(os.str());
  }
  return S;
}

}  // namespace

void check_text(const std::string& text, const std::string& where, std::size_t max_bytes, bool line_breaks,
                const char* kind) {
  if (text.size() > max_bytes)
    detail::invalid(where + ": expected at most " + std::to_string(max_bytes) + " bytes, got " +
                    std::to_string(text.size()) + " (" + kind + ")");
  // UTF-8 only (JSON holds nothing else: a name of Latin-1 bytes was built, then no file could be written), and no
  // control character, C0 nor C1 (U+0080 to U+009F: U+009B was accepted where U+001B was refused; found by an
  // independent attack)
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t len = detail::utf8_sequence(text, i);
    if (len == 0) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02x", static_cast<unsigned>(c));
      detail::invalid(where + ": expected UTF-8 text, got the byte " + byte + " at byte " + std::to_string(i) +
                      ", which starts no UTF-8 character (Latin-1 text?)");
    }
    if ((c < 0x20 && !(line_breaks && (c == '\t' || c == '\n' || c == '\r'))) || c == 0x7f)
      detail::invalid(where + ": expected printable text, got the control character " +
                      std::to_string(static_cast<int>(c)) + " at byte " + std::to_string(i));
    if (detail::utf8_c1_control(text, i, len)) {
      char code[16];
      std::snprintf(code, sizeof code, "U+%04X", static_cast<unsigned>(static_cast<unsigned char>(text[i + 1])));
      detail::invalid(where + ": expected printable text, got the control character " + code + " at byte " +
                      std::to_string(i));
    }
    i += len;
  }
}

void check_name(const std::string& name, const std::string& where) {
  check_text(name, where, kMaxNameBytes, /*line_breaks=*/false, "a name is a title");
}

System::System(Eigen::MatrixXd M, Eigen::MatrixXd K, Eigen::VectorXd w, double g0, std::string name)
    : name_(std::move(name)) {
  check_name(name_, "system: name");
  if (M.rows() == 0) detail::invalid("system: M must have at least one row, got an empty matrix");
  if (M.rows() != M.cols()) {
    std::ostringstream os;
    os << "system: M must be square, got " << M.rows() << " x " << M.cols();
    detail::invalid(os.str());
  }
  const Eigen::Index n = M.rows();
  if (K.rows() != n || K.cols() != n) {
    std::ostringstream os;
    os << "system: K must be " << n << " x " << n << " like M, got " << K.rows() << " x " << K.cols();
    detail::invalid(os.str());
  }
  if (w.size() != n) {
    std::ostringstream os;
    os << "system: w must have " << n << " entries like M, got " << w.size();
    detail::invalid(os.str());
  }
  if (n > kMaxDenseDofs) {
    std::ostringstream os;
    os << "system: n = " << n << " dofs is beyond the dense solver (at most " << kMaxDenseDofs
       << " dofs: its O(n^3) modal form would take half an hour or more); reduce the model first (spp reduce MODEL "
          "--modes m --out "
          "REDUCED.json, or spp::reduce)";
    detail::invalid(os.str());
  }
  check_finite(M, "M");
  check_finite(K, "K");
  check_finite(w, "w");
  if (!std::isfinite(g0)) {
    std::ostringstream os;
    os << "system: g0 must be finite, got " << g0;
    detail::invalid(os.str());
  }
  // the checks hold a few n x n copies (symmetrised, scaled, the eigensolver's)
  detail::naming_allocation("system: checking M and K of n = " + std::to_string(n) + " dofs, each " +
                                detail::dense_size(static_cast<double>(n), static_cast<double>(n)),
                            [&] {
                              M_ = check_spd(M, "M");
                              K_ = check_spd(K, "K");
                            });
  const double nw = w.stableNorm();  // no overflow for |w_i| ~ 1e200, no underflow for 1e-200
  if (!(nw > 0.0)) detail::invalid("system: w must be non-zero, got the zero vector");
  if (!std::isfinite(nw) || nw < std::numeric_limits<double>::min()) {
    std::ostringstream os;
    os << "system: |w| = " << nw << " is outside the range of normal doubles: rescale w and g0 by one factor";
    detail::invalid(os.str());
  }
  w_input_norm_ = nw;
  w_ = w / nw;
  g0_ = g0 / nw;
  if (!std::isfinite(g0_)) {
    std::ostringstream os;
    os << "system: g0 / |w| = " << g0 << " / " << nw << " overflows: rescale w and g0 by one factor";
    detail::invalid(os.str());
  }
  // a non-zero gap that divides to 0 or a denormal would be taken for the zero-gap case, or lose its digits
  if (g0 != 0.0 && std::abs(g0_) < std::numeric_limits<double>::min()) {
    std::ostringstream os;
    os << "system: g0 / |w| = " << g0 << " / " << nw
       << " underflows (below the normal doubles): rescale w and g0 by one factor";
    detail::invalid(os.str());
  }
  // The orbits scale with g0 and their energies with g0^2 |K|: beyond ~1e200 (or below 1e-200) an energy, a squared
  // norm or a stability product overflows (underflows) to inf/NaN or 0 (g0 = 1e155 gave a wrong spectral radius and
  // "stable" with status success; g0 = 1e-250 zero energies; found by an independent attack). Refused, with the
  // remedy: the same system in other units.
  constexpr double kMaxEnergyScale = 1e200;
  const double energy_scale = g0_ * g0_ * K_.cwiseAbs().maxCoeff();
  if (g0 != 0.0 && std::isfinite(g0_) && !(energy_scale >= 1.0 / kMaxEnergyScale && energy_scale <= kMaxEnergyScale)) {
    std::ostringstream os;
    os << "system: the energy scale (g0 / |w|)^2 max|K| = " << energy_scale << " (g0 / |w| = " << g0_
       << ") is outside [1e-200, 1e200], where energies and stability products stay within double precision: "
          "expected the system in units where g0 and K are nearer 1 (e.g. lengths in mm instead of m)";
    detail::invalid(os.str());
  }
}

System System::normalized(Eigen::MatrixXd M, Eigen::MatrixXd K, Eigen::VectorXd w, double g0, double input_norm,
                          std::string name) {
  if (!(std::abs(w.stableNorm() - 1.0) <= kSameToRounding)) {
    std::ostringstream os;
    os << "system: a stored (normalised) w must have |w| = 1, got |w| = " << w.stableNorm();
    detail::invalid(os.str());
  }
  if (!(input_norm > 0.0 && std::isfinite(input_norm))) {
    std::ostringstream os;
    os << "system: w_input_norm must be positive and finite, got " << input_norm;
    detail::invalid(os.str());
  }
  System s(std::move(M), std::move(K), w, g0, std::move(name));  // validates (and normalises a copy)
  s.w_ = std::move(w);
  s.g0_ = g0;
  s.w_input_norm_ = input_norm;
  return s;
}

Eigen::MatrixXd System::contact_stiffness() const {
  // eq. (2.4): K~ = (I - w w^T M^{-1} / (w^T M^{-1} w)) K
  const Eigen::VectorXd Minv_w = M_.llt().solve(w_);
  const double wMw = w_.dot(Minv_w);
  return K_ - w_ * (Minv_w.transpose() * K_) / wMw;
}

namespace {
bool same_to_rounding(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  const double scale = std::max(1.0, a.size() > 0 ? a.cwiseAbs().maxCoeff() : 0.0);
  return a.size() == 0 || (a - b).cwiseAbs().maxCoeff() <= kSameToRounding * scale;
}
}  // namespace

bool same_system(const System& a, const System& b) {
  return a.n() == b.n() && same_to_rounding(a.M(), b.M()) && same_to_rounding(a.K(), b.K()) &&
         same_to_rounding(a.w(), b.w()) &&
         std::abs(a.g0() - b.g0()) <= kSameToRounding * std::max(1.0, std::abs(a.g0()));
}

}  // namespace spp
