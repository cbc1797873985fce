// Circle-line contact: how users add one (registry.hpp).
#include "lagmb/elements/contact.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

/// One element in two groups: its force (normal and friction) and its
/// events (onset and release), sharing one slot of run state.
void build_contact(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  CircleLineContact c = build::joining<CircleLineContact>(m, name, a.body("circle_body"), a.body("line_body"));
  c.radius = a.real("radius");
  build::require_positive(c.radius, label, "radius");
  c.law = build::contact_law(a, label);
  build::require_on_particle(m, c.body_i, a.vec2("center"), label);
  c.s_c = m.local_point(c.body_i, a.vec2("center"));
  c.s_p = m.local_point(c.body_j, a.vec2("point"));
  c.u = build::local_direction(m, c.body_j, a.vec2("direction"), label);
  m.reserve_run_state(c);  // one offset for both entries of the same contact
  m.add_event_element(c, false);
  m.add_force_element(std::move(c));
}

}  // namespace

KindInfo contact_kind() {
  KindInfo k = build::kind("contact")
      .method("add_contact")
      .table("forces")
      .type("contact")
      .role(Role::kContact)
      .doc("Contact between a circle on circle_body and the line through `point` along `direction` on "
           "line_body; the circle belongs on the left of the direction. With penetration d > 0 the normal "
           "force is k d^1.5 (1 + c d' / v_impact) (Hunt-Crossley damping with c (1 + e) = ln((1 + c) / (1 - c e)): "
           "an impact under the contact force alone rebounds at exactly e times its speed), v_impact the "
           "approach speed at contact onset (at least 1e-3 m/s); "
           "Coulomb friction -mu F_n v_t / sqrt(v_t^2 + v_s^2). Onset and release are events "
           "(Result.events) where the integrator restarts.")
      .params({
          param::body("circle_body", "the body carrying the circle"),
          param::point("center", {"circle_body"}, "centre of the circle"),
          param::real("radius", "m", "radius of the circle"),
          param::body("line_body", "the body carrying the line (or the ground)"),
          param::point("point", {}, "a point of the line"),
          param::direction("direction", "direction of the line (the circle on its left)"),
      })
      .build(build_contact);
  for (Param& p : build::contact_law_params()) k.params.push_back(std::move(p));
  return k;
}

}  // namespace lagmb
