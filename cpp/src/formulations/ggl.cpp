#include <algorithm>
#include <cmath>

#include "../dae.hpp"
#include "lagmb/assembly.hpp"

namespace lagmb {

GglFormulation::GglFormulation(const Model& model)
    : model_(model), d_(model), n_(model.n_coordinates()), m_(model.n_constraints()) {
  const int n = n_, m = m_;
  const int V = n, L = 2 * n, U = 2 * n + m;  // first column of v, lam, mu
  const SpMat &Jp = model.jacobian_pattern(), &Hp = model.hessian_pattern();
  const SpMat &Qq = model.force_q_pattern(), &Qv = model.force_v_pattern();
  SparsityPattern p(size(), size());
  auto add = [&](const SpMat& A, int r0, int c0, bool transpose) {
    for (int c = 0; c < A.outerSize(); ++c)
      for (SpMat::InnerIterator it(A, c); it; ++it)
        transpose ? p.add(r0 + c, c0 + int(it.row())) : p.add(r0 + int(it.row()), c0 + c);
  };
  for (int i = 0; i < n; ++i) {
    p.add(i, i);
    p.add(i, V + i);
    p.add(V + i, V + i);
  }
  for (int i = 0; i < 2 * m; ++i) p.add(L + i, L + i);  // zero diagonal: room for pivoting
  add(Hp, 0, 0, false);
  add(Jp, 0, U, true);
  add(Hp, V, 0, false);
  add(Qq, V, 0, false);
  add(Qv, V, V, false);
  add(Jp, V, L, true);
  add(Jp, L, 0, false);
  add(Jp, U, 0, false);
  add(Jp, U, V, false);
  J_ = p.build();

  for (int i = 0; i < n; ++i) {
    q_diag_.push_back(slot(J_, i, i));
    qv_diag_.push_back(slot(J_, i, V + i));
    v_diag_.push_back(slot(J_, V + i, V + i));
  }
  jac_F3q_ = embed_slots(Jp, J_, L, 0);
  jac_F4v_ = embed_slots(Jp, J_, U, V);
  jac_F1mu_ = embed_slots(Jp, J_, 0, U, true);
  jac_F2lam_ = embed_slots(Jp, J_, V, L, true);
  vq_F4q_ = embed_slots(Jp, J_, U, 0);
  hess_F1q_ = embed_slots(Hp, J_, 0, 0);
  hess_F2q_ = embed_slots(Hp, J_, V, 0);
  Qq_F2q_ = embed_slots(Qq, J_, V, 0);
  Qv_F2v_ = embed_slots(Qv, J_, V, V);
  row_scale_ = VecX::Ones(size());
  col_scale_ = VecX::Ones(size());
}

void GglFormulation::ids(double* id) const {
  std::fill(id, id + 2 * n_, 1.0);
  std::fill(id + 2 * n_, id + size(), 0.0);
}

void GglFormulation::tolerances(double atol, double* abstol) const {
  // lam in N s and mu in m: the integrator divides them by the step size
  // (they are index-2 variables), giving a force and a velocity
  std::fill(abstol, abstol + 2 * n_, atol);
  std::fill(abstol + 2 * n_, abstol + 2 * n_ + m_, atol * model_.mass_scale());
  std::fill(abstol + 2 * n_ + m_, abstol + size(), atol);
}

void GglFormulation::initial(const ConsistentState& s, double* y, double* yp) const {
  std::fill(y, y + size(), 0.0);
  std::fill(yp, yp + size(), 0.0);
  std::copy(s.q.data(), s.q.data() + n_, y);
  std::copy(s.v.data(), s.v.data() + n_, y + n_);
  std::copy(s.lam.data(), s.lam.data() + m_, y + 2 * n_);
  std::copy(s.v.data(), s.v.data() + n_, yp);
  std::copy(s.qdd.data(), s.qdd.data() + n_, yp + n_);
}

int GglFormulation::residual(double t, const double* y, const double* yp, double* F) {
  const double *q = y, *v = y + n_, *lam = y + 2 * n_, *mu = y + 2 * n_ + m_;
  const double *qp = yp, *vp = yp + n_;
  double *F1 = F, *F2 = F + n_, *F3 = F + 2 * n_, *F4 = F + 2 * n_ + m_;
  const VecX& M = model_.mass_diagonal();

  assemble_jacobian(model_, d_, q, t);
  assemble_forces(model_, d_, q, v, t);
  for (int i = 0; i < n_; ++i) {
    F1[i] = qp[i] - v[i];
    F2[i] = M[i] * vp[i] - d_.Q[i];
  }
  add_jacobian_transpose_times(d_, mu, F1);
  add_jacobian_transpose_times(d_, lam, F2);

  assemble_constraints(model_, d_, q, t);
  std::copy(d_.Phi.data(), d_.Phi.data() + m_, F3);
  assemble_phi_t(model_, d_, q, t);
  std::copy(d_.phi_t.data(), d_.phi_t.data() + m_, F4);
  add_jacobian_times(d_, v, F4);

  double sum = 0.0;
  for (int i = 0; i < size(); ++i) sum += F[i];
  return std::isfinite(sum) ? 0 : 1;  // > 0: recoverable, IDA cuts the step
}

void GglFormulation::newton_matrix(double t, double cj, const double* y, const double*) {
  const double *q = y, *v = y + n_, *lam = y + 2 * n_, *mu = y + 2 * n_ + m_;
  const VecX& M = model_.mass_diagonal();
  // R = diag(h, h, 1, 1) on rows F1..F4, C = diag(1, 1, cj, cj) on columns q, v, lam, mu
  const double h = 1.0 / cj;
  row_scale_.head(2 * n_).setConstant(h);
  col_scale_.tail(2 * m_).setConstant(cj);
  double* J = J_.valuePtr();
  J_.coeffs().setZero();

  for (int i = 0; i < n_; ++i) {
    J[q_diag_[i]] += 1.0;
    J[qv_diag_[i]] = -h;
    J[v_diag_[i]] += M[i];
  }

  assemble_jacobian(model_, d_, q, t);
  const double* Jq = d_.Phi_q.valuePtr();
  for (size_t k = 0; k < jac_F3q_.size(); ++k) {
    J[jac_F3q_[k]] = Jq[k];
    J[jac_F4v_[k]] = Jq[k];
    J[jac_F1mu_[k]] = Jq[k];
    J[jac_F2lam_[k]] = Jq[k];
  }
  assemble_velocity_jacobian(model_, d_, q, v, t);
  const double* Vq = d_.Vq.valuePtr();
  for (size_t k = 0; k < vq_F4q_.size(); ++k) J[vq_F4q_[k]] = Vq[k];

  assemble_constraint_hessian(model_, d_, q, t, mu);
  for (size_t k = 0; k < hess_F1q_.size(); ++k) J[hess_F1q_[k]] += h * d_.H.valuePtr()[k];
  assemble_constraint_hessian(model_, d_, q, t, lam);
  for (size_t k = 0; k < hess_F2q_.size(); ++k) J[hess_F2q_[k]] += h * d_.H.valuePtr()[k];

  if (!model_.state_dependent_forces().empty()) {
    assemble_force_derivatives(model_, d_, q, v, t);
    for (size_t k = 0; k < Qq_F2q_.size(); ++k) J[Qq_F2q_[k]] -= h * d_.Q_q.valuePtr()[k];
    for (size_t k = 0; k < Qv_F2v_.size(); ++k) J[Qv_F2v_[k]] -= h * d_.Q_v.valuePtr()[k];
  }
}

}  // namespace lagmb
