// Joint stop: how users add one (registry.hpp).
#include "lagmb/elements/stop.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_stop(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), label);
  const std::optional<double> lower = a.optional_real("lower"), upper = a.optional_real("upper");
  if (!lower && !upper) throw ModelError(label + ": give a lower or an upper limit (or both)");
  if (lower && upper && !(*lower < *upper))
    throw ModelError(label + ": lower = " + to_text(*lower) + " must be below upper = " + to_text(*upper));
  JointStop s = build::joining<JointStop>(m, name, c.body_i, c.body_j);
  s.slide = c.slides;
  s.along = c.along;
  s.has_lower = bool(lower);
  s.has_upper = bool(upper);
  s.lower = lower.value_or(0.0);
  s.upper = upper.value_or(0.0);
  s.restitution = a.real("restitution");
  if (!(s.restitution >= 0.0 && s.restitution <= 1.0))
    throw ModelError(label + ": restitution must be in [0, 1], got " + to_text(s.restitution));
  // 0 would let rebounds shrink to rounding level (Zeno) before the rest test fires
  s.rest_speed = a.real("rest_speed");
  build::require_positive(s.rest_speed, label, "rest_speed");
  m.add_event_element(std::move(s));
}

}  // namespace

KindInfo stop_kind() {
  return {"stop", "add_stop", "stops", "", Role::kStop,
          "Limits a joint coordinate s to lower <= s <= upper: a revolute's relative angle or a "
          "translational's slide (0 in the initial configuration). Reaching a limit with approaching "
          "speed is an impact: s' reverses with Newton's restitution e (s'+ = -e s'-) and the integrator "
          "restarts; a rebound slower than rest_speed while the motion presses on the limit stops the "
          "run with SimulationError naming the stop (resting contact is not modelled). Impacts are "
          "listed in Result.events.",
          {
              param::joint("the revolute or translational joint limited"),
              param::optional_real("lower", "rad or m", "lower limit (None: none)"),
              param::optional_real("upper", "rad or m", "upper limit (None: none)"),
              param::real("restitution", 0.0, "", "Newton's coefficient of restitution e in [0, 1]"),
              param::real("rest_speed", 1e-3, "rad/s or m/s", "rebounds slower than this stop the run"),
          },
          build_stop};
}

}  // namespace lagmb
