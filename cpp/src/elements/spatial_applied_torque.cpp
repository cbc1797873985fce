// The spatial applied torque: how users add one (registry.hpp).
#include "elements/build.hpp"
#include "lagmb/elements/spatial_applied_torque.hpp"

namespace lagmb {

namespace {

void build_spatial_torque(Model& m, const std::string& name, const Args& a) {
  auto e = build::joining<SpatialAppliedTorque>(m, name, a.body("body"), kGround);
  e.components = build::drive_triple(m, a.function_triple("torque"));
  e.local = a.flag("local");
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo spatial_torque_kind() {
  return build::kind("spatial_torque")
      .method("add_torque")
      .table("forces")
      .type("torque")
      .role(Role::kForce)
      .in_space()
      .doc("A torque on a body, each component a number or a function of time.")
      .params({param::body("body", "the body turned"), param::function_triple("torque", "N m", "(tx, ty, tz)"),
               param::flag("local", false, "components in the body's axes, turning with it")})
      .build(build_spatial_torque)
      .effort("the torque (tx, ty, tz) (N m) in global axes as applied (turned with the body where local)",
              {"x", "y", "z"});
}

}  // namespace lagmb
