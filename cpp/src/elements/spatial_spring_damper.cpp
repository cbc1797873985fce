// The spatial spring-damper: how users add one (registry.hpp).
#include "elements/build.hpp"
#include "lagmb/elements/spatial_spring_damper.hpp"

namespace lagmb {

namespace {

void build_spatial_spring_damper(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  auto e = build::joining<SpatialSpringDamper>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec3 pi = a.vec3("point_i"), pj = a.vec3("point_j");
  e.s_i = m.local_point(e.body_i, pi);
  e.s_j = m.local_point(e.body_j, pj);
  e.stiffness = a.real("stiffness");
  e.damping = a.real("damping");
  build::require_nonnegative(e.stiffness, label, "stiffness");
  build::require_nonnegative(e.damping, label, "damping");
  e.free_value = a.given("free_length") ? a.real("free_length") : (pj - pi).norm();
  build::require_nonnegative(e.free_value, label, "free_length");
  if (!((pj - pi).norm() > 0.0))
    throw ModelError(label + ": point_i and point_j coincide; the spring's direction is undefined there");
  e.actuator = build::drive(m, a.function("force"));
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo spatial_spring_damper_kind() {
  return build::kind("spatial_spring_damper")
      .method("add_spring_damper")
      .table("forces")
      .type("spring_damper")
      .role(Role::kForce)
      .in_space()
      .doc("Translational spring-damper-actuator between point_i on body_i and point_j on body_j: "
           "F = -k (l - l0) - c l' + f(t) along the line, F > 0 pushing the points apart.")
      .params({param::body("body_i", "the first body"), param::point3("point_i", {"body_i"}, "attachment on body_i"),
               param::body("body_j", "the second body"), param::point3("point_j", {"body_j"}, "attachment on body_j"),
               param::real("stiffness", 0.0, "N/m", "spring stiffness k"),
               param::real("damping", 0.0, "N s/m", "damping coefficient c"),
               param::optional_real("free_length", "m", "free length l0 (default: the initial distance)"),
               param::function("force", "N", "actuator force f(t), positive pushes the points apart")})
      .build(build_spatial_spring_damper)
      .effort("the force F (N) along the line between the points, positive pushing them apart: -k (l - l0) - c l' +"
              " f(t), the actuator's force as applied included");
}

}  // namespace lagmb
