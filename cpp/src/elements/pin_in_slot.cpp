// Pin in slot: how users add one (registry.hpp).
#include "lagmb/elements/pin_in_slot.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_pin_in_slot(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  PinInSlotJoint j = build::joining<PinInSlotJoint>(m, name, a.body("body_i"), a.body("body_j"));
  build::require_rigid(m, j.body_i, label, "cannot carry a slot (it has no angle)");
  build::require_on_particle(m, j.body_j, a.vec2("at"), label);
  j.across = build::across_line(m, j.body_i, j.body_j, a.vec2("at"), a.vec2("axis"), label);
  m.add_constraint(std::move(j));
}

}  // namespace

KindInfo pin_in_slot_kind() {
  return build::kind("pin_in_slot")
      .method("add_pin_in_slot")
      .table("joints")
      .type("pin_in_slot")
      .role(Role::kJoint)
      .doc("The pin of body_j at `at` moves along the slot of body_i through `at` in direction `axis`; "
           "rotation is free.")
      .params({
          param::body("body_i", "the body with the slot"),
          param::body("body_j", "the body with the pin"),
          param::point("at", {"body_i", "body_j"}, "the pin, on the slot line"),
          param::direction("axis", "direction of the slot"),
      })
      .build(build_pin_in_slot);
}

}  // namespace lagmb
