// Bodies and particles: how users add them (registry.hpp).
#include "elements/build.hpp"
#include "lagmb/model/body.hpp"

namespace lagmb {

namespace {

// 0 is allowed (a massless body, for kinematic analysis); simulate refuses it in a dynamic run
void require_mass(double x, const std::string& element, const char* what) {
  if (!(x >= 0))
    throw ModelError(element + ": " + what + " must be positive (or 0: massless, run where its joints hold it) and finite, got " +
                     to_text(x));
}

void build_body(Model& m, const std::string& name, const Args& a) {
  const std::string label = "body '" + name + "'";
  Body b;
  b.name = name;
  b.mass = a.real("mass");
  b.inertia = a.real("inertia");
  require_mass(b.mass, label, "mass");
  require_mass(b.inertia, label, "inertia");
  b.position = a.vec2("position");
  b.angle = a.real("angle");
  b.velocity = a.vec2("velocity");
  b.angular_velocity = a.real("angular_velocity");
  m.add_body(std::move(b));
}

void build_particle(Model& m, const std::string& name, const Args& a) {
  Body b;
  b.name = name;
  b.mass = a.real("mass");
  require_mass(b.mass, "particle '" + name + "'", "mass");
  b.inertia = 0.0;
  b.position = a.vec2("position");
  b.velocity = a.vec2("velocity");
  b.particle = true;
  m.add_body(std::move(b));
}

}  // namespace

KindInfo body_kind() {
  return build::kind("body")
      .method("add_body")
      .table("bodies")
      .role(Role::kBody)
      .doc("A rigid body with coordinates x, y (its centre of mass) and phi (its angle).")
      .params({
          param::real("mass", "kg", "mass (0: massless: a dynamic run needs its joints to hold it)"),
          param::real("inertia", "kg m^2", "moment of inertia about the centre of mass"),
          param::vec2("position", Vec2::Zero(), "m", "initial position of the centre of mass"),
          param::real("angle", 0.0, "rad", "initial angle"),
          param::vec2("velocity", Vec2::Zero(), "m/s", "initial velocity of the centre of mass"),
          param::real("angular_velocity", 0.0, "rad/s", "initial angular velocity"),
      })
      .build(build_body);
}

KindInfo particle_kind() {
  return build::kind("particle")
      .method("add_particle")
      .table("particles")
      .role(Role::kBody)
      .doc("A point mass with coordinates x, y and no angle: it takes revolutes, distances, "
           "springs and forces at its centre, not joints that need an angle.")
      .params({
          param::real("mass", "kg", "mass (0: massless: a dynamic run needs its joints to hold it)"),
          param::point("position", {}, "initial position"),
          param::vec2("velocity", Vec2::Zero(), "m/s", "initial velocity"),
      })
      .build(build_particle);
}

}  // namespace lagmb
