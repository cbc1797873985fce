// Spatial joints: each a few rows of the terms of spatial_terms.hpp. All
// vectors and points are stored in their body's axes (the builders convert
// the global ones of the initial configuration). With
//   d = (r_j + A_j s_j) - (r_i + A_i s_i)
// the vector from the joint point on body i to the one on body j, the rows
// that hold d = 0 have multipliers equal to the force the joint puts on
// body i (the generalized force is -Phi_c^T lam), as in the plane.
// Joint axes (reactions in frame="joint"): A_i (f, g, a), the joint's
// triple fixed in body i, with a along its axis or normal.
#pragma once

#include <string>

#include "lagmb/elements/spatial_terms.hpp"

namespace lagmb {

namespace spatial {
/// The joint's triple (f, g, a) fixed in body i, in global axes.
inline Mat3 joint_axes(const Loc& c, const Vec3& f, const Vec3& g, const Vec3& a) {
  const Mat3 A = euler::A(c.segment<4>(3));
  Mat3 E;
  E << A * f, A * g, A * a;
  return E;
}
}  // namespace spatial

/// What every spatial joint holds: its bodies, the joint point in each
/// body's axes, and a triple (f, g, a) in body i's axes (a: the axis or
/// normal; f, g across it, f x g = a).
struct SpatialJointBase {
  static constexpr bool time_dependent = false;
  std::string name;
  int body_i = -1, body_j = -1;
  Vec3 s_i = Vec3::Zero(), s_j = Vec3::Zero();
  Vec3 f_i = Vec3::UnitX(), g_i = Vec3::UnitY(), a_i = Vec3::UnitZ();

  spatial::VectorTerm offset(const spatial::Loc& c, const spatial::Want& want) const {
    return spatial::minus(spatial::body_point(c, spatial::kBodyJ, s_j, want),
                          spatial::body_point(c, spatial::kBodyI, s_i, want));
  }
  Mat3 axes(const spatial::Loc& c, double) const { return spatial::joint_axes(c, f_i, g_i, a_i); }
};

/// Spherical joint: d = 0 (3 rows). lam: the force on body i.
struct SphericalJoint : SpatialJointBase, spatial::TermJoint<SphericalJoint, 3> {
  static constexpr const char* kind = "spherical";
  spatial::Terms<3> terms(const spatial::Loc& c, const spatial::Want& want) const {
    const spatial::VectorTerm d = offset(c, want);
    return {spatial::component(d, 0), spatial::component(d, 1), spatial::component(d, 2)};
  }
};

/// Revolute joint: d = 0 and the axis a_j of body j stays across f_i and
/// g_i of body i (Haug's dot-1 twice): 5 rows,
///   (A_i f_i) . (A_j a_j) = 0,  (A_i g_i) . (A_j a_j) = 0.
/// Its angle (drivers, rotational springs) turns f_j, body j's copy of f_i,
/// about a from f_i towards g_i.
struct SpatialRevoluteJoint : SpatialJointBase, spatial::TermJoint<SpatialRevoluteJoint, 5> {
  static constexpr const char* kind = "spatial_revolute";
  Vec3 a_j = Vec3::UnitZ(), f_j = Vec3::UnitX();  // the axis and f in body j's axes
  spatial::Terms<5> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want), aj = body_vector(c, kBodyJ, a_j, want);
    return {component(d, 0), component(d, 1), component(d, 2), dot(body_vector(c, kBodyI, f_i, want), aj, want),
            dot(body_vector(c, kBodyI, g_i, want), aj, want)};
  }
};

/// Cylindrical joint: the axes stay parallel (the revolute's two dot-1
/// rows) and d stays along them, (A_i f_i) . d = 0, (A_i g_i) . d = 0
/// (dot-2): 4 rows; it slides along and turns about a.
struct CylindricalJoint : SpatialJointBase, spatial::TermJoint<CylindricalJoint, 4> {
  static constexpr const char* kind = "cylindrical";
  Vec3 a_j = Vec3::UnitZ(), f_j = Vec3::UnitX();
  spatial::Terms<4> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want), aj = body_vector(c, kBodyJ, a_j, want);
    const VectorTerm fi = body_vector(c, kBodyI, f_i, want), gi = body_vector(c, kBodyI, g_i, want);
    return {dot(fi, aj, want), dot(gi, aj, want), dot(fi, d, want), dot(gi, d, want)};
  }
};

