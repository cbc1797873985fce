// Drivers (prescribed motion): how users add them (registry.hpp).
#include "lagmb/elements/drivers.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo joint_driver_kind() {
  return {"joint_driver", "drive_joint", "drivers", "joint", Role::kDriver,
          "Prescribes a revolute's relative angle phi_j - phi_i, or a translational's slide (0 in the "
          "initial configuration), as f(t).",
          {
              param::joint("the revolute or translational joint driven"),
              param::motion("f", "rad or m", "the joint coordinate as a function of time", "function"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.drive_joint(name, a.text("joint"), a.function("f"));
          }};
}

KindInfo body_driver_kind() {
  return {"body_driver", "drive_body", "drivers", "body", Role::kDriver,
          "Prescribes a body's \"x\", \"y\" or \"angle\" as f(t).",
          {
              param::body("body", "the body driven"),
              param::choice("coordinate", {"x", "y", "angle"}, "the coordinate driven"),
              param::motion("f", "m or rad", "the coordinate as a function of time", "function"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.drive_body(name, a.body("body"), a.text("coordinate"), a.function("f"));
          }};
}

}  // namespace lagmb
