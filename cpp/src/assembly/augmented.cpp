#include "lagmb/assembly/augmented.hpp"

#include <algorithm>
#include <cmath>

#include "lagmb/errors.hpp"

namespace lagmb {

AugmentedSystem::AugmentedSystem(const Model& model)
    : n_(model.n_coordinates()),
      m_(model.n_constraints()),
      eps_(1e-9 / model.mass_scale()),
      mass_scale_(model.mass_scale()),
      diagonal_mass_(model.constant_mass()) {
  const SpMat& J = model.jacobian_pattern();
  SparsityPattern p(n_ + m_, n_ + m_);
  for (int i = 0; i < n_ + m_; ++i) p.add(i, i);
  const SpMat& Mp = model.mass_pattern();
  for (int c = 0; c < n_; ++c)
    for (SpMat::InnerIterator it(Mp, c); it; ++it) p.add(int(it.row()), c);
  for (int c = 0; c < J.outerSize(); ++c)
    for (SpMat::InnerIterator it(J, c); it; ++it) {
      p.add(n_ + int(it.row()), c);
      p.add(c, n_ + int(it.row()));
    }
  K_ = p.build();
  mass_slots_ = embed_slots(model.mass_pattern(), K_, 0, 0);
  for (int i = 0; i < m_; ++i) reg_slots_.push_back(slot(K_, n_ + i, n_ + i));
  jac_slots_ = embed_slots(J, K_, n_, 0);
  jact_slots_ = embed_slots(J, K_, 0, n_, true);
  rhs_.resize(n_ + m_);
  x_.resize(n_ + m_);
  r_.resize(n_ + m_);
  dx_.resize(n_ + m_);
  positive_mass_ = model.positive_mass();
  if (positive_mass_ && m_ > 0) setup_schur(model);
}

void AugmentedSystem::setup_schur(const Model& model) {
  const SpMat& J = model.jacobian_pattern();
  m_inv_ = model.mass_pattern();
  w_n_.resize(n_);
  // J M^-1 keeps J's pattern where each block of M^-1 joins columns with the
  // same rows (a spatial body's Euler parameters: every element declares all
  // four); otherwise the LU takes every solve
  for (int c = 0; c < n_; ++c)
    for (SpMat::InnerIterator it(m_inv_, c); it; ++it) {
      const int a = int(it.row());
      const int na = J.outerIndexPtr()[a + 1] - J.outerIndexPtr()[a], nc = J.outerIndexPtr()[c + 1] - J.outerIndexPtr()[c];
      if (na != nc || !std::equal(J.innerIndexPtr() + J.outerIndexPtr()[a], J.innerIndexPtr() + J.outerIndexPtr()[a + 1],
                                  J.innerIndexPtr() + J.outerIndexPtr()[c])) {
        positive_mass_ = false;
        return;
      }
    }
  s_rhs_.resize(m_);
  work_.resize(m_);
  lam_.resize(m_);
  lam_prev_.resize(m_);
  j_values_.resize(J.nonZeros());
  const int* outer = J.outerIndexPtr();
  const int* row = J.innerIndexPtr();
  j_outer_.assign(outer, outer + n_ + 1);
  // S = J M^-1 J^T: entry (r_a, r_b) gathers J(r_a, c) J(r_b, c) / M_c over the columns c
  auto each_pair = [&](auto&& f) {
    for (int c = 0; c < n_; ++c)
      for (int a = outer[c]; a < outer[c + 1]; ++a)
        for (int b = outer[c]; b <= a; ++b) f(c, a, b);
  };
  // AMD on S's pattern in the constraints' own numbering...
  SparsityPattern p(m_, m_);
  for (int i = 0; i < m_; ++i) p.add(i, i);
  each_pair([&](int, int a, int b) { p.add(std::max(row[a], row[b]), std::min(row[a], row[b])); });
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> new_to_old;
  Eigen::AMDOrdering<int>()(p.build(), new_to_old);  // (Eigen's orderings give the inverse permutation)
  old_of_new_.assign(new_to_old.indices().data(), new_to_old.indices().data() + m_);
  new_of_old_.resize(m_);
  for (int k = 0; k < m_; ++k) new_of_old_[old_of_new_[k]] = k;
  // ...then S's upper triangle in that order
  j_row_.resize(J.nonZeros());
  for (Eigen::Index k = 0; k < J.nonZeros(); ++k) j_row_[k] = new_of_old_[row[k]];
  auto entry = [&](int a, int b) {
    return std::pair{std::min(j_row_[a], j_row_[b]), std::max(j_row_[a], j_row_[b])};
  };
  SparsityPattern u(m_, m_);
  for (int i = 0; i < m_; ++i) u.add(i, i);  // eps
  each_pair([&](int, int a, int b) {
    const auto [r, c] = entry(a, b);
    u.add(r, c);
  });
  S_ = u.build();
  // runs of neighbouring columns with the same rows: M^-1's blocks lie
  // within one (their columns share rows: checked above)
  int largest = 0;
  for (int c = 0; c < n_;) {
    const int rows = outer[c + 1] - outer[c];
    int end = c + 1;
    while (end < n_ && outer[end + 1] - outer[end] == rows &&
           std::equal(row + outer[c], row + outer[c + 1], row + outer[end]))
      ++end;
    if (rows > 0) {
      runs_.push_back({outer[c], rows, end - c, int(run_slots_.size())});
      for (int b = 0; b < rows; ++b)
        for (int a = b; a < rows; ++a) {
          const auto [r, s] = entry(outer[c] + a, outer[c] + b);
          run_slots_.push_back(slot(S_, r, s));
        }
      largest = std::max(largest, rows);
    }
    c = end;
  }
  run_product_.resize(largest * (largest + 1) / 2);
  j_scaled_.resize(J.nonZeros());
  for (int i = 0; i < m_; ++i) s_diag_.push_back(slot(S_, i, i));
  chol_.analyzePattern(S_);
  ++symbolic_analyses_;
}

long AugmentedSystem::factor_nonzeros() const {
  return schur_ ? long(chol_.matrixL().nestedExpression().nonZeros()) : 0;
}

void AugmentedSystem::fill_lu_matrix(const Data& d) {
  const double* J = d.Phi_q.valuePtr();
  double* K = K_.valuePtr();
  for (size_t k = 0; k < mass_slots_.size(); ++k) K[mass_slots_[k]] = d.M.valuePtr()[k];
  for (int i = 0; i < m_; ++i) K[reg_slots_[i]] = -eps_;
  for (size_t k = 0; k < jac_slots_.size(); ++k) K[jac_slots_[k]] = K[jact_slots_[k]] = J[k];
}

bool AugmentedSystem::factorize(const Data& d) {
  const double* J = d.Phi_q.valuePtr();
  const Eigen::Index nnz = d.Phi_q.nonZeros();
  ++factorizations_;
  factorized_ = schur_ = false;
  for (Eigen::Index k = 0; k < nnz; ++k)
    if (!std::isfinite(J[k])) return false;
  if (!diagonal_mass_ && !d.M.coeffs().allFinite()) return false;  // (a constant M is finite by construction)
  if (positive_mass_ && m_ > 0) {
    std::copy(J, J + nnz, j_values_.data());  // solve() uses the factorized Phi_q and M^-1
    m_inv_.coeffs() = d.M_inv.coeffs();
    if (factorize_schur(d)) return schur_ = factorized_ = true;
    // not positive definite in rounding (extreme scales): the LU decides
  }
  fill_lu_matrix(d);
  if (!lu_analyzed_) {
    lu_.analyze(K_);
    lu_analyzed_ = true;
  }
  factorized_ = lu_.factorize(K_);
  return factorized_;
}

bool AugmentedSystem::factorize_schur(const Data& d) {
  const double* J = j_values_.data();
  double* S = S_.valuePtr();
  double* Jw = j_scaled_.data();  // J M^-1: column c = sum over a of J's column a times M^-1(a, c)
  const int* mo = m_inv_.outerIndexPtr();
  const int* mi = m_inv_.innerIndexPtr();
  const double* mv = m_inv_.valuePtr();
  for (int c = 0; c < n_; ++c) {
    const int begin = j_outer_[c], count = j_outer_[c + 1] - begin;
    if (diagonal_mass_) {
      for (int k = 0; k < count; ++k) Jw[begin + k] = J[begin + k] * mv[mo[c]];
      continue;
    }
    for (int k = 0; k < count; ++k) Jw[begin + k] = 0.0;
    for (int e = mo[c]; e < mo[c + 1]; ++e) {
      const int a = j_outer_[mi[e]];  // (same rows as column c: setup_schur checked)
      for (int k = 0; k < count; ++k) Jw[begin + k] += J[a + k] * mv[e];
    }
  }
  // S = sum over the runs g of J_g (J M^-1)_g^T: small dense products
  // (the lower triangle, column b = sum over the run's columns of J_g[b.., c] (J M^-1)_g[b, c]:
  // contiguous axpys)
  S_.coeffs().setZero();
  for (const ColumnRun& g : runs_) {
    const int k = g.rows;
    double* P = run_product_.data();
    std::fill(P, P + k * (k + 1) / 2, 0.0);
    for (int c = 0; c < g.width; ++c) {
      const double* Jc = J + g.entry0 + c * k;
      const double* Wc = Jw + g.entry0 + c * k;
      double* column = P;
      for (int b = 0; b < k; ++b) {
        const double w = Wc[b];
        for (int a = b; a < k; ++a) column[a - b] += Jc[a] * w;
        column += k - b;
      }
    }
    const int* slot = run_slots_.data() + g.slot0;
    for (int e = 0; e < k * (k + 1) / 2; ++e) S[slot[e]] += P[e];
  }
  // a dropped (redundant) row has no entries; a unit diagonal keeps S definite, and its
  // right side is zero, so its multiplier stays 0
  for (int r : d.dropped_rows()) S[s_diag_[new_of_old_[r]]] = 1.0 / mass_scale_;
  // first S0 itself (eps = 0): exact, no refinement...
  chol_.factorize(S_);
  if (chol_.info() == Eigen::Success && pivots_above(1e-8)) {
    regularized_ = false;
    return true;
  }
  // ...unless a row is (nearly) a combination of others: then S0 + eps I and refinement
  for (int i : s_diag_) S[i] += eps_;
  chol_.factorize(S_);
  regularized_ = true;
  return chol_.info() == Eigen::Success;
}

/// Whether every pivot of S's Cholesky factor keeps more than `ratio` of its
/// row's diagonal: L_kk^2 / S_kk is the part of row k that the rows before
/// it do not explain (1 for an independent row, 0 for a dependent one).
bool AugmentedSystem::pivots_above(double ratio) const {
  const SpMat& L = chol_.matrixL().nestedExpression();
  const double* S = S_.valuePtr();
  for (int k = 0; k < m_; ++k) {
    const double l = L.valuePtr()[L.outerIndexPtr()[k]];  // the diagonal leads each column
    if (!(l * l > ratio * S[s_diag_[k]])) return false;
  }
  return true;
}

void AugmentedSystem::solve_range_space(const VecX& b1, const VecX& b2, VecX& x1, VecX& x2) {
  const double* J = j_values_.data();
  // s = J M^-1 b1 - b2, in S's order
  for (int k = 0; k < m_; ++k) s_rhs_[k] = -b2[old_of_new_[k]];
  const int* mo = m_inv_.outerIndexPtr();
  const double* mv = m_inv_.valuePtr();
  if (diagonal_mass_)
    for (int c = 0; c < n_; ++c) w_n_[c] = mv[mo[c]] * b1[c];
  else
    w_n_.noalias() = m_inv_ * b1;
  for (int c = 0; c < n_; ++c) {
    const double w = w_n_[c];
    for (int k = j_outer_[c]; k < j_outer_[c + 1]; ++k) s_rhs_[j_row_[k]] += J[k] * w;
  }
  lam_ = chol_.solve(s_rhs_);
  // with S0 + eps I, refine against eps = 0: the residual of lam_k is eps (lam_k - lam_{k-1}), lam_{-1} = 0
  const double tol = 1e-15 * (1.0 + std::max(b1.size() ? b1.lpNorm<Eigen::Infinity>() : 0.0,
                                             b2.lpNorm<Eigen::Infinity>()));
  double residual = regularized_ ? eps_ * lam_.lpNorm<Eigen::Infinity>() : 0.0;
  for (int it = 0; it < 3 && residual > tol; ++it) {
    work_ = s_rhs_ + eps_ * lam_;
    lam_prev_.swap(lam_);
    lam_ = chol_.solve(work_);
    residual = eps_ * (lam_ - lam_prev_).lpNorm<Eigen::Infinity>();
  }
  // x2 in the constraints' numbering; x1 = M^-1 (b1 - J^T x2)
  x2.resize(m_);
  for (int k = 0; k < m_; ++k) x2[old_of_new_[k]] = lam_[k];
  x1.resize(n_);
  for (int c = 0; c < n_; ++c) {
    double f = b1[c];
    for (int k = j_outer_[c]; k < j_outer_[c + 1]; ++k) f -= J[k] * lam_[j_row_[k]];
    w_n_[c] = f;
  }
  if (diagonal_mass_)
    for (int c = 0; c < n_; ++c) x1[c] = mv[mo[c]] * w_n_[c];
  else
    x1.noalias() = m_inv_ * w_n_;
}

void AugmentedSystem::solve(const VecX& b1, const VecX& b2, VecX& x1, VecX& x2) {
  // a solve with a failed factorization is undefined in Eigen: refuse it
  if (!factorized_) throw SimulationError("the augmented matrix [M Phi_q^T; Phi_q 0] is singular or not finite", NAN);
  if (schur_) return solve_range_space(b1, b2, x1, x2);
  rhs_ << b1, b2;
  lu_.solve(rhs_, x_);
  // refine against eps = 0: K0 x = K x + eps [0; x2]
  for (int it = 0; it < 3; ++it) {
    r_.noalias() = rhs_ - K_ * x_;
    r_.tail(m_) -= eps_ * x_.tail(m_);
    if (r_.lpNorm<Eigen::Infinity>() <= 1e-15 * (1.0 + rhs_.lpNorm<Eigen::Infinity>())) break;
    lu_.solve(r_, dx_);
    x_ += dx_;
  }
  x1 = x_.head(n_);
  x2 = x_.tail(m_);
}

}  // namespace lagmb
