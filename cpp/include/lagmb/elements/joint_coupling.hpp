// The spatial kind "joint_coupling" (registry.hpp; its builder in
// cpp/src/elements/joint_coupling.cpp): one joint's coordinate follows
// another's, as a URDF <mimic> or an MJCF <joint> equality says.
#pragma once

#include <array>
#include <string>

#include "lagmb/model/joint_reading.hpp"
#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

/// Joint b's coordinate follows joint a's:
///   Phi = s_b - (m s_a + s0) = 0,
/// s a revolute's angle (continuous through the joint's turns in a run) or
/// a translational's slide (spatial::JointReading), m the multiplier, s0 the
/// offset. Its local coordinates are joint a's 14 then joint b's 14
/// (SpatialJointPair; a body both joints share appears in each half and
/// its group adds the columns), so
///   Phi_c = (-m ds_a/dc_a, ds_b/dc_b),  H = diag(-m H_a, H_b).
/// dPhi/ds_b = 1: -lam is the torque (force) the coupling applies along
/// joint b's coordinate on its body j, and m lam the one along joint a's.
/// body_i, body_j: joint b's bodies; leader: joint a's.
struct JointCoupling {
  using Space = SpatialJointPair;
  static constexpr int rows = 1;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "joint_coupling";
  static constexpr bool ties_motion = true;  // (is_tie)
  static constexpr bool reads_inputs = true;  // the Instant: the run's turns of the joints
  using Loc = LocalVec<28>;
  using Row = Eigen::Matrix<double, 1, 1>;
  using Grad = Eigen::Matrix<double, 1, 28>;

  std::string name;
  int body_i = -1, body_j = -1;
  std::array<int, 2> leader = {-1, -1};
  spatial::JointReading a, b;
  double multiplier = 1.0, offset = 0.0;

  std::array<int, 4> bodies() const { return {leader[0], leader[1], body_i, body_j}; }

  Row phi(const Loc& c, const Instant& t) const {
    return Row(b(c.tail<14>(), {}, t).value - multiplier * a(c.head<14>(), {}, t).value - offset);
  }
  // (the derivatives do not depend on the turns)
  Grad jacobian(const Loc& c, const Instant&) const {
    Grad J;
    J << -multiplier * a(c.head<14>(), {}).gradient, b(c.tail<14>(), {}).gradient;
    return J;
  }
  void hessians(const Loc& c, const Instant&, LocalMat<28>* H) const {
    spatial::Want want;
    want.hessian = true;
    H[0].setZero();
    H[0].topLeftCorner<14, 14>() = -multiplier * a(c.head<14>(), want).hessian;
    H[0].bottomRightCorner<14, 14>() = b(c.tail<14>(), want).hessian;
  }
  Grad rates(const Loc& c, const Loc& cd, const Instant&) const {
    const spatial::Loc cd_a = cd.head<14>(), cd_b = cd.tail<14>();
    spatial::Want want_a, want_b;
    want_a.rate = &cd_a;
    want_b.rate = &cd_b;
    Grad V;
    V << -multiplier * a(c.head<14>(), want_a).gradient_rate, b(c.tail<14>(), want_b).gradient_rate;
    return V;
  }
  /// Joint b's triple (spatial_joint.hpp).
  Mat3 axes(const Loc& c, const Instant&) const {
    const spatial::Loc cb = c.tail<14>();
    return spatial::joint_axes(cb, b.f_i, b.g_i, b.a_i);
  }
};

}  // namespace lagmb
