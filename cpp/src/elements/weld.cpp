// Weld: how users add one (registry.hpp).
#include "lagmb/elements/weld.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_weld(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  WeldJoint j = build::joining<WeldJoint>(m, name, a.body("body_i"), a.body("body_j"));
  for (int b : {j.body_i, j.body_j}) build::require_rigid(m, b, label, "cannot be welded (it has no angle)");
  j.s_i = m.local_point(j.body_i, m.initial_position(j.body_j));
  j.phi0 = m.initial_angle(j.body_j) - m.initial_angle(j.body_i);
  const int body_i = j.body_i;
  const Vec2 holds = j.s_i;
  m.add_constraint(std::move(j));
  // drawn as a link from body_i to body_j's centre of mass, where the weld holds
  m.attach(name, body_i, holds);
}

}  // namespace

KindInfo weld_kind() {
  return build::kind("weld")
      .method("add_weld")
      .table("joints")
      .type("weld")
      .role(Role::kJoint)
      .doc("Fixes body_j to body_i in their initial relative pose.")
      .params({
          param::body("body_i", "the first body"),
          param::body("body_j", "the body fixed to it"),
      })
      .build(build_weld);
}

}  // namespace lagmb
