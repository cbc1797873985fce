// Translational joint: how users add one (registry.hpp).
#include "lagmb/elements/translational.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo translational_kind() {
  return {"translational", "add_translational", "joints", "translational", Role::kJoint,
          "body_j slides relative to body_i along the line through `at` with direction `axis` "
          "(global, initial configuration), without rotating.",
          {
              param::body("body_i", "the body carrying the guide"),
              param::body("body_j", "the sliding body"),
              param::point("at", {"body_i", "body_j"}, "a point of the sliding line"),
              param::direction("axis", "direction of sliding"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_translational(name, a.body("body_i"), a.body("body_j"), a.vec2("at"), a.vec2("axis"));
          }};
}

}  // namespace lagmb
