// The saddle-point block of lagmb's Newton matrices (saddle_point.hpp).
#include "assembly/saddle_point.hpp"

#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

void add_block(SparsityPattern& p, const SpMat& A, int row0, int col0, bool transpose) {
  for (int c = 0; c < A.outerSize(); ++c)
    for (SpMat::InnerIterator it(A, c); it; ++it)
      transpose ? p.add(row0 + c, col0 + int(it.row())) : p.add(row0 + int(it.row()), col0 + c);
}

void add_scaled(double* J, const std::vector<int>& slots, const SpMat& values, double scale) {
  const double* x = values.valuePtr();
  for (size_t k = 0; k < slots.size(); ++k) J[slots[k]] += scale * x[k];
}

void stiffness_times(const Model& model, const Data& d, const double* x, double* y) {
  const int n = model.n_coordinates();
  Eigen::Map<const VecX> X(x, n);
  Eigen::Map<VecX> Y(y, n);
  Y.noalias() = -(d.H * X);
  if (!model.state_dependent_forces().empty()) Y.noalias() += d.Q_q * X;
  if (!model.friction_groups().empty()) Y.noalias() += d.friction_Q_q * X;
  if (!model.constant_mass()) Y.noalias() -= d.M_qa * X;
}

void SaddlePoint::declare(SparsityPattern& p) const {
  add_block(p, model_.mass_pattern(), at_.momentum_row, at_.v_col);
  if (!model_.constant_mass()) add_block(p, model_.mass_pattern(), at_.momentum_row, at_.q_col);
  add_block(p, model_.hessian_pattern(), at_.momentum_row, at_.q_col);
  add_block(p, model_.force_q_pattern(), at_.momentum_row, at_.q_col);
  add_block(p, model_.force_v_pattern(), at_.momentum_row, at_.v_col);
  add_block(p, model_.jacobian_pattern(), at_.momentum_row, at_.lam_col, true);
  add_block(p, model_.jacobian_pattern(), at_.constraint_row, at_.q_col);
}

void SaddlePoint::bind(const SpMat& J) {
  mass = embed_slots(model_.mass_pattern(), J, at_.momentum_row, at_.v_col);
  mass_q.clear();
  if (!model_.constant_mass()) mass_q = embed_slots(model_.mass_pattern(), J, at_.momentum_row, at_.q_col);
  hessian = embed_slots(model_.hessian_pattern(), J, at_.momentum_row, at_.q_col);
  force_q = embed_slots(model_.force_q_pattern(), J, at_.momentum_row, at_.q_col);
  force_v = embed_slots(model_.force_v_pattern(), J, at_.momentum_row, at_.v_col);
  jacobian_t = embed_slots(model_.jacobian_pattern(), J, at_.momentum_row, at_.lam_col, true);
  jacobian = embed_slots(model_.jacobian_pattern(), J, at_.constraint_row, at_.q_col);
}

SpMat SaddlePoint::build_square(std::vector<int>& diagonal) {
  const int size = model_.n_coordinates() + model_.n_constraints();
  SparsityPattern p(size, size);
  for (int i = 0; i < size; ++i) p.add(i, i);
  declare(p);
  SpMat J = p.build();
  diagonal.clear();
  for (int i = 0; i < size; ++i) diagonal.push_back(slot(J, i, i));
  bind(J);
  return J;
}

void SaddlePoint::add_tangent(Data& d, double* J, const double* q, const double* v, double t, const double* lam,
                              const double* a, double s, double c) const {
  // the blocks overlap (diagonals of H, Q_q, Q_v): the order of the sums is fixed
  assemble_constraint_hessian(model_, d, q, t, lam);
  add_scaled(J, hessian, d.H, s);
  if (!model_.constant_mass()) {
    assemble_mass_derivative(model_, d, q, a);
    add_scaled(J, mass_q, d.M_qa, s);
  }
  if (!model_.state_dependent_forces().empty()) {
    assemble_force_derivatives(model_, d, q, v, t);
    add_scaled(J, force_q, d.Q_q, -s);
    add_scaled(J, force_v, d.Q_v, -c);
  }
  if (!model_.friction_groups().empty()) {
    // joint friction Q_f(q, v, lam) at these multipliers
    assemble_friction_derivatives(model_, d, q, v, lam);
    add_scaled(J, force_q, d.friction_Q_q, -s);
    add_scaled(J, force_v, d.friction_Q_v, -c);
  }
}

}  // namespace lagmb
