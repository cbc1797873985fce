// The augmented (saddle-point) system of one instant, solved through its Schur
// complement (sparse Cholesky) or, without a positive definite M, sparse LU:
// assembled, factorized and solved here; what is solved with it for a
// consistent state (positions, velocities, accelerations) is in
// lagmb/analyses/consistent_state.hpp.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "lagmb/model/data.hpp"
#include "lagmb/solvers/block_cholesky.hpp"
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
/// with a Cholesky factorization of S in dense blocks, one per element's
/// rows (solvers/block_cholesky.hpp): blocks eliminated in approximate
/// minimum degree order of the blocks' graph, which for a chain or tree is
/// leaves first and fills nothing, so the cost is linear in its length.
/// Each entry of S is a sum over the columns of Phi_q (one per coordinate),
/// listed once as pairs of Jacobian entries, and S is assembled directly in
/// the factor's layout, so a factorization copies and permutes nothing.
/// S is first factorized with eps = 0, which is exact when every pivot keeps
/// more than 1e-8 of its row's diagonal (no row nearly a combination of the
/// others). Otherwise (a singular position) S0 + eps I is factorized and
/// the solution refined against eps = 0 in S's space:
///   S lam_{k+1} = s + eps lam_k   has the residual   s - S0 lam_{k+1} = eps (lam_{k+1} - lam_k),
/// which is exactly the second block row of K0's residual (the first is zero
/// by construction of x1): each refinement costs one pair of triangular
/// solves and no product with K. Rows dropped as redundant get a unit
/// diagonal (their right sides are zero, so their multipliers stay 0).
/// A spatial body's Euler parameters p enter S in body rates (exact, not an
/// approximation): with P = [G(p); p^T] (P P^T = |p|^2 I) and p'' =
/// P^T y / |p|^2, y = (z, y4), z = G(p) p'' (half the angular acceleration
/// in body axes) and y4 = p^T p'', the mass block P M_p P^T / |p|^4 is
/// the constant diag(4 J', 4 jbar) (elements/spatial_body.hpp's M_p), and
/// the normalization row p^T p'' = b_N reads y4 = b_N: y4 is known, its
/// column moves to the right side and the row leaves S. S is then
/// assembled from R = the Jacobian with z's three columns Phi_p G^T / |p|^2
/// in place of p's four, over a constant block-diagonal M^-1 (1 / m, and
/// (4 J')^-1 on z): 5 rows per revolute link and 6 columns instead of 6 and
/// 7. Back: p'' = (G^T z + p y4) / |p|^2, and the normalization row's
/// multiplier lam_N = (p^T b1_p) / |p|^2 - 4 jbar y4 - (Phi_p p / |p|^2)^T lam
/// from y4's equation. A run that leaves a normalization row out (found
/// redundant) takes the LU instead.
/// Otherwise (a massless body, for kinematics) K is factorized by sparse LU
/// (COLAMD) and refined with K0's residual. Either way the pattern is fixed
/// by the model, so the orderings and the layouts are made once per model
/// (AugmentedPattern, shared by its runs); factorize() is numeric only.
/// Where no stop or stuck contact is closed (Data::closed_rows empty), S
/// leaves their rows out altogether (OpenRowsPattern): a joint's limits
/// that nothing touches cost nothing in the factorization.

/// What an AugmentedSystem needs of the model's patterns alone, made once
/// per model (Model::derived) and shared by every run: K's pattern and
/// where M, Phi_q and the regularization go in it; for the range-space path
/// the AMD order of S's rows, S's upper-triangle pattern and where each
/// column run's products go in it.
struct AugmentedPattern {
  /// `open_rows_out`: S without the rows a run opens and closes
  /// (Model::switched_rows: stops, stuck contacts), for where all are open.
  explicit AugmentedPattern(const Model& model, bool open_rows_out = false);

