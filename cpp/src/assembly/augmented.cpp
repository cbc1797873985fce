#include "lagmb/assembly/augmented.hpp"

#include <algorithm>
#include <cmath>

#include "lagmb/errors.hpp"

namespace lagmb {

AugmentedPattern::AugmentedPattern(const Model& model, bool open_rows_out) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  const SpMat& J = model.jacobian_pattern();
  SparsityPattern p(n + m, n + m);
  for (int i = 0; i < n + m; ++i) p.add(i, i);
  const SpMat& Mp = model.mass_pattern();
  for (int c = 0; c < n; ++c)
    for (SpMat::InnerIterator it(Mp, c); it; ++it) p.add(int(it.row()), c);
  for (int c = 0; c < J.outerSize(); ++c)
    for (SpMat::InnerIterator it(J, c); it; ++it) {
      p.add(n + int(it.row()), c);
      p.add(c, n + int(it.row()));
    }
  K = p.build();
  mass_slots = embed_slots(model.mass_pattern(), K, 0, 0);
  for (int i = 0; i < m; ++i) reg_slots.push_back(slot(K, n + i, n + i));
  jac_slots = embed_slots(J, K, n, 0);
  jact_slots = embed_slots(J, K, 0, n, true);
  if (model.positive_mass() && m > 0) setup_schur(model, open_rows_out);
}

void AugmentedPattern::setup_schur(const Model& model, bool open_rows_out) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  const SpMat& J = model.jacobian_pattern();
  const SpMat& Minv = model.mass_pattern();  // M^-1 has M's block pattern
  // the rows S is made of (open_rows_out: not the switched ones), and the
  // entries of Phi_q in them, column by column
  std::vector<char> kept(size_t(m), 1);
  if (open_rows_out)
    for (int r : model.switched_rows()) kept[size_t(r)] = 0;
  std::vector<int> kept_rows;
  for (int r = 0; r < m; ++r)
    if (kept[size_t(r)]) kept_rows.push_back(r);
  const int ms = int(kept_rows.size());
  if (ms == 0) return;  // (nothing left: the every-row pattern serves)
  std::vector<int> col_outer(size_t(n) + 1), row_of;  // the kept entries' CSC arrays (rows: the constraints')
  std::vector<int> entries;
  for (int c = 0; c < n; ++c) {
    col_outer[size_t(c)] = int(entries.size());
    for (int k = J.outerIndexPtr()[c]; k < J.outerIndexPtr()[c + 1]; ++k)
      if (kept[size_t(J.innerIndexPtr()[k])]) entries.push_back(k), row_of.push_back(J.innerIndexPtr()[k]);
  }
  col_outer[size_t(n)] = int(entries.size());
  const int* outer = col_outer.data();
  const int* row = row_of.data();
  // J M^-1 keeps J's pattern where each block of M^-1 joins columns with the
  // same rows (a spatial body's Euler parameters: every element declares all
  // four); otherwise the LU takes every solve
  for (int c = 0; c < n; ++c)
    for (SpMat::InnerIterator it(Minv, c); it; ++it) {
      const int a = int(it.row());
      if (outer[a + 1] - outer[a] != outer[c + 1] - outer[c] ||
          !std::equal(row + outer[a], row + outer[a + 1], row + outer[c]))
        return;
    }
  range_space = true;
  if (open_rows_out) j_entries = entries;
  j_outer = col_outer;
  // S = J M^-1 J^T: entry (r_a, r_b) gathers J(r_a, c) J(r_b, c) / M_c over the columns c
  auto each_pair = [&](auto&& f) {
    for (int c = 0; c < n; ++c)
      for (int a = outer[c]; a < outer[c + 1]; ++a)
        for (int b = outer[c]; b <= a; ++b) f(c, a, b);
  };
  // S's blocks: each element's rows (at most 12 to a block); the columns'
  // rows join theirs in S
  std::vector<int> block_of_row(size_t(m), -1), block_sizes, place_in_block(size_t(m), 0);
  for (int i = 0; i < ms; ++i) {
    const int r = kept_rows[size_t(i)];
    const bool same = i > 0 && model.element_of_row(r) == model.element_of_row(kept_rows[size_t(i) - 1]) &&
                      block_sizes.back() < 12;
    if (!same) block_sizes.push_back(0);
    block_of_row[size_t(r)] = int(block_sizes.size()) - 1;
    place_in_block[size_t(r)] = block_sizes.back()++;
  }
  std::vector<std::pair<int, int>> edges;
  each_pair([&](int, int a, int b) {
    const int ba = block_of_row[size_t(row[a])], bb = block_of_row[size_t(row[b])];
    if (ba != bb) edges.emplace_back(ba, bb);
  });
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  S = BlockCholeskyPattern(block_sizes, edges);
  // rows renumbered block by block in the elimination order
  new_of_old.assign(size_t(m), -1);
  old_of_new.resize(size_t(ms));
  for (int r : kept_rows) {
    new_of_old[size_t(r)] = S.start(S.position_of(block_of_row[size_t(r)])) + place_in_block[size_t(r)];
    old_of_new[size_t(new_of_old[size_t(r)])] = r;
  }
  j_row.resize(entries.size());
  for (size_t k = 0; k < entries.size(); ++k) j_row[k] = new_of_old[size_t(row[k])];
  auto entry = [&](int a, int b) {
    return std::pair{std::max(j_row[a], j_row[b]), std::min(j_row[a], j_row[b])};  // (lower triangle)
  };
  // runs of neighbouring columns with the same rows: M^-1's blocks lie
  // within one (their columns share rows: checked above)
  for (int c = 0; c < n;) {
    const int rows = outer[c + 1] - outer[c];
    int end = c + 1;
    while (end < n && outer[end + 1] - outer[end] == rows &&
           std::equal(row + outer[c], row + outer[c + 1], row + outer[end]))
      ++end;
    if (rows > 0) {
      runs.push_back({outer[c], rows, end - c, int(run_slots.size())});
      for (int b = 0; b < rows; ++b)
        for (int a = b; a < rows; ++a) {
          const auto [r, s] = entry(outer[c] + a, outer[c] + b);
          run_slots.push_back(S.slot(r, s));
        }
      largest_run = std::max(largest_run, rows);
    }
    c = end;
  }
  for (int i = 0; i < ms; ++i) s_diag.push_back(S.slot(i, i));
}

