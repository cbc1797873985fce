// Joint stop (limit): a unilateral bound on a joint coordinate, with impacts.
#pragma once

#include <string>

#include "lagmb/elements/projected_offset.hpp"
#include "lagmb/model/event_group.hpp"

namespace lagmb {

/// The joint coordinate s is a revolute's relative angle phi_j - phi_i, or a
/// translational's slide u_i . (p_j - p_i) (0 in the initial configuration),
/// as for drive_joint. Allowed: lower <= s <= upper. Event functions
///   g_0 = s - lower,   g_1 = upper - s       (an absent limit reads g = 1),
/// counted only when crossed downward (from allowed to beyond). At a crossing
/// with approaching velocity g' = dg/dc . cd < 0 the joint gets an impact:
/// an impulse along dg/dc with Newton's restitution, g'+ = -e g'- (the runner
/// solves the M-orthogonal jump, keeping the joints). A leaving velocity
/// (g' >= 0) is a separation: nothing happens. A state exactly at a limit
/// reads as just beyond it (g = -1e-300), so a restart there never puts a
/// root function at exactly zero (SUNDIALS would warn).
struct JointStop {
  static constexpr int roots = 2;
  /// Its event functions bound the motion: g < 0 is a place the body may not be.
  static constexpr bool bounds_motion = true;
  static constexpr const char* kind = "stop";

  std::string name;
  int body_i = -1, body_j = -1;
  bool slide = false;       // translational (else revolute)
  ProjectedOffset along;    // slide: w = the axis u' in body i's axes
  bool has_lower = false, has_upper = false;
  double lower = 0.0, upper = 0.0;
  double restitution = 0.0;
  double rest_speed = 0.0;  // rad/s or m/s

  double coordinate(const Local6& c) const { return slide ? along.value(c) : c[5] - c[2]; }
  Eigen::Matrix<double, 1, 6> coordinate_gradient(const Local6& c) const {
    if (slide) return along.gradient(c);
    Eigen::Matrix<double, 1, 6> J;
    J << 0, 0, -1, 0, 0, 1;
    return J;
  }
  /// d2s/dc2 (zero for the angle): for g'' = dg/dc . cdd + cd^T H cd.
  Mat6 coordinate_hessian(const Local6& c) const { return slide ? along.hessian(c) : Mat6::Zero(); }
  double sign(int r) const { return r == 0 ? 1.0 : -1.0; }

  double root(int r, const Local6& c, const Local6&, double) const {
    if (r == 0 ? !has_lower : !has_upper) return 1.0;
    const double g = r == 0 ? coordinate(c) - lower : upper - coordinate(c);
    return g != 0.0 ? g : -1e-300;
  }
  int direction(int) const { return -1; }
  EventAction crossing(int r, const Local6& c, const Local6& cd, double) const {
    EventAction a;
    if (r == 0 ? !has_lower : !has_upper) return a;
    const Eigen::Matrix<double, 1, 6> grad = sign(r) * coordinate_gradient(c);
    if (!(grad.dot(cd) < 0.0)) return a;  // leaving or at rest: no impact
    a.type = EventAction::kImpact;
    a.gradient = grad.transpose();
    a.restitution = restitution;
    a.rest_speed = rest_speed;
    a.hessian = sign(r) * coordinate_hessian(c);
    a.label = r == 0 ? "lower" : "upper";
    return a;
  }
};

}  // namespace lagmb
