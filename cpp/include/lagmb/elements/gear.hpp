// Gear pair: the pitch circles of two gears roll on each other without slip.
#pragma once

#include <cmath>
#include <string>

#include "lagmb/types.hpp"

namespace lagmb {

/// Phi = r_i (phi_i - theta) + s r_j (phi_j - theta) - c0 = 0
///
/// theta: angle of the line from centre i to centre j, d = c_j - c_i,
/// measured from its initial direction (so it stays continuous while the
/// line of centres turns less than 180 deg; gears on fixed pivots never turn
/// it). s = +1 external (ratio = omega_j/omega_i = -r_i/r_j < 0), s = -1
/// internal (ratio = r_i/r_j > 0). The multiplier is the tooth force
/// (tangential, N). With g = dtheta/dd = (-d_y, d_x)/|d|^2 and
/// D = dd/dc = [-I, -B_i c_i, I, B_j c_j]:
///   theta_c  = g^T D
///   theta_cc = D^T Theta D + g_x H_x + g_y H_y,  Theta = d2theta/dd2,
/// H_k the second derivatives of d_k (phi_i phi_i: (A_i c_i)_k,
/// phi_j phi_j: -(A_j c_j)_k). Joint axes: (d / |d|, turned +90 deg).
struct GearPair {
  static constexpr int rows = 1;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "gear";

  std::string name;
  int body_i = -1, body_j = -1;
  Vec2 c_i = Vec2::Zero(), c_j = Vec2::Zero();  // gear centres in each body's axes
  double r_i = 1.0, r_j = 1.0, s = 1.0;         // pitch radii, +1 external / -1 internal
  Vec2 d0 = Vec2::UnitX();                       // initial direction of the centre line
  double c0 = 0.0;

  Vec2 d(const Local6& c) const {
    return c.segment<2>(3) + rotation(c[5]) * c_j - c.segment<2>(0) - rotation(c[2]) * c_i;
  }
  Eigen::Matrix<double, 2, 6> D(const Local6& c) const {
    Eigen::Matrix<double, 2, 6> M;
    M << -Mat2::Identity(), -rotation_derivative(c[2]) * c_i, Mat2::Identity(),
        rotation_derivative(c[5]) * c_j;
    return M;
  }
  double theta(const Local6& c) const {
    const Vec2 v = d(c);
    return std::atan2(cross(d0, v), d0.dot(v));
  }
  double raw(const Local6& c) const {
    const double th = theta(c);
    return r_i * (c[2] - th) + s * r_j * (c[5] - th);
  }
  Eigen::Matrix<double, 1, 1> phi(const Local6& c, double) const {
    return Eigen::Matrix<double, 1, 1>(raw(c) - c0);
  }
  Eigen::Matrix<double, 1, 6> jacobian(const Local6& c, double) const {
    const Vec2 v = d(c);
    const Vec2 g = Vec2(-v.y(), v.x()) / v.squaredNorm();
    Eigen::Matrix<double, 1, 6> J = -(r_i + s * r_j) * g.transpose() * D(c);
    J(2) += r_i;
    J(5) += s * r_j;
    return J;
  }
  void hessians(const Local6& c, double, Mat6* H) const {
    const Vec2 v = d(c);
    const double x = v.x(), y = v.y(), rho2 = v.squaredNorm(), rho4 = rho2 * rho2;
    const Vec2 g(-y / rho2, x / rho2);
    Mat2 Theta;
    Theta << 2 * x * y / rho4, (y * y - x * x) / rho4, (y * y - x * x) / rho4, -2 * x * y / rho4;
    const auto Dm = D(c);
    Mat6 th = Dm.transpose() * Theta * Dm;
    th(2, 2) += g.dot(rotation(c[2]) * c_i);
    th(5, 5) -= g.dot(rotation(c[5]) * c_j);
    H[0] = -(r_i + s * r_j) * th;
  }
  Mat2 axes(const Local6& c, double) const {
    const Vec2 e = d(c).normalized();
    Mat2 E;
    E << e, Vec2(-e.y(), e.x());
    return E;
  }
};

}  // namespace lagmb
