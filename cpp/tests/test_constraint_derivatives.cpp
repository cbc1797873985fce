// A constraint group's derivatives (lagmb/model/constraint_group.hpp derives
// them from each kind's phi, jacobian and hessians) against central
// differences of what they differentiate, at random states, for joints in
// the plane and in space between two moving bodies:
//   Phi_q          columns of (Phi(q + h e_k) - Phi(q - h e_k)) / 2h
//   Phi_t          (Phi(t + h) - Phi(t - h)) / 2h
//   gamma = -(Phi_q v)_q v - 2 Phi_qt v - Phi_tt
//                  -d/ds (Phi_q v + Phi_t) along (q + s v, t + s)
//   Vq = (Phi_q v + Phi_t)_q   its columns, differenced along e_k.
// A driver on each joint makes its constraints depend on time, so the
// Phi_qt and Phi_tt terms of gamma are checked too.
#include <Eigen/Dense>
#include <functional>
#include <string>

#include "check.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/elements/spatial_revolute.hpp"
#include "lagmb/elements/spatial_translational.hpp"
#include "models.hpp"

using namespace lagmb_test;

namespace {

/// Two planar bodies joined by `kind` (with `extra` values) and driven along it.
std::shared_ptr<const Model> planar_pair(const std::string& kind, std::initializer_list<Given> extra) {
  ModelSpec spec;
  spec.add("body", "a", {{"mass", 1.0}, {"inertia", 0.1}, {"position", Vec2(0.1, 0.2)}, {"angle", 0.3}});
  spec.add("body", "b", {{"mass", 2.0}, {"inertia", 0.2}, {"position", Vec2(0.9, -0.4)}, {"angle", -0.5}});
  spec.add(kind, "joint", extra);
  spec.add("joint_driver", "drive", {{"joint", "joint"}, {"f", harmonic(0.3, 2.0, 0.1)}});
  return spec.compile();
}

/// Two spatial bodies joined by `kind` (with `extra` values), driven along
/// it when `driven`.
std::shared_ptr<const Model> spatial_pair(const std::string& kind, std::initializer_list<Given> extra, bool driven) {
  ModelSpec spec(3);
  spec.add("spatial_body", "a", {{"mass", 1.0}, {"inertia", Vec3(0.1, 0.2, 0.3)}, {"position", Vec3(0.1, 0.2, 0.3)},
                                 {"orientation", Vec4(0.9, 0.1, -0.3, 0.2).normalized()}});
  spec.add("spatial_body", "b", {{"mass", 2.0}, {"inertia", Vec3(0.3, 0.2, 0.4)}, {"position", Vec3(0.8, -0.4, 0.5)},
                                 {"orientation", Vec4(0.7, -0.2, 0.4, 0.5).normalized()}});
  spec.add(kind, "joint", extra);
  if (driven) spec.add("spatial_joint_driver", "drive", {{"joint", "joint"}, {"f", harmonic(0.3, 2.0, 0.1)}});
  return spec.compile();
}

/// Phi_q v + Phi_t at (q, t): what gamma and Vq differentiate.
VecX velocity_residual(const Model& model, Data& d, const VecX& q, const VecX& v, double t) {
  assemble_jacobian(model, d, q.data(), t);
  assemble_phi_t(model, d, q.data(), t);
  return d.Phi_q * v + d.phi_t;
}

/// Checks every derivative of the model's constraints at `trials` random states.
void check_derivatives(const std::string& what, const Model& model, int trials) {
  std::printf("  %s: %d constraints, %d coordinates\n", what.c_str(), model.n_constraints(), model.n_coordinates());
  std::mt19937 random(40);
  Data d(model);
  const int n = model.n_coordinates(), m = model.n_constraints();
  const double h = 1e-6, tol = 1e-7;
  for (int trial = 0; trial < trials; ++trial) {
    const VecX q = model.initial_q() + 0.5 * random_vector(n, random), v = 2.0 * random_vector(n, random);
    const double t = 1.5 * (1.0 + random_vector(1, random)[0]);
    auto phi = [&](const VecX& x, double s) {
      assemble_constraints(model, d, x.data(), s);
      return VecX(d.Phi);
    };

    assemble_jacobian(model, d, q.data(), t);
    const Eigen::MatrixXd J(d.Phi_q);
    Eigen::MatrixXd J_differences(m, n);
    for (int k = 0; k < n; ++k) {
      VecX up = q, down = q;
      up[k] += h, down[k] -= h;
      J_differences.col(k) = (phi(up, t) - phi(down, t)) / (2 * h);
    }
    CHECK_NEAR((J - J_differences).lpNorm<Eigen::Infinity>(), 0.0, tol * (1.0 + J.lpNorm<Eigen::Infinity>()));

    assemble_phi_t(model, d, q.data(), t);
    const VecX phi_t = d.phi_t, phi_t_differences = (phi(q, t + h) - phi(q, t - h)) / (2 * h);
    CHECK_NEAR((phi_t - phi_t_differences).lpNorm<Eigen::Infinity>(), 0.0, tol * (1.0 + phi_t.lpNorm<Eigen::Infinity>()));

    // (a step of 1e-5 along v: the differences of a product with v)
    const double hv = 1e-5;
    assemble_gamma(model, d, q.data(), v.data(), t);
    const VecX gamma = d.gamma;
    const VecX gamma_differences =
        -(velocity_residual(model, d, q + hv * v, v, t + hv) - velocity_residual(model, d, q - hv * v, v, t - hv)) /
        (2 * hv);
    CHECK_NEAR((gamma - gamma_differences).lpNorm<Eigen::Infinity>(), 0.0,
               tol * (1.0 + gamma.lpNorm<Eigen::Infinity>()));

    assemble_velocity_jacobian(model, d, q.data(), v.data(), t);
    const Eigen::MatrixXd Vq(d.Vq);
    Eigen::MatrixXd Vq_differences(m, n);
    for (int k = 0; k < n; ++k) {
      VecX up = q, down = q;
      up[k] += hv, down[k] -= hv;
      Vq_differences.col(k) = (velocity_residual(model, d, up, v, t) - velocity_residual(model, d, down, v, t)) / (2 * hv);
    }
    CHECK_NEAR((Vq - Vq_differences).lpNorm<Eigen::Infinity>(), 0.0, tol * (1.0 + Vq.lpNorm<Eigen::Infinity>()));
  }
}

}  // namespace

