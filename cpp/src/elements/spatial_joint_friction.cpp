// The spatial kind "spatial_joint_friction": how users add it (registry.hpp).
#include "lagmb/elements/spatial_joint_friction.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_spatial_joint_friction(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), label);
  if (c.turns && c.slides)
    throw ModelError(label + ": '" + a.text("joint") + "' turns and slides (a cylindrical joint); joint friction "
                     "acts on a revolute's angle or a translational's slide");
  SpatialJointFriction f = build::joining<SpatialJointFriction>(m, name, c.body_i, c.body_j);
  f.joint = build::joint_reading(c, 0.0);  // (only its rate matters)
  f.law.p.viscous = a.real("viscous");
  f.law.p.preload = a.real("preload");
  f.law.p.slip_velocity = a.real("slip_velocity");
  build::require_nonnegative(f.law.p.viscous, label, "viscous");
  build::require_nonnegative(f.law.p.preload, label, "preload");
  build::require_positive(f.law.p.slip_velocity, label, "slip_velocity");
  m.add_force_element(std::move(f));
}

}  // namespace

KindInfo spatial_joint_friction_kind() {
  return build::kind("spatial_joint_friction")
      .method("add_joint_friction")
      .table("forces")
      .type("joint_friction")
      .role(Role::kForce)
      .in_space()
      .doc("Friction in a revolute or translational joint, independent of the joint's load (a URDF joint's "
           "<dynamics damping friction>): with sd the joint's rate, F = -preload sd / sqrt(sd^2 + "
           "slip_velocity^2) - viscous sd, a torque about the axis (force along it) on the joint's second body, "
           "the opposite on the first. Coulomb friction from the joint's load (mu) is planar only so far.")
      .params({param::joint("the revolute or translational joint"),
               param::real("viscous", 0.0, "N m s/rad or N s/m", "viscous coefficient"),
               param::real("preload", 0.0, "N m or N", "the Coulomb friction torque or force"),
               param::real("slip_velocity", 1e-3, "rad/s or m/s", "below it the sign function is smoothed")})
      .build(build_spatial_joint_friction)
      .effort("the friction torque (N m) or force (N) on the joint's second body: -preload sd / sqrt(sd^2 + "
              "slip_velocity^2) - viscous sd");
}

}  // namespace lagmb
