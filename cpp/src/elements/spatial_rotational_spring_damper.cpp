// The spatial rotational spring-damper: how users add one (registry.hpp).
#include "elements/build.hpp"
#include "lagmb/elements/spatial_rotational_spring_damper.hpp"

namespace lagmb {

namespace {

void build_spatial_rotational_spring_damper(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), label);
  if (!c.turns) throw ModelError(label + ": '" + a.text("joint") + "' does not turn (a translational joint)");
  auto e = build::joining<SpatialRotationalSpringDamper>(m, name, c.body_i, c.body_j);
  e.joint = build::continuous_reading(m, a.text("joint"), c);
  e.stiffness = a.real("stiffness");
  e.damping = a.real("damping");
  build::require_nonnegative(e.stiffness, label, "stiffness");
  build::require_nonnegative(e.damping, label, "damping");
  e.free_value = a.real("free_angle");
  e.actuator = build::drive(m, a.function("torque"));
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo spatial_rotational_spring_damper_kind() {
  return build::kind("spatial_rotational_spring_damper")
      .method("add_rotational_spring_damper")
      .table("forces")
      .type("rotational_spring_damper")
      .role(Role::kForce)
      .in_space()
      .doc("Torsion spring-damper-actuator on a revolute's (or cylindrical joint's) angle theta (its `angle` in "
           "the initial configuration, counting whole turns: it winds through any number): torque -k "
           "(theta - theta0) - c theta' + tau(t) about the axis on body_j.")
      .params({param::joint("the revolute or cylindrical joint"),
               param::real("stiffness", 0.0, "N m/rad", "torsion stiffness k"),
               param::real("damping", 0.0, "N m s/rad", "damping coefficient c"),
               param::real("free_angle", 0.0, "rad", "free angle theta0"),
               param::function("torque", "N m", "actuator torque tau(t) on body_j")})
      .build(build_spatial_rotational_spring_damper)
      .effort("the torque (N m) about the axis on body_j: -k (theta - theta0) - c theta' + tau(t), the actuator's "
              "torque as applied included");
}

}  // namespace lagmb
