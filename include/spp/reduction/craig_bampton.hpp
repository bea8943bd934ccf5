#pragma once
// Craig-Bampton reduction of a large sparse model (core/sparse_system.hpp) to the contact coordinate and its first m
// fixed-interface modes: a small dense System (core/system.hpp) that spp solves like any other.
//
// The contact coordinate. Take p = the dof with the largest |w_p| and change coordinates x = A y, with y_j = x_j for
// j != p and y_p = u = w^T x / w_p (x_p = u - sum_{j != p} (w_j / w_p) y_j); then w^T x = w_p u: the constraint sees
// the one coordinate u. When w has one non-zero (w = w_c e_c, a contact dof: the common case) A is the identity and
// u = x_c. A general w is handled by the same change: M and K become A^T M A and A^T K A, whose row and column p
// gain the fill of the rows of the other dofs of w (cheap for a few non-zeros; a w with thousands of non-zeros makes
// them dense rows).
//
// Craig-Bampton with the boundary {u} (Craig & Bampton 1968): interior dofs i (all but p), the static constraint
// mode psi = -K_ii^{-1} K_ip (the interior's static response to u = 1), and the m fixed-interface modes Phi (the
// lowest eigenpairs of K_ii phi = lambda M_ii phi, u clamped, M_ii-normalised). x = A T q with
//   T = [ 1    0  ]   (row p)
//       [ psi  Phi]   (rows i),   q = (u, eta_1..eta_m);
// reduced M = T^T M T, K = T^T K T ((m+1) x (m+1), dense, SPD), w = w_p e_0, g0 unchanged (the System then
// normalises w and g0 by |w_p| as for any input). K_red(0,0) = K_pp + K_pi psi is the exact static stiffness of the
// full model at u (the Schur complement); K_red(1:,1:) = diag(lambda), the coupling is zero to rounding.
//
// Numerics: one sparse Cholesky factorisation of K_ii (CHOLMOD, SuiteSparse) serves psi and the shift-invert
// eigensolver (Spectra's SymGEigsShiftSolver, shift 0); a second factorisation (of M) checks that M is positive
// definite. Interiors of at most ReductionOptions::dense_interior dofs, or m above half the interior, use the dense
// generalised eigensolver (Eigen) instead: Spectra's Lanczos needs m < interior dofs.

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "spp/core/sparse_system.hpp"
#include "spp/core/system.hpp"

namespace spp {

/// Enough dofs for a picture of the model; their rows of the basis stay a few MB.
inline constexpr long kMaxExpansionDofs = 4000;

struct ReductionOptions {
  int modes = 20;                  ///< m: fixed-interface modes kept, 1 <= m <= n - 1 (the interior dofs)
  double eigen_tolerance = 1e-10;  ///< Spectra's relative tolerance on the Ritz values
  int max_iterations = 1000;       ///< Spectra's restarts
  int dense_interior = 400;        ///< interiors up to this size use the dense eigensolver
  /// Dofs of the full model (0-based) whose rows of the reduction basis A T are kept in ReductionResult::expansion
  /// (their displacements from q: the finite-element picture of an animation, io/layout_file.hpp). At most
  /// kMaxExpansionDofs of them.
  std::vector<int> expansion_dofs{};
  /// Throws std::invalid_argument naming the field, its value and the rule; n = the model's dofs (0: not checked).
  void validate(int n = 0) const;
};

struct ReductionTimings {
  double transform_seconds = 0;      ///< change of coordinates (general w) and partition
  double factorization_seconds = 0;  ///< Cholesky of K_ii and of M (the check)
  double eigen_seconds = 0;          ///< fixed-interface modes
  double projection_seconds = 0;     ///< T^T M T, T^T K T
  double total_seconds = 0;
};

struct ReductionResult {
  enum class Status {
    NotRun,             ///< the default: reduce() was not called
    Success,            ///< `reduced` holds the (m+1)-dof model
    EigenNotConverged,  ///< Spectra did not converge the m fixed-interface modes: `reduced` is empty
  };
  Status status = Status::NotRun;
  std::optional<System> reduced;                ///< q = (u, eta_1..eta_m); empty unless Success
  int n_full = 0;                               ///< dofs of the full model
  int modes = 0;                                ///< m
  int contact_dof = -1;                         ///< p (0-based): the dof whose coordinate became u
  int w_nonzeros = 0;                           ///< non-zeros of w (1: no change of coordinates)
  bool dense_eigensolver = false;               ///< the interior was small enough for the dense eigensolver
  double static_stiffness = 0;                  ///< K_pp + K_pi psi: the full model's static stiffness at u
  Eigen::VectorXd fixed_interface_frequencies;  ///< sqrt(lambda_k), ascending (rad per unit time)
  Eigen::VectorXd reduced_frequencies;          ///< the reduced model's natural frequencies, ascending
  /// One row per ReductionOptions::expansion_dofs entry, m + 1 columns: x[dof] = row . q
  Eigen::MatrixXd expansion;
  int eigen_iterations = 0;                     ///< Spectra's restarts (0 with the dense eigensolver)
  int eigen_operations = 0;                     ///< Spectra's solves with the K_ii factor
  ReductionTimings timings;
  /// One line: status, n -> m+1, lowest frequencies, time.
  std::string brief_report() const;
};

const char* to_string(ReductionResult::Status status);

/// Reduces the model to its contact coordinate and options.modes fixed-interface modes. Caller mistakes (options out
/// of range, M or K not positive definite) throw std::invalid_argument; non-convergence is a status.
ReductionResult reduce(const SparseSystem& system, const ReductionOptions& options = {});

/// The convergence study: one result per m of `modes` (increasing; options.modes is ignored), sharing one
/// factorisation and one eigensolve for the largest m (the lowest m' fixed-interface modes are the same for every
/// m' <= m). Each result's timings hold the shared stages once, its own projection, and total = time since the start.
std::vector<ReductionResult> reduce(const SparseSystem& system, const std::vector<int>& modes,
                                    const ReductionOptions& options = {});

}  // namespace spp
