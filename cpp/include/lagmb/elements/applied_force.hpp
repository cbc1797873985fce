// A force at a point of a body, and a pure torque.
#pragma once

#include <string>

#include "lagmb/time_function.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// Force F at the point s (body axes) of body i: Q_r = F, Q_phi = (A s) x F.
/// Global direction: F = (f_x(t), f_y(t)), Q_c at (phi, phi) = (B s) x F.
/// Body-fixed direction: F = A F'(t); then Q_r,phi = B F' and Q_phi = s x F'
/// is constant. Does no conservative work: potential 0. Its effort
/// (Result.effort) is F in global axes, as applied at the run's inputs.
struct AppliedForce {
  static constexpr bool state_dependent = true;
  static constexpr const char* kind = "force";
  static constexpr bool reads_inputs = true;

  std::string name;
  int body_i = -1, body_j = -1;  // body_j unused (-1)
  Vec2 s = Vec2::Zero();
  Drive fx, fy;
  bool local = false;

  Vec2 value(const Instant& t) const { return {fx.at(t).f, fy.at(t).f}; }
  Vec2 effort(const Local6& c, const Local6&, const Instant& t) const {
    return local ? Vec2(rotation(c[2]) * value(t)) : value(t);
  }
  Local6 force(const Local6& c, const Local6& cd, const Instant& t) const {
    const Mat2 A = rotation(c[2]);
    const Vec2 F = effort(c, cd, t);
    Local6 Q = Local6::Zero();
    Q.segment<2>(0) = F;
    Q[2] = cross(A * s, F);
    return Q;
  }
  void derivatives(const Local6& c, const Local6&, const Instant& t, Mat6& Q_c, Mat6& Q_cd) const {
    Q_c.setZero();
    Q_cd.setZero();
    const Vec2 F = value(t);
    if (local)
      Q_c.block<2, 1>(0, 2) = rotation_derivative(c[2]) * F;
    else
      Q_c(2, 2) = cross(rotation_derivative(c[2]) * s, F);
  }
  double potential(const Local6&, const Instant&) const { return 0.0; }
};

/// A pure torque tau(t) on body i; its effort (Result.effort) is tau.
struct AppliedTorque {
  static constexpr bool state_dependent = false;
  static constexpr const char* kind = "torque";
  static constexpr bool reads_inputs = true;

  std::string name;
  int body_i = -1, body_j = -1;
  Drive torque;

  double effort(const Local6&, const Local6&, const Instant& t) const { return torque.at(t).f; }
  Local6 force(const Local6& c, const Local6& cd, const Instant& t) const {
    Local6 Q = Local6::Zero();
    Q[2] = effort(c, cd, t);
    return Q;
  }
  void derivatives(const Local6&, const Local6&, const Instant&, Mat6&, Mat6&) const {}
  double potential(const Local6&, const Instant&) const { return 0.0; }
};

}  // namespace lagmb
