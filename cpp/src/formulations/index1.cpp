// The index-1 form with Baumgarte terms (Index1Formulation, dae.hpp).
#include <algorithm>

#include "formulations/dae.hpp"
#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

Index1Formulation::Index1Formulation(const Model& model, double alpha, double beta, const Data* run)
    : MultiplierDae(model, 2 * model.n_coordinates() + model.n_constraints(), run), alpha_(alpha), beta_(beta) {
  SparsityPattern p(size_, size_);
  declare_common(p);  // with F3 x q: the pattern of Phi_q
  add_block(p, model.jacobian_pattern(), 2 * n_, n_);  // F3 x v
  bind_common(p);
  F3v_ = jacobian_slots(2 * n_, n_);
  scratch_.resize(m_);
}

void Index1Formulation::ids(double* id) const {
  std::fill(id, id + 2 * n_, 1.0);
  std::fill(id + 2 * n_, id + size_, 0.0);
}

void Index1Formulation::index_levels(int* level) const { std::fill(level, level + size_, 1); }

void Index1Formulation::tolerances(const VecX& atol, double* abstol) const {
  coordinate_tolerances(atol, abstol);
  std::fill(abstol + 2 * n_, abstol + size_, atol.mean() * model_.mass_scale());
}

int Index1Formulation::residual(double t, const double* y, const double* yp, double* F) {
  const double *q = y, *v = y + n_, *vp = yp + n_;
  double* F3 = F + 2 * n_;
  momentum_residual(t, y, yp, F);
  // F3 = Phi_q v' - gamma + 2 alpha (Phi_q v + Phi_t) + beta^2 Phi
  assemble_gamma(model_, d_, q, v, t);
  for (int r = 0; r < m_; ++r) F3[r] = -d_.gamma[r];
  add_jacobian_times(d_, vp, F3);
  if (alpha_ != 0.0) {
    assemble_phi_t(model_, d_, q, t);
    scratch_ = d_.phi_t;
    add_jacobian_times(d_, v, scratch_.data());
    for (int r = 0; r < m_; ++r) F3[r] += 2.0 * alpha_ * scratch_[r];
  }
  if (beta_ != 0.0) {
    assemble_constraints(model_, d_, q, t);
    for (int r = 0; r < m_; ++r) F3[r] += beta_ * beta_ * d_.Phi[r];
  }
  return check_finite(F, size_);
}

void Index1Formulation::newton_matrix(double t, double cj, const double* y, const double* yp) {
  const double *q = y, *v = y + n_, *vp = yp + n_;
  const double h = 1.0 / cj;
  momentum_jacobian(t, cj, y, yp, h, h, 1.0, cj);
  row_scale_.tail(m_).setConstant(h);
  double* J = J_.valuePtr();
  const std::vector<int>& F3q = saddle_.jacobian;
  // (Phi_q v')_q: the velocity Jacobian evaluated with v' (Phi_tq is zero for
  // every kind lagmb has)
  assemble_velocity_jacobian(model_, d_, q, vp, t);
  for (size_t k = 0; k < F3q.size(); ++k) J[F3q[k]] += h * d_.Vq.valuePtr()[k];
  assemble_velocity_jacobian(model_, d_, q, v, t);
  for (size_t k = 0; k < F3q.size(); ++k) {
    J[F3q[k]] += h * 2.0 * alpha_ * d_.Vq.valuePtr()[k];
    J[F3v_[k]] += h * 2.0 * d_.Vq.valuePtr()[k];
  }
  put_jacobian(F3v_, 1.0 + 2.0 * alpha_ * h);
  put_jacobian(F3q, h * beta_ * beta_);
  pin_dropped_multipliers();
}

}  // namespace lagmb
