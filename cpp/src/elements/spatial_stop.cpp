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
  const build::StopValues v = build::stop_values(a, label);
  // a spatial angle is read within a turn: the limits must lie within one
  if (c.turns && v.has_lower && v.has_upper && !(v.upper - v.lower < 2.0 * kPi))
    throw ModelError(label + ": upper - lower = " + to_text(v.upper - v.lower) +
                     " rad; a joint angle in space is read within one turn, so the limits must be less than "
                     "2 pi apart");
  SpatialJointStop s = build::joining<SpatialJointStop>(m, name, c.body_i, c.body_j);
  // read the angle within pi of the middle of the range (of a quarter turn inside a lone limit)
  s.joint = build::joint_reading(c, v.has_lower && v.has_upper ? 0.5 * (v.lower + v.upper)
                                    : v.has_lower              ? v.lower + 0.5 * kPi
                                                               : v.upper - 0.5 * kPi);
  s.has_lower = v.has_lower, s.has_upper = v.has_upper;
  s.lower = v.lower, s.upper = v.upper;
  s.restitution = v.restitution, s.rest_speed = v.rest_speed;
  m.add_event_element(std::move(s));
}

}  // namespace

KindInfo spatial_stop_kind() {
  return build::in_space(
      {"spatial_stop", "add_stop", "stops", "", Role::kStop,
       "Limits a revolute's angle (limits less than 2 pi apart) or a translational's slide to lower <= s <= "
       "upper (their "
       "`angle` or `slide` in the initial configuration, 0 by default). Reaching a limit with approaching speed is an impact: s' reverses with Newton's "
       "restitution e and the integrator restarts; a rebound slower than rest_speed while the motion presses on "
       "the limit stops the run with SimulationError naming the stop (resting contact is not modelled).",
       build::stop_params(),
       build_spatial_stop});
}

}  // namespace lagmb
