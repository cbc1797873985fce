// The spatial kind "spherical" (registry.hpp; its builder in cpp/src/elements/spherical.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

/// Spherical joint: d = 0 (3 rows). lam: the force on body i.
struct SphericalJoint : SpatialJointBase, spatial::TermJoint<SphericalJoint, 3> {
  static constexpr const char* kind = "spherical";
  spatial::Terms<3> terms(const spatial::Loc& c, const spatial::Want& want) const {
    const spatial::VectorTerm d = offset(c, want);
    return {spatial::component(d, 0), spatial::component(d, 1), spatial::component(d, 2)};
  }
};

}  // namespace lagmb
