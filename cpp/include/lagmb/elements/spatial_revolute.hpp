// The spatial kind "spatial_revolute" (registry.hpp; its builder in cpp/src/elements/spatial_revolute.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

/// Revolute joint: d = 0 and the axis a_j of body j stays across f_i and
/// g_i of body i (Haug's dot-1 twice): 5 rows,
///   (A_i f_i) . (A_j a_j) = 0,  (A_i g_i) . (A_j a_j) = 0.
/// Its angle (drivers, rotational springs) turns f_j, body j's copy of f_i,
/// about a from f_i towards g_i.
struct SpatialRevoluteJoint : SpatialJointBase, spatial::TermJoint<SpatialRevoluteJoint, 5> {
  static constexpr const char* kind = "spatial_revolute";
  Vec3 a_j = Vec3::UnitZ(), f_j = Vec3::UnitX();  // the axis and f in body j's axes
  /// Its coordinate: the angle, f_j turned about a from f_i towards g_i.
  JointCoordinate coordinate() const { return joint_coordinate(true, false, f_j); }
  spatial::Terms<5> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want), aj = body_vector(c, kBodyJ, a_j, want);
    return {component(d, 0), component(d, 1), component(d, 2), dot(body_vector(c, kBodyI, f_i, want), aj, want),
            dot(body_vector(c, kBodyI, g_i, want), aj, want)};
  }
};

}  // namespace lagmb
