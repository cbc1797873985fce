// The spatial kind "spatial_distance": how users add it (registry.hpp). Points and axes
// are given globally in the initial configuration and stored in body axes.
#include "lagmb/elements/spatial_distance.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_spatial_distance(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  SpatialDistanceJoint j = build::joining<SpatialDistanceJoint>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec3 pi = a.vec3("point_i"), pj = a.vec3("point_j");
  j.s_i = m.local_point(j.body_i, pi);
  j.s_j = m.local_point(j.body_j, pj);
  j.length = a.given("length") ? a.real("length") : (pj - pi).norm();
  build::require_positive(j.length, label, "the length");
  build::require_squarable(j.length, label, "the length");
  m.add_constraint(std::move(j));
}

}  // namespace

KindInfo spatial_distance_kind() {
  return build::kind("spatial_distance")
      .method("add_distance")
      .table("joints")
      .type("distance")
      .role(Role::kJoint)
      .in_space()
      .doc("A massless rigid link between point_i on body_i and point_j on body_j (1 equation; its "
           "multiplier is the tension).")
      .params({param::body("body_i", "the first body"),
               param::point3("point_i", {"body_i"}, "the link's end on body_i"),
               param::body("body_j", "the second body"),
               param::point3("point_j", {"body_j"}, "the link's end on body_j"),
               param::optional_real("length", "m", "the link's length (default: the initial distance)")})
      .build(build_spatial_distance);
}

}  // namespace lagmb
