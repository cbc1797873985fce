// Pin-in-slot joint: a pin of body j stays on a line (slot) fixed in body i.
#pragma once

#include <string>

#include "lagmb/projected_offset.hpp"

namespace lagmb {

/// Phi = n_i . (p_j - p_i) = 0, n_i = A_i n' the slot's normal, p_i a point
/// of the slot line, p_j the pin. Rotation stays free. Joint axes: (u_i, n_i);
/// the normal component is the slot's bearing force.
struct PinInSlotJoint {
  static constexpr int rows = 1;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "pin_in_slot";

  std::string name;
  int body_i = -1, body_j = -1;
  ProjectedOffset across;  // w = n', the slot's normal in body i's axes

  Eigen::Matrix<double, 1, 1> phi(const Local6& c, double) const {
    return Eigen::Matrix<double, 1, 1>(across.value(c));
  }
  Eigen::Matrix<double, 1, 6> jacobian(const Local6& c, double) const { return across.gradient(c); }
  void hessians(const Local6& c, double, Mat6* H) const { H[0] = across.hessian(c); }
  Mat2 axes(const Local6& c, double) const { return across.line_axes(c); }
  /// The pin (reactions about the joint).
  Vec2 origin(const Local6& c, double) const { return across.point_j(c); }
};

}  // namespace lagmb
