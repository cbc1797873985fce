// Rack and pinion: how users add one (registry.hpp).
#include "lagmb/elements/rack_pinion.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_rack_pinion(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  RackPinion r = build::joining<RackPinion>(m, name, a.body("pinion"), a.body("rack"));
  for (int b : {r.body_i, r.body_j})
    build::require_rigid(m, b, label, "cannot be a rack or pinion (it has no angle)");
  if (r.body_i == kGround) throw ModelError(label + ": the pinion cannot be the ground");
  r.radius = a.real("radius");
  build::require_positive(r.radius, label, "radius");
  r.along.w = build::local_direction(m, r.body_j, a.vec2("axis"), label);
  r.along.s_i = m.local_point(r.body_j, m.initial_position(r.body_i));  // on swapped coordinates: the rack is "i"
  r.along.s_j = Vec2::Zero();
  r.c0 = r.radius * (m.initial_angle(r.body_i) - m.initial_angle(r.body_j));
  m.add_constraint(std::move(r));
}

}  // namespace

KindInfo rack_pinion_kind() {
  return build::kind("rack_pinion")
      .method("add_rack_pinion")
      .table("joints")
      .type("rack_pinion")
      .role(Role::kJoint)
      .doc("The pinion (centre at its centre of mass) rolls without slipping on the rack's pitch line "
           "along `axis`; the pinion is on the left of the axis (axis turned +90 deg points from the rack "
           "to it).")
      .params({
          param::body("pinion", "the pinion"),
          param::body("rack", "the rack (or the ground)"),
          param::real("radius", "m", "pitch radius of the pinion"),
          param::direction("axis", "direction of the rack's pitch line"),
      })
      .build(build_rack_pinion);
}

}  // namespace lagmb