AugmentedSystem::AugmentedSystem(const Model& model)
    : p_(&model.derived<AugmentedPattern>()),
      every_(p_),
      open_(nullptr),
      n_(model.n_coordinates()),
      m_(model.n_constraints()),
      eps_(1e-9 / model.mass_scale()),
      K_(p_->K),
      mass_scale_(model.mass_scale()),
      diagonal_mass_(model.constant_mass()) {
  rhs_.resize(n_ + m_);
  x_.resize(n_ + m_);
  r_.resize(n_ + m_);
  dx_.resize(n_ + m_);
  if (p_->range_space) {
    m_inv_ = model.mass_pattern();
    w_n_.resize(n_);
    s_rhs_.resize(m_);
    work_.resize(m_);
    lam_.resize(m_);
    lam_prev_.resize(m_);
    j_values_.resize(model.jacobian_pattern().nonZeros());
    j_scaled_.resize(j_values_.size());
    run_product_.resize(p_->largest_run * (p_->largest_run + 1) / 2);
    S_.resize(p_->S.values());
    s_diagonal_.resize(m_);
    ++symbolic_analyses_;
    if (!model.switched_rows().empty()) {
      const AugmentedPattern& open = model.derived<OpenRowsPattern>();
      if (open.range_space) open_ = &open;
    }
  }
}

void AugmentedSystem::use_pattern(const AugmentedPattern* pattern) {
  if (pattern == p_) return;
  p_ = pattern;
  const int rows = int(p_->s_diag.size());
  S_.resize(p_->S.values());
  s_diagonal_.resize(rows);
  s_rhs_.resize(rows);
  work_.resize(rows);
  lam_.resize(rows);
  lam_prev_.resize(rows);
}

long AugmentedSystem::factor_nonzeros() const { return schur_ ? p_->S.factor_nonzeros() : 0; }

void AugmentedSystem::fill_lu_matrix(const Data& d) {
  const double* J = d.Phi_q.valuePtr();
  double* K = K_.valuePtr();
  for (size_t k = 0; k < every_->mass_slots.size(); ++k) K[every_->mass_slots[k]] = d.M.valuePtr()[k];
  for (int i = 0; i < m_; ++i) K[every_->reg_slots[i]] = -eps_;
  for (size_t k = 0; k < every_->jac_slots.size(); ++k) K[every_->jac_slots[k]] = K[every_->jact_slots[k]] = J[k];
}

