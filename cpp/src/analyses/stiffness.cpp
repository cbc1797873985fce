// The fastest rates of a model's applied forces (stiffness.hpp).
#include "lagmb/analyses/stiffness.hpp"

#include <cmath>
#include <memory>
#include <random>

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/assembly/augmented.hpp"
#include "lagmb/model/data.hpp"

namespace lagmb {

namespace {

/// |lambda_max| of P A (A: n x n sparse) by power iteration from a fixed
/// random start; 0 for A = 0. P is the inverse mass the joints leave:
/// y = P b solves [M Phi_q^T; Phi_q 0] [y; mu] = [b; 0] (kkt, factorized:
/// a force on a joint coordinate moves every body outboard of it, not one
/// body alone), or M^-1 where kkt is null (no constraints). The ratio of
/// successive norms converges to |lambda_max| for the dominant real
/// eigenvalues of a spring or damper network (P K is similar to a
/// symmetric matrix where K is).
double dominant_magnitude(const Data& d, AugmentedSystem* kkt, const SpMat& A, int n, int m) {
  if (A.nonZeros() == 0) return 0.0;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VecX x(n), y(n), Ax(n), mu(m);
  for (int i = 0; i < n; ++i) x[i] = uniform(random);
  x.normalize();
  double estimate = 0.0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    Ax = A * x;
    if (kkt)
      kkt->solve(Ax, VecX::Zero(m), y, mu);
    else
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
  const int m = model.n_constraints();
  assemble_mass(model, d, q);
  assemble_mass_inverse(model, d, q);
  assemble_force_derivatives(model, d, q, v, t);
  // (the joints' inverse mass where the augmented matrix factorizes; M^-1 else)
  std::unique_ptr<AugmentedSystem> kkt;
  if (m > 0) {
    assemble_jacobian(model, d, q, t);
    kkt = std::make_unique<AugmentedSystem>(model);
    if (!kkt->factorize(d)) kkt.reset();
  }
  ForceRates r;
  try {
    r.omega = std::sqrt(dominant_magnitude(d, kkt.get(), d.Q_q, n, m));
    r.sigma = dominant_magnitude(d, kkt.get(), d.Q_v, n, m);
  } catch (const SimulationError&) {  // (a solve the factorization could not give)
    r.omega = std::sqrt(dominant_magnitude(d, nullptr, d.Q_q, n, m));
    r.sigma = dominant_magnitude(d, nullptr, d.Q_v, n, m);
  }
  return r;
}

}  // namespace lagmb
