// Sparse LU of a matrix with a fixed pattern by KLU (SuiteSparse; Davis &
// Palamadai Natarajan, "Algorithm 907: KLU", ACM TOMS 37(3), 2010).
//
// The Newton matrices of the BDF formulations are small-bandwidth saddle-point
// matrices whose supernodes are one or two columns wide: a left-looking LU
// without supernodes (KLU) factorizes them with less than half the
// instructions of Eigen's supernodal SparseLU (GGL on a 128-link chain, with
// callgrind: 590 -> 256 million), and once a pivot sequence is known,
// refactorizes with it and no search at all.
#pragma once

#include <klu.h>

#include "lagmb/sparsity.hpp"

namespace lagmb {

class KluLU {
 public:
  KluLU() { klu_defaults(&common_); }
  ~KluLU() { release(); }
  KluLU(const KluLU&) = delete;
  KluLU& operator=(const KluLU&) = delete;

  /// The ordering (block triangular form, then AMD in each block), from the
  /// pattern alone: once per pattern.
  void analyze(const SpMat& A) {
    release();
    n_ = int(A.rows());
    symbolic_ = klu_analyze(n_, const_cast<int*>(A.outerIndexPtr()), const_cast<int*>(A.innerIndexPtr()),
                            &common_);
  }
  bool analyzed() const { return symbolic_ != nullptr; }

  /// Numeric factorization of A (the pattern given to analyze); false if A
  /// holds a value that is not finite or is singular. After the first
  /// factorization the previous pivot sequence is reused (klu_refactor); a
  /// fresh factorization with partial pivoting follows when that fails or
  /// its pivots degrade (reciprocal pivot ratio below eps^(2/3)).
  bool factorize(const SpMat& A) {
    if (!symbolic_) return false;
    const double* x = A.valuePtr();
    for (Eigen::Index k = 0; k < A.nonZeros(); ++k)
      if (!std::isfinite(x[k])) return false;
    int* p = const_cast<int*>(A.outerIndexPtr());
    int* i = const_cast<int*>(A.innerIndexPtr());
    double* v = const_cast<double*>(x);
    if (numeric_ && klu_refactor(p, i, v, symbolic_, numeric_, &common_) && klu_rcond(symbolic_, numeric_, &common_) &&
        common_.rcond > 3.7e-11)  // eps^(2/3)
      return true;
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    numeric_ = klu_factor(p, i, v, symbolic_, &common_);
    return numeric_ != nullptr && common_.status == KLU_OK;
  }

  /// Nonzeros of L and U (with their diagonals) of the last factorization; 0 before one.
  long factor_nonzeros() const { return numeric_ ? long(numeric_->lnz) + long(numeric_->unz) : 0; }

  /// b := A^-1 b (length n), after a successful factorize().
  void solve_in_place(double* b) { klu_solve(symbolic_, numeric_, n_, 1, b, &common_); }

 private:
  void release() {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
  }

  klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
  int n_ = 0;
};

}  // namespace lagmb
