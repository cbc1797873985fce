// The scalar coordinate of a joint: what drivers, stops, friction and
// rotational springs act on. Each joint kind that has one declares it next
// to its equations; constraint_group.hpp hands it out by element.
#pragma once

#include "lagmb/projected_offset.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// The scalar coordinate a joint has (its angle, its slide or both), which
/// drivers, stops, friction and rotational springs act on. A joint kind
/// that has one says what it is, in its own header:
///   JointCoordinate coordinate() const
/// (what each field means for it below); kinds without one declare nothing.
struct JointCoordinate {
  bool turns = false, slides = false;
  int body_i = -1, body_j = -1;
  /// plane, slide: the offset of body j's joint point along the axis
  /// (w: the axis in body i's axes); the angle is phi_j - phi_i
  ProjectedOffset along;
  /// space: the joint point in each body's axes, the triple (f, g, a) in
  /// body i's axes (a the axis) and f_j, body j's copy of f (the angle
  /// turns f_j about a from f towards g)
  Vec3 s_i = Vec3::Zero(), s_j = Vec3::Zero();
  Vec3 f_i = Vec3::UnitX(), g_i = Vec3::UnitY(), a_i = Vec3::UnitZ(), f_j = Vec3::UnitX();
};

}  // namespace lagmb
