// The spatial kind "spatial_weld": how users add it (registry.hpp). Points and axes
// are given globally in the initial configuration and stored in body axes.
#include "lagmb/elements/spatial_weld.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

/// Held at body j's centre of mass; the triples are the global axes of the
/// initial configuration in each body's axes.
void build_spatial_weld(Model& m, const std::string& name, const Args& a) {
  SpatialWeldJoint j = build::joining<SpatialWeldJoint>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec3 at = m.body_position(j.body_j);
  j.s_i = m.local_point(j.body_i, at);
  j.s_j = m.local_point(j.body_j, at);
  j.f_i = m.local_direction(j.body_i, Vec3::UnitX());
  j.g_i = m.local_direction(j.body_i, Vec3::UnitY());
  j.a_i = m.local_direction(j.body_i, Vec3::UnitZ());
  j.x_j = m.local_direction(j.body_j, Vec3::UnitX());
  j.y_j = m.local_direction(j.body_j, Vec3::UnitY());
  j.z_j = m.local_direction(j.body_j, Vec3::UnitZ());
  const int body_i = j.body_i;
  const Vec3 holds = j.s_i;
  m.add_constraint(std::move(j));
  m.attach(name, body_i, holds);  // drawn as a link to body j's centre of mass
}

}  // namespace

KindInfo spatial_weld_kind() {
  return build::kind("spatial_weld")
      .method("add_weld")
      .table("joints")
      .type("weld")
      .role(Role::kJoint)
      .in_space()
      .doc("Fixes body_j to body_i in their initial relative pose (6 equations).")
      .params({param::body("body_i", "the first body"), param::body("body_j", "the body fixed to it")})
      .build(build_spatial_weld);
}

}  // namespace lagmb