/// Translational joint: the cylindrical joint's rows and no turn about the
/// axis, (A_i f_i) . (A_j g_j) = 0 with g_j body j's copy of g_i: 5 rows.
struct SpatialTranslationalJoint : SpatialJointBase, spatial::TermJoint<SpatialTranslationalJoint, 5> {
  static constexpr const char* kind = "spatial_translational";
  Vec3 a_j = Vec3::UnitZ(), g_j = Vec3::UnitY();
  spatial::Terms<5> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want), aj = body_vector(c, kBodyJ, a_j, want);
    const VectorTerm fi = body_vector(c, kBodyI, f_i, want), gi = body_vector(c, kBodyI, g_i, want);
    return {dot(fi, aj, want), dot(gi, aj, want), dot(fi, d, want), dot(gi, d, want),
            dot(fi, body_vector(c, kBodyJ, g_j, want), want)};
  }
};

/// Universal (Hooke) joint: d = 0 and the cross axes stay perpendicular,
/// (A_i a_i) . (A_j b_j) = 0, a_i the axis fixed in body i and b_j the one
/// fixed in body j: 4 rows. Joint axes: (b_i, a_i x b_i, a_i) with b_i body
/// i's copy of the second axis.
struct UniversalJoint : SpatialJointBase, spatial::TermJoint<UniversalJoint, 4> {
  static constexpr const char* kind = "universal";
  Vec3 b_j = Vec3::UnitY();
  spatial::Terms<4> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want);
    return {component(d, 0), component(d, 1), component(d, 2),
            dot(body_vector(c, kBodyI, a_i, want), body_vector(c, kBodyJ, b_j, want), want)};
  }
};

/// Planar joint: body j slides and turns in a plane of body i. The normals
/// stay parallel, (A_i f_i) . (A_j n_j) = 0, (A_i g_i) . (A_j n_j) = 0, and
/// d stays in the plane, (A_i a_i) . d = 0 (a_i the normal): 3 rows.
struct PlanarJoint : SpatialJointBase, spatial::TermJoint<PlanarJoint, 3> {
  static constexpr const char* kind = "planar";
  Vec3 n_j = Vec3::UnitZ();
  spatial::Terms<3> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm nj = body_vector(c, kBodyJ, n_j, want);
    return {dot(body_vector(c, kBodyI, f_i, want), nj, want), dot(body_vector(c, kBodyI, g_i, want), nj, want),
            dot(body_vector(c, kBodyI, a_i, want), offset(c, want), want)};
  }
};

/// Weld: d = 0 at body j's centre of mass and the relative orientation
/// held, by three dot-1 rows between body i's copies (x_i, y_i, z_i) of the
/// global axes and body j's (x_j, y_j, z_j) in the initial configuration:
///   x_i . y_j = 0,  y_i . z_j = 0,  z_i . x_j = 0
/// (each 0 there, and together independent of d = 0 near it): 6 rows.
struct SpatialWeldJoint : SpatialJointBase, spatial::TermJoint<SpatialWeldJoint, 6> {
  static constexpr const char* kind = "spatial_weld";
  Vec3 x_j = Vec3::UnitX(), y_j = Vec3::UnitY(), z_j = Vec3::UnitZ();
  spatial::Terms<6> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want);
    return {component(d, 0),
            component(d, 1),
            component(d, 2),
            dot(body_vector(c, kBodyI, f_i, want), body_vector(c, kBodyJ, y_j, want), want),
            dot(body_vector(c, kBodyI, g_i, want), body_vector(c, kBodyJ, z_j, want), want),
            dot(body_vector(c, kBodyI, a_i, want), body_vector(c, kBodyJ, x_j, want), want)};
  }
};

/// Distance: a massless rigid link between the points s_i and s_j,
///   Phi = (d . d - L^2) / (2 L),
/// scaled so that lam is the link's tension (the force on body j is -lam d / L).
/// Joint axes: (f, g, d / |d|), f and g across the link.
struct SpatialDistanceJoint : SpatialJointBase, spatial::TermJoint<SpatialDistanceJoint, 1> {
  static constexpr const char* kind = "spatial_distance";
  double length = 1.0;
  spatial::Terms<1> terms(const spatial::Loc& c, const spatial::Want& want) const {
    const spatial::VectorTerm d = offset(c, want);
    spatial::ScalarTerm f = spatial::dot(d, d, want);
    f.value = (f.value - length * length) / (2.0 * length);
    f.gradient /= 2.0 * length;
    f.gradient_rate /= 2.0 * length;
    if (want.hessian) f.hessian /= 2.0 * length;
    return {f};
  }
  Mat3 axes(const spatial::Loc& c, double) const {
    Vec3 e = offset(c, {}).value;
    e = e.norm() > 0.0 ? Vec3(e.normalized()) : Vec3::UnitZ();
    Vec3 f, g;
    euler::complete_basis(e, f, g);
    Mat3 E;
    E << f, g, e;
    return E;
  }
};

}  // namespace lagmb
