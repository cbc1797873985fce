// The fastest rates of a model's applied forces (stiffness.hpp).
#include "lagmb/analyses/stiffness.hpp"

#include <cmath>
#include <random>

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/model/data.hpp"

namespace lagmb {

namespace {

/// |lambda_max| of M^-1 A (A: n x n sparse) by power iteration from a fixed
/// random start; 0 for A = 0. The ratio of successive norms converges to
/// |lambda_max| for the dominant real eigenvalues of a spring or damper
/// network (M^-1 K is similar to the symmetric M^-1/2 K M^-1/2).
double dominant_magnitude(const Data& d, const SpMat& A, int n) {
  if (A.nonZeros() == 0) return 0.0;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VecX x(n), y(n), Ax(n);
  for (int i = 0; i < n; ++i) x[i] = uniform(random);
  x.normalize();
  double estimate = 0.0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    Ax = A * x;
    mass_inverse_times(d, Ax.data(), y.data());
    const double norm = y.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) return std::isfinite(norm) ? 0.0 : INFINITY;
    const double previous = estimate;
    estimate = norm;
    x = y / norm;
    if (iteration > 10 && std::abs(estimate - previous) <= 1e-3 * estimate) break;
  }
  return estimate;
}

}  // namespace

ForceRates force_rates(const Model& model, const double* q, const double* v, double t) {
  Data d(model);
  const int n = model.n_coordinates();
  assemble_mass(model, d, q);
  assemble_force_derivatives(model, d, q, v, t);
  ForceRates r;
  r.omega = std::sqrt(dominant_magnitude(d, d.Q_q, n));
  r.sigma = dominant_magnitude(d, d.Q_v, n);
  return r;
}

}  // namespace lagmb
