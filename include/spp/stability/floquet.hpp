#pragma once
// Floquet multipliers of an SPP under Newton's impact law with restitution e in [0, 1) (docs/stability.md).
// Over one period, from just before the contact onset, a small perturbation dX = (dx, dv) evolves as
//   dX(T) = Mono dX(0),   Mono = exp(2 t1 A1) exp(2 t2 A2) Pi,   Pi = diag(P, P),
//   P = I - M^-1 w w^T / (w^T M^-1 w)  (the M-orthogonal projection on w^T x = 0, positions and velocities),
// A1, A2 the first-order flows of flight and contact (paper eqs. 3.9-3.11). The onset acts as the plastic
// projection Pi whatever e < 1 (the perturbed orbit arrives with a normal velocity of order |dX|^(2/3), impacts or
// chatters, and ends in contact within a time of order |dX|^(1/3)); the release is a switch between two vector
// fields equal on it (zero force), so its saltation matrix is the identity. The remainder is O(|dX|^(4/3)), so a
// finite-difference monodromy converges at the rate delta^(1/3).
// Structure: Pi has rank 2n - 2 (two zero multipliers); the flow direction f is a right eigenvector (Mono f = f) and
// the energy gradient a left one (energy is conserved to first order: the onset removes it at O(|dX|^(4/3)) only),
// with grad E . f = 0: the multiplier 1 is double, with one Jordan block. The other 2n - 4 decide stability.

#include <Eigen/Dense>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "spp/core/system.hpp"
#include "spp/modal/modal.hpp"
#include "spp/orbit/orbit.hpp"

namespace spp {

struct Floquet {
  /// All 2n multipliers of the monodromy, sorted by modulus (then argument): the two structural ones equal to 1
  /// exactly (flow direction and energy), the two zeros of the onset's projection, and those of the reduced map.
  /// Modes that never see the contact (ModalForm::omega_decoupled) give exp(+-i omega T), of modulus 1.
  std::vector<std::complex<double>> multipliers;
  /// Largest modulus over every multiplier but the two structural 1s (dimensionless). NaN: not computed.
  double spectral_radius = std::numeric_limits<double>::quiet_NaN();
  /// 1 - spectral_radius: > 0 exactly when stable (linearly, orbitally, up to the energy direction).
  double margin = std::numeric_limits<double>::quiet_NaN();
  /// spectral_radius < 1: transversal linear stability, NOT Lyapunov stability. The energy direction is neutral to
  /// first order and impacts only dissipate: perturbed orbits of such SPPs were measured to leave after
  /// ~C eps^(-1/3) periods (docs/stability.md §4), slowly instead of at the rate rho^k of an unstable SPP.
  bool stable = false;
  /// max(|Mono f - f| / |f|, |Mono^T y0 - y0| / |y0|) in energy-scaled modal coordinates: how well the two
  /// structural multipliers hold in the computed monodromy (rounding; a large value means a bad orbit).
  double structure_residual = std::numeric_limits<double>::quiet_NaN();
  /// "stable, rho = 0.9858 (margin 0.0142)" / "unstable, ...": one line.
  std::string brief_report() const;
};

/// Floquet multipliers of an axially symmetric orbit (Symmetry::Axial) of `modal`'s system. Meaningful for admissible
/// SPPs; for a potential one it is the linearisation of its (unphysical) orbit. Dimensionless and invariant under
/// changes of units and of coordinates. Cost O(m^3): three contact-phase matrix functions and one nonsymmetric
/// eigenproblem of size 2m - 2 (m the modes that see the contact). Throws std::invalid_argument for a point-symmetric
/// orbit (its obstacle moves during contact) or an orbit whose sizes do not match.
Floquet floquet(const ModalForm& modal, const Orbit& orbit);

/// The monodromy itself, 2n x 2n in physical coordinates (dx, dv), from just before the contact onset to one period
/// later (the formula above). For checks against a finite-difference monodromy of the simulator. Cost O(n^3).
Eigen::MatrixXd monodromy(const ModalForm& modal, const Orbit& orbit);

}  // namespace spp
