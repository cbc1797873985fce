// The bushing: how users add one (registry.hpp).
#include "elements/build.hpp"
#include "lagmb/elements/bushing.hpp"

namespace lagmb {

namespace {

void build_bushing(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  auto e = build::joining<Bushing>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec3 at = a.vec3("at");
  e.s_i = m.local_point(e.body_i, at);
  e.s_j = m.local_point(e.body_j, at);
  for (int k = 0; k < 3; ++k) {
    e.axes_i[k] = m.local_direction(e.body_i, Vec3::Unit(k));
    e.axes_j[k] = m.local_direction(e.body_j, Vec3::Unit(k));
  }
  e.stiffness = a.vec3("stiffness");
  e.damping = a.vec3("damping");
  e.rotational_stiffness = a.vec3("rotational_stiffness");
  e.rotational_damping = a.vec3("rotational_damping");
  for (const auto& [v, what] : {std::pair{e.stiffness, "stiffness"}, {e.damping, "damping"},
                                {e.rotational_stiffness, "rotational_stiffness"},
                                {e.rotational_damping, "rotational_damping"}})
    if (!((v.array() >= 0.0).all())) throw ModelError(label + ": " + what + " must be >= 0, got " + to_text(v));
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo bushing_kind() {
  return build::kind("bushing")
      .method("add_bushing")
      .table("forces")
      .type("bushing")
      .role(Role::kForce)
      .in_space()
      .doc("Six-axis spring-damper between frames at `at` fixed in body_i and body_j (global axes of "
           "the initial configuration): force -k delta - c delta' along each axis, torque -k rho - c "
           "rho' about each (rho: the relative rotation, sin of the angle for a turn about one axis).")
      .params({param::body("body_i", "the first body"), param::body("body_j", "the second body"),
               param::point3("at", {"body_i", "body_j"}, "the frames' origin"),
               param::vec3("stiffness", Vec3::Zero(), "N/m", "translational stiffness (x, y, z)"),
               param::vec3("damping", Vec3::Zero(), "N s/m", "translational damping (x, y, z)"),
               param::vec3("rotational_stiffness", Vec3::Zero(), "N m/rad", "rotational stiffness (x, y, z)"),
               param::vec3("rotational_damping", Vec3::Zero(), "N m s/rad", "rotational damping (x, y, z)")})
      .build(build_bushing)
      .effort("the force (N) on body_j along the axes of the frame fixed in body_i and the torque (N m) about them:"
              " -k s - c s' for s = delta and rho (the torque for small relative turns)",
              {"x", "y", "z", "torque.x", "torque.y", "torque.z"});
}

}  // namespace lagmb
