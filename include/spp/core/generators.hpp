#pragma once
// The paper's models as Systems (same file format as any other system once written with system_json).

#include <functional>
#include <vector>

#include "spp/core/parametric.hpp"
#include "spp/core/sparse_system.hpp"
#include "spp/core/system.hpp"

namespace spp {

enum class ContactSide {
  Upper,  ///< obstacle above the dof: g = g0 - x_c (paper §5.2: w = -e_c)
  Lower,  ///< obstacle below the dof: g = x_c + g0
};

/// Spring-mass chain fixed at its first end (paper fig. 3, eq. 5.4): spring k_1 ties mass 1 to the ground,
/// spring k_i ties masses i-1 and i. masses, stiffnesses: one value (all equal) or n values.
/// contact_dof is 0-based. Throws std::invalid_argument on bad sizes or values.
System chain(int n, const std::vector<double>& masses, const std::vector<double>& stiffnesses, int contact_dof,
             ContactSide side, double g0);

/// 4-dof finite-element rod with slip (paper §5.3, eqs. 5.6-5.7), obstacle line y = a x + b:
/// w = (0, a, -1, 0) / sqrt(1 + a^2), g0 = b / sqrt(1 + a^2) as printed in eq. (5.7).
System rod_with_slip(double a, double b);

/// 2-dof system of paper §2.3 (eq. 2.5), obstacle on the second mass: g = g0 - x2.
System two_dof(double m1, double m2, double k1, double k2, double g0);

/// A random dense system (benchmarks, tests, cross-checks): w ~ N(0, I_n), then K = Q_K diag(e_K) Q_K^T with e_K
/// uniform in [0.5, 2 n], then M = Q_M diag(e_M) Q_M^T with e_M uniform in [0.5, 2], each Q the orthogonal factor of
/// the Householder QR of an n x n matrix of N(0, 1) entries; gap g0. Drawn in that order from std::mt19937(seed)
/// through std::normal_distribution / std::uniform_real_distribution, so one seed gives one system with a given
/// standard library (libstdc++ here; another library may draw other values). n in [1, kMaxDenseDofs]. Cost O(n^3).
System random_dense(int n, unsigned seed, double g0 = 1.0);

enum class BarMass {
  Consistent,  ///< element mass rho A h / 6 [[2, 1], [1, 2]] (frequencies from above)
  Lumped,      ///< rho A h / 2 on each node (frequencies from below)
};

/// 1-D fixed-free bar of unit length, E A = 1, rho A = 1 (wave speed 1: continuous frequencies (2k - 1) pi / 2), cut
/// into n linear rod elements of length h = 1 / n: node 0 is fixed, the dofs are the axial displacements of nodes
/// 1..n (K = tridiag(-1, 2, -1) / h with K(n, n) = 1 / h). The obstacle meets contact_node (1..n, the free end n
/// by default in the CLI): Upper g = g0 - x, Lower g = x + g0. Held sparse, any n >= 1.
SparseSystem bar(int n, BarMass mass, int contact_node, ContactSide side, double g0);

/// A generator with one argument left free: the family mu -> make(mu) as a ParametricSystem (masses and
/// stiffnesses of chain and two_dof enter M and K linearly). The parts come from make(min) and make(max); the
/// family must be affine (checked at the midpoint) with g0 and |w| fixed, else std::invalid_argument (e.g. the
/// rod's slope a enters w non-linearly).
ParametricSystem parametrize(const std::function<System(double)>& make, const Parameter& parameter);

}  // namespace spp
