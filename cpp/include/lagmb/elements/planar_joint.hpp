// The spatial kind "planar_joint" (registry.hpp; its builder in cpp/src/elements/planar_joint.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

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

}  // namespace lagmb
