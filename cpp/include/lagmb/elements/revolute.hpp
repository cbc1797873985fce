// Revolute joint: a point of body i and a point of body j coincide.
#pragma once

#include <string>

#include "lagmb/model/joint_coordinate.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// Phi = r_j + A(phi_j) s_j - r_i - A(phi_i) s_i = 0            (2 rows)
///
/// with s_i, s_j the joint point in each body's local axes. With B = dA/dphi:
///   Phi_q = [ -I, -B_i s_i,  I, B_j s_j ]
///   d2Phi/dphi_i2 = +A_i s_i,  d2Phi/dphi_j2 = -A_j s_j   (all else zero)
/// so gamma = A_j s_j phid_j^2 - A_i s_i phid_i^2.
/// The multipliers lam are the force the joint puts on body i, in global
/// axes (the generalized force on the bodies is -Phi_q^T lam).
/// Joint axes: radial, from the joint point to body j's centre of mass (or,
/// if the joint sits there, from body i's centre to the joint point), and
/// tangential (radial turned +90 deg).
struct RevoluteJoint {
  static constexpr int rows = 2;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "revolute";

  std::string name;
  int body_i = -1, body_j = -1;  // -1: ground
  Vec2 s_i = Vec2::Zero(), s_j = Vec2::Zero();

  /// Its coordinate: the relative angle phi_j - phi_i.
  JointCoordinate coordinate() const {
    JointCoordinate c;
    c.turns = true;
    c.body_i = body_i;
    c.body_j = body_j;
    return c;
  }

  Eigen::Vector2d phi(const Local6& c, double) const {
    return c.segment<2>(3) + rotation(c[5]) * s_j - c.segment<2>(0) - rotation(c[2]) * s_i;
  }

  Eigen::Matrix<double, 2, 6> jacobian(const Local6& c, double) const {
    Eigen::Matrix<double, 2, 6> J;
    J.block<2, 2>(0, 0) = -Mat2::Identity();
    J.col(2) = -rotation_derivative(c[2]) * s_i;
    J.block<2, 2>(0, 3) = Mat2::Identity();
    J.col(5) = rotation_derivative(c[5]) * s_j;
    return J;
  }

  void hessians(const Local6& c, double, Mat6* H) const {
    const Vec2 ai = rotation(c[2]) * s_i, aj = rotation(c[5]) * s_j;
    for (int r = 0; r < 2; ++r) {
      H[r].setZero();
      H[r](2, 2) = ai[r];
      H[r](5, 5) = -aj[r];
    }
  }

  /// gamma = A_j s_j phid_j^2 - A_i s_i phid_i^2 (the Hessians' closed form)
  Eigen::Vector2d gamma(const Local6& c, const Local6& cd, double) const {
    return rotation(c[5]) * s_j * (cd[5] * cd[5]) - rotation(c[2]) * s_i * (cd[2] * cd[2]);
  }

  /// The joint point on body j (reactions about the joint).
  Vec2 origin(const Local6& c, double) const { return c.segment<2>(3) + rotation(c[5]) * s_j; }
  Mat2 axes(const Local6& c, double) const {
    Vec2 e = -(rotation(c[5]) * s_j);
    if (e.norm() == 0.0) e = rotation(c[2]) * s_i;
    e = e.norm() > 0.0 ? Vec2(e.normalized()) : Vec2::UnitX();
    Mat2 E;
    E << e, Vec2(-e.y(), e.x());
    return E;
  }
};

}  // namespace lagmb
