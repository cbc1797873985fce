// The rows and Newton blocks the multiplier DAE forms share (MultiplierDae, dae.hpp).
#include <algorithm>
#include <cmath>

#include "formulations/dae.hpp"
#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

MultiplierDae::MultiplierDae(const Model& model, int size, const Data* run)
    : model_(model),
      d_(model, run),
      n_(model.n_coordinates()),
      m_(model.n_constraints()),
      size_(size),
      saddle_(model, {n_, 0, n_, 2 * n_, 2 * n_}) {}

void MultiplierDae::declare_common(SparsityPattern& p) const {
  const int V = n_;
  for (int i = 0; i < n_; ++i) {
    p.add(i, i);
    p.add(i, V + i);
  }
  for (int i = 2 * n_; i < size_; ++i) p.add(i, i);  // zero diagonal: room for pivoting
  saddle_.declare(p);
}

void MultiplierDae::bind_common(const SparsityPattern& p) {
  J_ = p.build();
  const int V = n_;
  for (int i = 0; i < n_; ++i) {
    q_diag_.push_back(slot(J_, i, i));
    qv_diag_.push_back(slot(J_, i, V + i));
  }
  for (int i = 2 * n_; i < size_; ++i) alg_diag_.push_back(slot(J_, i, i));
  saddle_.bind(J_);
  row_scale_ = VecX::Ones(size_);
  col_scale_ = VecX::Ones(size_);
}

void MultiplierDae::initial(const ConsistentState& s, double* y, double* yp) const {
  std::fill(y, y + size_, 0.0);
  std::fill(yp, yp + size_, 0.0);
  std::copy(s.q.data(), s.q.data() + n_, y);
  std::copy(s.v.data(), s.v.data() + n_, y + n_);
  std::copy(s.lam.data(), s.lam.data() + m_, y + 2 * n_);
  std::copy(s.v.data(), s.v.data() + n_, yp);
  std::copy(s.qdd.data(), s.qdd.data() + n_, yp + n_);
}

std::vector<int> MultiplierDae::jacobian_slots(int row0, int col0, bool transpose) const {
  return embed_slots(model_.jacobian_pattern(), J_, row0, col0, transpose);
}

void MultiplierDae::momentum_residual(double t, const double* y, const double* yp, double* F) {
  const double *q = y, *v = y + n_, *lam = y + 2 * n_, *qp = yp, *vp = yp + n_;
  double *F1 = F, *F2 = F + n_;
  assemble_jacobian(model_, d_, q, t);  // (and M(q))
  assemble_forces(model_, d_, q, v, t);
  if (!model_.friction_groups().empty()) add_friction_forces(model_, d_, q, v, lam);  // Q_f(q, v, lam)
  mass_times(d_, vp, F2);
  for (int i = 0; i < n_; ++i) {
    F1[i] = qp[i] - v[i];
    F2[i] -= d_.Q[i];
  }
  add_jacobian_transpose_times(d_, lam, F2);
}

void MultiplierDae::momentum_jacobian(double t, double cj, const double* y, const double* yp, double r1, double r2,
                                      double cv, double cl) {
  const double *q = y, *v = y + n_, *lam = y + 2 * n_, *vp = yp + n_;
  double* J = J_.valuePtr();
  J_.coeffs().setZero();
  row_scale_.head(n_).setConstant(r1);
  row_scale_.segment(n_, n_).setConstant(r2);
  col_scale_.segment(n_, n_).setConstant(cv);
  col_scale_.segment(2 * n_, m_).setConstant(cl);
  for (int i = 0; i < n_; ++i) {
    J[q_diag_[i]] = r1 * cj;
    J[qv_diag_[i]] = -r1 * cv;
  }
  assemble_jacobian(model_, d_, q, t);  // (and M(q))
  saddle_.add_mass(d_, J, r2 * cv * cj);
  put_jacobian(saddle_.jacobian_t, r2 * cl);
  // (Phi_q^T lam)_q + (M v')_q - Q_q - Q_v, with joint friction Q_f(q, v,
  // lam)'s -Q_f,q and -Q_f,v; its -Q_f,lam goes beside Phi_q^T (a joint's
  // friction depends only on that joint's multipliers)
  saddle_.add_tangent(d_, J, q, v, t, lam, vp, r2, r2 * cv);
  if (!model_.friction_groups().empty()) add_scaled(J, saddle_.jacobian_t, d_.friction_Q_lam, -r2 * cl);
}

void MultiplierDae::pin_dropped_multipliers() {
  // alg_diag_[k] is the diagonal of unknown 2n + k: lam rows first, then mu (GGL)
  double* J = J_.valuePtr();
  for (int r : d_.dropped_rows())
    for (size_t k = r; k < alg_diag_.size(); k += m_) J[alg_diag_[k]] = 1.0;
}

int MultiplierDae::check_finite(const double* F, int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += F[i];
  return std::isfinite(s) ? 0 : 1;
}

void MultiplierDae::put_jacobian(const std::vector<int>& slots, double scale) {
  add_scaled(J_.valuePtr(), slots, d_.Phi_q, scale);
}

}  // namespace lagmb
