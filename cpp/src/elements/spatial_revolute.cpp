// The spatial kind "spatial_revolute": how users add it (registry.hpp). Points and axes
// are given globally in the initial configuration and stored in body axes.
#include "lagmb/elements/spatial_revolute.hpp"

#include <cmath>

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_spatial_revolute(Model& m, const std::string& name, const Args& a) {
  const Vec3 axis = build::unit_direction(a, "axis", build::label(a, name));
  auto j = build::spatial_joint<SpatialRevoluteJoint>(m, name, a, axis);
  j.a_j = m.local_direction(j.body_j, axis);
  // body j's copy of f, turned by the joint's angle in the initial configuration
  const double angle = a.real("angle");
  const Vec3 f = m.body_direction(j.body_i, j.f_i), g = m.body_direction(j.body_i, j.g_i);
  j.f_j = m.local_direction(j.body_j, std::cos(angle) * f + std::sin(angle) * g);
  m.add_constraint(std::move(j));
  build::count_turns(m, name, angle);
}

}  // namespace

KindInfo spatial_revolute_kind() {
  return build::kind("spatial_revolute")
      .method("add_revolute")
      .table("joints")
      .type("revolute")
      .role(Role::kJoint)
      .in_space()
      .coordinate(CoordinateKind::kAngle)
      .doc("Hinge: body_j turns about the line through `at` along `axis`, fixed in body_i (5 equations).")
      .params({param::body("body_i", "the first body (the multipliers of the point are the force on it)"),
               param::body("body_j", "the second body"),
               param::point3("at", {"body_i", "body_j"}, "a point on the axis"),
               param::direction3("axis", "the hinge axis"),
               param::real("angle", 0.0, "rad",
                           "the joint's angle in the initial configuration (what its drivers, stops and "
                           "springs read there)")})
      .build(build_spatial_revolute);
}

}  // namespace lagmb
