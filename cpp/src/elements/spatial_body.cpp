// Spatial rigid bodies: how users add them (registry.hpp).
#include "lagmb/elements/spatial_body.hpp"

#include "elements/build.hpp"
#include "lagmb/model/body.hpp"

namespace lagmb {

namespace {

/// The body (7 coordinates: r, p), the normalization of its Euler
/// parameters and its gyroscopic force, the last two as the body's own
/// elements (not named: messages call them after the body).
void build_spatial_body(Model& m, const std::string& name, const Args& a) {
  const std::string label = "body '" + name + "'";
  Body b;
  b.name = name;
  b.spatial = true;
  b.mass = a.real("mass");
  if (!(b.mass >= 0))
    throw ModelError(label + ": mass must be positive (or 0: massless, run where its joints hold it) and finite, got " +
                     to_text(b.mass));
  b.inertia_tensor = a.inertia("inertia", a.flag("rigid_inertia"));
  b.inertia = b.inertia_tensor.trace() / 3.0;
  b.r0 = a.vec3("position");
  b.p0 = a.orientation("orientation");
  b.rdot0 = a.vec3("velocity");
  b.omega0 = a.vec3("angular_velocity");
  const int index = m.add_body(b);
  EulerParameterNorm norm;
  norm.name = name + " (Euler parameters)";
  norm.body_i = index;
  norm.body_j = kGround;
  m.add_constraint(std::move(norm), false);
  GyroscopicForce gyro;
  gyro.name = name + " (gyroscopic)";
  gyro.body_i = index;
  gyro.body_j = kGround;
  gyro.J = b.inertia_tensor;
  gyro.jbar = b.inertia;
  m.add_force_element(std::move(gyro), false);
}

}  // namespace

KindInfo spatial_body_kind() {
  return build::kind("spatial_body")
      .method("add_body")
      .table("bodies")
      .role(Role::kBody)
      .in_space()
      .doc("A rigid body in space with coordinates r (its centre of mass, x, y, z) and Euler parameters p "
           "(a unit quaternion w, x, y, z: its orientation, body axes into global axes).")
      .params({
          param::real("mass", "kg", "mass (0: massless: a dynamic run needs its joints to hold it)"),
          param::inertia("inertia",
                         "inertia about the centre of mass in body axes: principal moments (Ixx, Iyy, Izz) "
                         "or a 3 x 3 tensor"),
          param::vec3("position", Vec3::Zero(), "m", "initial position of the centre of mass"),
          param::orientation("orientation",
                             "initial orientation: a unit quaternion (w, x, y, z) or a 3 x 3 rotation matrix, "
                             "body axes into global axes"),
          param::vec3("velocity", Vec3::Zero(), "m/s", "initial velocity of the centre of mass"),
          param::vec3("angular_velocity", Vec3::Zero(), "rad/s", "initial angular velocity (global axes)"),
          param::flag("rigid_inertia", true,
                      "True: refuse principal moments that break the triangle inequality (no rigid body has "
                      "them); False: accept them (robot files hold such inertias; the mass matrix needs "
                      "positive semi-definite moments only)"),
      })
      .build(build_spatial_body);
}

}  // namespace lagmb
