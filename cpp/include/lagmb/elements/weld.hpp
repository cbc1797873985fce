// Weld (fixed) joint: body j keeps its initial pose relative to body i.
#pragma once

#include <string>

#include "lagmb/types.hpp"

namespace lagmb {

/// Phi_{1,2} = r_j - r_i - A_i s_i = 0, s_i = body j's centre in body i's axes;
/// Phi_3 = phi_j - phi_i - phi0 = 0. Joint axes: body i's axes. Its point
/// (reactions about the joint) is body j's centre of mass, where its rows
/// hold body j.
struct WeldJoint {
  static constexpr int rows = 3;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "weld";

  std::string name;
  int body_i = -1, body_j = -1;
  Vec2 s_i = Vec2::Zero();
  double phi0 = 0.0;

  Eigen::Vector3d phi(const Local6& c, double) const {
    Eigen::Vector3d f;
    f << c.segment<2>(3) - c.segment<2>(0) - rotation(c[2]) * s_i, c[5] - c[2] - phi0;
    return f;
  }
  Eigen::Matrix<double, 3, 6> jacobian(const Local6& c, double) const {
    Eigen::Matrix<double, 3, 6> J = Eigen::Matrix<double, 3, 6>::Zero();
    J.block<2, 2>(0, 0) = -Mat2::Identity();
    J.block<2, 1>(0, 2) = -rotation_derivative(c[2]) * s_i;
    J.block<2, 2>(0, 3) = Mat2::Identity();
    J(2, 2) = -1.0;
    J(2, 5) = 1.0;
    return J;
  }
  void hessians(const Local6& c, double, Mat6* H) const {
    const Vec2 a = rotation(c[2]) * s_i;
    for (int r = 0; r < 3; ++r) H[r].setZero();
    H[0](2, 2) = a.x();
    H[1](2, 2) = a.y();
  }
  Mat2 axes(const Local6& c, double) const { return rotation(c[2]); }
  Vec2 origin(const Local6& c, double) const { return c.segment<2>(3); }
};

}  // namespace lagmb
