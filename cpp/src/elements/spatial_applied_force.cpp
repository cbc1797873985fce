// The spatial applied force: how users add one (registry.hpp).
#include "elements/build.hpp"
#include "lagmb/elements/spatial_applied_force.hpp"

namespace lagmb {

namespace {

void build_spatial_force(Model& m, const std::string& name, const Args& a) {
  auto e = build::joining<SpatialAppliedForce>(m, name, a.body("body"), kGround);
  if (a.given("point")) e.s = m.local_point(e.body_i, a.vec3("point"));
  e.components = build::drive_triple(m, a.function_triple("force"));
  e.local = a.flag("local");
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo spatial_force_kind() {
  return build::kind("spatial_force")
      .method("add_force")
      .table("forces")
      .type("force")
      .role(Role::kForce)
      .in_space()
      .doc("A force on a body at a point, each component a number or a function of time.")
      .params({param::body("body", "the body pushed"), param::function_triple("force", "N", "(fx, fy, fz)"),
               param::optional_point3("point", {"body"}, "where it acts (default: the centre of mass)"),
               param::flag("local", false, "components in the body's axes, turning with it")})
      .build(build_spatial_force)
      .effort("the force (fx, fy, fz) (N) in global axes as applied (turned with the body where local)",
              {"x", "y", "z"});
}

}  // namespace lagmb
