#include <algorithm>
#include <cmath>

#include "../dae.hpp"
#include "lagmb/assembly.hpp"

namespace lagmb {

namespace {

void add_block(SparsityPattern& p, const SpMat& A, int r0, int c0, bool transpose) {
  for (int c = 0; c < A.outerSize(); ++c)
    for (SpMat::InnerIterator it(A, c); it; ++it)
      transpose ? p.add(r0 + c, c0 + int(it.row())) : p.add(r0 + int(it.row()), c0 + c);
}

}  // namespace

MultiplierDae::MultiplierDae(const Model& model, int size)
    : model_(model), d_(model), n_(model.n_coordinates()), m_(model.n_constraints()), size_(size) {}

void MultiplierDae::declare_common(SparsityPattern& p) const {
  const int V = n_, L = 2 * n_;
  for (int i = 0; i < n_; ++i) {
    p.add(i, i);
    p.add(i, V + i);
    p.add(V + i, V + i);
  }
  for (int i = 2 * n_; i < size_; ++i) p.add(i, i);  // zero diagonal: room for pivoting
  add_block(p, model_.hessian_pattern(), V, 0, false);
  add_block(p, model_.force_q_pattern(), V, 0, false);
  add_block(p, model_.force_v_pattern(), V, V, false);
  add_block(p, model_.jacobian_pattern(), V, L, true);
}

void MultiplierDae::bind_common(const SparsityPattern& p) {
  J_ = p.build();
  const int V = n_, L = 2 * n_;
  for (int i = 0; i < n_; ++i) {
    q_diag_.push_back(slot(J_, i, i));
    qv_diag_.push_back(slot(J_, i, V + i));
    v_diag_.push_back(slot(J_, V + i, V + i));
  }
  jac_F2lam_ = jacobian_slots(V, L, true);
  for (int i = 2 * n_; i < size_; ++i) alg_diag_.push_back(slot(J_, i, i));
  hess_F2q_ = embed_slots(model_.hessian_pattern(), J_, V, 0);
  Qq_F2q_ = embed_slots(model_.force_q_pattern(), J_, V, 0);
  Qv_F2v_ = embed_slots(model_.force_v_pattern(), J_, V, V);
  row_scale_ = VecX::Ones(size_);
  col_scale_ = VecX::Ones(size_);
}

std::vector<int> MultiplierDae::jacobian_slots(int row0, int col0, bool transpose) const {
  return embed_slots(model_.jacobian_pattern(), J_, row0, col0, transpose);
}

void MultiplierDae::momentum_residual(double t, const double* y, const double* yp, double* F) {
  const double *q = y, *v = y + n_, *lam = y + 2 * n_, *qp = yp, *vp = yp + n_;
  double *F1 = F, *F2 = F + n_;
  const VecX& M = model_.mass_diagonal();
  assemble_jacobian(model_, d_, q, t);
  assemble_forces(model_, d_, q, v, t);
  if (!model_.friction_groups().empty()) add_friction_forces(model_, d_, q, v, lam);  // Q_f(q, v, lam)
  for (int i = 0; i < n_; ++i) {
    F1[i] = qp[i] - v[i];
    F2[i] = M[i] * vp[i] - d_.Q[i];
  }
  add_jacobian_transpose_times(d_, lam, F2);
}

void MultiplierDae::momentum_jacobian(double t, double cj, const double* y, double r1, double r2, double cv,
                                      double cl) {
  const double *q = y, *v = y + n_, *lam = y + 2 * n_;
  const VecX& M = model_.mass_diagonal();
  double* J = J_.valuePtr();
  J_.coeffs().setZero();
  row_scale_.head(n_).setConstant(r1);
  row_scale_.segment(n_, n_).setConstant(r2);
  col_scale_.segment(n_, n_).setConstant(cv);
  col_scale_.segment(2 * n_, m_).setConstant(cl);
  for (int i = 0; i < n_; ++i) {
    J[q_diag_[i]] = r1 * cj;
    J[qv_diag_[i]] = -r1 * cv;
    J[v_diag_[i]] = r2 * cv * cj * M[i];
  }
  assemble_jacobian(model_, d_, q, t);
  put_jacobian(jac_F2lam_, r2 * cl);
  assemble_constraint_hessian(model_, d_, q, t, lam);
  for (size_t k = 0; k < hess_F2q_.size(); ++k) J[hess_F2q_[k]] += r2 * d_.H.valuePtr()[k];
  if (!model_.state_dependent_forces().empty()) {
    assemble_force_derivatives(model_, d_, q, v, t);
    for (size_t k = 0; k < Qq_F2q_.size(); ++k) J[Qq_F2q_[k]] -= r2 * d_.Q_q.valuePtr()[k];
    for (size_t k = 0; k < Qv_F2v_.size(); ++k) J[Qv_F2v_[k]] -= r2 * cv * d_.Q_v.valuePtr()[k];
  }
  if (!model_.friction_groups().empty()) {
    // joint friction Q_f(q, v, lam): -Q_f,q, -Q_f,v, and -Q_f,lam beside
    // Phi_q^T (a joint's friction depends only on that joint's multipliers)
    assemble_friction_derivatives(model_, d_, q, v, lam);
    for (size_t k = 0; k < Qq_F2q_.size(); ++k) J[Qq_F2q_[k]] -= r2 * d_.friction_Q_q.valuePtr()[k];
    for (size_t k = 0; k < Qv_F2v_.size(); ++k) J[Qv_F2v_[k]] -= r2 * cv * d_.friction_Q_v.valuePtr()[k];
    for (size_t k = 0; k < jac_F2lam_.size(); ++k) J[jac_F2lam_[k]] -= r2 * cl * d_.friction_Q_lam.valuePtr()[k];
  }
}

void MultiplierDae::pin_dropped_multipliers() {
  // alg_diag_[k] is the diagonal of unknown 2n + k: lam rows first, then mu (GGL)
  double* J = J_.valuePtr();
  for (int r : d_.dropped_rows)
    for (size_t k = r; k < alg_diag_.size(); k += m_) J[alg_diag_[k]] = 1.0;
}

int MultiplierDae::check_finite(const double* F, int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += F[i];
  return std::isfinite(s) ? 0 : 1;
}

void MultiplierDae::put_jacobian(const std::vector<int>& slots, double scale) {
  double* J = J_.valuePtr();
  const double* G = d_.Phi_q.valuePtr();
  for (size_t k = 0; k < slots.size(); ++k) J[slots[k]] += scale * G[k];
}

}  // namespace lagmb
