#pragma once
// A large finite-element model held sparse: M x'' + K x = w lambda, g = w^T x + g0 >= 0 (the same mechanics as
// System, system.hpp). It is not solved directly: spp reduces it (reduction/craig_bampton.hpp) to a small dense
// System. An immutable value, validated once when built.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <string>

namespace spp {

/// A sparse n-dof system with one affine unilateral constraint; w and g0 are kept as given (not normalised).
class SparseSystem {
 public:
  /// Validates sizes, finiteness, symmetry of M and K (relative tolerance kSymmetryTolerance of system.hpp), positive
  /// diagonals of M and K, w finite and non-zero, g0 finite. Positive definiteness needs a factorisation: reduce()
  /// checks it with the ones it computes. Throws std::invalid_argument naming the field and the rule.
  /// M, K: n x n (column-major sparse, any one or both triangles given: stored as both); w: (n); units as System.
  /// Cost O(nnz) (no factorisation).
  SparseSystem(Eigen::SparseMatrix<double> M, Eigen::SparseMatrix<double> K, Eigen::VectorXd w, double g0,
               std::string name = "");

  int n() const { return static_cast<int>(M_.rows()); }
  const Eigen::SparseMatrix<double>& M() const { return M_; }  ///< both triangles stored
  const Eigen::SparseMatrix<double>& K() const { return K_; }  ///< both triangles stored
  const Eigen::VectorXd& w() const { return w_; }              ///< contact direction as given
  double g0() const { return g0_; }                            ///< gap at rest, as given
  const std::string& name() const { return name_; }

 private:
  Eigen::SparseMatrix<double> M_, K_;
  Eigen::VectorXd w_;
  double g0_ = 0.0;
  std::string name_;
};

}  // namespace spp
