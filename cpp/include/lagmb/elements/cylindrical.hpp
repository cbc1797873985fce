// The spatial kind "cylindrical" (registry.hpp; its builder in cpp/src/elements/cylindrical.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

/// Cylindrical joint: the axes stay parallel (the revolute's two dot-1
/// rows) and d stays along them, (A_i f_i) . d = 0, (A_i g_i) . d = 0
/// (dot-2): 4 rows; it slides along and turns about a.
struct CylindricalJoint : SpatialJointBase, spatial::TermJoint<CylindricalJoint, 4> {
  static constexpr const char* kind = "cylindrical";
  Vec3 a_j = Vec3::UnitZ(), f_j = Vec3::UnitX();
  /// Its coordinates: the angle about a (as the revolute's) and the slide along it.
  JointCoordinate coordinate() const { return joint_coordinate(true, true, f_j); }
  spatial::Terms<4> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want), aj = body_vector(c, kBodyJ, a_j, want);
    const VectorTerm fi = body_vector(c, kBodyI, f_i, want), gi = body_vector(c, kBodyI, g_i, want);
    return {dot(fi, aj, want), dot(gi, aj, want), dot(fi, d, want), dot(gi, d, want)};
  }
};

}  // namespace lagmb
