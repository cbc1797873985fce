// The index-3 form (Index3Formulation, dae.hpp).
#include <algorithm>

#include "formulations/dae.hpp"
#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

Index3Formulation::Index3Formulation(const Model& model, const Data* run)
    : MultiplierDae(model, 2 * model.n_coordinates() + model.n_constraints(), run) {
  SparsityPattern p(size_, size_);
  declare_common(p);  // with F3 x q: Phi_q
  bind_common(p);
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

int Index3Formulation::residual(double t, const double* y, const double* yp, double* F) {
  momentum_residual(t, y, yp, F);
  assemble_constraints(model_, d_, y, t);
  std::copy(d_.Phi.data(), d_.Phi.data() + m_, F + 2 * n_);
  return check_finite(F, size_);
}

void Index3Formulation::newton_matrix(double t, double cj, const double* y, const double* yp) {
  const double h = 1.0 / cj;
  momentum_jacobian(t, cj, y, yp, h, h * h, cj, cj * cj);
  put_jacobian(saddle_.jacobian, 1.0);  // F3 x q
  pin_dropped_multipliers();
}

}  // namespace lagmb
