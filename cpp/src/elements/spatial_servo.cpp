// The joint servo's registry entry and builder (elements/spatial_servo.hpp).
#include "lagmb/elements/spatial_servo.hpp"

#include <cmath>

#include "elements/build.hpp"
#include "lagmb/model/model.hpp"

namespace lagmb {

namespace {

void build_spatial_joint_servo(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), label);
  auto e = build::joining<SpatialJointServo>(m, name, c.body_i, c.body_j);
  e.joint = build::continuous_reading(m, a.text("joint"), c);  // (a cylindrical joint: its angle)
  e.kp = a.real("kp");
  e.kd = a.real("kd");
  build::require_nonnegative(e.kp, label, "kp");
  build::require_nonnegative(e.kd, label, "kd");
  const bool slides = c.slides && !c.turns;
  build::require_within_largest(e.kp, label, "kp", slides ? "N/m" : "N m/rad");
  build::require_within_largest(e.kd, label, "kd", slides ? "N s/m" : "N m s/rad");
  if (const auto limit = a.optional_real("limit")) {
    if (!(*limit > 0.0)) throw ModelError(label + ": limit must be > 0 (None: no limit), got " + to_text(*limit));
    build::require_within_largest(*limit, label, "limit", slides ? "N" : "N m");
    e.limit = *limit;
  }
  e.target = build::drive(m, a.function("target"));
  e.feedforward = build::drive(m, a.function("feedforward"));
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo spatial_joint_servo_kind() {
  return build::kind("spatial_joint_servo")
      .method("add_servo")
      .table("forces")
      .type("servo")
      .role(Role::kForce)
      .in_space()
      .doc("A servo on a revolute's, cylindrical or translational joint's coordinate theta (an angle "
           "counting whole turns, or a slide): the torque (force) along it on body_j "
           "sat(kp (theta* - theta) + kd (theta*' - theta') + tau_ff), clamped to +-limit; theta* "
           "and tau_ff functions of time or mb.Input (a step: theta*' = 0). Evaluated inside the "
           "integrator: a control law needs no Python per step.")
      .params({param::joint("the revolute, cylindrical or translational joint"),
               param::motion("target", "rad or m", "the target theta*(t)", "target"),
               param::real("kp", 0.0, "N m/rad or N/m", "position gain kp"),
               param::real("kd", 0.0, "N m s/rad or N s/m", "velocity gain kd"),
               param::function("feedforward", "N m or N", "feed-forward torque tau_ff(t)"),
               param::optional_real("limit", "N m or N", "the largest |torque| (None: no limit)")})
      .build(build_spatial_joint_servo)
      .effort("the torque (N m) about the joint's axis, or force (N) along its slide, on body_j as applied: after "
              "the clamp to +-limit");
}

}  // namespace lagmb
