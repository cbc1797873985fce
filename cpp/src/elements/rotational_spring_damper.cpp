// Rotational spring-damper-actuator: how users add one (registry.hpp).
#include "lagmb/elements/rotational_spring_damper.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_rotational_spring_damper(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  RotationalSpringDamper e = build::joining<RotationalSpringDamper>(m, name, a.body("body_i"), a.body("body_j"));
  for (int b : {e.body_i, e.body_j}) build::require_rigid(m, b, label, "has no angle");
  e.stiffness = a.real("stiffness");
  e.damping = a.real("damping");
  build::require_nonnegative(e.stiffness, label, "stiffness");
  build::require_nonnegative(e.damping, label, "damping");
  e.free_angle = a.optional_real("free_angle").value_or(m.initial_angle(e.body_j) - m.initial_angle(e.body_i));
  e.actuator = build::drive(m, a.function("torque"));
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo rotational_spring_damper_kind() {
  return build::kind("rotational_spring_damper")
      .method("add_rotational_spring_damper")
      .table("forces")
      .type("rotational_spring_damper")
      .role(Role::kForce)
      .doc("Torsion spring, damper and actuator between two bodies: the torque on body_j is "
           "-k (theta - theta0) - c theta' + tau(t), theta = phi_j - phi_i; body_i gets the opposite.")
      .params({
          param::body("body_i", "the first body"),
          param::body("body_j", "the second body"),
          param::real("stiffness", 0.0, "N m/rad", "torsion stiffness k"),
          param::real("damping", 0.0, "N m s/rad", "damping coefficient c"),
          param::optional_real("free_angle", "rad", "free angle theta0 (default: the initial relative angle)"),
          param::function("torque", "N m", "actuator torque tau(t) on body_j"),
      })
      .build(build_rotational_spring_damper)
      .effort("the torque (N m) on body_j: -k (theta - theta0) - c theta' + tau(t), the actuator's torque as "
              "applied included");
}

}  // namespace lagmb
