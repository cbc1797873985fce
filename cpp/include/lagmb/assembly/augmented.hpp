// The augmented (saddle-point) system of one instant, solved through its Schur
// complement (sparse Cholesky) or, without a positive definite M, sparse LU:
// assembled, factorized and solved here; what is solved with it for a
// consistent state (positions, velocities, accelerations) is in
// lagmb/analyses/consistent_state.hpp.
#pragma once

#include <Eigen/SparseCholesky>
#include <array>
#include <string>
#include <vector>

#include "lagmb/model/data.hpp"
#include "lagmb/solvers/sparse_lu.hpp"

namespace lagmb {

/// K = [ M      Phi_q^T  ]
///     [ Phi_q  -eps I   ]
///
/// eps > 0 keeps K invertible when Phi_q loses rank (redundant constraints,
/// singular positions); solve() then refines the solution against the
/// unregularized K, so for a full-rank Phi_q the answer is exact.
///
/// With every mass and inertia positive (M, block diagonal by body, is then
/// positive definite), K is solved through its Schur complement (range-space method):
///   S = Phi_q M^-1 Phi_q^T + eps I   (symmetric positive definite for any Phi_q),
///   S lam = Phi_q M^-1 b1 - b2,   x1 = M^-1 (b1 - Phi_q^T lam),
/// with a sparse Cholesky factorization of S. Its cost is linear in a
/// chain's or tree's length; each entry of S is a sum over the columns of
/// Phi_q (one per coordinate), listed once as pairs of Jacobian entries.
/// The rows of S are renumbered once by approximate minimum degree (AMD),
/// and S is assembled directly in that order, so a factorization copies and
/// permutes nothing.
/// S is first factorized with eps = 0, which is exact when every pivot keeps
/// more than 1e-8 of its row's diagonal (no row nearly a combination of the
/// others). Otherwise (a singular position) S0 + eps I is factorized and
/// the solution refined against eps = 0 in S's space:
///   S lam_{k+1} = s + eps lam_k   has the residual   s - S0 lam_{k+1} = eps (lam_{k+1} - lam_k),
/// which is exactly the second block row of K0's residual (the first is zero
/// by construction of x1): each refinement costs one pair of triangular
/// solves and no product with K. Rows dropped as redundant get a unit
/// diagonal (their right sides are zero, so their multipliers stay 0).
/// Otherwise (a massless body, for kinematics) K is factorized by sparse LU
/// (COLAMD) and refined with K0's residual. Either way the pattern is fixed
/// by the model, so the ordering and symbolic analysis run once per
/// AugmentedSystem; factorize() is numeric only.
class AugmentedSystem {
 public:
  explicit AugmentedSystem(const Model& model);

  /// Factorizes K with the current d.Phi_q and d.M (d.M_inv); false if the
  /// factorization fails or K is not finite.
  bool factorize(const Data& d);
  /// Solves K [x1; x2] = [b1; b2] (sizes n, m), refining against eps = 0.
  /// SimulationError if the last factorization failed.
  void solve(const VecX& b1, const VecX& b2, VecX& x1, VecX& x2);

  int factorizations() const { return factorizations_; }
  double regularization() const { return eps_; }
  /// Whether the last factorization went through the Schur complement.
  bool range_space() const { return schur_; }
  /// Nonzeros of the Cholesky factor of S (0 before the first range-space
  /// factorization): linear in a chain's length.
  long factor_nonzeros() const;
  /// How often S's pattern was analyzed (ordering, elimination tree): once.
  int symbolic_analyses() const { return symbolic_analyses_; }

 private:
  void setup_schur(const Model& model);
  void fill_lu_matrix(const Data& d);
  bool factorize_schur(const Data& d);
  bool pivots_above(double ratio) const;
  void solve_range_space(const VecX& b1, const VecX& b2, VecX& x1, VecX& x2);

  int n_, m_;
  double eps_;
  SpMat K_;
  std::vector<int> mass_slots_, jac_slots_, jact_slots_, reg_slots_;
  double mass_scale_;
  bool diagonal_mass_;  // M constant and diagonal (a planar model)
  SupernodalLU lu_;
  bool lu_analyzed_ = false;
  bool factorized_ = false;
  VecX rhs_, x_, r_, dx_;
  int factorizations_ = 0;
  // the range-space path
  bool positive_mass_ = false, schur_ = false, regularized_ = false;
  std::vector<int> j_outer_;    // Phi_q's column starts (its pattern)
  std::vector<int> j_row_;      // each Phi_q entry's row of S (AMD order)
  std::vector<int> old_of_new_;  // S's row k is constraint row old_of_new_[k]
  std::vector<int> new_of_old_;
  VecX j_values_;               // Phi_q's values at the last factorization
  SpMat m_inv_;                 // M^-1 at the last factorization (block diagonal)
  SpMat S_;                     // upper triangle, AMD order
  VecX s_rhs_, work_, lam_, lam_prev_, w_n_;
  // Phi_q's columns in runs with the same rows (a body's position, its Euler
  // parameters): each run adds the dense product J_g (J M^-1)_g^T, rows x
  // rows, to S; its lower triangle goes to S's entries slots_[slot0 ..)
  struct ColumnRun {
    int entry0, rows, width, slot0;
  };
  std::vector<ColumnRun> runs_;
  std::vector<int> run_slots_;
  VecX run_product_;  // the lower triangle of the largest run's product, by columns
  VecX j_scaled_;  // J M^-1, per entry (a block of M^-1 mixes columns with the same rows)
  std::vector<int> s_diag_;
  Eigen::SimplicialLLT<SpMat, Eigen::Upper, Eigen::NaturalOrdering<int>> chol_;
  int symbolic_analyses_ = 0;
};

}  // namespace lagmb
