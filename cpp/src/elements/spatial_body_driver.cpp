// The spatial body driver: how users add one (registry.hpp).
#include "elements/build.hpp"
#include "lagmb/elements/spatial_body_driver.hpp"

namespace lagmb {

namespace {

void build_spatial_body_driver(Model& m, const std::string& name, const Args& a) {
  auto d = build::joining<SpatialPositionDriver>(m, name, kGround, a.body("body"));
  const std::string& coordinate = a.text("coordinate");
  d.axis = coordinate == "x" ? 0 : coordinate == "y" ? 1 : 2;
  d.f = build::drive(m, a.function("f"));
  m.add_constraint(std::move(d));
}

}  // namespace

KindInfo spatial_body_driver_kind() {
  return build::kind("spatial_body_driver")
      .method("drive_body")
      .table("drivers")
      .type("body")
      .role(Role::kDriver)
      .in_space()
      .doc("Prescribes a coordinate \"x\", \"y\" or \"z\" of a body's centre of mass as f(t).")
      .params({param::body("body", "the body driven"),
               param::choice("coordinate", {"x", "y", "z"}, "the coordinate driven"),
               param::motion("f", "m", "the coordinate as a function of time", "function")})
      .build(build_spatial_body_driver)
      .effort("the force (N) along x, y or z that imposes the motion, positive along increasing coordinate: -lam of"
              " its row");
}

}  // namespace lagmb
