// Joint stop: how users add one (registry.hpp).
#include "lagmb/elements/stop.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_stop(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), label);
  JointStop s = build::joining<JointStop>(m, name, c.body_i, c.body_j);
  static_cast<StopLimits&>(s) = build::stop_limits(a, label);
  s.slide = c.slides;
  s.along = c.along;
  m.add_constraint(std::move(s));
}

}  // namespace

KindInfo stop_kind() {
  return build::kind("stop")
      .method("add_stop")
      .table("stops")
      .role(Role::kStop)
      .doc("Limits a joint coordinate s to lower <= s <= upper: a revolute's relative angle or a "
           "translational's slide (0 in the initial configuration). Reaching a limit with approaching "
           "speed is an impact: s' reverses with Newton's restitution e (s'+ = -e s'-) and the integrator "
           "restarts. A joint that comes to rest on the limit (restitution 0, a rebound slower than "
           "rest_speed, or bounces that would end within capture_time) is captured: the limit holds as a "
           "joint equation whose multiplier is the stop's force (Result.effort), until the stop would have "
           "to pull, where it releases. Impacts, captures and releases are listed in Result.events.")
      .params(build::stop_params())
      .build(build_stop)
      .effort("the force (N) along the joint's slide or torque (N m) about its angle while the joint rests on a "
              "limit (0 while it is off its limits), positive along increasing coordinate: lam_upper - lam_lower of"
              " its two rows");
}

}  // namespace lagmb
