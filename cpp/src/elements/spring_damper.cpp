// Spring-damper-actuator: how users add one (registry.hpp).
#include "lagmb/elements/spring_damper.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_spring_damper(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  SpringDamper e = build::joining<SpringDamper>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec2 p_i = a.vec2("point_i"), p_j = a.vec2("point_j");
  if (!((p_j - p_i).norm() > 0))
    throw ModelError(label + ": the two points coincide; the line of action is undefined");
  build::require_on_particle(m, e.body_i, p_i, label);
  build::require_on_particle(m, e.body_j, p_j, label);
  e.s_i = m.local_point(e.body_i, p_i);
  e.s_j = m.local_point(e.body_j, p_j);
  e.stiffness = a.real("stiffness");
  e.damping = a.real("damping");
  build::require_nonnegative(e.stiffness, label, "stiffness");
  build::require_nonnegative(e.damping, label, "damping");
  e.free_length = a.optional_real("free_length").value_or((p_j - p_i).norm());
  build::require_nonnegative(e.free_length, label, "free_length");
  e.actuator = build::drive(m, a.function("force"));
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo spring_damper_kind() {
  return build::kind("spring_damper")
      .method("add_spring_damper")
      .table("forces")
      .type("spring_damper")
      .role(Role::kForce)
      .doc("Spring, damper and actuator between point_i of body_i and point_j of body_j; the force "
           "-k (l - l0) - c l' + f(t) pushes the points apart.")
      .params({
          param::body("body_i", "the first body"),
          param::point("point_i", {"body_i"}, "attachment on body_i"),
          param::body("body_j", "the second body"),
          param::point("point_j", {"body_j"}, "attachment on body_j"),
          param::real("stiffness", 0.0, "N/m", "spring stiffness k"),
          param::real("damping", 0.0, "N s/m", "damping coefficient c"),
          param::optional_real("free_length", "m", "free length l0 (default: the initial distance)"),
          param::function("force", "N", "actuator force f(t), positive pushes the points apart"),
      })
      .build(build_spring_damper)
      .effort("the force F (N) along the line between the points, positive pushing them apart: -k (l - l0) - c l' +"
              " f(t), the actuator's force as applied included");
}

}  // namespace lagmb
