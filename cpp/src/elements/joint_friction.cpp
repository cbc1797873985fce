// Joint friction: how users add it (registry.hpp).
#include "lagmb/elements/joint_friction.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

/// A revolute's friction acts on its relative angle with the pin radius as
/// arm; a translational's on its slide (build::joint_coordinate).
void build_joint_friction(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  JointFrictionParameters p;
  p.mu = a.real("mu");
  p.viscous = a.real("viscous");
  p.preload = a.real("preload");
  p.slip_velocity = a.real("slip_velocity");
  p.load_smoothing = a.real("load_smoothing");
  for (auto [x, key] : {std::pair{p.mu, "mu"}, std::pair{p.viscous, "viscous"}, std::pair{p.preload, "preload"}})
    build::require_nonnegative(x, label, key);
  for (auto [x, key] : {std::pair{p.slip_velocity, "slip_velocity"}, std::pair{p.load_smoothing, "load_smoothing"}})
    build::require_positive(x, label, key);
  for (const char* key : {"pin_radius", "bearing_length"})
    if (a.given(key)) build::require_positive(a.real(key), label, key);
  p.pin_radius = a.optional_real("pin_radius").value_or(0.0);
  p.bearing_length = a.optional_real("bearing_length").value_or(0.0);

  const std::string& joint = a.text("joint");
  const build::JointOf c = build::joint_coordinate(m, joint, label);
  // the friction element of the joint's kind, reading the joint's multipliers
  auto on_joint = [&](auto f, double arm) {
    f.joint_group = c.joint.group;
    f.joint_index = c.joint.index;
    f.law.p = p;
    f.law.arm = arm;
    return f;
  };
  if (c.slides) {
    if (p.pin_radius != 0.0)
      throw ModelError(label + ": pin_radius applies to revolute joints; '" + joint + "' is translational");
    auto f = on_joint(build::joining<TranslationalFriction>(m, name, c.body_i, c.body_j), 1.0);
    f.along = c.along;
    m.add_friction(std::move(f));
  } else {
    if (p.bearing_length != 0.0)
      throw ModelError(label + ": bearing_length applies to translational joints; '" + joint + "' is revolute");
    if (p.mu > 0.0 && !(p.pin_radius > 0.0))
      throw ModelError(label + ": mu = " + to_text(p.mu) + " needs the pin radius (pin_radius > 0) of revolute '" +
                       joint + "'");
    for (int b : {c.body_i, c.body_j})
      build::require_rigid(m, b, label, "cannot take revolute friction (it has no angle)");
    m.add_friction(on_joint(build::joining<RevoluteFriction>(m, name, c.body_i, c.body_j), p.pin_radius));
  }
}

}  // namespace

KindInfo joint_friction_kind() {
  return build::kind("joint_friction")
      .method("add_joint_friction")
      .table("forces")
      .type("joint_friction")
      .role(Role::kFriction)
      .doc("Friction in a revolute or translational joint: Coulomb with the load taken from the joint's "
           "own reaction, plus viscous. With sd the joint's relative rate, F = -(mu rho N + preload) "
           "sd / sqrt(sd^2 + slip_velocity^2) - viscous sd on body_j (body_i gets the opposite); revolute: "
           "rho = pin_radius, N = |joint force|; translational: rho = 1, N = |normal force| + "
           "|reaction moment| / bearing_length (the moment only if bearing_length is given).")
      .params({
          param::joint("the revolute or translational joint"),
          param::real("mu", 0.0, "", "Coulomb coefficient"),
          param::real("viscous", 0.0, "N m s/rad or N s/m", "viscous coefficient"),
          param::optional_real("pin_radius", "m", "revolute: friction arm of the load (needed with mu > 0)"),
          param::optional_real("bearing_length", "m", "translational: L in |N| + |M| / L"),
          param::real("preload", 0.0, "N m or N", "load-independent Coulomb part"),
          param::real("slip_velocity", 1e-3, "rad/s or m/s", "below it the sign function is smoothed"),
          param::real("load_smoothing", 1e-6, "N", "rounds |.| of the load near 0"),
      })
      .build(build_joint_friction)
      .effort("the friction torque (N m) or force (N) on the joint's second body, as Result.friction reads it");
}

}  // namespace lagmb
