// Joint friction: how users add it (registry.hpp).
#include "lagmb/elements/joint_friction.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

KindInfo joint_friction_kind() {
  return {"joint_friction", "add_joint_friction", "forces", "joint_friction", Role::kFriction,
          "Friction in a revolute or translational joint: Coulomb with the load taken from the joint's "
          "own reaction, plus viscous. With sd the joint's relative rate, F = -(mu rho N + preload) "
          "sd / sqrt(sd^2 + slip_velocity^2) - viscous sd on body_j (body_i gets the opposite); revolute: "
          "rho = pin_radius, N = |joint force|; translational: rho = 1, N = |normal force| + "
          "|reaction moment| / bearing_length (the moment only if bearing_length is given).",
          {
              param::joint("the revolute or translational joint"),
              param::real("mu", 0.0, "", "Coulomb coefficient"),
              param::real("viscous", 0.0, "N m s/rad or N s/m", "viscous coefficient"),
              param::optional_real("pin_radius", "m", "revolute: friction arm of the load (needed with mu > 0)"),
              param::optional_real("bearing_length", "m", "translational: L in |N| + |M| / L"),
              param::real("preload", 0.0, "N m or N", "load-independent Coulomb part"),
              param::real("slip_velocity", 1e-3, "rad/s or m/s", "below it the sign function is smoothed"),
              param::real("load_smoothing", 1e-6, "N", "rounds |.| of the load near 0"),
          },
          [](Model& m, const std::string& name, const Args& a) {
            JointFrictionParameters p;
            p.mu = a.real("mu");
            p.viscous = a.real("viscous");
            p.preload = a.real("preload");
            p.slip_velocity = a.real("slip_velocity");
            p.load_smoothing = a.real("load_smoothing");
            for (const char* key : {"pin_radius", "bearing_length"}) {
              const std::optional<double> x = a.optional_real(key);
              if (x && !(*x > 0))
                throw ModelError("joint friction '" + name + "': " + key + " must be positive, got " + to_text(*x));
              (key[0] == 'p' ? p.pin_radius : p.bearing_length) = x.value_or(0.0);
            }
            m.add_joint_friction(name, a.text("joint"), p);
          }};
}

}  // namespace lagmb
