// Pin in slot: how users add one (registry.hpp).
#include "lagmb/elements/pin_in_slot.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo pin_in_slot_kind() {
  return {"pin_in_slot", "add_pin_in_slot", "joints", "pin_in_slot", Role::kJoint,
          "The pin of body_j at `at` moves along the slot of body_i through `at` in direction `axis`; "
          "rotation is free.",
          {
              param::body("body_i", "the body with the slot"),
              param::body("body_j", "the body with the pin"),
              param::point("at", {"body_i", "body_j"}, "the pin, on the slot line"),
              param::direction("axis", "direction of the slot"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_pin_in_slot(name, a.body("body_i"), a.body("body_j"), a.vec2("at"), a.vec2("axis"));
          }};
}

}  // namespace lagmb
