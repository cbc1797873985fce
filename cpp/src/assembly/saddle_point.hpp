// The saddle-point block that every Newton matrix of lagmb holds (the
// formulations' -- multiplier DAEs, projection, ali3p -- and the static
// equilibrium's): its pattern at given offsets, the slots of its entries,
// and the values of its tangent block T0.
#pragma once

#include <vector>

#include "lagmb/model/data.hpp"
#include "lagmb/sparsity.hpp"

namespace lagmb {

/// Declares the entries of A in p, shifted by (row0, col0), transposed if asked.
void add_block(SparsityPattern& p, const SpMat& A, int row0, int col0, bool transpose = false);

/// J[slots[k]] += scale * values[k], values stored in the slots' order.
void add_scaled(double* J, const std::vector<int>& slots, const SpMat& values, double scale);

/// Where the blocks sit: the first row or column of each.
struct SaddlePointLayout {
  int momentum_row;    // rows of T0 and Phi_q^T (the momentum equations)
  int q_col, v_col;    // columns of (Phi_q^T lam)_q and Q_q; columns of Q_v
  int lam_col;         // columns of Phi_q^T
  int constraint_row;  // rows of Phi_q (in the q columns)
};

/// The blocks
///   [ T0      Phi_q^T ]      T0 = s ((Phi_q^T lam)_q + (M(q) a)_q - Q_q) - c Q_v
///   [ Phi_q   .       ]
/// of a Newton matrix, in the patterns of the Model (hessian_pattern,
/// force_q_pattern, force_v_pattern, jacobian_pattern, mass_pattern),
/// placed by a layout, and room for M itself in the momentum rows and the
/// v columns (`mass`; where the formulation puts a multiple of it). (M a)_q
/// is there only where M depends on q (spatial bodies). Each formulation adds
/// its own entries (diagonals, further rows) around them and chooses s and c.
class SaddlePoint {
 public:
  SaddlePoint(const Model& model, SaddlePointLayout layout) : model_(model), at_(layout) {}
  /// Declares the blocks' entries in p.
  void declare(SparsityPattern& p) const;
  /// Finds the slots of the blocks in J, built from a pattern declare() filled.
  void bind(const SpMat& J);
  /// The square n + m system [T0 Phi_q^T; Phi_q D] with layout (0, 0, 0, n,
  /// n): builds it with its whole diagonal (D gives room to a regularization
  /// or to pivoting), binds the slots and returns the diagonal's slots.
  SpMat build_square(std::vector<int>& diagonal);
  /// J[T0] += s ((Phi_q^T lam)_q + (M(q) a)_q - Q_q) - c Q_v at (q, v, t,
  /// lam, a), the joint friction's Q_f,q and Q_f,v (at lam) counted in Q_q
  /// and Q_v. Leaves H, M_qa, Q_q, Q_v and the friction derivatives (Q_f,lam
  /// too) in d.
  void add_tangent(Data& d, double* J, const double* q, const double* v, double t, const double* lam,
                   const double* a, double s, double c) const;
  /// J[mass] += scale M (M as assembled in d).
  void add_mass(const Data& d, double* J, double scale) const { add_scaled(J, mass, d.M, scale); }

  /// Slots in J's values of each block's entries, in the storage order of
  /// the Model's pattern (and of the matching values in Data).
  std::vector<int> hessian, force_q, force_v, jacobian, jacobian_t, mass, mass_q;

 private:
  const Model& model_;
  SaddlePointLayout at_;
};

/// y = (Q_q - (Phi_q^T lam)_q - (M a)_q) x from the derivatives add_tangent
/// left in d (Q_f,q included).
void stiffness_times(const Model& model, const Data& d, const double* x, double* y);

}  // namespace lagmb
