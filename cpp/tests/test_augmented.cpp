// The augmented system (lagmb/assembly/augmented.hpp): the accelerations and
// multipliers solve_accelerations gives satisfy
//   M a + Phi_q^T lam = Q   and   Phi_q a = gamma,
// agree with a dense solve of the same matrix, and the seed pendulum's pin
// carries m g / 4 at release (closed form, tests/elements/test_pendulum.py).
#include <Eigen/Dense>
#include <string>

#include "check.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/assembly/augmented.hpp"
#include "models.hpp"

using namespace lagmb_test;

namespace {

struct Solved {
  VecX a, lam;
};

Solved accelerations(const Model& model, Data& d, const VecX& q, const VecX& v, double t = 0.0) {
  AugmentedSystem kkt(model);
  Solved s{VecX(model.n_coordinates()), VecX(model.n_constraints())};
  solve_accelerations(model, d, kkt, q.data(), v.data(), t, s.a.data(), s.lam.data());
  return s;
}

/// The rows of Phi of the element `name`, in order.
std::vector<int> rows_of(const Model& model, const std::string& name) {
  std::vector<int> rows;
  for (int r = 0; r < model.n_constraints(); ++r)
    if (model.constraint_name_of_row(r) == name) rows.push_back(r);
  return rows;
}

/// Both block rows of the augmented system hold to 1e-12 of their terms'
/// size, and a dense LU of [M Phi_q^T; Phi_q 0] (M, Phi_q, Q, gamma as the
/// kernels left them in d) gives the same a and lam.
void check_solves_the_augmented_system(const Model& model, const VecX& q, const VecX& v) {
  Data d(model);
  const Solved s = accelerations(model, d, q, v);
  const int n = model.n_coordinates(), m = model.n_constraints();
  const Eigen::MatrixXd M(d.M), J(d.Phi_q);
  const VecX Ma = M * s.a, Jt_lam = J.transpose() * s.lam, Ja = J * s.a;
  const double force_scale = 1.0 + std::max({d.Q.lpNorm<Eigen::Infinity>(), Ma.lpNorm<Eigen::Infinity>(),
                                             Jt_lam.lpNorm<Eigen::Infinity>()});
  const double gamma_scale = 1.0 + std::max(d.gamma.lpNorm<Eigen::Infinity>(), Ja.lpNorm<Eigen::Infinity>());
  CHECK_NEAR((Ma + Jt_lam - d.Q).lpNorm<Eigen::Infinity>(), 0.0, 1e-12 * force_scale);
  CHECK_NEAR((Ja - d.gamma).lpNorm<Eigen::Infinity>(), 0.0, 1e-12 * gamma_scale);

  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
  K.topLeftCorner(n, n) = M;
  K.topRightCorner(n, m) = J.transpose();
  K.bottomLeftCorner(m, n) = J;
  VecX b(n + m);
  b << d.Q, d.gamma;
  const VecX x = K.fullPivLu().solve(b);
  CHECK_NEAR((x.head(n) - s.a).lpNorm<Eigen::Infinity>(), 0.0, 1e-10 * (1.0 + s.a.lpNorm<Eigen::Infinity>()));
  CHECK_NEAR((x.tail(m) - s.lam).lpNorm<Eigen::Infinity>(), 0.0,
             1e-10 * (1.0 + s.lam.lpNorm<Eigen::Infinity>()));
}

}  // namespace

// A uniform rod (m, L) pinned at one end, released from horizontal:
// phi'' = -m g (L/2) / (I + m (L/2)^2) = -3 g / (2 L), its centre falls with
// (L/2) phi'' = -3 g / 4, so the pin pushes it up with m g - 3 m g / 4 = m g / 4.
TEST_CASE(pendulum_pin_carries_a_quarter_of_the_weight_at_release) {
  const auto model = pendulum();
  Data d(*model);
  const Solved s = accelerations(*model, d, model->initial_q(), model->initial_v());
  const double m = 1.0, L = 1.0;
  CHECK_NEAR(s.a[0], 0.0, 1e-12);                       // x of the centre
  CHECK_NEAR(s.a[1], -3.0 * kG / 4.0, 1e-12 * kG);      // y of the centre
  CHECK_NEAR(s.a[2], -3.0 * kG / (2.0 * L), 1e-12 * kG);  // the angle
  // the multipliers are the force on body_i (the ground): the rod gets -lam
  const std::vector<int> pin = rows_of(*model, "pin");
  CHECK(pin.size() == 2);
  CHECK_NEAR(-s.lam[pin[0]], 0.0, 1e-12 * m * kG);
  CHECK_NEAR(-s.lam[pin[1]], m * kG / 4.0, 1e-12 * m * kG);
}

// The same rod in space on a spherical joint (a 4 x 4 mass block at its
// Euler parameters, one normalization row beside the joint's three).
TEST_CASE(spatial_pendulum_pin_carries_a_quarter_of_the_weight_at_release) {
  const auto model = spatial_pendulum();
  Data d(*model);
  const Solved s = accelerations(*model, d, model->initial_q(), model->initial_v());
  const std::vector<int> pin = rows_of(*model, "pin");
  CHECK(pin.size() == 3);
  CHECK_NEAR(-s.lam[pin[0]], 0.0, 1e-12 * kG);
  CHECK_NEAR(-s.lam[pin[1]], 0.0, 1e-12 * kG);
  CHECK_NEAR(-s.lam[pin[2]], kG / 4.0, 1e-12 * kG);
  CHECK_NEAR(s.a[2], -3.0 * kG / 4.0, 1e-12 * kG);  // the centre's z
}

// At states off the initial one (positions moved, any velocities: gamma
// then has its velocity terms), for a chain, a closed loop with a slider
// and a spatial body.
TEST_CASE(accelerations_and_multipliers_solve_the_augmented_system) {
  std::mt19937 random(40);
  for (const auto& model : {pendulum(), double_pendulum(), slider_crank(), spatial_pendulum()}) {
    check_solves_the_augmented_system(*model, model->initial_q(), model->initial_v());
    for (int trial = 0; trial < 5; ++trial) {
      const int n = model->n_coordinates();
      VecX q = model->initial_q() + 0.2 * random_vector(n, random);
      if (model->dimension() == 3) q.segment<4>(3).normalize();  // the rod's Euler parameters
      check_solves_the_augmented_system(*model, q, 3.0 * random_vector(n, random));
    }
  }
}

LAGMB_TEST_MAIN()
