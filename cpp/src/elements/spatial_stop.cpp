// The spatial kind "spatial_stop": how users add it (registry.hpp).
#include "lagmb/elements/spatial_stop.hpp"

#include <cmath>

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_spatial_stop(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), label);
  if (c.turns && c.slides)
    throw ModelError(label + ": '" + a.text("joint") + "' turns and slides (a cylindrical joint); a stop limits a "
                     "revolute's angle or a translational's slide");
  const StopLimits v = build::stop_limits(a, label);
  SpatialJointStop s = build::joining<SpatialJointStop>(m, name, c.body_i, c.body_j);
  s.joint = build::continuous_reading(m, a.text("joint"), c);  // (limits any distance apart)
  static_cast<StopLimits&>(s) = v;
  m.add_constraint(std::move(s));
}

}  // namespace

KindInfo spatial_stop_kind() {
  return build::kind("spatial_stop")
      .method("add_stop")
      .table("stops")
      .role(Role::kStop)
      .in_space()
      .doc("Limits a revolute's angle (its turns counted: limits any distance apart) or a translational's slide "
           "to lower <= s <= upper (their "
           "`angle` or `slide` in the initial configuration, 0 by default). Reaching a limit with approaching speed is "
           "an impact: s' reverses with Newton's restitution e and the integrator restarts. A joint that comes to rest "
           "on the limit is captured: the limit holds as a joint equation whose multiplier is the stop's force "
           "(Result.effort), until the stop would have to pull, where it releases.")
      .params(build::stop_params())
      .build(build_spatial_stop)
      .effort("the force (N) along the joint's slide or torque (N m) about its angle while the joint rests on a "
              "limit (0 while it is off its limits), positive along increasing coordinate: lam_upper - lam_lower of"
              " its two rows");
}

}  // namespace lagmb
