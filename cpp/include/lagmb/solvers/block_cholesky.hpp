// Cholesky factorization of a symmetric positive definite matrix whose rows
// come in small blocks (a joint's rows): dense blocks, eliminated in the
// order of the blocks' graph. For the Schur complement S = Phi_q M^-1 Phi_q^T
// of a chain or tree the block graph is the joints' adjacency, and leaves
// first it fills nothing: O(N) with 5 x 5 dense blocks (Baraff, "Linear-time
// dynamics using Lagrange multipliers", SIGGRAPH 1996, orders the same
// graph); a closed loop adds the fill of the few blocks that close it.
#pragma once

#include <utility>
#include <vector>

namespace lagmb {

/// The symbolic part, made once per pattern: the blocks' elimination order
/// (approximate minimum degree on the block graph), the fill, and where each
/// block of the lower factor lives in one values array.
///
/// Layout: block column k (elimination position k, rows [start[k],
/// start[k] + size[k]) of the new numbering) is one dense panel, column-major
/// with height[k] rows: its diagonal block on top, then the blocks below
/// it in elimination order. A symmetric matrix is given by its lower
/// triangle in these panels (the diagonal block's upper part is not read);
/// factorize() overwrites it with L, S = L L^T.
class BlockCholeskyPattern {
 public:
  BlockCholeskyPattern() = default;
  /// sizes[b]: rows of block b (the caller's numbering); edges: pairs of
  /// blocks with a nonzero between them (either order, repeats allowed).
  BlockCholeskyPattern(const std::vector<int>& sizes, const std::vector<std::pair<int, int>>& edges);

  int blocks() const { return int(start_.size()); }
  int rows() const { return rows_; }
  /// Position of the caller's block b in the elimination order.
  int position_of(int b) const { return position_of_[b]; }
  /// First row of the block at position k in the new numbering.
  int start(int k) const { return start_[k]; }
  int size(int k) const { return size_[k]; }
  /// Index into the values array of entry (r, c), r >= c in the new
  /// numbering and within the factor's pattern; -1 if outside it.
  int slot(int r, int c) const;
  /// Length of the values array.
  int values() const { return values_; }
  /// Nonzeros of L's lower triangle (diagonal blocks counted by their lower half).
  long factor_nonzeros() const;

  /// Factorizes in place: values hold S's lower triangle on entry, L on
  /// return. false if a pivot is not positive or, with pivot_ratio > 0, if a
  /// pivot keeps no more than pivot_ratio of its row's diagonal (diagonal[r],
  /// S's diagonal in the new numbering): the row is nearly a combination of
  /// the rows before it.
  bool factorize(double* values, const double* diagonal, double pivot_ratio) const;
  /// Solves L L^T x = y in place (new numbering).
  void solve(const double* values, double* y) const;

 private:
  int rows_ = 0, values_ = 0;
  std::vector<int> position_of_, start_, size_, block_at_row_;
  std::vector<int> panel_, height_;  // values offset and height of each block column's panel
  // the blocks below each diagonal block: entries below_begin_[k] ..
  // below_begin_[k + 1], in elimination order, each with its row offset in
  // panel k; update_begin_[e]: for entry e = (k, j), the row offsets in
  // panel j of the entries e, e + 1, .. of panel k (fill keeps them there)
  std::vector<int> below_begin_, below_block_, below_row_, update_begin_, update_row_;
};

}  // namespace lagmb
