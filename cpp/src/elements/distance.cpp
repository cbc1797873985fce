// Distance (massless link): how users add one (registry.hpp).
#include "lagmb/elements/distance.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_distance(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  DistanceJoint j = build::joining<DistanceJoint>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec2 p_i = a.vec2("point_i"), p_j = a.vec2("point_j");
  j.length = a.optional_real("length").value_or((p_j - p_i).norm());
  build::require_positive(j.length, label, "length");
  build::require_squarable(j.length, label, "length");
  build::require_on_particle(m, j.body_i, p_i, label);
  build::require_on_particle(m, j.body_j, p_j, label);
  j.s_i = m.local_point(j.body_i, p_i);
  j.s_j = m.local_point(j.body_j, p_j);
  m.add_constraint(std::move(j));
}

}  // namespace

KindInfo distance_kind() {
  return build::kind("distance")
      .method("add_distance")
      .table("joints")
      .type("distance")
      .role(Role::kJoint)
      .doc("A massless rigid link of `length` between point_i of body_i and point_j of body_j.")
      .params({
          param::body("body_i", "the first body"),
          param::point("point_i", {"body_i"}, "the link's end on body_i"),
          param::body("body_j", "the second body"),
          param::point("point_j", {"body_j"}, "the link's end on body_j"),
          param::optional_real("length", "m", "the link's length (default: the initial distance)"),
      })
      .build(build_distance);
}

}  // namespace lagmb
