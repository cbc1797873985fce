// SparseQR (sparse_qr.hpp) on SuiteSparseQR through Eigen's SPQR module.
#include "solvers/sparse_qr.hpp"

#include <algorithm>

#include <Eigen/SPQRSupport>

namespace lagmb {

using LongSpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;

struct SparseQR::Impl {
  Eigen::SPQR<LongSpMat> qr;
  int cols = 0;
};

SparseQR::SparseQR(const SpMat& A, double tol) : impl_(std::make_unique<Impl>()) {
  impl_->cols = int(A.cols());
  if (tol >= 0.0) impl_->qr.setPivotThreshold(tol);
  LongSpMat a = A.cast<double>();
  a.makeCompressed();
  impl_->qr.compute(a);
}

SparseQR::~SparseQR() = default;

bool SparseQR::ok() const { return impl_->qr.info() == Eigen::Success; }

int SparseQR::rank() const { return int(impl_->qr.rank()); }

std::vector<int> SparseQR::dependent_columns() const {
  // SuiteSparseQR moves the columns it finds dependent behind the others.
  // (colsPermutation() returns a Map by value: keep it, not a reference into it.)
  const auto P = impl_->qr.colsPermutation();
  std::vector<int> out;
  for (int k = rank(); k < impl_->cols; ++k) out.push_back(int(P.indices()[k]));
  std::sort(out.begin(), out.end());
  return out;
}

VecX SparseQR::solve(const VecX& b) const { return impl_->qr.solve(b); }

}  // namespace lagmb
