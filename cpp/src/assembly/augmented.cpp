#include "lagmb/assembly/augmented.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "lagmb/elements/spatial_body.hpp"
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
  {
    const SpMat& J = model.jacobian_pattern();
    const SpMat& Minv = model.mass_pattern();  // M^-1 has M's block pattern
    // J M^-1 keeps J's pattern where each block of M^-1 joins columns with the
    // same rows (a spatial body's Euler parameters: every element declares all
    // four); otherwise the LU takes every solve
    const int* outer = J.outerIndexPtr();
    const int* row = J.innerIndexPtr();
    for (int c = 0; c < n; ++c)
      for (SpMat::InnerIterator it(Minv, c); it; ++it) {
        const int a = int(it.row());
        if (outer[a + 1] - outer[a] != outer[c + 1] - outer[c] ||
            !std::equal(row + outer[a], row + outer[a + 1], row + outer[c]))
          return;
      }
  }
  std::vector<int> r_rows;  // each R entry's constraint row
  if (!setup_reduced(model, r_rows, open_rows_out)) return;
  range_space = true;
  n_r = int(q_column.size());
  const int* outer = j_outer.data();
  const int* row = r_rows.data();
  // S = R M^-1 R^T: entry (r_a, r_b) gathers R(r_a, c) R(r_b, c) M^-1_c over the columns c
  auto each_pair = [&](auto&& f) {
    for (int c = 0; c < n_r; ++c)
      for (int a = outer[c]; a < outer[c + 1]; ++a)
        for (int b = outer[c]; b <= a; ++b) f(c, a, b);
  };
  // S's blocks: each element's rows (at most 12 to a block; the
  // normalization rows are not in S); the columns' rows join theirs in S
  new_of_old.assign(m, -1);
  for (const BodyRates& b : bodies) new_of_old[b.norm_row] = -2;  // (marked: left out)
  for (int r = 0; r < m; ++r)
    if (!switched_out.empty() && switched_out[size_t(r)]) new_of_old[r] = -2;
  std::vector<int> block_of_row(m, -1), block_sizes;
  int last = -1;  // the last row in S
  for (int r = 0; r < m; ++r) {
    if (new_of_old[r] == -2) continue;
    const bool same = last >= 0 && model.element_of_row(r) == model.element_of_row(last) && block_sizes.back() < 12;
    if (!same) block_sizes.push_back(0);
    block_of_row[r] = int(block_sizes.size()) - 1;
    ++block_sizes.back();
    last = r;
  }
  std::vector<std::pair<int, int>> edges;
  each_pair([&](int, int a, int b) {
    if (block_of_row[row[a]] != block_of_row[row[b]]) edges.emplace_back(block_of_row[row[a]], block_of_row[row[b]]);
  });
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  S = BlockCholeskyPattern(block_sizes, edges);
  // rows renumbered block by block in the elimination order
  old_of_new.resize(S.rows());
  std::vector<int> filled(block_sizes.size(), 0);  // rows of each block numbered so far
  for (int r = 0; r < m; ++r) {
    if (block_of_row[r] < 0) {
      new_of_old[r] = -1;
      continue;
    }
    const int b = block_of_row[r], k = S.position_of(b);
    new_of_old[r] = S.start(k) + filled[b]++;
    old_of_new[new_of_old[r]] = r;
  }
  j_row.resize(r_rows.size());
  for (size_t k = 0; k < r_rows.size(); ++k) j_row[k] = new_of_old[row[k]];
  auto entry = [&](int a, int b) {
    return std::pair{std::max(j_row[a], j_row[b]), std::min(j_row[a], j_row[b])};  // (lower triangle)
  };
  // runs of neighbouring columns with the same rows: M^-1's blocks lie
  // within one (their columns share rows: checked above)
  for (int c = 0; c < n_r;) {
    const int rows = outer[c + 1] - outer[c];
    int end = c + 1;
    while (end < n_r && outer[end + 1] - outer[end] == rows &&
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
  for (int i = 0; i < S.rows(); ++i) s_diag.push_back(S.slot(i, i));
}

bool AugmentedPattern::setup_reduced(const Model& model, std::vector<int>& r_rows, bool open_rows_out) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  const SpMat& J = model.jacobian_pattern();
  const int* outer = J.outerIndexPtr();
  const int* row = J.innerIndexPtr();
  // each spatial body's normalization row: the one row of its kind on its Euler parameters
  std::vector<const Model::SpatialMass*> body_at(n, nullptr);
  for (const Model::SpatialMass& s : model.spatial_masses()) body_at[s.p] = &s;
  std::vector<bool> normalization(m, false);
  std::vector<int> norm_row_of(n, -1);
  for (const Model::SpatialMass& s : model.spatial_masses()) {
    for (int k = outer[s.p]; k < outer[s.p + 1]; ++k) {
      const int r = row[k];
      if (std::string(model.constraint_groups()[model.group_of_row(r)]->kind()) != EulerParameterNorm::kind) continue;
      if (norm_row_of[s.p] >= 0) return false;
      norm_row_of[s.p] = r;
      normalization[r] = true;
    }
    if (norm_row_of[s.p] < 0 || s.jbar <= 0.0 || !s.J_inverse.allFinite()) return false;
  }
  // (and, open_rows_out, the switched rows: S without them where all are open)
  if (open_rows_out) {
    switched_out.assign(size_t(m), 0);
    for (int r : model.switched_rows()) switched_out[size_t(r)] = 1;
  }
  auto in_s = [&](int r) { return !normalization[r] && (switched_out.empty() || !switched_out[size_t(r)]); };
  // R's columns in q's order: a column of q as it is (without the normalization
  // rows, which are 0 outside their parameters), a body's four parameters as
  // its three rates
  std::vector<Eigen::Triplet<double>> m_inv_entries;
  j_outer.assign(1, 0);
  for (int c = 0; c < n;) {
    const Model::SpatialMass* s = body_at[c];
    if (!s) {
      if (!(model.mass_diagonal()[c] > 0.0)) return false;
      for (int k = outer[c]; k < outer[c + 1]; ++k)
        if (in_s(row[k])) {
          r_rows.push_back(row[k]);
          j_source.push_back(k);
        }
      const int column = int(q_column.size());
      m_inv_entries.emplace_back(column, column, 1.0 / model.mass_diagonal()[c]);
      q_column.push_back(c);
      j_outer.push_back(int(r_rows.size()));
      ++c;
      continue;
    }
    BodyRates b;
    b.p = c;
    b.z = int(q_column.size());
    b.norm_row = norm_row_of[c];
    b.rows = outer[c + 1] - outer[c];
    b.norm = int(std::find(row + outer[c], row + outer[c + 1], b.norm_row) - (row + outer[c]));
    b.mass4 = 4.0 * s->jbar;
    for (int a = 0; a < 4; ++a) b.q_entry0[a] = outer[c + a];
    for (int k = outer[c]; k < outer[c + 1]; ++k)
      if (in_s(row[k])) b.in_r.push_back(k - outer[c]);
    for (int a = 0; a < 3; ++a) {
      b.r_entry0[a] = int(r_rows.size());
      for (int k : b.in_r) {
        r_rows.push_back(row[outer[c] + k]);
        j_source.push_back(-1);
      }
      q_column.push_back(-1);
      j_outer.push_back(int(r_rows.size()));
    }
    const Mat3 inverse = 0.25 * s->J_inverse;  // (4 J')^-1
    for (int a = 0; a < 3; ++a)
      for (int e = 0; e < 3; ++e)
        if (a == e || inverse(e, a) != 0.0) {
          m_inv_entries.emplace_back(b.z + e, b.z + a, inverse(e, a));
          diagonal_m_inv = diagonal_m_inv && a == e;
        }
    bodies.push_back(b);
    c += 4;
  }
  r_is_jacobian = bodies.empty() && j_source.size() == size_t(J.nonZeros());
  for (size_t e = 0; r_is_jacobian && e < j_source.size(); ++e) r_is_jacobian = j_source[e] == int(e);
  const int n_columns = int(q_column.size());
  m_inv.resize(n_columns, n_columns);
  m_inv.setFromTriplets(m_inv_entries.begin(), m_inv_entries.end());
  m_inv.makeCompressed();
  return true;
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
      constant_mass_(model.constant_mass()) {
  rhs_.resize(n_ + m_);
  x_.resize(n_ + m_);
  r_.resize(n_ + m_);
  dx_.resize(n_ + m_);
  if (p_->range_space) {
    const int rows = p_->S.rows();
    w_n_.resize(p_->n_r);
    b_r_.resize(p_->n_r);
    x_r_.resize(p_->n_r);
    s_rhs_.resize(rows);
    work_.resize(rows);
    lam_.resize(rows);
    lam_prev_.resize(rows);
    j_values_.resize(p_->j_row.size());
    j_scaled_.resize(j_values_.size());
    y4_column_.resize(j_values_.size());
    body_p_.resize(4 * p_->bodies.size());
    body_y_.resize(2 * p_->bodies.size());
    run_product_.resize(p_->largest_run * (p_->largest_run + 1) / 2);
    S_.resize(p_->S.values());
    s_diagonal_.resize(rows);
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
  const int rows = p_->S.rows();
  S_.resize(p_->S.values());
  s_diagonal_.resize(rows);
  s_rhs_.resize(rows);
  work_.resize(rows);
  lam_.resize(rows);
  lam_prev_.resize(rows);
  j_values_.resize(Eigen::Index(p_->j_row.size()));
  j_scaled_.resize(j_values_.size());
  y4_column_.resize(j_values_.size());
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
  if (!constant_mass_ && !d.M.coeffs().allFinite()) return false;  // (a constant M is finite by construction)
  // (S without the stops' and stuck contacts' rows where none is closed)
  if (every_->range_space) use_pattern(open_ && d.closed_rows().empty() ? open_ : every_);
  if (p_->range_space && reduce_jacobian(d) && factorize_schur(d)) return schur_ = factorized_ = true;
  // not positive definite in rounding (extreme scales), or a normalization
  // row left out: the LU decides
  fill_lu_matrix(d);
  if (!lu_analyzed_) {
    lu_.analyze(K_);
    lu_analyzed_ = true;
  }
  factorized_ = lu_.factorize(K_);
  return factorized_;
}

/// R's values from Phi_q's: copies, and each body's rates z = G(p) a / |p|^2
/// for the row's entries a on p (p itself read from the normalization row,
/// Phi_N,p = p^T), with the row's y4 entry a.p / |p|^2 beside them.
bool AugmentedSystem::reduce_jacobian(const Data& d) {
  for (int r : d.dropped_rows())
    if (p_->new_of_old[r] < 0 && (p_->switched_out.empty() || !p_->switched_out[size_t(r)]))
      return false;  // (a normalization row left out)
  const double* J = d.Phi_q.valuePtr();
  double* R = j_values_.data();
  if (p_->r_is_jacobian) {
    std::copy(J, J + d.Phi_q.nonZeros(), R);
    return true;
  }
  const int* source = p_->j_source.data();
  for (size_t e = 0; e < p_->j_source.size(); ++e)
    if (source[e] >= 0) R[e] = J[source[e]];
  for (size_t i = 0; i < p_->bodies.size(); ++i) {
    const AugmentedPattern::BodyRates& b = p_->bodies[i];
    const auto& q0 = b.q_entry0;
    const Vec4 p(J[q0[0] + b.norm], J[q0[1] + b.norm], J[q0[2] + b.norm], J[q0[3] + b.norm]);
    const double p2 = p.squaredNorm();
    if (!(p2 > 0.0)) return false;
    body_p_.segment<4>(4 * i) = p;
    const Mat34 g = euler::G(p) / p2;
    int o = 0;
    for (int k : b.in_r) {
      const Vec4 a(J[q0[0] + k], J[q0[1] + k], J[q0[2] + k], J[q0[3] + k]);
      const Vec3 z = g * a;
      for (int c = 0; c < 3; ++c) R[b.r_entry0[c] + o] = z[c];
      y4_column_[b.r_entry0[0] + o] = a.dot(p) / p2;
      ++o;
    }
  }
  return true;
}

void AugmentedSystem::assemble_schur(const Data& d) {
  const double* J = j_values_.data();
  double* S = S_.data();
  double* Jw = j_scaled_.data();  // R M^-1: column c = sum over a of R's column a times M^-1(a, c)
  const SpMat& m_inv = p_->m_inv;
  const int* mo = m_inv.outerIndexPtr();
  const int* mi = m_inv.innerIndexPtr();
  const double* mv = m_inv.valuePtr();
  for (int c = 0; c < p_->n_r; ++c) {
    const int begin = p_->j_outer[c], count = p_->j_outer[c + 1] - begin;
    if (p_->diagonal_m_inv) {
      for (int k = 0; k < count; ++k) Jw[begin + k] = J[begin + k] * mv[mo[c]];
      continue;
    }
    for (int k = 0; k < count; ++k) Jw[begin + k] = 0.0;
    for (int e = mo[c]; e < mo[c + 1]; ++e) {
      const int a = p_->j_outer[mi[e]];  // (same rows as column c: setup_schur checked)
      for (int k = 0; k < count; ++k) Jw[begin + k] += J[a + k] * mv[e];
    }
  }
  // S = sum over the runs g of R_g (R M^-1)_g^T: small dense products
  // (the lower triangle, column b = sum over the run's columns of R_g[b.., c] (R M^-1)_g[b, c]:
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
  // (the diagonal of Phi_q M^-1 Phi_q^T, as without body rates: S's and y4's part)
  assemble_schur(d);
  for (int k = 0; k < p_->S.rows(); ++k) s_diagonal_[k] = S_[p_->s_diag[k]];
  for (const AugmentedPattern::BodyRates& b : p_->bodies)
    for (int k = b.r_entry0[0]; k < p_->j_outer[b.z + 1]; ++k)
      s_diagonal_[p_->j_row[k]] += y4_column_[k] * y4_column_[k] / b.mass4;
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
  const AugmentedPattern& p = *p_;
  const double* J = j_values_.data();
  const int nr = p.n_r, ms = p.S.rows();
  // b1 over R's columns: q's own, and each body's G(p) b1_p / |p|^2; the
  // body's y4 = b2_N (its normalization row) and (p^T b1_p) / |p|^2 (where
  // R is Phi_q, b1 and x1 are over R's columns themselves)
  const bool plain = p.r_is_jacobian;
  if (!plain)
    for (int c = 0; c < nr; ++c)
      if (p.q_column[c] >= 0) b_r_[c] = b1[p.q_column[c]];
  for (size_t i = 0; i < p.bodies.size(); ++i) {
    const AugmentedPattern::BodyRates& b = p.bodies[i];
    const Vec4 e = body_p_.segment<4>(4 * i), f = b1.segment<4>(b.p);
    const double p2 = e.squaredNorm();
    b_r_.segment<3>(b.z) = euler::G(e) * f / p2;
    body_y_[2 * i] = b2[b.norm_row];
    body_y_[2 * i + 1] = e.dot(f) / p2;
  }
  // s = R M^-1 b_r - (b2 - y4's column y4), in S's order
  for (int k = 0; k < ms; ++k) s_rhs_[k] = -b2[p.old_of_new[k]];
  for (size_t i = 0; i < p.bodies.size(); ++i) {
    const AugmentedPattern::BodyRates& b = p.bodies[i];
    const double y4 = body_y_[2 * i];
    for (int k = b.r_entry0[0]; k < p.j_outer[b.z + 1]; ++k) s_rhs_[p.j_row[k]] += y4_column_[k] * y4;
  }
  const VecX& b_r = plain ? b1 : b_r_;
  if (p.diagonal_m_inv)
    for (int c = 0; c < nr; ++c) w_n_[c] = p.m_inv.valuePtr()[c] * b_r[c];
  else
    w_n_.noalias() = p.m_inv * b_r;
  for (int c = 0; c < nr; ++c) {
    const double w = w_n_[c];
    for (int k = p.j_outer[c]; k < p.j_outer[c + 1]; ++k) s_rhs_[p.j_row[k]] += J[k] * w;
  }
  lam_ = s_rhs_;
  p.S.solve(S_.data(), lam_.data());
  // with S0 + eps I, refine against eps = 0: the residual of lam_k is eps (lam_k - lam_{k-1}), lam_{-1} = 0
  double residual = regularized_ ? eps_ * lam_.lpNorm<Eigen::Infinity>() : 0.0, tol = 0.0;
  if (residual > 0.0)
    tol = 1e-15 * (1.0 + std::max(b1.size() ? b1.lpNorm<Eigen::Infinity>() : 0.0, b2.lpNorm<Eigen::Infinity>()));
  for (int it = 0; it < 3 && residual > tol; ++it) {
    work_ = s_rhs_ + eps_ * lam_;
    lam_prev_.swap(lam_);
    lam_ = work_;
    p.S.solve(S_.data(), lam_.data());
    residual = eps_ * (lam_ - lam_prev_).lpNorm<Eigen::Infinity>();
  }
  // x_r = M^-1 (b_r - R^T lam)
  for (int c = 0; c < nr; ++c) {
    double f = b_r[c];
    for (int k = p.j_outer[c]; k < p.j_outer[c + 1]; ++k) f -= J[k] * lam_[p.j_row[k]];
    w_n_[c] = f;
  }
  x1.resize(n_);
  x2.setZero(m_);  // (a row S leaves out: an open stop's, 0)
  VecX& x_r = plain ? x1 : x_r_;
  if (p.diagonal_m_inv)
    for (int c = 0; c < nr; ++c) x_r[c] = p.m_inv.valuePtr()[c] * w_n_[c];
  else
    x_r.noalias() = p.m_inv * w_n_;
  // back to q and the constraints' numbering: p'' = (G^T z + p y4) / |p|^2,
  // lam_N from y4's equation 4 jbar y4 + (Phi_p p / |p|^2)^T lam + lam_N = (p^T b1_p) / |p|^2
  if (!plain)
    for (int c = 0; c < nr; ++c)
      if (p.q_column[c] >= 0) x1[p.q_column[c]] = x_r_[c];
  for (int k = 0; k < ms; ++k) x2[p.old_of_new[k]] = lam_[k];
  for (size_t i = 0; i < p.bodies.size(); ++i) {
    const AugmentedPattern::BodyRates& b = p.bodies[i];
    const Vec4 e = body_p_.segment<4>(4 * i);
    const double p2 = e.squaredNorm(), y4 = body_y_[2 * i];
    x1.segment<4>(b.p) = (euler::G(e).transpose() * x_r_.segment<3>(b.z) + e * y4) / p2;
    double lam_n = body_y_[2 * i + 1] - b.mass4 * y4;
    for (int k = b.r_entry0[0]; k < p.j_outer[b.z + 1]; ++k) lam_n -= y4_column_[k] * lam_[p.j_row[k]];
    x2[b.norm_row] = lam_n;
  }
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
