// The spatial kind "planar_joint": how users add it (registry.hpp). Points and axes
// are given globally in the initial configuration and stored in body axes.
#include "lagmb/elements/planar_joint.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_planar(Model& m, const std::string& name, const Args& a) {
  const Vec3 normal = build::unit_direction(a, "normal", build::label(a, name));
  auto j = build::spatial_joint<PlanarJoint>(m, name, a, normal);
  j.n_j = m.local_direction(j.body_j, normal);
  m.add_constraint(std::move(j));
}

}  // namespace

KindInfo planar_joint_kind() {
  return build::kind("planar")
      .method("add_planar")
      .table("joints")
      .type("planar")
      .role(Role::kJoint)
      .in_space()
      .doc("body_j slides and turns in the plane through `at` with normal `normal`, fixed in body_i "
           "(3 equations).")
      .params({param::body("body_i", "the first body"), param::body("body_j", "the second body"),
               param::point3("at", {"body_i", "body_j"}, "a point of the plane"),
               param::direction3("normal", "the plane's normal")})
      .build(build_planar);
}

}  // namespace lagmb
