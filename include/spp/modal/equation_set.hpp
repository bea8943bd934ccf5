#pragma once
// The SPP equations of one case of Theorem 3.1 behind one interface (issue 11, "one model, one layout"). The modal
// form (modal.hpp) is data: frequencies, mode shapes, G, d, u, z, the contact flows and the poles. An equation set
// builds on it the matrices one case solves: H (symmetric m x m, PSD partial derivatives), its pole-free form N with
// the same zeros, and the onset state of the orbit from N's null vector. The search, the orbit and the continuation
// take a `const EquationSet&`; a new case (e.g. k-impact orbits) is one more class, not a branch in each of them:
// src/modal/axial_equations.cpp and point_equations.cpp are the two cases of Theorem 3.1.
//
// Every set satisfies, with b = cos(W t1) a (modal form §2):
//   N(t1, t2) = contact_cos(t2) H(t1, t2) cos(W t1),   so N a = 0 exactly where H b = 0;
//   z^T onset_position(t1, a) = onset_direction(t2)^T b   where H b = 0.
// Cost: O(m) for the diagonals, O(m^2) for a vector through G, O(m^3) for a matrix (H, N and their derivatives).

#include <Eigen/Dense>
#include <memory>

#include "spp/modal/modal.hpp"

namespace spp {

/// Shape of H's diagonal phase functions in one frequency f (flight_part in t1, contact_eigs in t2): what the bounds
/// of the certified search (search/step_certificate, search/bordered_form) are written for.
enum class PhaseShape {
  FTan,      ///< f tan(f t)
  TanOverF,  ///< tan(f t) / f, with its limit t at f = 0
};

class EquationSet {
 public:
  explicit EquationSet(const ModalForm& modal) : md_(modal) {}
  virtual ~EquationSet() = default;
  EquationSet(const EquationSet&) = delete;
  EquationSet& operator=(const EquationSet&) = delete;

  /// The modal form the equations are written on (held by reference: it must outlive the set).
  const ModalForm& modal() const { return md_; }
  /// The user-facing option that selects this set (SolveOptions::symmetry, Orbit::symmetry, the JSON's "symmetry").
  virtual Symmetry symmetry() const = 0;

  /// H(t1,t2) = diag(flight_part(t1)) + contact_part(t2), symmetric m x m, with PSD derivatives (design note §3).
  Eigen::MatrixXd H(double t1, double t2) const;
  Eigen::MatrixXd contact_part(double t2) const;  ///< G diag(contact_eigs(t2)) G^T
  /// Diagonal of the contact part in the G basis (axial D tan(D t2), point tan(D t2) D^-1).
  virtual Eigen::VectorXd contact_eigs(double t2) const = 0;
  /// Diagonal flight part (axial W tan(W t1), point W^-1 tan(W t1)).
  virtual Eigen::VectorXd flight_part(double t1) const = 0;
  /// d/dt1 of flight_part, >= 0 (axial W^2 sec^2(W t1), point sec^2(W t1)).
  virtual Eigen::VectorXd dflight_dt1(double t1) const = 0;
  /// d/dt2 of contact_eigs, >= 0 (axial D^2 sec^2(D t2), point sec^2(D t2)).
  virtual Eigen::VectorXd dcontact_eigs(double t2) const = 0;
  Eigen::MatrixXd dcontact_dt2(double t2) const;  ///< G diag(dcontact_eigs(t2)) G^T

  /// Pole-free N(t1,t2) = contact_cos(t2) H cos(W t1) (an entire function, design note §2) and its derivatives.
  virtual Eigen::MatrixXd N(double t1, double t2) const = 0;
  virtual Eigen::MatrixXd dN_dt1(double t1, double t2) const = 0;
  virtual Eigen::MatrixXd dN_dt2(double t1, double t2) const = 0;

  /// Modal position and velocity at contact onset from the null vector a of N: axial p0 = cos(W t1) a,
  /// p0' = -W sin(W t1) a; point p0 = W^-1 sin(W t1) a, p0' = cos(W t1) a. Linear in a, diagonal: O(m).
  virtual Eigen::VectorXd onset_position(double t1, const Eigen::VectorXd& a) const = 0;
  virtual Eigen::VectorXd onset_velocity(double t1, const Eigen::VectorXd& a) const = 0;
  /// d/dt1 of onset_position.
  virtual Eigen::VectorXd onset_position_dt1(double t1, const Eigen::VectorXd& a) const = 0;
  /// c(t2) with z^T p0 = c^T b for the null vector b of H: axial z; point -G tan(D t2) D^-1 G^T z (then b = v).
  /// And dc/dt2.
  virtual Eigen::VectorXd onset_direction(double t2) const = 0;
  virtual Eigen::VectorXd onset_direction_dt2(double t2) const = 0;

  // ---- capabilities: what the callers' proofs and reports depend on ----

  /// Shape of the phase functions of flight_part and contact_eigs.
  virtual PhaseShape phase_shape() const = 0;
  /// A lower bound of every entry of dflight_dt1 over all t1 (the slope of H along t1 never falls below it).
  virtual double min_flight_slope() const = 0;
  /// True when onset_direction is the constant z; otherwise it is -contact_part(t2) z, which moves with t2.
  virtual bool onset_direction_fixed() const = 0;
  /// False when no orbit of this set can satisfy ineqs. (5.3) (point symmetry: the force is odd about t2).
  virtual bool can_be_admissible() const = 0;
  /// True when the normal velocity at onset is not zero by symmetry, so that the obstacle must move during contact
  /// at Orbit::obstacle_velocity unless g0 = 0.
  virtual bool moving_obstacle() const = 0;
  /// A time in the contact phase where the force of an orbit of this set has the sign it keeps if admissible (axial:
  /// mid-contact t2; point: t2 / 2, the force vanishing at t2): fixes the sign of a free-scale orbit.
  virtual double force_probe(double t2) const = 0;
  /// Flag added to every solution of this set (Solution::flags), or nullptr.
  virtual const char* solution_flag() const = 0;

 protected:
  const ModalForm& md_;
};

/// The equation set of one Symmetry on `modal` (held by reference). The one place a Symmetry becomes equations.
std::unique_ptr<EquationSet> make_equations(const ModalForm& modal, Symmetry sym);

}  // namespace spp
