// Translational (prismatic) joint: body j slides along an axis fixed in body i.
#pragma once

#include <string>

#include "lagmb/model/joint_coordinate.hpp"
#include "lagmb/projected_offset.hpp"

namespace lagmb {

/// Phi_1 = n_i . (p_j - p_i) = 0    (no motion across the axis)
/// Phi_2 = phi_j - phi_i - phi0 = 0 (no relative rotation)
/// with u_i = A_i u' the axis, n_i = A_i n' its normal (u' turned +90 deg),
/// p_i, p_j the joint point fixed on each body. The slide displacement is
/// u_i . (p_j - p_i). Joint axes for reactions: (u_i, n_i).
struct TranslationalJoint {
  static constexpr int rows = 2;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "translational";

  std::string name;
  int body_i = -1, body_j = -1;
  ProjectedOffset across;  // w = n', the normal of the axis in body i's axes
  double phi0 = 0.0;

  /// Its coordinate: the slide, the offset along the axis (0 in the
  /// initial configuration).
  JointCoordinate coordinate() const {
    JointCoordinate c;
    c.slides = true;
    c.body_i = body_i;
    c.body_j = body_j;
    c.along = across;
    c.along.w = across.line_direction();
    return c;
  }

  Eigen::Vector2d phi(const Local6& c, double) const {
    return {across.value(c), c[5] - c[2] - phi0};
  }
  Eigen::Matrix<double, 2, 6> jacobian(const Local6& c, double) const {
    Eigen::Matrix<double, 2, 6> J;
    J.row(0) = across.gradient(c);
    J.row(1) << 0, 0, -1, 0, 0, 1;
    return J;
  }
  void hessians(const Local6& c, double, Mat6* H) const {
    H[0] = across.hessian(c);
    H[1].setZero();
  }
  Mat2 axes(const Local6& c, double) const { return across.line_axes(c); }
  /// The point `at` fixed on body j (reactions about the joint).
  Vec2 origin(const Local6& c, double) const { return across.point_j(c); }
};

}  // namespace lagmb
