// Bodies and particles: how users add them (registry.hpp).
#include "lagmb/elements/body.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo body_kind() {
  return {"body", "add_body", "bodies", "", Role::kBody,
          "A rigid body with coordinates x, y (its centre of mass) and phi (its angle).",
          {
              param::real("mass", "kg", "mass (0: massless, for kinematic analysis only)"),
              param::real("inertia", "kg m^2", "moment of inertia about the centre of mass"),
              param::vec2("position", Vec2::Zero(), "m", "initial position of the centre of mass"),
              param::real("angle", 0.0, "rad", "initial angle"),
              param::vec2("velocity", Vec2::Zero(), "m/s", "initial velocity of the centre of mass"),
              param::real("angular_velocity", 0.0, "rad/s", "initial angular velocity"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_body(name, a.real("mass"), a.real("inertia"), a.vec2("position"), a.real("angle"), a.vec2("velocity"),
                       a.real("angular_velocity"));
          }};
}

KindInfo particle_kind() {
  return {"particle", "add_particle", "particles", "", Role::kBody,
          "A point mass with coordinates x, y and no angle: it takes revolutes, distances, "
          "springs and forces at its centre, not joints that need an angle.",
          {
              param::real("mass", "kg", "mass (0: massless, for kinematic analysis only)"),
              param::point("position", {}, "initial position"),
              param::vec2("velocity", Vec2::Zero(), "m/s", "initial velocity"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            m.add_particle(name, a.real("mass"), a.vec2("position"), a.vec2("velocity"));
          }};
}

}  // namespace lagmb