  SpMat K;  // pattern of [M Phi_q^T; Phi_q -eps I] (values zero)
  std::vector<int> mass_slots, jac_slots, jact_slots, reg_slots;
  bool range_space = false;  // positive masses, constraints, and J M^-1 keeps J's pattern
  // the range-space path, on R (Phi_q with each spatial body's Euler
  // parameters in body rates z; Phi_q itself in the plane): n_r columns,
  // the rows other than the normalizations
  int n_r = 0;
  std::vector<int> j_outer;     // R's column starts (its pattern)
  std::vector<int> j_row;       // each R entry's row of S (AMD order)
  std::vector<int> j_source;    // the Phi_q entry each R entry copies (-1: a body-rate column's, computed)
  bool r_is_jacobian = false;   // R is Phi_q entry for entry (no spatial body): copied whole
  std::vector<int> q_column;    // R's column c is q's column q_column[c] (-1: a body-rate column)
  std::vector<int> old_of_new;  // S's row k is constraint row old_of_new[k]
  std::vector<int> new_of_old;  // (-1: a normalization row, or a switched row left out, not in S)
  std::vector<char> switched_out;  // per constraint row: a switched row S leaves out (open_rows_out)
  SpMat m_inv;                  // M^-1 over R's columns: constant, block diagonal
  bool diagonal_m_inv = true;   // (every block 1 x 1)
  /// A spatial body in body rates: its Euler parameters' columns p .. p + 3
  /// of Phi_q hold the same `rows` rows from entries q_entry0[0..3], the
  /// normalization row at offset norm (its values are p); its z columns
  /// z .. z + 2 of R hold the others, in order, from entries r_entry0[0..2].
  struct BodyRates {
    int p, z, norm_row, rows, norm;
    std::vector<int> in_r;  // the rows (offsets into its `rows`) R holds: all but norm (and those left out)
    std::array<int, 4> q_entry0;
    std::array<int, 3> r_entry0;
    double mass4;  // 4 jbar: y4's mass
  };
  std::vector<BodyRates> bodies;
  BlockCholeskyPattern S;  // S's blocks (an element's rows), their order and L's layout
  // R's columns in runs with the same rows (a body's position and rates, or
  // in the plane its coordinates): each run adds the dense product
  // R_g (R M^-1)_g^T, rows x rows, to S; its lower triangle goes to S's
  // entries run_slots[slot0 ..)
  struct ColumnRun {
    int entry0, rows, width, slot0;
  };
  std::vector<ColumnRun> runs;
  std::vector<int> run_slots;
  int largest_run = 0;
  std::vector<int> s_diag;  // S's diagonal (new numbering) in its values

 private:
  void setup_schur(const Model& model, bool open_rows_out);
  /// R's pattern, its rows and columns, m_inv and bodies from Phi_q's
  /// pattern; false if a spatial body's parameters cannot go to body rates.
  bool setup_reduced(const Model& model, std::vector<int>& r_rows, bool open_rows_out);
};

/// The model's AugmentedPattern with S leaving out every switched row (Model::derived).
struct OpenRowsPattern : AugmentedPattern {
  explicit OpenRowsPattern(const Model& model) : AugmentedPattern(model, true) {}
};

class AugmentedSystem {
 public:
  explicit AugmentedSystem(const Model& model);

  /// Factorizes K with the current d.Phi_q and d.M; false if the
  /// factorization fails or K is not finite.
  bool factorize(const Data& d);
  /// Solves K [x1; x2] = [b1; b2] (sizes n, m), refining against eps = 0.
  /// SimulationError if the last factorization failed.
  void solve(const VecX& b1, const VecX& b2, VecX& x1, VecX& x2);

  int factorizations() const { return factorizations_; }
  double regularization() const { return eps_; }
  /// Whether the last factorization went through the Schur complement.
  bool range_space() const { return schur_; }
  /// Whether it went through it with every pivot above 1e-8 of its row's
  /// diagonal: no row (nearly) a combination of the others.
  bool independent_rows() const { return schur_ && !regularized_; }
  /// Nonzeros of the Cholesky factor of S (0 before the first range-space
  /// factorization): linear in a chain's length.
  long factor_nonzeros() const;
  /// How many analyses of S's pattern (ordering, fill) this system's
  /// factorizations rest on: one (made once per model, whatever the number
  /// of factorizations and runs).
  int symbolic_analyses() const { return symbolic_analyses_; }

 private:
  void fill_lu_matrix(const Data& d);
  void assemble_schur(const Data& d);
  bool reduce_jacobian(const Data& d);
  bool factorize_schur(const Data& d);
  void solve_range_space(const VecX& b1, const VecX& b2, VecX& x1, VecX& x2);

  /// Points S at `pattern` (the model's every-row one, or its open-rows one).
  void use_pattern(const AugmentedPattern* pattern);

  const AugmentedPattern* p_;      // the one S was last assembled in
  const AugmentedPattern* every_;  // the model's (Model::derived)
  const AugmentedPattern* open_;   // S without the switched rows; null: the model has none
  int n_, m_;
  double eps_;
  SpMat K_;
  double mass_scale_;
  bool constant_mass_;  // no spatial body
  SupernodalLU lu_;
  bool lu_analyzed_ = false;
  bool factorized_ = false;
  VecX rhs_, x_, r_, dx_;
  int factorizations_ = 0;
  // the range-space path
  bool schur_ = false, regularized_ = false;
  VecX j_values_;  // R's values at the last factorization
  VecX y4_column_;  // per entry of a body's first z column of R: its row's Phi_p p / |p|^2
  VecX body_p_;     // the bodies' Euler parameters at the last factorization (4 each)
  VecX body_y_;     // per body in a solve: y4 and (p^T b1_p) / |p|^2
  VecX b_r_, x_r_;  // scratch over R's columns
  VecX S_;         // S's lower triangle in p_->S's panels, then its factor L
  VecX s_diagonal_;  // S's diagonal before the factorization (new numbering)
  VecX s_rhs_, work_, lam_, lam_prev_, w_n_;
  VecX run_product_;  // the lower triangle of the largest run's product, by columns
  VecX j_scaled_;  // R M^-1, per entry (a block of M^-1 mixes columns with the same rows)
  int symbolic_analyses_ = 0;
};

}  // namespace lagmb
