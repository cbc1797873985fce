// Drivers: prescribed motion g(q) - f(t) = 0 with f a time function. The
// derivatives of f enter Phi_t = -f', Phi_tt = -f'' (so gamma gets +f'').
// The effort a driver applies is -lam, positive along increasing g.
#pragma once

#include <string>

#include "lagmb/projected_offset.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

/// Common part: one row, time dependent through f only.
struct DriverBase {
  static constexpr int rows = 1;
  static constexpr bool time_dependent = true;
  std::string name;
  int body_i = -1, body_j = -1;
  Drive f;  // the prescribed value
  static constexpr bool reads_inputs = true;
  static constexpr bool ties_motion = true;  // (is_tie)

  Eigen::Matrix<double, 1, 1> phi_t(const Local6&, const Instant& t) const {
    return Eigen::Matrix<double, 1, 1>(-f.at(t).df);
  }
  Eigen::Matrix<double, 1, 6> phi_tc(const Local6&, const Instant&) const {
    return Eigen::Matrix<double, 1, 6>::Zero();
  }
  Eigen::Matrix<double, 1, 1> phi_tt(const Local6&, const Instant& t) const {
    return Eigen::Matrix<double, 1, 1>(-f.at(t).ddf);
  }
};

/// Relative angle of a revolute joint: Phi = phi_j - phi_i - f(t).
/// Effort: the torque on body j (body i gets the opposite).
struct AngleDriver : DriverBase {
  static constexpr const char* kind = "angle_driver";
  Eigen::Matrix<double, 1, 1> phi(const Local6& c, const Instant& t) const {
    return Eigen::Matrix<double, 1, 1>(c[5] - c[2] - f.at(t).f);
  }
  Eigen::Matrix<double, 1, 6> jacobian(const Local6&, const Instant&) const {
    Eigen::Matrix<double, 1, 6> J;
    J << 0, 0, -1, 0, 0, 1;
    return J;
  }
  void hessians(const Local6&, const Instant&, Mat6* H) const { H[0].setZero(); }
  Mat2 axes(const Local6&, const Instant&) const { return Mat2::Identity(); }
};

/// Slide of a translational joint: Phi = u_i . (p_j - p_i) - f(t).
/// Effort: the force along u_i on body j.
struct SlideDriver : DriverBase {
  static constexpr const char* kind = "slide_driver";
  ProjectedOffset along;  // w = u'
  Eigen::Matrix<double, 1, 1> phi(const Local6& c, const Instant& t) const {
    return Eigen::Matrix<double, 1, 1>(along.value(c) - f.at(t).f);
  }
  Eigen::Matrix<double, 1, 6> jacobian(const Local6& c, const Instant&) const { return along.gradient(c); }
  void hessians(const Local6& c, const Instant&, Mat6* H) const { H[0] = along.hessian(c); }
  Mat2 axes(const Local6& c, const Instant&) const {
    const Vec2 u = rotation(c[2]) * along.w;
    Mat2 E;
    E << u, Vec2(-u.y(), u.x());
    return E;
  }
};

/// An absolute coordinate of body j (x: 0, y: 1, angle: 2): Phi = q_k - f(t).
/// Body i is the ground. Effort: the force (x, y) or torque (angle) on body j.
struct CoordinateDriver : DriverBase {
  static constexpr const char* kind = "coordinate_driver";
  int coordinate = 0;
  Eigen::Matrix<double, 1, 1> phi(const Local6& c, const Instant& t) const {
    return Eigen::Matrix<double, 1, 1>(c[3 + coordinate] - f.at(t).f);
  }
  Eigen::Matrix<double, 1, 6> jacobian(const Local6&, const Instant&) const {
    Eigen::Matrix<double, 1, 6> J = Eigen::Matrix<double, 1, 6>::Zero();
    J(3 + coordinate) = 1.0;
    return J;
  }
  void hessians(const Local6&, const Instant&, Mat6* H) const { H[0].setZero(); }
  Mat2 axes(const Local6&, const Instant&) const { return Mat2::Identity(); }
};

}  // namespace lagmb
