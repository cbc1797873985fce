// Circle-line contact: how users add one (registry.hpp).
#include "lagmb/elements/contact.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo contact_kind() {
  return {"contact", "add_contact", "forces", "contact", Role::kContact,
          "Contact between a circle on circle_body and the line through `point` along `direction` on "
          "line_body; the circle belongs on the left of the direction. With penetration d > 0 the normal "
          "force is k d^1.5 (1 + 8 (1 - e) / (5 e) d' / v_impact) (Hunt-Crossley damping calibrated to "
          "the restitution e, Flores et al. 2011), v_impact the approach speed at contact onset; "
          "Coulomb friction -mu F_n v_t / sqrt(v_t^2 + v_s^2). Onset and release are events "
          "(Result.events) where the integrator restarts.",
          {
              param::body("circle_body", "the body carrying the circle"),
              param::point("center", {"circle_body"}, "centre of the circle"),
              param::real("radius", "m", "radius of the circle"),
              param::body("line_body", "the body carrying the line (or the ground)"),
              param::point("point", {}, "a point of the line"),
              param::direction("direction", "direction of the line (the circle on its left)"),
              param::real("stiffness", "N/m^1.5", "contact stiffness k"),
              param::real("restitution", "", "coefficient of restitution e in (0, 1]"),
              param::real("friction", 0.0, "", "Coulomb coefficient mu"),
              param::real("slip_velocity", 1e-4, "m/s", "v_s below which friction is smoothed"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_contact(name, a.body("circle_body"), a.vec2("center"), a.real("radius"), a.body("line_body"),
                          a.vec2("point"), a.vec2("direction"), a.real("stiffness"), a.real("restitution"),
                          a.real("friction"), a.real("slip_velocity"));
          }};
}

}  // namespace lagmb
