// Spatial drivers and force elements: how users add them (registry.hpp).
#include "elements/build.hpp"
#include "lagmb/elements/spatial_drivers.hpp"
#include "lagmb/elements/spatial_forces.hpp"

namespace lagmb {

namespace {

/// A revolute's driver holds its angle, a translational's or cylindrical's
/// its slide.
void build_spatial_joint_driver(Model& m, const std::string& name, const Args& a) {
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), build::label(a, name));
  if (c.slides) {
    auto d = build::joining<SpatialSlideDriver>(m, name, c.body_i, c.body_j);
    d.s_i = c.s_i;
    d.s_j = c.s_j;
    d.a_i = c.a_i;
    d.f = build::drive(m, a.function("f"));
    m.add_constraint(std::move(d));
  } else {
    auto d = build::joining<SpatialAngleDriver>(m, name, c.body_i, c.body_j);
    d.f_i = c.f_i;
    d.g_i = c.g_i;
    d.f_j = c.f_j;
    d.f = build::drive(m, a.function("f"));
    m.add_constraint(std::move(d));
  }
}

void build_spatial_body_driver(Model& m, const std::string& name, const Args& a) {
  auto d = build::joining<SpatialPositionDriver>(m, name, kGround, a.body("body"));
  const std::string& coordinate = a.text("coordinate");
  d.axis = coordinate == "x" ? 0 : coordinate == "y" ? 1 : 2;
  d.f = build::drive(m, a.function("f"));
  m.add_constraint(std::move(d));
}

void build_spatial_spring_damper(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  auto e = build::joining<SpatialSpringDamper>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec3 pi = a.vec3("point_i"), pj = a.vec3("point_j");
  e.s_i = m.local_point(e.body_i, pi);
  e.s_j = m.local_point(e.body_j, pj);
  e.stiffness = a.real("stiffness");
  e.damping = a.real("damping");
  build::require_nonnegative(e.stiffness, label, "stiffness");
  build::require_nonnegative(e.damping, label, "damping");
  e.free_value = a.given("free_length") ? a.real("free_length") : (pj - pi).norm();
  build::require_nonnegative(e.free_value, label, "free_length");
  if (!((pj - pi).norm() > 0.0))
    throw ModelError(label + ": point_i and point_j coincide; the spring's direction is undefined there");
  e.actuator = build::drive(m, a.function("force"));
  m.add_force_element(std::move(e));
}

void build_spatial_rotational_spring_damper(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const build::JointOf c = build::joint_coordinate(m, a.text("joint"), label);
  if (!c.turns) throw ModelError(label + ": '" + a.text("joint") + "' does not turn (a translational joint)");
  auto e = build::joining<SpatialRotationalSpringDamper>(m, name, c.body_i, c.body_j);
  e.joint = build::continuous_reading(m, a.text("joint"), c);
  e.stiffness = a.real("stiffness");
  e.damping = a.real("damping");
  build::require_nonnegative(e.stiffness, label, "stiffness");
  build::require_nonnegative(e.damping, label, "damping");
  e.free_value = a.real("free_angle");
  e.actuator = build::drive(m, a.function("torque"));
  m.add_force_element(std::move(e));
}

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

void build_spatial_force(Model& m, const std::string& name, const Args& a) {
  auto e = build::joining<SpatialAppliedForce>(m, name, a.body("body"), kGround);
  if (a.given("point")) e.s = m.local_point(e.body_i, a.vec3("point"));
  e.components = build::drive_triple(m, a.function_triple("force"));
  e.local = a.flag("local");
  m.add_force_element(std::move(e));
}

void build_spatial_torque(Model& m, const std::string& name, const Args& a) {
  auto e = build::joining<SpatialAppliedTorque>(m, name, a.body("body"), kGround);
  e.components = build::drive_triple(m, a.function_triple("torque"));
  e.local = a.flag("local");
  m.add_force_element(std::move(e));
}

}  // namespace

KindInfo spatial_joint_driver_kind() {
  return build::with_effort(build::in_space({"spatial_joint_driver", "drive_joint", "drivers", "joint", Role::kDriver,
                   "Prescribes a revolute's angle (about its axis; its `angle` in the initial configuration, 0 "
                   "by default), or a translational's or cylindrical's slide along its axis, as f(t).",
                   {param::joint("the revolute, cylindrical or translational joint driven"),
                    param::motion("f", "rad or m", "the joint coordinate as a function of time", "function")},
                   build_spatial_joint_driver}),
      "the torque (N m) about a revolute's angle, or the force (N) along a translational's slide, that "
      "imposes the motion, positive along increasing coordinate: -lam of its row");
}

KindInfo spatial_body_driver_kind() {
  return build::with_effort(build::in_space({"spatial_body_driver", "drive_body", "drivers", "body", Role::kDriver,
                   "Prescribes a coordinate \"x\", \"y\" or \"z\" of a body's centre of mass as f(t).",
                   {param::body("body", "the body driven"),
                    param::choice("coordinate", {"x", "y", "z"}, "the coordinate driven"),
                    param::motion("f", "m", "the coordinate as a function of time", "function")},
                   build_spatial_body_driver}),
      "the force (N) along x, y or z that imposes the motion, positive along increasing coordinate: -lam of"
      " its row");
}