TEST_CASE(planar_revolute) {
  check_derivatives("revolute", *planar_pair("revolute", {{"body_i", "a"}, {"body_j", "b"}, {"at", Vec2(0.4, 0.1)}}), 5);
}

TEST_CASE(planar_translational) {
  check_derivatives("translational",
                    *planar_pair("translational", {{"body_i", "a"}, {"body_j", "b"}, {"at", Vec2(0.4, 0.1)},
                                                   {"axis", Vec2(0.6, 0.8)}}),
                    5);
}

TEST_CASE(spherical) {
  // (a spherical joint has no coordinate to drive)
  check_derivatives("spherical", *spatial_pair("spherical", {{"body_i", "a"}, {"body_j", "b"}, {"at", Vec3(0.5, 0.0, 0.4)}}, false),
                    5);
}

TEST_CASE(spatial_revolute) {
  check_derivatives("spatial_revolute",
                    *spatial_pair("spatial_revolute", {{"body_i", "a"}, {"body_j", "b"}, {"at", Vec3(0.5, 0.0, 0.4)},
                                                       {"axis", Vec3(0.2, -0.3, 0.9)}},
                                  true),
                    5);
}

/// A spatial joint's own Phi_c and gamma (its elements/*.hpp) against the
/// gradients and convective terms of its rows as terms() gives them, at
/// random states (unit Euler parameters, any velocities).
template <class Joint>
void check_closed_forms_equal_terms(const Joint& joint) {
  const auto& terms = static_cast<const spatial::TermJoint<Joint, 5>&>(joint);
  for (int trial = 0; trial < 5; ++trial) {
    spatial::Loc c = spatial::Loc::Random(), cd = spatial::Loc::Random();
    c.segment<4>(3).normalize();
    c.segment<4>(10).normalize();
    const double scale = 1.0 + terms.jacobian(c, 0.0).template lpNorm<Eigen::Infinity>();
    CHECK_NEAR((joint.jacobian(c, 0.0) - terms.jacobian(c, 0.0)).template lpNorm<Eigen::Infinity>(), 0.0, 1e-14 * scale);
    const double g_scale = 1.0 + terms.gamma(c, cd, 0.0).template lpNorm<Eigen::Infinity>();
    CHECK_NEAR((joint.gamma(c, cd, 0.0) - terms.gamma(c, cd, 0.0)).template lpNorm<Eigen::Infinity>(), 0.0, 1e-14 * g_scale);
  }
}

TEST_CASE(spatial_revolute_closed_forms_equal_its_terms) {
  SpatialRevoluteJoint joint;
  joint.s_i = Vec3(0.3, -0.2, 0.1), joint.s_j = Vec3(-0.4, 0.25, 0.2);
  joint.a_j = Vec3(0.2, -0.3, 0.9).normalized();
  euler::complete_basis(Vec3(0.6, 0.0, 0.8), joint.f_i, joint.g_i);
  check_closed_forms_equal_terms(joint);
}

TEST_CASE(spatial_translational) {
  check_derivatives("spatial_translational",
                    *spatial_pair("spatial_translational", {{"body_i", "a"}, {"body_j", "b"}, {"at", Vec3(0.5, 0.0, 0.4)},
                                                            {"axis", Vec3(0.2, -0.3, 0.9)}},
                                  true),
                    5);
}

TEST_CASE(spatial_translational_closed_forms_equal_its_terms) {
  SpatialTranslationalJoint joint;
  joint.s_i = Vec3(0.3, -0.2, 0.1), joint.s_j = Vec3(-0.4, 0.25, 0.2);
  joint.a_j = Vec3(0.2, -0.3, 0.9).normalized();
  joint.g_j = Vec3(0.9, 0.1, -0.2).normalized();
  euler::complete_basis(Vec3(0.6, 0.0, 0.8), joint.f_i, joint.g_i);
  check_closed_forms_equal_terms(joint);
}

LAGMB_TEST_MAIN()
