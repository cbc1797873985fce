#include <algorithm>

#include "../dae.hpp"
#include "lagmb/assembly.hpp"

namespace lagmb {

Index3Formulation::Index3Formulation(const Model& model)
    : MultiplierDae(model, 2 * model.n_coordinates() + model.n_constraints()) {
  SparsityPattern p(size_, size_);
  declare_common(p);
  const SpMat& G = model.jacobian_pattern();
  for (int c = 0; c < G.outerSize(); ++c)
    for (SpMat::InnerIterator it(G, c); it; ++it) p.add(2 * n_ + int(it.row()), c);  // F3 x q
  bind_common(p);
  jac_F3q_ = jacobian_slots(2 * n_, 0);
}

void Index3Formulation::ids(double* id) const {
  std::fill(id, id + 2 * n_, 1.0);
  std::fill(id + 2 * n_, id + size_, 0.0);
}

void Index3Formulation::index_levels(int* level) const {
  std::fill(level, level + n_, 1);
  std::fill(level + n_, level + 2 * n_, 2);
  std::fill(level + 2 * n_, level + size_, 3);
}

void Index3Formulation::tolerances(const VecX& atol, double* abstol) const {
  // v in m (divided by h: m/s); lam in N s^2 (divided by h^2: N)
  coordinate_tolerances(atol, abstol);
  std::fill(abstol + 2 * n_, abstol + size_, atol.mean() * model_.mass_scale());
}

void Index3Formulation::initial(const ConsistentState& s, double* y, double* yp) const {
  std::fill(y, y + size_, 0.0);
  std::fill(yp, yp + size_, 0.0);
  std::copy(s.q.data(), s.q.data() + n_, y);
  std::copy(s.v.data(), s.v.data() + n_, y + n_);
  std::copy(s.lam.data(), s.lam.data() + m_, y + 2 * n_);
  std::copy(s.v.data(), s.v.data() + n_, yp);
  std::copy(s.qdd.data(), s.qdd.data() + n_, yp + n_);
}

int Index3Formulation::residual(double t, const double* y, const double* yp, double* F) {
  momentum_residual(t, y, yp, F);
  assemble_constraints(model_, d_, y, t);
  std::copy(d_.Phi.data(), d_.Phi.data() + m_, F + 2 * n_);
  return check_finite(F, size_);
}

void Index3Formulation::newton_matrix(double t, double cj, const double* y, const double*) {
  const double h = 1.0 / cj;
  momentum_jacobian(t, cj, y, h, h * h, cj, cj * cj);
  put_jacobian(jac_F3q_, 1.0);
  pin_dropped_multipliers();
}

}  // namespace lagmb
