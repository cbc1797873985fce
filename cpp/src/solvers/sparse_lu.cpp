#include "lagmb/solvers/sparse_lu.hpp"

#include <Eigen/SparseLU>
#include <cmath>

namespace lagmb {

struct SupernodalLU::Factors {
  Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>> lu;
};

SupernodalLU::SupernodalLU() : f_(std::make_unique<Factors>()) {}
SupernodalLU::~SupernodalLU() = default;
SupernodalLU::SupernodalLU(SupernodalLU&&) noexcept = default;
SupernodalLU& SupernodalLU::operator=(SupernodalLU&&) noexcept = default;

void SupernodalLU::analyze(const SpMat& A) { f_->lu.analyzePattern(A); }

bool SupernodalLU::factorize(const SpMat& A) {
  const double* x = A.valuePtr();
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k)
    if (!std::isfinite(x[k])) return false;
  f_->lu.factorize(A);
  return f_->lu.info() == Eigen::Success;
}

bool SupernodalLU::compute(const SpMat& A) {
  analyze(A);
  return factorize(A);
}

void SupernodalLU::solve(const VecX& b, VecX& x) const { x = f_->lu.solve(b); }

void SupernodalLU::solve_transposed(const VecX& b, VecX& x) const { x = f_->lu.transpose().solve(b); }

}  // namespace lagmb
