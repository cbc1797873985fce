// Weld: how users add one (registry.hpp).
#include "lagmb/elements/weld.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo weld_kind() {
  return {"weld", "add_weld", "joints", "weld", Role::kJoint,
          "Fixes body_j to body_i in their initial relative pose.",
          {
              param::body("body_i", "the first body"),
              param::body("body_j", "the body fixed to it"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            const int i = a.body("body_i"), j = a.body("body_j");
            m.add_weld(name, i, j);
            // drawn as a link from body_i to body_j's centre of mass, where the weld holds
            m.attach(name, i, m.local_point(i, m.initial_position(j)));
          }};
}

}  // namespace lagmb
