// Revolute joint: how users add one (registry.hpp).
#include "lagmb/elements/revolute.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

/// The joint point in each body's axes: from `at` (global, initial
/// configuration) or given as local_i and local_j.
void build_revolute(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  RevoluteJoint j = build::joining<RevoluteJoint>(m, name, a.body("body_i"), a.body("body_j"));
  const bool local_i = a.given("local_i"), local_j = a.given("local_j");
  if (a.given("at")) {
    if (local_i || local_j) throw ModelError(label + ": give either 'at' or 'local_i' and 'local_j'");
    j.s_i = m.local_point(j.body_i, a.vec2("at"));
    j.s_j = m.local_point(j.body_j, a.vec2("at"));
  } else if (local_i && local_j) {
    j.s_i = a.vec2("local_i");
    j.s_j = a.vec2("local_j");
  } else {
    throw ModelError(label + ": give the joint point 'at' (global) or both 'local_i' and 'local_j'");
  }
  for (auto [b, s] : {std::pair{j.body_i, j.s_i}, std::pair{j.body_j, j.s_j}})
    if (b != kGround && m.body(b).particle && s.norm() != 0.0)
      throw ModelError(label + ": particle '" + m.body(b).name +
                       "' has no extent; its joint point must be the particle itself");
  m.add_constraint(std::move(j));
}

}  // namespace

KindInfo revolute_kind() {
  return build::kind("revolute")
      .method("add_revolute")
      .table("joints")
      .type("revolute")
      .role(Role::kJoint)
      .coordinate(CoordinateKind::kAngle)
      .doc("Pins body_i and body_j together at the global point `at` (in the initial configuration), "
           "or at `local_i` on body_i and `local_j` on body_j (each in its body's own axes).")
      .params({
          param::body("body_i", "the first body (the reaction is the force on it)"),
          param::body("body_j", "the second body"),
          param::optional_point("at", {"body_i", "body_j"}, "the joint point"),
          param::local_point("local_i", "body_i", "the joint point on body_i (instead of `at`)"),
          param::local_point("local_j", "body_j", "the joint point on body_j (instead of `at`)"),
      })
      .build(build_revolute);
}

}  // namespace lagmb
