#pragma once
// The contact part C(e) = G diag(e) G^T of H (modal form §2) in O(m^2) instead of O(m^3), from the structure of G:
// its columns are the eigenvectors of S = W^2 - z z^T, g_j = (W^2 - d_j^2)^{-1} z / N_j (modal form §1), so with
// a_k = omega_k^2, x_j = d_j^2, delta_kj = a_k - x_j and c_j = e_j / N_j^2,
//   C_kl = z_k z_l sum_j c_j / (delta_kj delta_lj) = z_k z_l (phi_k - phi_l) / (a_l - a_k)   (k != l, partial
//   fractions) C_kk = z_k^2 sum_j c_j / delta_kj^2,   phi_k = sum_j c_j / delta_kj:
// H is a symmetric Cauchy-like (Loewner) matrix (issue 12; design note §3b). The differences delta_kj come from
// LAPACK's secular-equation solver dlaed4 (Gu–Eisenstat: to high relative accuracy, which a_k - d_j^2 subtracted
// would not have next to clustered frequencies), once per system.
//
// The divided difference (phi_k - phi_l) / (a_l - a_k) cancels where a_k and a_l are close: every call bounds the
// rounding of the formula a posteriori, entry by entry (first order in eps),
//   |dC_kl| <= gamma |z_k z_l| (psi_k + psi_l) / |a_l - a_k| + 2 eps |C_kl|,   psi_k = sum_j |c_j| / |delta_kj|,
//   |dC_kk| <= gamma z_k^2 sum_j |c_j| / delta_kj^2 + 2 eps |C_kk|,   gamma = 2 (m + 4) eps,
// and declines (returns false: the caller forms G diag(e) G^T densely) where the bound's largest row sum exceeds
// `budget` m eps || |H| ||_inf (budget 16: twice the evaluator's error bound 8 m eps |H|; measured on the chain at an
// ordinary point: 2.8 m eps |H| at m = 30, 4.1 at 100, 5.7 at 300, 8.0 at 1000, bench_evaluator LoewnerEntries). The
// caller adds the bound to its error bound (DenseEvaluator), so every certificate stays sound, only that much less
// sharp: the dense product's own rounding (at most
// gamma_{m+2} |G| |e| |G^T|, besides G's own error) is not in that error bound at all. Measured against a long double
// reference, the structured entries' errors are 1-250x below the dense product's, on chains and random systems of
// 30-1000 dofs, away from and next to contact pole lines (test LoewnerContact.AtLeastAsAccurateAsTheDenseProduct).
// No Debian library forms Loewner matrices; the sums are ours.

#include <Eigen/Dense>

#include "spp/modal/modal.hpp"

namespace spp::search {

class LoewnerContact {
 public:
  /// From the modal form; applies() is false where the structure does not hold (m < 2, a zero z_k, a repeated
  /// frequency, dlaed4 failing, or its roots disagreeing with the modal form's d beyond rounding).
  explicit LoewnerContact(const ModalForm& modal);
  bool applies() const { return applies_; }
  /// H = diag(f) + C(e) into H when the a posteriori bound allows (see above); false (H unspecified) otherwise.
  /// ref > 0: the bound and the norm are those of S H S, S = diag(1 / sqrt(max(|H_ii|, ref))) (onset_inertia's
  /// scaling).
  bool form(const Eigen::VectorXd& f, const Eigen::VectorXd& e, Eigen::MatrixXd& H, double budget = 16.0,
            double ref = 0.0) const;
  /// C(e) alone (f = 0), same rule.
  bool contact_part(const Eigen::VectorXd& e, Eigen::MatrixXd& C, double budget = 16.0) const;
  /// Largest row sum of the last bound computed by form(): a bound of the rounding of H's entries in the 2-norm.
  double last_bound() const { return last_bound_; }
  double last_norm() const { return last_norm_; }  ///< || |H| ||_inf of the last form() (scaled when ref > 0)

 private:
  bool applies_ = false;
  Eigen::VectorXd a_, z_, n2_;   // omega^2, z, N_j^2
  Eigen::MatrixXd r_, ra_, r2_;  // 1 / delta_kj, its absolute value, 1 / delta_kj^2
  mutable double last_bound_ = 0.0, last_norm_ = 0.0;
};

}  // namespace spp::search
