// What every spatial joint kind shares (one kind per header beside this one):
// each is a few rows of the terms of spatial_terms.hpp. All
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

#include "lagmb/model/joint_coordinate.hpp"
#include "lagmb/spatial_terms.hpp"

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
  /// The joint point on body j, global (reactions about the joint; a weld's
  /// is body j's centre of mass, a distance's the link's end on body j).
  Vec3 origin(const spatial::Loc& c, double) const { return c.segment<3>(7) + euler::rotate(c.segment<4>(10), s_j); }

  /// The joint's scalar coordinate from its point and triple, with f_j
  /// body j's copy of f (joint_coordinate.hpp).
  JointCoordinate joint_coordinate(bool turns, bool slides, const Vec3& f_j) const {
    JointCoordinate c;
    c.turns = turns;
    c.slides = slides;
    c.body_i = body_i;
    c.body_j = body_j;
    c.s_i = s_i;
    c.s_j = s_j;
    c.f_i = f_i;
    c.g_i = g_i;
    c.a_i = a_i;
    c.f_j = f_j;
    return c;
  }
};

}  // namespace lagmb
