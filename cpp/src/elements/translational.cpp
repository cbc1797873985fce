// Translational joint: how users add one (registry.hpp).
#include "lagmb/elements/translational.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_translational(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  TranslationalJoint j = build::joining<TranslationalJoint>(m, name, a.body("body_i"), a.body("body_j"));
  for (int b : {j.body_i, j.body_j})
    build::require_rigid(m, b, label, "cannot take a translational joint (it has no angle)");
  j.across = build::across_line(m, j.body_i, j.body_j, a.vec2("at"), a.vec2("axis"), label);
  j.phi0 = m.initial_angle(j.body_j) - m.initial_angle(j.body_i);
  m.add_constraint(std::move(j));
}

}  // namespace

KindInfo translational_kind() {
  return build::kind("translational")
      .method("add_translational")
      .table("joints")
      .type("translational")
      .role(Role::kJoint)
      .coordinate(CoordinateKind::kSlide)
      .doc("body_j slides relative to body_i along the line through `at` with direction `axis` "
           "(global, initial configuration), without rotating.")
      .params({
          param::body("body_i", "the body carrying the guide"),
          param::body("body_j", "the sliding body"),
          param::point("at", {"body_i", "body_j"}, "a point of the sliding line"),
          param::direction("axis", "direction of sliding"),
      })
      .build(build_translational);
}

}  // namespace lagmb
