// Spring-damper-actuator: how users add one (registry.hpp).
#include "lagmb/elements/spring_damper.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo spring_damper_kind() {
  return {"spring_damper", "add_spring_damper", "forces", "spring_damper", Role::kForce,
          "Spring, damper and actuator between point_i of body_i and point_j of body_j; the force "
          "-k (l - l0) - c l' + f(t) pushes the points apart.",
          {
              param::body("body_i", "the first body"),
              param::point("point_i", {"body_i"}, "attachment on body_i"),
              param::body("body_j", "the second body"),
              param::point("point_j", {"body_j"}, "attachment on body_j"),
              param::real("stiffness", 0.0, "N/m", "spring stiffness k"),
              param::real("damping", 0.0, "N s/m", "damping coefficient c"),
              param::optional_real("free_length", "m", "free length l0 (default: the initial distance)"),
              param::function("force", "N", "actuator force f(t), positive pushes the points apart"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_spring_damper(name, a.body("body_i"), a.vec2("point_i"), a.body("body_j"), a.vec2("point_j"),
                                a.real("stiffness"), a.real("damping"), a.optional_real("free_length"), a.function("force"));
          }};
}

}  // namespace lagmb
