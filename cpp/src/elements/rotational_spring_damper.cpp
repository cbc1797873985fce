// Rotational spring-damper-actuator: how users add one (registry.hpp).
#include "lagmb/elements/rotational_spring_damper.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo rotational_spring_damper_kind() {
  return {"rotational_spring_damper", "add_rotational_spring_damper", "forces", "rotational_spring_damper", Role::kForce,
          "Torsion spring, damper and actuator between two bodies: the torque on body_j is "
          "-k (theta - theta0) - c theta' + tau(t), theta = phi_j - phi_i; body_i gets the opposite.",
          {
              param::body("body_i", "the first body"),
              param::body("body_j", "the second body"),
              param::real("stiffness", 0.0, "N m/rad", "torsion stiffness k"),
              param::real("damping", 0.0, "N m s/rad", "damping coefficient c"),
              param::optional_real("free_angle", "rad", "free angle theta0 (default: the initial relative angle)"),
              param::function("torque", "N m", "actuator torque tau(t) on body_j"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_rotational_spring_damper(name, a.body("body_i"), a.body("body_j"), a.real("stiffness"),
                                           a.real("damping"), a.optional_real("free_angle"), a.function("torque"));
          }};
}

}  // namespace lagmb
