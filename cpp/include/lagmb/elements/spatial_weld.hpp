// The spatial kind "spatial_weld" (registry.hpp; its builder in cpp/src/elements/spatial_weld.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

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

}  // namespace lagmb
