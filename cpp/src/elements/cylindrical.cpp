// The spatial kind "cylindrical": how users add it (registry.hpp). Points and axes
// are given globally in the initial configuration and stored in body axes.
#include "lagmb/elements/cylindrical.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_cylindrical(Model& m, const std::string& name, const Args& a) {
  const Vec3 axis = build::unit_direction(a, "axis", build::label(a, name));
  auto j = build::spatial_joint<CylindricalJoint>(m, name, a, axis);
  j.a_j = m.local_direction(j.body_j, axis);
  j.f_j = m.local_direction(j.body_j, m.body_direction(j.body_i, j.f_i));
  m.add_constraint(std::move(j));
  build::count_turns(m, name);
}

}  // namespace

KindInfo cylindrical_kind() {
  return build::kind("cylindrical")
      .method("add_cylindrical")
      .table("joints")
      .type("cylindrical")
      .role(Role::kJoint)
      .in_space()
      .coordinate(CoordinateKind::kAngleAndSlide)
      .doc("body_j slides along and turns about the line through `at` along `axis`, fixed in body_i "
           "(4 equations).")
      .params({param::body("body_i", "the first body"), param::body("body_j", "the second body"),
               param::point3("at", {"body_i", "body_j"}, "a point on the axis"),
               param::direction3("axis", "the axis")})
      .build(build_cylindrical);
}

}  // namespace lagmb
