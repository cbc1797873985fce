// Rank-revealing sparse QR: which columns of a matrix are dependent, and
// least-squares solves. Givens rotations row by row in a fill-reducing column
// order, so a chain's Jacobian costs time linear in its length (Eigen's
// SparseQR grew as N^2.6 there: 6.4 s for 2,000 links).
#pragma once

#include <memory>
#include <vector>

#include "lagmb/sparsity.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

class SparseQR {
 public:
  /// Factorizes A P = Q R with column pivoting: a column whose remaining
  /// norm falls to `tol` (absolute) or below counts as dependent on those
  /// before it in the column order (Heath's rule). tol < 0: 20 (rows + cols)
  /// eps times the largest column norm (SuiteSparseQR's default).
  SparseQR(const SpMat& A, double tol = -1.0);
  ~SparseQR();
  SparseQR(const SparseQR&) = delete;
  SparseQR& operator=(const SparseQR&) = delete;

  bool ok() const;
  int rank() const;
  /// The dependent columns, ascending.
  std::vector<int> dependent_columns() const;
  /// Entries stored in R (its fill: linear in a chain's length).
  long nonzeros() const;
  /// A least-squares solution x of A x = b (dependent columns get 0).
  VecX solve(const VecX& b) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lagmb
