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
  return build::in_space({"spherical", "add_spherical", "joints", "spherical", Role::kJoint,
                  "Ball joint: the point `at` of body_j stays at the point `at` of body_i (3 equations).",
                  {param::body("body_i", "the first body (the multipliers are the force on it)"),
                   param::body("body_j", "the second body"), param::point3("at", {"body_i", "body_j"}, "the joint point")},
                  build_spherical});
}

}  // namespace lagmb
