// The stabilized index-2 form of Gear, Gupta and Leimkuhler (GglFormulation, dae.hpp).
#include <algorithm>
#include <cmath>

#include "formulations/dae.hpp"
#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

std::unique_ptr<DaeFormulation> make_sensitivity_formulation(const Model& model, const Data& run) {
  return std::make_unique<GglFormulation>(model, &run);
}

GglFormulation::GglFormulation(const Model& model, const Data* run)
    : MultiplierDae(model, 2 * model.n_coordinates() + 2 * model.n_constraints(), run) {
  const int V = n_, U = 2 * n_ + m_;  // first rows/columns of v, mu
  SparsityPattern p(size_, size_);
  declare_common(p);  // with F3 x q: Phi_q
  const SpMat& G = model.jacobian_pattern();
  add_block(p, model.hessian_pattern(), 0, 0);  // F1 x q: (Phi_q^T mu)_q
  add_block(p, G, 0, U, true);                  // F1 x mu: Phi_q^T
  add_block(p, G, U, 0);                        // F4 x q: (Phi_q v + Phi_t)_q
  add_block(p, G, U, V);                        // F4 x v: Phi_q
  bind_common(p);
  jac_F4v_ = jacobian_slots(U, V);
  jac_F1mu_ = jacobian_slots(0, U, true);
  vq_F4q_ = jacobian_slots(U, 0);
  hess_F1q_ = embed_slots(model.hessian_pattern(), J_, 0, 0);
}

void GglFormulation::ids(double* id) const {
  std::fill(id, id + 2 * n_, 1.0);
  std::fill(id + 2 * n_, id + size_, 0.0);
}

void GglFormulation::index_levels(int* level) const {
  std::fill(level, level + 2 * n_, 1);
  std::fill(level + 2 * n_, level + size_, 2);
}

void GglFormulation::tolerances(const VecX& atol, double* abstol) const {
  // lam in N s and mu in m: divided by h they are a force and a velocity
  coordinate_tolerances(atol, abstol);
  std::fill(abstol + 2 * n_, abstol + 2 * n_ + m_, atol.mean() * model_.mass_scale());
  std::fill(abstol + 2 * n_ + m_, abstol + size_, atol.mean());
}

int GglFormulation::residual(double t, const double* y, const double* yp, double* F) {
  const double *q = y, *v = y + n_, *mu = y + 2 * n_ + m_;
  double *F1 = F, *F3 = F + 2 * n_, *F4 = F + 2 * n_ + m_;
  momentum_residual(t, y, yp, F);
  add_jacobian_transpose_times(d_, mu, F1);
  assemble_constraints(model_, d_, q, t);
  std::copy(d_.Phi.data(), d_.Phi.data() + m_, F3);
  assemble_phi_t(model_, d_, q, t);
  std::copy(d_.phi_t.data(), d_.phi_t.data() + m_, F4);
  add_jacobian_times(d_, v, F4);
  return check_finite(F, size_);
}

void GglFormulation::newton_matrix(double t, double cj, const double* y, const double* yp) {
  const double *q = y, *v = y + n_, *mu = y + 2 * n_ + m_;
  const double h = 1.0 / cj;
  momentum_jacobian(t, cj, y, yp, h, h, 1.0, cj);
  col_scale_.tail(m_).setConstant(cj);
  double* J = J_.valuePtr();
  put_jacobian(saddle_.jacobian, 1.0);  // F3 x q
  put_jacobian(jac_F4v_, 1.0);
  put_jacobian(jac_F1mu_, 1.0);  // h (row) x cj (column)
  assemble_velocity_jacobian(model_, d_, q, v, t);
  for (size_t k = 0; k < vq_F4q_.size(); ++k) J[vq_F4q_[k]] += d_.Vq.valuePtr()[k];
  assemble_constraint_hessian(model_, d_, q, t, mu);
  for (size_t k = 0; k < hess_F1q_.size(); ++k) J[hess_F1q_[k]] += h * d_.H.valuePtr()[k];
  pin_dropped_multipliers();
}

bool GglFormulation::sensitivity_products(double t, const double* y, const double* yp, bool same_state, int k,
                                          const double* const* s, const double* const* sp, double* const* out) {
  if (!model_.friction_groups().empty()) return false;
  const int n = n_, m = m_;
  if (!same_state) {
    // the blocks at (t, y, y'): Phi_q and M(q); H(mu); the momentum tangent
    // T = (M v')_q + H(lam) - Q_q and -Q_v; Vq
    const double *q = y, *v = y + n_, *lam = y + 2 * n_, *mu = y + 2 * n_ + m_, *vp = yp + n_;
    assemble_jacobian(model_, d_, q, t);
    sens_Phi_q_ = d_.Phi_q;
    sens_M_ = d_.M;
    assemble_constraint_hessian(model_, d_, q, t, mu);
    sens_H_mu_ = d_.H;
    assemble_constraint_hessian(model_, d_, q, t, lam);
    assemble_force_derivatives(model_, d_, q, v, t);
    assemble_mass_derivative(model_, d_, q, vp);
    sens_T_ = d_.M_qa + d_.H - d_.Q_q;
    sens_Q_v_ = d_.Q_v;
    assemble_velocity_jacobian(model_, d_, q, v, t);
    sens_Vq_ = d_.Vq;
  }
  using Map = Eigen::Map<const VecX>;
  for (int i = 0; i < k; ++i) {
    const Map s_q(s[i], n), s_v(s[i] + n, n), s_lam(s[i] + 2 * n, m), s_mu(s[i] + 2 * n + m, m);
    const Map sp_q(sp[i], n), sp_v(sp[i] + n, n);
    Eigen::Map<VecX> o1(out[i], n), o2(out[i] + n, n), o3(out[i] + 2 * n, m), o4(out[i] + 2 * n + m, m);
    o1 = sp_q - s_v + sens_H_mu_ * s_q;
    o1.noalias() += sens_Phi_q_.transpose() * s_mu;
    o2 = sens_M_ * sp_v + sens_T_ * s_q;
    o2.noalias() -= sens_Q_v_ * s_v;
    o2.noalias() += sens_Phi_q_.transpose() * s_lam;
    o3 = sens_Phi_q_ * s_q;
    o4 = sens_Vq_ * s_q;
    o4.noalias() += sens_Phi_q_ * s_v;
  }
  return true;
}

}  // namespace lagmb
