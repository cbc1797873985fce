// Distance (massless link): how users add one (registry.hpp).
#include "lagmb/elements/distance.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo distance_kind() {
  return {"distance", "add_distance", "joints", "distance", Role::kJoint,
          "A massless rigid link of `length` between point_i of body_i and point_j of body_j.",
          {
              param::body("body_i", "the first body"),
              param::point("point_i", {"body_i"}, "the link's end on body_i"),
              param::body("body_j", "the second body"),
              param::point("point_j", {"body_j"}, "the link's end on body_j"),
              param::optional_real("length", "m", "the link's length (default: the initial distance)"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_distance(name, a.body("body_i"), a.vec2("point_i"), a.body("body_j"), a.vec2("point_j"),
                           a.optional_real("length"));
          }};
}

}  // namespace lagmb
