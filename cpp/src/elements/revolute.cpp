// Revolute joint: how users add one (registry.hpp).
#include "lagmb/elements/revolute.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo revolute_kind() {
  return {"revolute", "add_revolute", "joints", "revolute", Role::kJoint,
          "Pins body_i and body_j together at the global point `at` (in the initial configuration), "
          "or at `local_i` on body_i and `local_j` on body_j (each in its body's own axes).",
          {
              param::body("body_i", "the first body (the reaction is the force on it)"),
              param::body("body_j", "the second body"),
              param::optional_point("at", {"body_i", "body_j"}, "the joint point"),
              param::local_point("local_i", "body_i", "the joint point on body_i (instead of `at`)"),
              param::local_point("local_j", "body_j", "the joint point on body_j (instead of `at`)"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            const int i = a.body("body_i"), j = a.body("body_j");
            const bool local_i = a.given("local_i"), local_j = a.given("local_j");
            if (a.given("at")) {
              if (local_i || local_j)
                throw ModelError("revolute '" + name + "': give either 'at' or 'local_i' and 'local_j'");
              m.add_revolute(name, i, j, a.vec2("at"));
            } else if (local_i && local_j) {
              m.add_revolute_local(name, i, j, a.vec2("local_i"), a.vec2("local_j"));
            } else {
              throw ModelError("revolute '" + name + "': give the joint point 'at' (global) or both 'local_i' and 'local_j'");
            }
          }};
}

}  // namespace lagmb
