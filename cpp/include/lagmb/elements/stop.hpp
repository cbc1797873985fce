// Joint stop (limit): a unilateral bound on a joint coordinate (docs/methods.md, "The active set, step by step").
#pragma once

#include <string>

#include "lagmb/projected_offset.hpp"
#include "lagmb/model/constraint_group.hpp"

namespace lagmb {

/// Values a stop shares in the plane and in space: its limits and what it
/// does at contact (constraint_group.hpp, UnilateralRow).
struct StopLimits {
  bool has_lower = false, has_upper = false;
  double lower = 0.0, upper = 0.0;
  double restitution = 0.0;
  double rest_speed = 0.0;    // 0: none given (capture_time decides)
  double capture_time = 0.0;  // s

  /// Row 0 bounds from below (g_0 = s - lower), row 1 from above (g_1 = upper - s).
  UnilateralRow unilateral_row(int r) const {
    return {r == 0 ? has_lower : has_upper, restitution, rest_speed, capture_time, r == 0 ? "lower" : "upper"};
  }
  /// The gaps at coordinate s (an absent limit reads 0: its row is never closed).
  Eigen::Vector2d gaps(double s) const { return {has_lower ? s - lower : 0.0, has_upper ? upper - s : 0.0}; }
  /// Its effort (Result.effort) from its rows' multipliers: the force along
  /// s, -lam_0 pushing up from the lower limit, +lam_1 down from the upper.
  double effort(const Eigen::Vector2d& lam) const { return lam[1] - lam[0]; }
};

/// The joint coordinate s is a revolute's relative angle phi_j - phi_i, or a
/// translational's slide u_i . (p_j - p_i) (0 in the initial configuration),
/// as for drive_joint. Allowed: lower <= s <= upper. Two unilateral rows,
///   Phi_0 = g_0 = s - lower >= 0,   Phi_1 = g_1 = upper - s >= 0,
/// left out while open; the event runner closes a row when the joint comes
/// to rest on that limit and opens it where its multiplier would pull. While
/// closed, the stop's force along s is f = -lam_0 (lower) or +lam_1 (upper):
/// Result.effort reads lam_1 - lam_0.
struct JointStop : StopLimits {
  static constexpr int rows = 2;
  static constexpr bool time_dependent = false;
  static constexpr bool unilateral = true;
  static constexpr const char* kind = "stop";

  std::string name;
  int body_i = -1, body_j = -1;
  bool slide = false;     // translational (else revolute)
  ProjectedOffset along;  // slide: w = the axis u' in body i's axes

  double coordinate_value(const Local6& c) const { return slide ? along.value(c) : c[5] - c[2]; }
  Eigen::Matrix<double, 1, 6> coordinate_gradient(const Local6& c) const {
    if (slide) return along.gradient(c);
    Eigen::Matrix<double, 1, 6> J;
    J << 0, 0, -1, 0, 0, 1;
    return J;
  }

  Eigen::Vector2d phi(const Local6& c, double) const { return gaps(coordinate_value(c)); }
  Eigen::Matrix<double, 2, 6> jacobian(const Local6& c, double) const {
    Eigen::Matrix<double, 2, 6> J;
    J.row(0) = coordinate_gradient(c);
    J.row(1) = -J.row(0);
    return J;
  }
  void hessians(const Local6& c, double, Mat6* H) const {
    H[0] = slide ? along.hessian(c) : Mat6::Zero();
    H[1] = -H[0];
  }
  Mat2 axes(const Local6&, double) const { return Mat2::Identity(); }
};

}  // namespace lagmb