bool AugmentedSystem::factorize(const Data& d) {
  const double* J = d.Phi_q.valuePtr();
  const Eigen::Index nnz = d.Phi_q.nonZeros();
  ++factorizations_;
  factorized_ = schur_ = false;
  for (Eigen::Index k = 0; k < nnz; ++k)
    if (!std::isfinite(J[k])) return false;
  if (!diagonal_mass_ && !d.M.coeffs().allFinite()) return false;  // (a constant M is finite by construction)
  if (every_->range_space) {
    // (S without the stops' and stuck contacts' rows where none is closed)
    use_pattern(open_ && d.closed_rows().empty() ? open_ : every_);
    // solve() uses the factorized Phi_q and M^-1
    if (p_->j_entries.empty())
      std::copy(J, J + nnz, j_values_.data());
    else
      for (size_t k = 0; k < p_->j_entries.size(); ++k) j_values_[Eigen::Index(k)] = J[p_->j_entries[k]];
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

void AugmentedSystem::assemble_schur(const Data& d) {
  const double* J = j_values_.data();
  double* S = S_.data();
  double* Jw = j_scaled_.data();  // J M^-1: column c = sum over a of J's column a times M^-1(a, c)
  const int* mo = m_inv_.outerIndexPtr();
  const int* mi = m_inv_.innerIndexPtr();
  const double* mv = m_inv_.valuePtr();
  for (int c = 0; c < n_; ++c) {
    const int begin = p_->j_outer[c], count = p_->j_outer[c + 1] - begin;
    if (diagonal_mass_) {
      for (int k = 0; k < count; ++k) Jw[begin + k] = J[begin + k] * mv[mo[c]];
      continue;
    }
    for (int k = 0; k < count; ++k) Jw[begin + k] = 0.0;
    for (int e = mo[c]; e < mo[c + 1]; ++e) {
      const int a = p_->j_outer[mi[e]];  // (same rows as column c: setup_schur checked)
      for (int k = 0; k < count; ++k) Jw[begin + k] += J[a + k] * mv[e];
    }
  }
  // S = sum over the runs g of J_g (J M^-1)_g^T: small dense products
  // (the lower triangle, column b = sum over the run's columns of J_g[b.., c] (J M^-1)_g[b, c]:
  // contiguous axpys)
  S_.setZero();
  for (const AugmentedPattern::ColumnRun& g : p_->runs) {
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
    const int* slot = p_->run_slots.data() + g.slot0;
    for (int e = 0; e < k * (k + 1) / 2; ++e) S[slot[e]] += P[e];
  }
  // a dropped (redundant) row has no entries; a unit diagonal keeps S definite, and its
  // right side is zero, so its multiplier stays 0
  for (int r : d.dropped_rows())
    if (const int k = p_->new_of_old[size_t(r)]; k >= 0) S[p_->s_diag[size_t(k)]] = 1.0 / mass_scale_;
}

bool AugmentedSystem::factorize_schur(const Data& d) {
  // first S0 itself (eps = 0): exact, no refinement, unless a pivot keeps no
  // more than 1e-8 of its row's diagonal (the row is nearly a combination of
  // the rows before it: L_kk^2 / S_kk is the part they do not explain)...
  assemble_schur(d);
  for (int k = 0; k < int(p_->s_diag.size()); ++k) s_diagonal_[k] = S_[p_->s_diag[size_t(k)]];
  if (p_->S.factorize(S_.data(), s_diagonal_.data(), 1e-8)) {
    regularized_ = false;
    return true;
  }
  // ...then S0 + eps I and refinement
  assemble_schur(d);
  for (int i : p_->s_diag) S_[i] += eps_;
  regularized_ = true;
  return p_->S.factorize(S_.data(), s_diagonal_.data(), 0.0);
}

void AugmentedSystem::solve_range_space(const VecX& b1, const VecX& b2, VecX& x1, VecX& x2) {
  const double* J = j_values_.data();
  // s = J M^-1 b1 - b2, in S's order
  const int rows = int(p_->old_of_new.size());  // (S's: without the open stops' where none is closed)
  for (int k = 0; k < rows; ++k) s_rhs_[k] = -b2[p_->old_of_new[size_t(k)]];
  const int* mo = m_inv_.outerIndexPtr();
  const double* mv = m_inv_.valuePtr();
  if (diagonal_mass_)
    for (int c = 0; c < n_; ++c) w_n_[c] = mv[mo[c]] * b1[c];
  else
    w_n_.noalias() = m_inv_ * b1;
  for (int c = 0; c < n_; ++c) {
    const double w = w_n_[c];
    for (int k = p_->j_outer[c]; k < p_->j_outer[c + 1]; ++k) s_rhs_[p_->j_row[k]] += J[k] * w;
  }
  lam_ = s_rhs_;
  p_->S.solve(S_.data(), lam_.data());
  // with S0 + eps I, refine against eps = 0: the residual of lam_k is eps (lam_k - lam_{k-1}), lam_{-1} = 0
  const double tol = 1e-15 * (1.0 + std::max(b1.size() ? b1.lpNorm<Eigen::Infinity>() : 0.0,
                                             b2.lpNorm<Eigen::Infinity>()));
  double residual = regularized_ ? eps_ * lam_.lpNorm<Eigen::Infinity>() : 0.0;
  for (int it = 0; it < 3 && residual > tol; ++it) {
    work_ = s_rhs_ + eps_ * lam_;
    lam_prev_.swap(lam_);
    lam_ = work_;
    p_->S.solve(S_.data(), lam_.data());
    residual = eps_ * (lam_ - lam_prev_).lpNorm<Eigen::Infinity>();
  }
  // x2 in the constraints' numbering; x1 = M^-1 (b1 - J^T x2)
  if (rows < m_)
    x2.setZero(m_);
  else
    x2.resize(m_);
  for (int k = 0; k < rows; ++k) x2[p_->old_of_new[size_t(k)]] = lam_[k];
  x1.resize(n_);
  for (int c = 0; c < n_; ++c) {
    double f = b1[c];
    for (int k = p_->j_outer[c]; k < p_->j_outer[c + 1]; ++k) f -= J[k] * lam_[p_->j_row[k]];
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
