// The block Cholesky factorization (lagmb/solvers/block_cholesky.hpp): on
// symmetric positive definite matrices with the block graphs of a chain, a
// tree and a closed loop, L L^T equals the matrix and solve() agrees with a
// dense Cholesky; a chain or tree fills nothing (the factor has the matrix's
// own lower pattern: linear in its length); a row that is a combination of
// others is refused at the pivot ratio and factorized without it.
#include <Eigen/Dense>
#include <random>
#include <utility>
#include <vector>

#include "check.hpp"
#include "lagmb/solvers/block_cholesky.hpp"

using namespace lagmb_test;
using lagmb::BlockCholeskyPattern;

namespace {

using Edges = std::vector<std::pair<int, int>>;

struct Problem {
  std::vector<int> sizes;
  Edges edges;
  std::vector<int> first;  // first row of each block (the caller's numbering)
  Eigen::MatrixXd S;       // dense, the caller's numbering
};

/// S = B B^T + I with B's nonzeros only where the block graph has them: a
/// random symmetric positive definite matrix with exactly that block pattern.
Problem make(std::vector<int> sizes, Edges edges, unsigned seed) {
  Problem p{std::move(sizes), std::move(edges), {}, {}};
  int rows = 0;
  for (int s : p.sizes) {
    p.first.push_back(rows);
    rows += s;
  }
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  p.S = Eigen::MatrixXd::Identity(rows, rows);
  auto block = [&](int b) { return std::pair{p.first[b], p.sizes[b]}; };
  for (size_t b = 0; b < p.sizes.size(); ++b) {
    auto [r, s] = block(int(b));
    Eigen::MatrixXd D = Eigen::MatrixXd::NullaryExpr(s, s, [&] { return u(gen); });
    p.S.block(r, r, s, s) += D * D.transpose() + double(s) * Eigen::MatrixXd::Identity(s, s);
  }
  for (auto [a, b] : p.edges) {
    auto [ra, sa] = block(a);
    auto [rb, sb] = block(b);
    const Eigen::MatrixXd C = 0.3 * Eigen::MatrixXd::NullaryExpr(sa, sb, [&] { return u(gen); });
    p.S.block(ra, rb, sa, sb) += C;
    p.S.block(rb, ra, sb, sa) += C.transpose();
  }
  // diagonally dominant by blocks of size <= 6 and coupling 0.3: positive definite
  for (int i = 0; i < rows; ++i) p.S(i, i) += 2.0 * p.S.row(i).cwiseAbs().sum();
  return p;
}

struct Factored {
  BlockCholeskyPattern pattern;
  std::vector<int> new_of_old;
  std::vector<double> values;
  bool ok;
};

Factored factor(const Problem& p, double ratio = 1e-8) {
  Factored f{BlockCholeskyPattern(p.sizes, p.edges), {}, {}, false};
  const int rows = int(p.S.rows());
  f.new_of_old.resize(rows);
  for (size_t b = 0; b < p.sizes.size(); ++b)
    for (int i = 0; i < p.sizes[b]; ++i) f.new_of_old[p.first[b] + i] = f.pattern.start(f.pattern.position_of(int(b))) + i;
  f.values.assign(f.pattern.values(), 0.0);
  std::vector<double> diagonal(rows);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c <= r; ++c) {
      const int nr = f.new_of_old[r], nc = f.new_of_old[c];
      const int slot = nr >= nc ? f.pattern.slot(nr, nc) : f.pattern.slot(nc, nr);
      if (p.S(r, c) != 0.0) CHECK(slot >= 0);  // every nonzero has its place
      if (slot >= 0) f.values[slot] = p.S(r, c);
    }
  for (int r = 0; r < rows; ++r) diagonal[f.new_of_old[r]] = p.S(r, r);
  f.ok = f.pattern.factorize(f.values.data(), diagonal.data(), ratio);
  return f;
}

