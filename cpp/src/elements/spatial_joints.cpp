// Spatial joints: how users add them (registry.hpp). Points and axes are
// given globally in the initial configuration and stored in body axes.
#include "lagmb/elements/spatial_joints.hpp"

#include <cmath>

#include "elements/build.hpp"

namespace lagmb {

namespace {

/// A unit global direction from `key`; ModelError for a zero vector.
Vec3 unit(const Args& a, const std::string& key, const std::string& label) {
  const Vec3 v = a.vec3(key);
  if (!(v.norm() > 0.0)) throw ModelError(label + ": " + key + " must be a non-zero vector, got " + to_text(v));
  return v.normalized();
}

/// A new joint of Kind at `at` with the triple (f, g, a) around the global
/// direction `axis`, all in the axes of the bodies' initial configuration.
template <class Kind>
Kind spatial_joint(Model& m, const std::string& name, const Args& a, const Vec3& axis) {
  Kind j = build::joining<Kind>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec3 at = a.vec3("at");
  j.s_i = m.local_point(j.body_i, at);
  j.s_j = m.local_point(j.body_j, at);
  Vec3 f, g;
  euler::complete_basis(axis, f, g);
  j.f_i = m.local_direction(j.body_i, f);
  j.g_i = m.local_direction(j.body_i, g);
  j.a_i = m.local_direction(j.body_i, axis);
  return j;
}

void build_spherical(Model& m, const std::string& name, const Args& a) {
  m.add_constraint(spatial_joint<SphericalJoint>(m, name, a, Vec3::UnitZ()));
}

void build_revolute(Model& m, const std::string& name, const Args& a) {
  const Vec3 axis = unit(a, "axis", build::label(a, name));
  auto j = spatial_joint<SpatialRevoluteJoint>(m, name, a, axis);
  j.a_j = m.local_direction(j.body_j, axis);
  j.f_j = m.local_direction(j.body_j, m.body_direction(j.body_i, j.f_i));
  m.add_constraint(std::move(j));
}

void build_cylindrical(Model& m, const std::string& name, const Args& a) {
  const Vec3 axis = unit(a, "axis", build::label(a, name));
  auto j = spatial_joint<CylindricalJoint>(m, name, a, axis);
  j.a_j = m.local_direction(j.body_j, axis);
  j.f_j = m.local_direction(j.body_j, m.body_direction(j.body_i, j.f_i));
  m.add_constraint(std::move(j));
}

void build_translational(Model& m, const std::string& name, const Args& a) {
  const Vec3 axis = unit(a, "axis", build::label(a, name));
  auto j = spatial_joint<SpatialTranslationalJoint>(m, name, a, axis);
  j.a_j = m.local_direction(j.body_j, axis);
  j.g_j = m.local_direction(j.body_j, m.body_direction(j.body_i, j.g_i));
  m.add_constraint(std::move(j));
}

void build_universal(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const Vec3 axis_i = unit(a, "axis_i", label), axis_j = unit(a, "axis_j", label);
  if (!(std::abs(axis_i.dot(axis_j)) <= 1e-9))
    throw ModelError(label + ": axis_i and axis_j must be perpendicular (their cosine is " +
                     to_text(axis_i.dot(axis_j)) + ")");
  // joint axes (b, a x b, a): a = axis_i, f = axis_j
  auto j = spatial_joint<UniversalJoint>(m, name, a, axis_i);
  j.f_i = m.local_direction(j.body_i, axis_j);
  j.g_i = m.local_direction(j.body_i, axis_i.cross(axis_j));
  j.b_j = m.local_direction(j.body_j, axis_j);
  m.add_constraint(std::move(j));
}

void build_planar(Model& m, const std::string& name, const Args& a) {
  const Vec3 normal = unit(a, "normal", build::label(a, name));
  auto j = spatial_joint<PlanarJoint>(m, name, a, normal);
  j.n_j = m.local_direction(j.body_j, normal);
  m.add_constraint(std::move(j));
}

/// Held at body j's centre of mass; the triples are the global axes of the
/// initial configuration in each body's axes.
void build_weld(Model& m, const std::string& name, const Args& a) {
  SpatialWeldJoint j = build::joining<SpatialWeldJoint>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec3 at = m.body_position(j.body_j);
  j.s_i = m.local_point(j.body_i, at);
  j.s_j = m.local_point(j.body_j, at);
  j.f_i = m.local_direction(j.body_i, Vec3::UnitX());
  j.g_i = m.local_direction(j.body_i, Vec3::UnitY());
  j.a_i = m.local_direction(j.body_i, Vec3::UnitZ());
  j.x_j = m.local_direction(j.body_j, Vec3::UnitX());
  j.y_j = m.local_direction(j.body_j, Vec3::UnitY());
  j.z_j = m.local_direction(j.body_j, Vec3::UnitZ());
  const int body_i = j.body_i;
  const Vec3 holds = j.s_i;
  m.add_constraint(std::move(j));
  m.attach(name, body_i, holds);  // drawn as a link to body j's centre of mass
}

void build_distance(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  SpatialDistanceJoint j = build::joining<SpatialDistanceJoint>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec3 pi = a.vec3("point_i"), pj = a.vec3("point_j");
  j.s_i = m.local_point(j.body_i, pi);
  j.s_j = m.local_point(j.body_j, pj);
  j.length = a.given("length") ? a.real("length") : (pj - pi).norm();
  build::require_positive(j.length, label, "the length");
  build::require_squarable(j.length, label, "the length");
  m.add_constraint(std::move(j));
}

KindInfo in_space(KindInfo k) {
  k.dimension = 3;
  return k;
}

}  // namespace

KindInfo spherical_kind() {
  return in_space({"spherical", "add_spherical", "joints", "spherical", Role::kJoint,
                  "Ball joint: the point `at` of body_j stays at the point `at` of body_i (3 equations).",
                  {param::body("body_i", "the first body (the multipliers are the force on it)"),
                   param::body("body_j", "the second body"), param::point3("at", {"body_i", "body_j"}, "the joint point")},
                  build_spherical});
}

KindInfo spatial_revolute_kind() {
  return in_space({"spatial_revolute", "add_revolute", "joints", "revolute", Role::kJoint,
                  "Hinge: body_j turns about the line through `at` along `axis`, fixed in body_i (5 equations).",
                  {param::body("body_i", "the first body (the multipliers of the point are the force on it)"),
                   param::body("body_j", "the second body"), param::point3("at", {"body_i", "body_j"}, "a point on the axis"),
                   param::direction3("axis", "the hinge axis")},
                  build_revolute});
}

KindInfo cylindrical_kind() {
  return in_space({"cylindrical", "add_cylindrical", "joints", "cylindrical", Role::kJoint,
                  "body_j slides along and turns about the line through `at` along `axis`, fixed in body_i "
                  "(4 equations).",
                  {param::body("body_i", "the first body"), param::body("body_j", "the second body"),
                   param::point3("at", {"body_i", "body_j"}, "a point on the axis"),
                   param::direction3("axis", "the axis")},
                  build_cylindrical});
}

KindInfo spatial_translational_kind() {
  return in_space({"spatial_translational", "add_translational", "joints", "translational", Role::kJoint,
                  "Prismatic joint: body_j slides along the line through `at` along `axis`, fixed in body_i, "
                  "without turning (5 equations).",
                  {param::body("body_i", "the first body"), param::body("body_j", "the second body"),
                   param::point3("at", {"body_i", "body_j"}, "a point on the axis"),
                   param::direction3("axis", "the sliding direction")},
                  build_translational});
}

KindInfo universal_kind() {
  return in_space({"universal", "add_universal", "joints", "universal", Role::kJoint,
                  "Hooke joint at `at`: body_i turns about axis_i (fixed in it), body_j about axis_j (fixed in "
                  "it), the two perpendicular (4 equations).",
                  {param::body("body_i", "the first body"), param::body("body_j", "the second body"),
                   param::point3("at", {"body_i", "body_j"}, "the centre of the cross"),
                   param::direction3("axis_i", "the cross's axis fixed in body_i"),
                   param::direction3("axis_j", "the cross's axis fixed in body_j (perpendicular to axis_i)")},
                  build_universal});
}

KindInfo planar_joint_kind() {
  return in_space({"planar", "add_planar", "joints", "planar", Role::kJoint,
                  "body_j slides and turns in the plane through `at` with normal `normal`, fixed in body_i "
                  "(3 equations).",
                  {param::body("body_i", "the first body"), param::body("body_j", "the second body"),
                   param::point3("at", {"body_i", "body_j"}, "a point of the plane"),
                   param::direction3("normal", "the plane's normal")},
                  build_planar});
}

KindInfo spatial_weld_kind() {
  return in_space({"spatial_weld", "add_weld", "joints", "weld", Role::kJoint,
                  "Fixes body_j to body_i in their initial relative pose (6 equations).",
                  {param::body("body_i", "the first body"), param::body("body_j", "the body fixed to it")},
                  build_weld});
}

KindInfo spatial_distance_kind() {
  return in_space({"spatial_distance", "add_distance", "joints", "distance", Role::kJoint,
                  "A massless rigid link between point_i on body_i and point_j on body_j (1 equation; its "
                  "multiplier is the tension).",
                  {param::body("body_i", "the first body"), param::point3("point_i", {"body_i"}, "the link's end on body_i"),
                   param::body("body_j", "the second body"), param::point3("point_j", {"body_j"}, "the link's end on body_j"),
                   param::optional_real("length", "m", "the link's length (default: the initial distance)")},
                  build_distance});
}

}  // namespace lagmb
