// Gear pair: how users add one (registry.hpp).
#include "lagmb/elements/gear.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo gear_kind() {
  return {"gear", "add_gear", "joints", "gear", Role::kJoint,
          "Gear pair with omega_j / omega_i = ratio while the centres stay put (negative: external, "
          "positive: internal); pitch radii from the initial centre distance.",
          {
              param::body("body_i", "the first gear"),
              param::body("body_j", "the second gear"),
              param::real("ratio", "", "omega_j / omega_i with the centres fixed"),
              param::optional_point("center_i", {"body_i"}, "centre of gear i (default: its centre of mass; "
                                                            "required on the ground)"),
              param::optional_point("center_j", {"body_j"}, "centre of gear j (default: its centre of mass; "
                                                            "required on the ground)"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_gear(name, a.body("body_i"), a.body("body_j"), a.real("ratio"), a.optional_vec2("center_i"),
                       a.optional_vec2("center_j"));
          }};
}

}  // namespace lagmb
