// Applied forces and torques: how users add them (registry.hpp).
#include "lagmb/elements/applied_force.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_force(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  AppliedForce e = build::joining<AppliedForce>(m, name, a.body("body"), kGround);
  if (const std::optional<Vec2> point = a.optional_vec2("point")) {
    build::require_on_particle(m, e.body_i, *point, label);
    e.s = m.local_point(e.body_i, *point);
  }
  const auto [fx, fy] = a.function_pair("force");
  e.fx = build::drive(m, fx);
  e.fy = build::drive(m, fy);
  e.local = a.flag("local");
  m.add_force_element(std::move(e));
}

void build_torque(Model& m, const std::string& name, const Args& a) {
  AppliedTorque e = build::joining<AppliedTorque>(m, name, a.body("body"), kGround);
  build::require_rigid(m, e.body_i, build::label(a, name), "cannot take a torque");
  e.torque = build::drive(m, a.function("torque"));
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo force_kind() {
  return build::kind("force")
      .method("add_force")
      .table("forces")
      .type("force")
      .role(Role::kForce)
      .doc("A force on a body: (fx, fy) of numbers or time functions, or a callable t -> (fx, fy), "
           "applied at `point`.")
      .params({
          param::body("body", "the body pushed"),
          param::function_pair("force", "N", "(fx, fy)"),
          param::optional_point("point", {"body"}, "where it acts (default: the centre of mass)"),
          param::flag("local", false, "components in the body's axes, turning with it"),
      })
      .build(build_force)
      .effort("the force (fx, fy) (N) in global axes as applied (turned with the body where local)",
              {"x", "y"});
}

KindInfo torque_kind() {
  return build::kind("torque")
      .method("add_torque")
      .table("forces")
      .type("torque")
      .role(Role::kForce)
      .doc("A pure torque on a body.")
      .params({
          param::body("body", "the body turned"),
          param::function("torque", "N m", "the torque: a number, time function or callable", true),
      })
      .build(build_torque)
      .effort("the torque (N m) as applied");
}

}  // namespace lagmb