KindInfo spatial_spring_damper_kind() {
  return build::with_effort(
      build::in_space({"spatial_spring_damper", "add_spring_damper", "forces", "spring_damper", Role::kForce,
                   "Translational spring-damper-actuator between point_i on body_i and point_j on body_j: "
                   "F = -k (l - l0) - c l' + f(t) along the line, F > 0 pushing the points apart.",
                   {param::body("body_i", "the first body"), param::point3("point_i", {"body_i"}, "attachment on body_i"),
                    param::body("body_j", "the second body"), param::point3("point_j", {"body_j"}, "attachment on body_j"),
                    param::real("stiffness", 0.0, "N/m", "spring stiffness k"),
                    param::real("damping", 0.0, "N s/m", "damping coefficient c"),
                    param::optional_real("free_length", "m", "free length l0 (default: the initial distance)"),
                    param::function("force", "N", "actuator force f(t), positive pushes the points apart")},
                   build_spatial_spring_damper}),
      "the force F (N) along the line between the points, positive pushing them apart: -k (l - l0) - c l' +"
      " f(t), the actuator's force as applied included");
}

KindInfo spatial_rotational_spring_damper_kind() {
  return build::with_effort(
      build::in_space({"spatial_rotational_spring_damper", "add_rotational_spring_damper", "forces",
                   "rotational_spring_damper", Role::kForce,
                   "Torsion spring-damper-actuator on a revolute's (or cylindrical joint's) angle theta (its `angle` in "
                   "the initial configuration, counting whole turns: it winds through any number): torque -k "
                   "(theta - theta0) - c theta' + tau(t) about the axis on body_j.",
                   {param::joint("the revolute or cylindrical joint"),
                    param::real("stiffness", 0.0, "N m/rad", "torsion stiffness k"),
                    param::real("damping", 0.0, "N m s/rad", "damping coefficient c"),
                    param::real("free_angle", 0.0, "rad", "free angle theta0"),
                    param::function("torque", "N m", "actuator torque tau(t) on body_j")},
                   build_spatial_rotational_spring_damper}),
      "the torque (N m) about the axis on body_j: -k (theta - theta0) - c theta' + tau(t), the actuator's "
      "torque as applied included");
}

KindInfo bushing_kind() {
  return build::with_effort(build::in_space({"bushing", "add_bushing", "forces", "bushing", Role::kForce,
                   "Six-axis spring-damper between frames at `at` fixed in body_i and body_j (global axes of "
                   "the initial configuration): force -k delta - c delta' along each axis, torque -k rho - c "
                   "rho' about each (rho: the relative rotation, sin of the angle for a turn about one axis).",
                   {param::body("body_i", "the first body"), param::body("body_j", "the second body"),
                    param::point3("at", {"body_i", "body_j"}, "the frames' origin"),
                    param::vec3("stiffness", Vec3::Zero(), "N/m", "translational stiffness (x, y, z)"),
                    param::vec3("damping", Vec3::Zero(), "N s/m", "translational damping (x, y, z)"),
                    param::vec3("rotational_stiffness", Vec3::Zero(), "N m/rad", "rotational stiffness (x, y, z)"),
                    param::vec3("rotational_damping", Vec3::Zero(), "N m s/rad", "rotational damping (x, y, z)")},
                   build_bushing}),
      "the force (N) on body_j along the axes of the frame fixed in body_i and the torque (N m) about them:"
      " -k s - c s' for s = delta and rho (the torque for small relative turns)",
      {"x", "y", "z", "torque.x", "torque.y", "torque.z"});
}

KindInfo spatial_force_kind() {
  return build::with_effort(build::in_space({"spatial_force", "add_force", "forces", "force", Role::kForce,
                   "A force on a body at a point, each component a number or a function of time.",
                   {param::body("body", "the body pushed"), param::function_triple("force", "N", "(fx, fy, fz)"),
                    param::optional_point3("point", {"body"}, "where it acts (default: the centre of mass)"),
                    param::flag("local", false, "components in the body's axes, turning with it")},
                   build_spatial_force}),
      "the force (fx, fy, fz) (N) in global axes as applied (turned with the body where local)", {"x", "y", "z"});
}

KindInfo spatial_torque_kind() {
  return build::with_effort(build::in_space({"spatial_torque", "add_torque", "forces", "torque", Role::kForce,
                   "A torque on a body, each component a number or a function of time.",
                   {param::body("body", "the body turned"), param::function_triple("torque", "N m", "(tx, ty, tz)"),
                    param::flag("local", false, "components in the body's axes, turning with it")},
                   build_spatial_torque}),
      "the torque (tx, ty, tz) (N m) in global axes as applied (turned with the body where local)",
      {"x", "y", "z"});
}

}  // namespace lagmb
