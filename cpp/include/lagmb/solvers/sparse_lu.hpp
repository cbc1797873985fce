// Sparse LU with partial pivoting for general (unsymmetric, possibly
// indefinite) sparse matrices: Eigen's supernodal SparseLU with a COLAMD
// column ordering, compiled in one source file (solvers/sparse_lu.cpp)
// instead of in each of the four that factorize with it.
#pragma once

#include <memory>

#include "lagmb/sparsity.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

class SupernodalLU {
 public:
  SupernodalLU();
  ~SupernodalLU();
  SupernodalLU(SupernodalLU&&) noexcept;
  SupernodalLU& operator=(SupernodalLU&&) noexcept;

  /// The column ordering and elimination tree, from A's pattern alone.
  void analyze(const SpMat& A);
  /// Numeric factorization of A (the pattern given to analyze); false if A
  /// holds a value that is not finite (Eigen's SparseLU is not made for
  /// them: it may report success and corrupt memory in a later solve) or
  /// the factorization fails (a structurally or numerically zero pivot).
  bool factorize(const SpMat& A);
  /// analyze(A), then factorize(A).
  bool compute(const SpMat& A);
  /// x = A^-1 b, after a successful factorize.
  void solve(const VecX& b, VecX& x) const;
  /// x = A^-T b, after a successful factorize.
  void solve_transposed(const VecX& b, VecX& x) const;

 private:
  struct Factors;
  std::unique_ptr<Factors> f_;
};

}  // namespace lagmb
