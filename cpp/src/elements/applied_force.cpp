// Applied forces and torques: how users add them (registry.hpp).
#include "lagmb/elements/applied_force.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo force_kind() {
  return {"force", "add_force", "forces", "force", Role::kForce,
          "A force on a body: (fx, fy) of numbers or time functions, or a callable t -> (fx, fy), "
          "applied at `point`.",
          {
              param::body("body", "the body pushed"),
              param::function_pair("force", "N", "(fx, fy)"),
              param::optional_point("point", {"body"}, "where it acts (default: the centre of mass)"),
              param::flag("local", false, "components in the body's axes, turning with it"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            auto [fx, fy] = a.function_pair("force");
            m.add_force(name, a.body("body"), fx, fy, a.optional_vec2("point"), a.flag("local"));
          }};
}

KindInfo torque_kind() {
  return {"torque", "add_torque", "forces", "torque", Role::kForce,
          "A pure torque on a body.",
          {
              param::body("body", "the body turned"),
              param::function("torque", "N m", "the torque: a number, time function or callable", true),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_torque(name, a.body("body"), a.function("torque"));
          }};
}

}  // namespace lagmb
