// The spatial kind "spherical": how users add it (registry.hpp). Points and axes
// are given globally in the initial configuration and stored in body axes.
#include "lagmb/elements/spherical.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_spherical(Model& m, const std::string& name, const Args& a) {
  m.add_constraint(build::spatial_joint<SphericalJoint>(m, name, a, Vec3::UnitZ()));
}

}  // namespace

KindInfo spherical_kind() {
  return build::kind("spherical")
      .method("add_spherical")
      .table("joints")
      .type("spherical")
      .role(Role::kJoint)
      .in_space()
      .doc("Ball joint: the point `at` of body_j stays at the point `at` of body_i (3 equations).")
      .params({param::body("body_i", "the first body (the multipliers are the force on it)"),
               param::body("body_j", "the second body"), param::point3("at", {"body_i", "body_j"}, "the joint point")})
      .build(build_spherical);
}

}  // namespace lagmb
