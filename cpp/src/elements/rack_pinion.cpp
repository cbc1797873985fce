// Rack and pinion: how users add one (registry.hpp).
#include "lagmb/elements/rack_pinion.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo rack_pinion_kind() {
  return {"rack_pinion", "add_rack_pinion", "joints", "rack_pinion", Role::kJoint,
          "The pinion (centre at its centre of mass) rolls without slipping on the rack's pitch line "
          "along `axis`; the pinion is on the left of the axis (axis turned +90 deg points from the rack "
          "to it).",
          {
              param::body("pinion", "the pinion"),
              param::body("rack", "the rack (or the ground)"),
              param::real("radius", "m", "pitch radius of the pinion"),
              param::direction("axis", "direction of the rack's pitch line"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_rack_pinion(name, a.body("pinion"), a.body("rack"), a.real("radius"), a.vec2("axis"));
          }};
}

}  // namespace lagmb
