// Joint stop: how users add one (registry.hpp).
#include "lagmb/elements/stop.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

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
          [](Model& m, const std::string& name, const Args& a) {
            m.add_stop(name, a.text("joint"), a.optional_real("lower"), a.optional_real("upper"), a.real("restitution"),
                       a.real("rest_speed"));
          }};
}

}  // namespace lagmb
