// The spatial kind "spatial_translational": how users add it (registry.hpp). Points and axes
// are given globally in the initial configuration and stored in body axes.
#include "lagmb/elements/spatial_translational.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_spatial_translational(Model& m, const std::string& name, const Args& a) {
  const Vec3 axis = build::unit_direction(a, "axis", build::label(a, name));
  auto j = build::spatial_joint<SpatialTranslationalJoint>(m, name, a, axis);
  // body j's joint point sits `slide` along the axis from body i's
  j.s_j = m.local_point(j.body_j, Vec3(a.vec3("at") + a.real("slide") * axis));
  j.a_j = m.local_direction(j.body_j, axis);
  j.g_j = m.local_direction(j.body_j, m.body_direction(j.body_i, j.g_i));
  m.add_constraint(std::move(j));
}

}  // namespace

KindInfo spatial_translational_kind() {
  return build::kind("spatial_translational")
      .method("add_translational")
      .table("joints")
      .type("translational")
      .role(Role::kJoint)
      .in_space()
      .coordinate(CoordinateKind::kSlide)
      .doc("Prismatic joint: body_j slides along the line through `at` along `axis`, fixed in body_i, "
           "without turning (5 equations).")
      .params({param::body("body_i", "the first body"), param::body("body_j", "the second body"),
               param::point3("at", {"body_i", "body_j"}, "a point on the axis"),
               param::direction3("axis", "the sliding direction"),
               param::real("slide", 0.0, "m",
                           "the joint's slide in the initial configuration: body_j's joint point is that far "
                           "along the axis from body_i's (what its drivers, stops and springs read there)")})
      .build(build_spatial_translational);
}

}  // namespace lagmb
