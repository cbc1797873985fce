// The rank-revealing sparse QR (lagmb/solvers/sparse_qr.hpp) against Eigen's
// dense QR with column pivoting: the same rank on random sparse matrices with
// planted dependent columns, each column it calls dependent a combination of
// the others it keeps (and those independent); least-squares solutions equal
// to the dense ones, dependent columns at 0 with the residual orthogonal to
// the rest; R's fill per column of a chain's Jacobian the same at 100 and
// 2,000 links (linear cost); empty and zero columns.
#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <vector>

#include "check.hpp"
#include "lagmb/solvers/sparse_qr.hpp"

using namespace lagmb_test;
using lagmb::SparseQR;
using lagmb::SpMat;

namespace {

/// rows x cols with about `per_column` random entries per column; the
/// columns listed in `copies` are then replaced by combinations of two
/// earlier ones (so the rank drops by their number).
Eigen::MatrixXd random_sparse(int rows, int cols, int per_column, const std::vector<int>& copies, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> row(0, rows - 1);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, cols);
  for (int c = 0; c < cols; ++c)
    for (int k = 0; k < per_column; ++k) A(row(gen), c) = u(gen);
  for (int c : copies) A.col(c) = 0.7 * A.col(c - 1) - 1.3 * A.col(c / 2);
  return A;
}

SpMat sparse(const Eigen::MatrixXd& A) { return A.sparseView(); }

/// The columns of A not in `dependent`.
Eigen::MatrixXd keep(const Eigen::MatrixXd& A, const std::vector<int>& dependent, bool kept) {
  std::vector<int> cols;
  for (int c = 0; c < A.cols(); ++c)
    if ((std::find(dependent.begin(), dependent.end(), c) == dependent.end()) == kept) cols.push_back(c);
  Eigen::MatrixXd out(A.rows(), int(cols.size()));
  for (size_t k = 0; k < cols.size(); ++k) out.col(int(k)) = A.col(cols[k]);
  return out;
}

/// A planar chain's constraint Jacobian transposed (coordinates x columns =
/// rows of Phi_q): link i (x, y, theta) pinned to link i - 1 (two rows).
SpMat chain_jacobian_t(int links) {
  std::vector<Eigen::Triplet<double>> e;
  for (int i = 0; i < links; ++i)
    for (int k = 0; k < 2; ++k) {
      const int row = 2 * i + k;
      e.emplace_back(3 * i + k, row, 1.0);
      e.emplace_back(3 * i + 2, row, k == 0 ? 0.5 : -0.5);
      if (i > 0) {
        e.emplace_back(3 * (i - 1) + k, row, -1.0);
        e.emplace_back(3 * (i - 1) + 2, row, k == 0 ? 0.5 : 0.5);
      }
    }
  SpMat JT(3 * links, 2 * links);
  JT.setFromTriplets(e.begin(), e.end());
  return JT;
}

}  // namespace

TEST_CASE(rank_and_dependent_columns_match_the_dense_qr) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const std::vector<int> copies = {7, 19, 20, 33};
    const Eigen::MatrixXd A = random_sparse(60, 40, 4, copies, seed);
    const SparseQR qr(sparse(A));
    CHECK(qr.ok());
    const int dense_rank = int(A.colPivHouseholderQr().rank());
    CHECK(qr.rank() == dense_rank);
    const std::vector<int> dependent = qr.dependent_columns();
    CHECK(int(dependent.size()) == A.cols() - qr.rank());
    // what it keeps is independent, and what it drops lies in their span
    const Eigen::MatrixXd kept = keep(A, dependent, true), dropped = keep(A, dependent, false);
    CHECK(int(kept.colPivHouseholderQr().rank()) == kept.cols());
    if (dropped.cols()) {
      const Eigen::MatrixXd fit = kept.colPivHouseholderQr().solve(dropped);
      CHECK((kept * fit - dropped).norm() <= 1e-10 * (1.0 + dropped.norm()));
    }
  }
}

TEST_CASE(least_squares_equals_the_dense_solution) {
  std::mt19937 gen(5);
  std::normal_distribution<double> g;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const Eigen::MatrixXd A = random_sparse(50, 30, 5, {}, seed) + Eigen::MatrixXd::Identity(50, 30);
    const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(50, [&] { return g(gen); });
    const SparseQR qr(sparse(A));
    CHECK(qr.rank() == 30);
    const Eigen::VectorXd x = qr.solve(b), reference = A.colPivHouseholderQr().solve(b);
    CHECK((x - reference).norm() <= 1e-12 * reference.norm());
  }
}

TEST_CASE(dependent_columns_get_zero_and_the_residual_is_orthogonal_to_the_rest) {
  std::mt19937 gen(9);
  std::normal_distribution<double> g;
  const Eigen::MatrixXd A = random_sparse(40, 25, 4, {10, 21}, 3);
  const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(40, [&] { return g(gen); });
  const SparseQR qr(sparse(A));
  const Eigen::VectorXd x = qr.solve(b);
  const std::vector<int> dependent = qr.dependent_columns();
  CHECK(!dependent.empty());
  for (int c : dependent) CHECK(x[c] == 0.0);
  const Eigen::VectorXd residual = b - A * x;
  const Eigen::MatrixXd kept = keep(A, dependent, true);
  CHECK((kept.transpose() * residual).norm() <= 1e-11 * b.norm() * A.norm());
}

TEST_CASE(a_chain_fills_R_linearly) {
  const SpMat small = chain_jacobian_t(100), large = chain_jacobian_t(2000);
  const SparseQR a(small), b(large);
  CHECK(a.rank() == 200);
  CHECK(b.rank() == 4000);
  const double per_column_small = double(a.nonzeros()) / 200, per_column_large = double(b.nonzeros()) / 4000;
  CHECK(per_column_large <= 1.02 * per_column_small);
  CHECK(per_column_large <= 4.0);
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(large.rows());
  const Eigen::VectorXd x = b.solve(rhs);
  const Eigen::VectorXd normal = Eigen::MatrixXd(large).transpose() * (rhs - large * x);
  CHECK(normal.norm() <= 1e-10 * rhs.norm());
}

TEST_CASE(empty_and_zero_columns) {
  const SparseQR none(SpMat(5, 0));
  CHECK(none.rank() == 0);
  CHECK(none.dependent_columns().empty());
  CHECK(none.solve(Eigen::VectorXd::Ones(5)).size() == 0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 3);
  A(0, 0) = 2.0;
  A(3, 2) = -1.0;
  const SparseQR qr(sparse(A));
  CHECK(qr.rank() == 2);
  CHECK(qr.dependent_columns() == std::vector<int>{1});
  const Eigen::VectorXd x = qr.solve(Eigen::Vector4d(4.0, 1.0, 1.0, 3.0));
  CHECK_NEAR(x[0], 2.0, 1e-15);
  CHECK(x[1] == 0.0);
  CHECK_NEAR(x[2], -3.0, 1e-15);
}

LAGMB_TEST_MAIN()
