// The consistent-state solves (lagmb/analyses/consistent_state.hpp):
// solve_positions lands on Phi = 0 by a least change in the M-metric,
// make_consistent on Phi = 0 and Phi_q v + Phi_t = 0 with the qdd and lam
// of that state, and start_state does so for the model's initial state.
#include <Eigen/Dense>

#include "check.hpp"
#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/analyses/redundancy.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/assembly/augmented.hpp"
#include "models.hpp"

using namespace lagmb_test;

namespace {

double max_phi(const Model& model, Data& d, const VecX& q, double t = 0.0) {
  assemble_constraints(model, d, q.data(), t);
  return d.Phi.lpNorm<Eigen::Infinity>();
}

}  // namespace

// From positions moved off the constraints (a closed loop, a spatial body
// whose Euler parameters are moved off the unit sphere too), the positions
// solved satisfy Phi = 0; the change from the given ones is least in the
// M-metric, so M dq lies in the range of Phi_q^T (no part along the
// joints' free motion) to first order.
TEST_CASE(solve_positions_lands_on_the_constraints) {
  std::mt19937 random(42);
  for (const auto& model : {pendulum(), double_pendulum(), slider_crank(), spatial_pendulum()}) {
    const int n = model->n_coordinates();
    Data d(*model);
    AugmentedSystem kkt(*model);
    const VecX given = model->initial_q() + 1e-4 * random_vector(n, random);
    const VecX q = solve_positions(*model, d, kkt, given, 0.0);
    CHECK(max_phi(*model, d, given) > 1e-6);
    CHECK_NEAR(max_phi(*model, d, q), 0.0, 1e-12 * (1.0 + q.lpNorm<Eigen::Infinity>()));
    // M dq = -Phi_q^T kappa for some kappa: its part M-orthogonal to the rows is second order
    assemble_jacobian(*model, d, q.data(), 0.0);
    const Eigen::MatrixXd J(d.Phi_q), M(d.M);
    const VecX Mdq = M * (q - given);
    const VecX kappa = (J * J.transpose()).completeOrthogonalDecomposition().solve(J * Mdq);
    CHECK_NEAR((Mdq - J.transpose() * kappa).lpNorm<Eigen::Infinity>(), 0.0, 1e-6);
  }
}

// Positions already on the constraints stay where they are.
TEST_CASE(solve_positions_keeps_consistent_positions) {
  for (const auto& model : {pendulum(), slider_crank(), spatial_pendulum()}) {
    Data d(*model);
    AugmentedSystem kkt(*model);
    const VecX q0 = model->initial_q();
    const VecX q = solve_positions(*model, d, kkt, q0, 0.0);
    CHECK_NEAR((q - q0).lpNorm<Eigen::Infinity>(), 0.0, 1e-12);
  }
}

// make_consistent: from positions and velocities moved off the constraints,
// a state on them (Phi = 0, Phi_q v = 0) whose qdd and lam solve the system.
TEST_CASE(make_consistent_returns_a_state_on_the_constraints) {
  std::mt19937 random(41);
  const auto model = slider_crank();
  Data d(*model);
  AugmentedSystem kkt(*model);
  const int n = model->n_coordinates(), m = model->n_constraints();
  const ConsistentState s = make_consistent(*model, d, kkt, model->initial_q() + 1e-3 * random_vector(n, random),
                                            model->initial_v() + random_vector(n, random), 0.0);
  CHECK_NEAR(max_phi(*model, d, s.q), 0.0, 1e-10);
  assemble_jacobian(*model, d, s.q.data(), 0.0);
  CHECK_NEAR((d.Phi_q * s.v).lpNorm<Eigen::Infinity>(), 0.0, 1e-10);
  VecX a(n), lam(m);
  solve_accelerations(*model, d, kkt, s.q.data(), s.v.data(), 0.0, a.data(), lam.data());
  CHECK_NEAR((a - s.qdd).lpNorm<Eigen::Infinity>(), 0.0, 1e-9 * (1.0 + s.qdd.lpNorm<Eigen::Infinity>()));
  CHECK_NEAR((lam - s.lam).lpNorm<Eigen::Infinity>(), 0.0, 1e-9 * (1.0 + s.lam.lpNorm<Eigen::Infinity>()));
}

// start_state of the seed pendulum: its initial state is consistent and has
// no redundant rows; the pin carries m g / 4 at release.
TEST_CASE(start_state_of_the_pendulum) {
  const auto model = pendulum();
  Data d(*model);
  AugmentedSystem kkt(*model);
  Redundancy redundancy;
  const ConsistentState s = start_state(*model, d, kkt, model->initial_q(), model->initial_v(), 0.0, &redundancy);
  CHECK(redundancy.rows.empty() && s.dropped_rows.empty());
  CHECK_NEAR((s.q - model->initial_q()).lpNorm<Eigen::Infinity>(), 0.0, 1e-12);
  CHECK_NEAR(s.qdd[1], -3.0 * kG / 4.0, 1e-12 * kG);
}

LAGMB_TEST_MAIN()
