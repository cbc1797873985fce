// The spatial kind "spatial_stop" (registry.hpp; its builder in
// cpp/src/elements/spatial_stop.cpp): a joint limit in space, a pair of
// unilateral rows (docs/methods.md, "The active set, step by step").
#pragma once

#include <string>

#include "lagmb/model/joint_reading.hpp"
#include "lagmb/elements/stop.hpp"

namespace lagmb {

/// The coordinate s of a spatial revolute (its angle, spatial::joint_angle,
/// with the turns the run has counted: model/joint_turns.hpp, so the limits
/// may be any distance apart) or translational joint (its slide,
/// spatial::joint_slide), the joint's `angle` or `slide` in the initial
/// configuration (0 by default). Allowed: lower <= s <= upper. As the
/// planar JointStop (stop.hpp): rows
///   Phi_0 = g_0 = s - lower >= 0,   Phi_1 = g_1 = upper - s >= 0,
/// left out while open, closed by the event runner while the joint rests on
/// that limit; the stop's force along s is lam_1 - lam_0.
struct SpatialJointStop : StopLimits {
  using Space = Spatial;
  static constexpr int rows = 2;
  static constexpr bool time_dependent = false;
  static constexpr bool unilateral = true;
  static constexpr bool reads_inputs = true;  // the Instant: the run's turns of the joint
  static constexpr const char* kind = "spatial_stop";
  using Rows = Eigen::Matrix<double, 2, 1>;
  using Jac = Eigen::Matrix<double, 2, 14>;

  std::string name;
  int body_i = -1, body_j = -1;
  spatial::JointReading joint;  // the joint's counted angle, or its slide

  Rows phi(const spatial::Loc& c, const Instant& at) const { return gaps(joint(c, {}, at).value); }
  // (the turns shift the angle by a constant: the derivatives are joint_angle's)
  Jac jacobian(const spatial::Loc& c, const Instant&) const {
    Jac J;
    J.row(0) = joint(c, {}).gradient;
    J.row(1) = -J.row(0);
    return J;
  }
  void hessians(const spatial::Loc& c, const Instant&, spatial::Mat14* H) const {
    spatial::Want want;
    want.hessian = true;
    H[0] = joint(c, want).hessian;
    H[1] = -H[0];
  }
  Jac rates(const spatial::Loc& c, const spatial::Loc& cd, const Instant&) const {
    spatial::Want want;
    want.rate = &cd;
    Jac V;
    V.row(0) = joint(c, want).gradient_rate;
    V.row(1) = -V.row(0);
    return V;
  }
  Mat3 axes(const spatial::Loc&, const Instant&) const { return Mat3::Identity(); }
};

}  // namespace lagmb
