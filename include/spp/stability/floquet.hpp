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

/// What the computed multipliers prove about transversal linear stability (docs/stability.md §2, "The verdict").
enum class StabilityVerdict {
  NotComputed,  ///< no multipliers (the default; compute_stability off, point symmetry, eigensolver failure)
  Stable,       ///< spectral_radius + spectral_radius_error < 1: every multiplier that decides is inside the circle
  Unstable,     ///< spectral_radius - spectral_radius_error > 1: one is outside, whatever the rounding
  Undecided,    ///< |spectral_radius - 1| <= spectral_radius_error: rounding cannot tell (a guess is not given)
  /// The coupled multipliers are inside the circle (proved as for Stable), but modes that never see the contact
  /// (ModalForm::omega_decoupled) give multipliers exp(+-i omega T) exactly on it: neutral, not asymptotically stable.
  Neutral,
};
const char* to_string(StabilityVerdict v);
/// Its values: 0 .. 4 (Neutral last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(StabilityVerdict) {
  return 5;
}

struct Floquet {
  /// All 2n multipliers of the monodromy, sorted by modulus (then argument): the two structural ones equal to 1
  /// exactly (flow direction and energy), the two zeros of the onset's projection, and those of the reduced map.
  /// Modes that never see the contact (ModalForm::omega_decoupled) give exp(+-i omega T), of modulus 1.
  std::vector<std::complex<double>> multipliers;
  /// The multiplier of largest modulus among those of the modes that see the contact (not the structural 1s), with
  /// its conjugate when complex (one real or a conjugate pair, positive imaginary part first); empty for m <= 2 and
  /// for solutions read from a result file (not written there: the multipliers are).
  std::vector<std::complex<double>> leading;
  /// Largest modulus over every multiplier but the two structural 1s (dimensionless), the decoupled modes' taken as
  /// exactly 1. NaN: not computed.
  double spectral_radius = std::numeric_limits<double>::quiet_NaN();
  /// Estimated bound on the rounding error of the coupled modes' largest modulus (first-order perturbation theory:
  /// the monodromy's estimated backward error times the eigenvalue condition numbers, floquet.cpp). Infinite when
  /// the leading multiplier is (numerically) defective. NaN: not computed, or read from a file written before it.
  double spectral_radius_error = std::numeric_limits<double>::quiet_NaN();
  /// The part of spectral_radius_error that comes from the SPP's location error (floquet(EquationSet, Orbit) only;
  /// 0 from floquet(ModalForm, Orbit), which takes the orbit as exact): how far rho moves over the estimated distance
  /// of the computed (t1, t2, a) from the SPP, large near a fold of a branch (docs/stability.md §2, "The verdict").
  /// Result files hold it ("spectral_radius_location_error"); NaN when read from a file written before it.
  double location_error = 0.0;
  /// 1 - spectral_radius.
  double margin = std::numeric_limits<double>::quiet_NaN();
  StabilityVerdict verdict = StabilityVerdict::NotComputed;
  /// verdict == Stable: transversal linear stability proved up to rounding, NOT Lyapunov stability. The energy
  /// direction is neutral to first order and impacts only dissipate: perturbed orbits of such SPPs were measured to
  /// leave after ~C eps^(-1/3) periods (docs/stability.md §4), slowly instead of at the rate rho^k of an unstable SPP.
  bool stable = false;
  /// max(|Mono f - f| / |f|, |Mono^T y0 - y0| / |y0|) in energy-scaled modal coordinates: how well the two
  /// structural multipliers hold in the computed monodromy (rounding; a large value means a bad orbit).
  double structure_residual = std::numeric_limits<double>::quiet_NaN();
  /// "stable, spectral radius 0.985756 +- 2.1e-14 (margin 0.0142), 10 multipliers" / "unstable, ..." / ...: one line.
  std::string brief_report() const;
};

/// The verdict for a coupled spectral radius `rho` with error bound `error` (>= 0, may be infinite), with or without
/// modes that never see the contact (their multipliers lie on the unit circle).
StabilityVerdict stability_verdict(double rho, double error, bool has_decoupled_modes);

/// Floquet multipliers of an axially symmetric orbit (Symmetry::Axial) of `modal`'s system. Meaningful for admissible
/// SPPs; for a potential one it is the linearisation of its (unphysical) orbit. Dimensionless and invariant under
/// changes of units and of coordinates. Cost O(m^3): three contact-phase matrix functions and one nonsymmetric
/// eigenproblem of size 2m - 2 (m the modes that see the contact). Throws std::invalid_argument for a point-symmetric
/// orbit (its obstacle moves during contact) or an orbit whose sizes do not match.
Floquet floquet(const ModalForm& modal, const Orbit& orbit);

/// floquet(eq.modal(), orbit) with the SPP's location error in spectral_radius_error (and location_error) and the
/// verdict that gives: orbit is the SPP of eq's equations near (orbit.t1, orbit.t2) as computed, and near a fold its
/// (t1, t2) can be far from it (1e-11 and more) where the radius moves with them. What solve(), the continuation and
/// verify report. Cost O(m^3): floquet's, one SVD of size m + 2 and two more monodromies. Throws
/// std::invalid_argument as floquet(modal, orbit) does, and for a point-symmetric equation set.
Floquet floquet(const EquationSet& eq, const Orbit& orbit);

/// The monodromy itself, 2n x 2n in physical coordinates (dx, dv), from just before the contact onset to one period
/// later (the formula above). For checks against a finite-difference monodromy of the simulator. Cost O(n^3).
Eigen::MatrixXd monodromy(const ModalForm& modal, const Orbit& orbit);

}  // namespace spp
