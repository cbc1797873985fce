// The spatial joint driver: how users add one (registry.hpp).
#include "elements/build.hpp"
#include "lagmb/elements/spatial_joint_driver.hpp"

namespace lagmb {

namespace {

/// A revolute's driver holds its angle, a translational's or cylindrical's
/// its slide.
void build_spatial_joint_driver(Model& m, const std::string& name, const Args& a) {
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), build::label(a, name));
  if (c.slides) {
    auto d = build::joining<SpatialSlideDriver>(m, name, c.body_i, c.body_j);
    d.s_i = c.s_i;
    d.s_j = c.s_j;
    d.a_i = c.a_i;
    d.f = build::drive(m, a.function("f"));
    m.add_constraint(std::move(d));
  } else {
    auto d = build::joining<SpatialAngleDriver>(m, name, c.body_i, c.body_j);
    d.f_i = c.f_i;
    d.g_i = c.g_i;
    d.f_j = c.f_j;
    d.f = build::drive(m, a.function("f"));
    m.add_constraint(std::move(d));
  }
}

}  // namespace

KindInfo spatial_joint_driver_kind() {
  return build::kind("spatial_joint_driver")
      .method("drive_joint")
      .table("drivers")
      .type("joint")
      .role(Role::kDriver)
      .in_space()
      .doc("Prescribes a revolute's angle (about its axis; its `angle` in the initial configuration, 0 "
           "by default), or a translational's or cylindrical's slide along its axis, as f(t).")
      .params({param::joint("the revolute, cylindrical or translational joint driven"),
               param::motion("f", "rad or m", "the joint coordinate as a function of time", "function")})
      .build(build_spatial_joint_driver)
      .effort("the torque (N m) about a revolute's angle, or the force (N) along a translational's slide, that "
              "imposes the motion, positive along increasing coordinate: -lam of its row");
}

}  // namespace lagmb