/// L L^T = S (permuted) and solve() = S^-1 y, to 1e-12 relative.
void check_factor(const Problem& p, const Factored& f) {
  CHECK(f.ok);
  const int rows = int(p.S.rows());
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(rows, rows);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c <= r; ++c) {
      const int slot = f.pattern.slot(r, c);
      if (slot >= 0) L(r, c) = f.values[slot];
    }
  Eigen::MatrixXd S_new(rows, rows);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < rows; ++c) S_new(f.new_of_old[r], f.new_of_old[c]) = p.S(r, c);
  CHECK_NEAR((L * L.transpose() - S_new).lpNorm<Eigen::Infinity>(), 0.0, 1e-12 * S_new.lpNorm<Eigen::Infinity>());
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(rows, -1.0, 2.0);
  Eigen::VectorXd x = y;
  f.pattern.solve(f.values.data(), x.data());
  const Eigen::VectorXd dense = S_new.llt().solve(y);
  CHECK_NEAR((x - dense).lpNorm<Eigen::Infinity>(), 0.0, 1e-12 * (1.0 + dense.lpNorm<Eigen::Infinity>()));
}

long lower_nonzeros(const Eigen::MatrixXd& S) {
  long count = 0;
  for (int r = 0; r < S.rows(); ++r)
    for (int c = 0; c <= r; ++c) count += S(r, c) != 0.0;
  return count;
}

/// The Schur complement's blocks of a spatial chain: joint k (5 rows) is
/// coupled to joint k + 1 and to the normalization rows (1) of its bodies.
Problem chain(int links, unsigned seed) {
  std::vector<int> sizes;
  Edges edges;
  for (int k = 0; k < links; ++k) {
    sizes.push_back(5);  // joint k: block 2k
    sizes.push_back(1);  // body k's normalization: block 2k + 1
    edges.emplace_back(2 * k, 2 * k + 1);
    if (k + 1 < links) {
      edges.emplace_back(2 * k, 2 * k + 2);
      edges.emplace_back(2 * k + 1, 2 * k + 2);
    }
  }
  return make(sizes, edges, seed);
}

}  // namespace

TEST_CASE(a_chain_factorizes_without_fill) {
  for (int links : {1, 2, 7, 40}) {
    const Problem p = chain(links, unsigned(links));
    const Factored f = factor(p);
    check_factor(p, f);
    CHECK(f.pattern.factor_nonzeros() == lower_nonzeros(p.S));
  }
}

TEST_CASE(a_tree_factorizes_without_fill) {
  // a base joined to four legs of three links each: blocks of 6, 5 and 3 rows
  std::vector<int> sizes{6};
  Edges edges;
  for (int leg = 0; leg < 4; ++leg) {
    int parent = 0;
    for (int k = 0; k < 3; ++k) {
      sizes.push_back(k == 0 ? 5 : 3);
      const int b = int(sizes.size()) - 1;
      edges.emplace_back(parent, b);
      parent = b;
    }
  }
  // the legs' first joints share the base: they are coupled to each other too
  for (int a = 1; a < 13; a += 3)
    for (int b = a + 3; b < 13; b += 3) edges.emplace_back(a, b);
  const Problem p = make(sizes, edges, 3);
  const Factored f = factor(p);
  check_factor(p, f);
  CHECK(f.pattern.factor_nonzeros() == lower_nonzeros(p.S));
}

TEST_CASE(a_closed_loop_fills_and_factorizes) {
  // a ring of 12 blocks: eliminating it fills one row of blocks around
  std::vector<int> sizes(12, 2);
  Edges edges;
  for (int k = 0; k < 12; ++k) edges.emplace_back(k, (k + 1) % 12);
  const Problem p = make(sizes, edges, 5);
  const Factored f = factor(p);
  check_factor(p, f);
  CHECK(f.pattern.factor_nonzeros() > lower_nonzeros(p.S));
}

TEST_CASE(a_dependent_row_is_refused_at_the_pivot_ratio) {
  Problem p = chain(3, 11);
  // row 3 of joint 1 := row 0 of joint 1 (a redundant constraint): S singular
  const int a = p.first[2], b = p.first[2] + 3;
  p.S.row(b) = p.S.row(a);
  p.S.col(b) = p.S.col(a);
  CHECK(!factor(p, 1e-8).ok);
  // with the row's diagonal raised (what the augmented system's eps does) it factorizes
  p.S(b, b) += 1e-3;
  CHECK(factor(p, 0.0).ok);
}

LAGMB_TEST_MAIN();
