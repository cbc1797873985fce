// Drivers (prescribed motion): how users add them (registry.hpp).
#include "lagmb/elements/drivers.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

/// A revolute's driver is an AngleDriver, a translational's a SlideDriver
/// (build::joint_coordinate).
void build_joint_driver(Model& m, const std::string& name, const Args& a) {
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), build::label(a, name));
  if (c.slides) {
    SlideDriver d = build::joining<SlideDriver>(m, name, c.body_i, c.body_j);
    d.along = c.along;
    d.f = build::drive(m, a.function("f"));
    m.add_constraint(std::move(d));
  } else {
    AngleDriver d = build::joining<AngleDriver>(m, name, c.body_i, c.body_j);
    d.f = build::drive(m, a.function("f"));
    m.add_constraint(std::move(d));
  }
}

void build_body_driver(Model& m, const std::string& name, const Args& a) {
  CoordinateDriver d = build::joining<CoordinateDriver>(m, name, kGround, a.body("body"));
  const std::string& coordinate = a.text("coordinate");  // one of the choices (Args::set)
  d.coordinate = coordinate == "x" ? 0 : coordinate == "y" ? 1 : 2;
  if (d.coordinate == 2) build::require_rigid(m, d.body_j, build::label(a, name), "has no angle to drive");
  d.f = build::drive(m, a.function("f"));
  m.add_constraint(std::move(d));
}

}  // namespace

KindInfo joint_driver_kind() {
  return build::kind("joint_driver")
      .method("drive_joint")
      .table("drivers")
      .type("joint")
      .role(Role::kDriver)
      .doc("Prescribes a revolute's relative angle phi_j - phi_i, or a translational's slide (0 in the "
           "initial configuration), as f(t).")
      .params({
          param::joint("the revolute or translational joint driven"),
          param::motion("f", "rad or m", "the joint coordinate as a function of time", "function"),
      })
      .build(build_joint_driver)
      .effort("the torque (N m) about a revolute's angle, or the force (N) along a translational's slide, that "
              "imposes the motion, positive along increasing coordinate: -lam of its row");
}

KindInfo body_driver_kind() {
  return build::kind("body_driver")
      .method("drive_body")
      .table("drivers")
      .type("body")
      .role(Role::kDriver)
      .doc("Prescribes a body's \"x\", \"y\" or \"angle\" as f(t).")
      .params({
          param::body("body", "the body driven"),
          param::choice("coordinate", {"x", "y", "angle"}, "the coordinate driven"),
          param::motion("f", "m or rad", "the coordinate as a function of time", "function"),
      })
      .build(build_body_driver)
      .effort("the force (N) along x or y, or the torque (N m) about the angle, that imposes the motion, positive "
              "along increasing coordinate: -lam of its row");
}

}  // namespace lagmb
