// The spatial kind "spatial_stop" (registry.hpp; its builder in
// cpp/src/elements/spatial_stop.cpp): a joint limit in space, with impacts.
#pragma once

#include <cmath>
#include <string>

#include "lagmb/elements/spatial_drivers.hpp"
#include "lagmb/model/event_group.hpp"

namespace lagmb {

/// The coordinate s of a spatial revolute (its angle, spatial::joint_angle,
/// read in (center - pi, center + pi]: center is the middle of the limits,
/// or a quarter turn inside a lone limit, so that the reading never wraps
/// inside the allowed range) or translational joint (its slide,
/// spatial::joint_slide), the joint's `angle` or `slide` in the initial
/// configuration (0 by default). Allowed: lower <=
/// s <= upper. As the planar JointStop (stop.hpp): event functions
///   g_0 = s - lower,   g_1 = upper - s       (an absent limit reads g = 1),
/// counted when crossed downward; a crossing with approaching velocity
/// g' = dg/dc . cd < 0 is an impact along dg/dc with Newton's restitution;
/// a state exactly at a limit reads as just beyond it (g = -1e-300).
struct SpatialJointStop {
  using Space = Spatial;
  static constexpr int roots = 2;
  static constexpr bool bounds_motion = true;
  static constexpr const char* kind = "spatial_stop";

  std::string name;
  int body_i = -1, body_j = -1;
  spatial::JointReading joint;  // its center: the middle of the limits
  bool has_lower = false, has_upper = false;
  double lower = 0.0, upper = 0.0;
  double restitution = 0.0;
  double rest_speed = 0.0;  // rad/s or m/s

  spatial::ScalarTerm coordinate(const spatial::Loc& c, bool hessian) const {
    spatial::Want want;
    want.hessian = hessian;
    return joint(c, want);
  }
  double root(int r, const spatial::Loc& c, const spatial::Loc&, double) const {
    if (r == 0 ? !has_lower : !has_upper) return 1.0;
    const double s = coordinate(c, false).value;
    const double g = r == 0 ? s - lower : upper - s;
    return g != 0.0 ? g : -1e-300;
  }
  int direction(int) const { return -1; }
  EventAction crossing(int r, const spatial::Loc& c, const spatial::Loc& cd, double) const {
    EventAction a;
    if (r == 0 ? !has_lower : !has_upper) return a;
    const double sign = r == 0 ? 1.0 : -1.0;
    const spatial::ScalarTerm s = coordinate(c, true);
    if (!(sign * s.gradient.dot(cd) < 0.0)) return a;  // leaving or at rest: no impact
    a.type = EventAction::kImpact;
    a.gradient = sign * s.gradient.transpose();
    a.hessian = sign * s.hessian;
    a.restitution = restitution;
    a.rest_speed = rest_speed;
    a.label = r == 0 ? "lower" : "upper";
    return a;
  }
};

}  // namespace lagmb
