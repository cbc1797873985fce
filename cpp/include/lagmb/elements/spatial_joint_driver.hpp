// Prescribed motion of a spatial joint's coordinate: a revolute's (or
// cylindrical joint's) angle, or a translational's or cylindrical's slide.
#pragma once

#include "lagmb/model/joint_reading.hpp"
#include "lagmb/elements/spatial_driver_base.hpp"

namespace lagmb {

/// The angle of a revolute (or cylindrical) joint, g = theta
/// (spatial::joint_angle); the row theta - f(t), wrapped (periodic), holds
/// theta = f(t) mod 2 pi. dPhi/dtheta = 1, so lam is minus the torque about
/// a on body j.
struct SpatialAngleDriver : SpatialCoordinateDriverBase<SpatialAngleDriver> {
  static constexpr const char* kind = "spatial_angle_driver";
  static constexpr bool periodic = true;
  Vec3 f_i = Vec3::UnitX(), g_i = Vec3::UnitY(), f_j = Vec3::UnitX();

  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want& want) const {
    return spatial::joint_angle(c, f_i, g_i, f_j, want);
  }
};

/// The slide of a translational or cylindrical joint, g = (A_i a_i) . d
/// (spatial::joint_slide). Effort: the force along a on body j.
struct SpatialSlideDriver : SpatialCoordinateDriverBase<SpatialSlideDriver> {
  static constexpr const char* kind = "spatial_slide_driver";
  Vec3 s_i = Vec3::Zero(), s_j = Vec3::Zero(), a_i = Vec3::UnitZ();
  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want& want) const {
    return spatial::joint_slide(c, s_i, s_j, a_i, want);
  }
};

}  // namespace lagmb
