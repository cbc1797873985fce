// Sparsity patterns fixed at finalize, and the slots elements write into.
#pragma once

#include <cmath>

#include <Eigen/SparseCore>
#include <utility>
#include <vector>

namespace lagmb {

/// Column-major sparse matrix with 32-bit indices. Patterns are built once;
/// kernels then write into valuePtr() through precomputed slots.
using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Collects the (row, column) entries a matrix may ever hold, then builds the
/// compressed matrix with explicit zeros, so its pattern never changes.
class SparsityPattern {
 public:
  SparsityPattern(int rows, int cols) : rows_(rows), cols_(cols) {}
  void add(int r, int c) {
    if (r >= 0 && c >= 0) entries_.emplace_back(r, c);
  }
  SpMat build() const;

 private:
  int rows_, cols_;
  std::vector<std::pair<int, int>> entries_;
};

/// Index of entry (r, c) in A.valuePtr(), or -1 when r or c is negative.
/// Throws std::logic_error if the entry is not in the pattern.
int slot(const SpMat& A, int r, int c);

/// For every stored entry of `part` (in storage order), the slot of the same
/// entry in `whole`, shifted by (row0, col0), transposed if asked.
std::vector<int> embed_slots(const SpMat& part, const SpMat& whole, int row0, int col0,
                             bool transpose = false);

}  // namespace lagmb
