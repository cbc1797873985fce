// The spatial kind "spatial_translational" (registry.hpp; its builder in cpp/src/elements/spatial_translational.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

/// Translational joint: the cylindrical joint's rows and no turn about the
/// axis, (A_i f_i) . (A_j g_j) = 0 with g_j body j's copy of g_i: 5 rows.
struct SpatialTranslationalJoint : SpatialJointBase, spatial::TermJoint<SpatialTranslationalJoint, 5> {
  static constexpr const char* kind = "spatial_translational";
  Vec3 a_j = Vec3::UnitZ(), g_j = Vec3::UnitY();
  /// Its coordinate: the slide along a, (A_i a_i) . d.
  JointCoordinate coordinate() const { return joint_coordinate(false, true, Vec3::UnitX()); }
  spatial::Terms<5> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want), aj = body_vector(c, kBodyJ, a_j, want);
    const VectorTerm fi = body_vector(c, kBodyI, f_i, want), gi = body_vector(c, kBodyI, g_i, want);
    return {dot(fi, aj, want), dot(gi, aj, want), dot(fi, d, want), dot(gi, d, want),
            dot(fi, body_vector(c, kBodyJ, g_j, want), want)};
  }
};

}  // namespace lagmb
