// A translational spring-damper-actuator between two points of two bodies.
#pragma once

#include "lagmb/elements/spatial_force_base.hpp"

namespace lagmb {

/// Translational spring-damper-actuator between the points s_i and s_j, on
/// l = |d| (s0: the free length): F > 0 pushes the points apart.
struct SpatialSpringDamper : ScalarSpringDamper<SpatialSpringDamper> {
  static constexpr const char* kind = "spatial_spring_damper";
  Vec3 s_i = Vec3::Zero(), s_j = Vec3::Zero();

  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want& want, const Instant&) const {
    using namespace spatial;
    return length(minus(body_point(c, kBodyJ, s_j, want), body_point(c, kBodyI, s_i, want)));
  }
};

}  // namespace lagmb
