#include "spp/core/generators.hpp"

#include <Eigen/QR>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include "spp/detail/invalid.hpp"
#include "spp/detail/out_of_memory.hpp"

namespace spp {

namespace {
std::vector<double> expand(const std::vector<double>& v, int n, const char* name) {
  if (v.size() == 1) return std::vector<double>(static_cast<size_t>(n), v[0]);
  if (v.size() != static_cast<size_t>(n)) {
    std::ostringstream os;
    os << "chain: " << name << " must have 1 or n = " << n << " values, got " << v.size();
    detail::invalid(os.str());
  }
  return v;
}
}  // namespace

System chain(int n, const std::vector<double>& masses, const std::vector<double>& stiffnesses, int contact_dof,
             ContactSide side, double g0) {
  if (n < 1) detail::invalid("chain: n must be >= 1, got " + std::to_string(n));
  // the dense solver's limit before the n x n matrices are allocated (n = 20000 took 6.4 GB before System refused it;
  // found by an independent attack)
  if (n > kMaxDenseDofs)
    detail::invalid("chain: n must be at most " + std::to_string(kMaxDenseDofs) +
                    " (the dense solver's limit; a larger chain as a sparse model: spp generate bar), got " +
                    std::to_string(n));
  if (contact_dof < 0 || contact_dof >= n) {
    std::ostringstream os;
    os << "chain: contact dof must be in [1, " << n << "], got " << contact_dof + 1;
    detail::invalid(os.str());
  }
  const auto m = expand(masses, n, "masses"), k = expand(stiffnesses, n, "stiffnesses");
  for (int i = 0; i < n; ++i)
    if (!(m[i] > 0) || !(k[i] > 0)) {
      std::ostringstream os;
      os << "chain: masses and stiffnesses must be positive, got m" << i + 1 << " = " << m[i] << ", k" << i + 1 << " = "
         << k[i];
      detail::invalid(os.str());
    }
  Eigen::MatrixXd M, K;
  detail::naming_allocation("chain: M and K of n = " + std::to_string(n) + " dofs, each " + detail::dense_size(n, n),
                            [&] {
                              M = Eigen::MatrixXd::Zero(n, n);
                              K = Eigen::MatrixXd::Zero(n, n);
                            });
  for (int i = 0; i < n; ++i) {
    M(i, i) = m[i];
    K(i, i) += k[i];
    if (i > 0) {
      K(i - 1, i - 1) += k[i];
      K(i - 1, i) -= k[i];
      K(i, i - 1) -= k[i];
    }
  }
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  w(contact_dof) = side == ContactSide::Upper ? -1.0 : 1.0;
  return System(M, K, w, g0, "chain" + std::to_string(n));
}

System random_dense(int n, unsigned seed, double g0) {
  if (n < 1 || n > kMaxDenseDofs)
    detail::invalid_option("random_dense", "n", n,
                           "in [1, " + std::to_string(kMaxDenseDofs) + "] (the dense solver's limit)");
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  auto spd = [&](double lo, double hi) {
    Eigen::MatrixXd A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
    std::uniform_real_distribution<double> uniform(lo, hi);
    Eigen::VectorXd e(n);
    for (int i = 0; i < n; ++i) e(i) = uniform(rng);
    return Eigen::MatrixXd(Q * e.asDiagonal() * Q.transpose());
  };
  // Drawn w, K, M: the order GCC gave the benchmarks' and test_evaluator's copies of this generator (which
  // evaluated the call System(spd(M range), spd(K range), w) right to left), so their systems are kept.
  Eigen::VectorXd w(n);
  for (int i = 0; i < n; ++i) w(i) = normal(rng);
  Eigen::MatrixXd M, K;
  detail::naming_allocation(
      "random_dense: M and K of n = " + std::to_string(n) + " dofs, each " + detail::dense_size(n, n), [&] {
        K = spd(0.5, 2.0 * n);
        M = spd(0.5, 2.0);
      });
  return System(std::move(M), std::move(K), std::move(w), g0,
                "random" + std::to_string(n) + "-seed" + std::to_string(seed));
}

SparseSystem bar(int n, BarMass mass, int contact_node, ContactSide side, double g0) {
  if (n < 1) detail::invalid_option("bar", "n", n, ">= 1");
  if (contact_node < 1 || contact_node > n)
    detail::invalid_option("bar", "contact node", contact_node, "in [1, n = " + std::to_string(n) + "]");
  const double h = 1.0 / n;
  const double k = 1.0 / h;  // E A / h
  const bool lumped = mass == BarMass::Lumped;
  const double m_diag = lumped ? h / 2 : h / 3, m_off = lumped ? 0.0 : h / 6;  // rho A h (1/2 | 2/6, 1/6)
  std::vector<Eigen::Triplet<double>> mt, kt;
  mt.reserve(3 * static_cast<size_t>(n));
  kt.reserve(3 * static_cast<size_t>(n));
  // element e joins nodes e and e + 1 (e = 0..n-1); node j is dof j - 1; node 0 is fixed
  for (int e = 0; e < n; ++e) {
    const int a = e - 1, b = e;  // dofs of the element's nodes (a = -1: the fixed node)
    kt.emplace_back(b, b, k);
    mt.emplace_back(b, b, m_diag);
    if (a >= 0) {
      kt.emplace_back(a, a, k);
      kt.emplace_back(a, b, -k);
      kt.emplace_back(b, a, -k);
      mt.emplace_back(a, a, m_diag);
      if (m_off != 0.0) {
        mt.emplace_back(a, b, m_off);
        mt.emplace_back(b, a, m_off);
      }
    }
  }
  Eigen::SparseMatrix<double> M(n, n), K(n, n);
  M.setFromTriplets(mt.begin(), mt.end());
  K.setFromTriplets(kt.begin(), kt.end());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  w(contact_node - 1) = side == ContactSide::Upper ? -1.0 : 1.0;
  return SparseSystem(std::move(M), std::move(K), std::move(w), g0,
                      "bar" + std::to_string(n) + (lumped ? "-lumped" : ""));
}

System rod_with_slip(double a, double b) {
  Eigen::MatrixXd M(4, 4), K(4, 4);
  M << 4, 1, 0, 0, 1, 2, 0, 0, 0, 0, 3, 1.5, 0, 0, 1.5, 6;  // eq. (5.6)
  K << 2, -1, 0, 0, -1, 1, 0, 0, 0, 0, 2.5, -2.5, 0, 0, -2.5, 5;
  if (!std::isfinite(a) || !std::isfinite(b)) {
    std::ostringstream os;
    os << "rod_with_slip: a and b must be finite, got a = " << a << ", b = " << b;
    detail::invalid(os.str());
  }
  // w = (0, a, -1, 0) (eq. 5.7), normalised by System (hypot-like: a = 1e308 gave 1 + a^2 = inf and w = 0)
  Eigen::VectorXd w(4);
  w << 0, a, -1, 0;
  return System(M, K, w, b, "rod4");
}

System two_dof(double m1, double m2, double k1, double k2, double g0) {
  Eigen::MatrixXd M(2, 2), K(2, 2);
  M << m1, 0, 0, m2;  // eq. (2.5)
  K << k1 + k2, -k2, -k2, k2;
  Eigen::VectorXd w(2);
  w << 0, -1;
  return System(M, K, w, g0, "two_dof");
}

ParametricSystem parametrize(const std::function<System(double)>& make, const Parameter& p) {
  if (!(p.min < p.max)) {
    std::ostringstream os;
    os << "parameter \"" << p.name << "\": needs min < max, got " << p.min << ", " << p.max;
    detail::invalid(os.str());
  }
  const System a = make(p.min), b = make(p.max), mid = make(0.5 * (p.min + p.max));
  const double span = p.max - p.min;
  const Eigen::MatrixXd M1 = (b.M() - a.M()) / span, K1 = (b.K() - a.K()) / span;
  const Eigen::VectorXd w1 = (b.w() - a.w()) / span;
  const Eigen::MatrixXd M0 = a.M() - p.min * M1, K0 = a.K() - p.min * K1;
  const Eigen::VectorXd w0 = a.w() - p.min * w1;
  const double mu = 0.5 * (p.min + p.max);
  const double scale = a.M().norm() + a.K().norm() + b.M().norm() + b.K().norm() + 1.0;
  const bool affine = (M0 + mu * M1 - mid.M()).norm() <= kSameToRounding * scale &&
                      (K0 + mu * K1 - mid.K()).norm() <= kSameToRounding * scale &&
                      (w0 + mu * w1 - mid.w()).norm() <= kSameToRounding && a.g0() == b.g0() && a.g0() == mid.g0();
  if (!affine)
    detail::invalid("parameter \"" + p.name +
                    "\": the system is not affine in it (M, K and w must be affine, g0 fixed)");
  return ParametricSystem(M0, M1, K0, K1, w0, w1, a.g0(), p, a.name() + " (" + p.name + ")");
}

}  // namespace spp
