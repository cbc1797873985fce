// The spatial kind "universal" (registry.hpp; its builder in cpp/src/elements/universal.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

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

}  // namespace lagmb
