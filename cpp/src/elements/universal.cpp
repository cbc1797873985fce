// The spatial kind "universal": how users add it (registry.hpp). Points and axes
// are given globally in the initial configuration and stored in body axes.
#include "lagmb/elements/universal.hpp"

#include <cmath>

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_universal(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const Vec3 axis_i = build::unit_direction(a, "axis_i", label), axis_j = build::unit_direction(a, "axis_j", label);
  if (!(std::abs(axis_i.dot(axis_j)) <= 1e-9))
    throw ModelError(label + ": axis_i and axis_j must be perpendicular (their cosine is " +
                     to_text(axis_i.dot(axis_j)) + ")");
  // joint axes (b, a x b, a): a = axis_i, f = axis_j
  auto j = build::spatial_joint<UniversalJoint>(m, name, a, axis_i);
  j.f_i = m.local_direction(j.body_i, axis_j);
  j.g_i = m.local_direction(j.body_i, axis_i.cross(axis_j));
  j.b_j = m.local_direction(j.body_j, axis_j);
  m.add_constraint(std::move(j));
}

}  // namespace

KindInfo universal_kind() {
  return build::kind("universal")
      .method("add_universal")
      .table("joints")
      .type("universal")
      .role(Role::kJoint)
      .in_space()
      .doc("Hooke joint at `at`: body_i turns about axis_i (fixed in it), body_j about axis_j (fixed in "
           "it), the two perpendicular (4 equations).")
      .params({param::body("body_i", "the first body"), param::body("body_j", "the second body"),
               param::point3("at", {"body_i", "body_j"}, "the centre of the cross"),
               param::direction3("axis_i", "the cross's axis fixed in body_i"),
               param::direction3("axis_j", "the cross's axis fixed in body_j (perpendicular to axis_i)")})
      .build(build_universal);
}

}  // namespace lagmb
