// The spatial kind "spatial_stop": how users add it (registry.hpp).
#include "lagmb/elements/spatial_stop.hpp"

#include <cmath>
#include <utility>

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_spatial_stop(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), label);
  if (c.turns && c.slides)
    throw ModelError(label + ": '" + a.text("joint") + "' turns and slides (a cylindrical joint); a stop limits a "
                     "revolute's angle or a translational's slide");
  const std::optional<double> lower = a.optional_real("lower"), upper = a.optional_real("upper");
  if (!lower && !upper) throw ModelError(label + ": give a lower or an upper limit (or both)");
  if (lower && upper && !(*lower < *upper))
    throw ModelError(label + ": lower = " + to_text(*lower) + " must be below upper = " + to_text(*upper));
  // a spatial angle is read within a turn: the limits must lie within one
  if (c.turns && lower && upper && !(*upper - *lower < 2.0 * kPi))
    throw ModelError(label + ": upper - lower = " + to_text(*upper - *lower) +
                     " rad; a joint angle in space is read within one turn, so the limits must be less than "
                     "2 pi apart");
  SpatialJointStop s = build::joining<SpatialJointStop>(m, name, c.body_i, c.body_j);
  // read the angle within pi of the middle of the range (of a quarter turn inside a lone limit)
  s.center = lower && upper ? 0.5 * (*lower + *upper) : lower ? *lower + 0.5 * kPi : *upper - 0.5 * kPi;
  s.slide = c.slides;
  s.f_i = c.f_i, s.g_i = c.g_i, s.f_j = c.f_j;
  s.s_i = c.s_i, s.s_j = c.s_j, s.a_i = c.a_i;
  s.has_lower = bool(lower);
  s.has_upper = bool(upper);
  s.lower = lower.value_or(0.0);
  s.upper = upper.value_or(0.0);
  s.restitution = a.real("restitution");
  if (!(s.restitution >= 0.0 && s.restitution <= 1.0))
    throw ModelError(label + ": restitution must be in [0, 1], got " + to_text(s.restitution));
  s.rest_speed = a.real("rest_speed");
  build::require_positive(s.rest_speed, label, "rest_speed");
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
       {
           param::joint("the revolute or translational joint limited"),
           param::optional_real("lower", "rad or m", "lower limit (None: none)"),
           param::optional_real("upper", "rad or m", "upper limit (None: none)"),
           param::real("restitution", 0.0, "", "Newton's coefficient of restitution e in [0, 1]"),
           param::real("rest_speed", 1e-3, "rad/s or m/s", "rebounds slower than this stop the run"),
       },
       build_spatial_stop});
}

}  // namespace lagmb
