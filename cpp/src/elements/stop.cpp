// Joint stop: how users add one (registry.hpp).
#include "lagmb/elements/stop.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_stop(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), label);
  const build::StopValues v = build::stop_values(a, label);
  JointStop s = build::joining<JointStop>(m, name, c.body_i, c.body_j);
  s.slide = c.slides;
  s.along = c.along;
  s.has_lower = v.has_lower, s.has_upper = v.has_upper;
  s.lower = v.lower, s.upper = v.upper;
  s.restitution = v.restitution, s.rest_speed = v.rest_speed;
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
          build::stop_params(),
          build_stop};
}

}  // namespace lagmb
