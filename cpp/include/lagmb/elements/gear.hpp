// Gear pair: the pitch circles of two gears roll on each other without slip.
#pragma once

#include <cmath>
#include <string>

#include "lagmb/types.hpp"

namespace lagmb {

/// Rolling pitch circles: r_i (phi_i - theta) + s r_j (phi_j - theta) = c0,
/// theta the angle of the line from centre i to centre j, d = c_j - c_i;
/// s = +1 external (ratio = omega_j/omega_i = -r_i/r_j < 0), s = -1 internal
/// (ratio = r_i/r_j > 0). theta is only known modulo 2 pi (atan2), so the
/// equation is written in the phase psi, kappa = r_i + s r_j:
///   psi = (r_i phi_i + s r_j phi_j - c0) / kappa - theta
///   Phi = kappa sin(psi) = 0
/// which is smooth however often the line of centres turns (a planet carrier
/// may run full turns) and equals the linear form to first order on the
/// solution psi = 0, where the multiplier is the tooth force (tangential, N).
/// With g = dtheta/dd = (-d_y, d_x)/|d|^2, D = dd/dc = [-I, -B_i c_i, I, B_j c_j]:
///   theta_c  = g^T D,  theta_cc = D^T Theta D + g_x H_x + g_y H_y,
/// Theta = d2theta/dd2, H_k the second derivatives of d_k (phi_i phi_i:
/// (A_i c_i)_k, phi_j phi_j: -(A_j c_j)_k);
///   Phi_c = kappa cos(psi) psi_c,  Phi_cc = kappa (cos(psi) psi_cc - sin(psi) psi_c psi_c^T).
/// Joint axes: (d / |d|, turned +90 deg).
struct GearPair {
  static constexpr int rows = 1;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "gear";
  static constexpr bool ties_motion = true;  // (is_tie)

  std::string name;
  int body_i = -1, body_j = -1;
  Vec2 c_i = Vec2::Zero(), c_j = Vec2::Zero();  // gear centres in each body's axes
  double r_i = 1.0, r_j = 1.0, s = 1.0;         // pitch radii, +1 external / -1 internal
  double c0 = 0.0;

  double kappa() const { return r_i + s * r_j; }
  Vec2 d(const Local6& c) const {
    return c.segment<2>(3) + rotation(c[5]) * c_j - c.segment<2>(0) - rotation(c[2]) * c_i;
  }
  Eigen::Matrix<double, 2, 6> D(const Local6& c) const {
    Eigen::Matrix<double, 2, 6> M;
    M << -Mat2::Identity(), -rotation_derivative(c[2]) * c_i, Mat2::Identity(),
        rotation_derivative(c[5]) * c_j;
    return M;
  }
  /// r_i phi_i + s r_j phi_j - kappa theta: constant while the gears roll.
  double rolled(const Local6& c) const {
    const Vec2 v = d(c);
    return r_i * c[2] + s * r_j * c[5] - kappa() * std::atan2(v.y(), v.x());
  }
  double psi(const Local6& c) const { return (rolled(c) - c0) / kappa(); }
  Local6 psi_c(const Local6& c) const {
    const Vec2 v = d(c);
    const Vec2 g = Vec2(-v.y(), v.x()) / v.squaredNorm();
    Local6 p = -(g.transpose() * D(c)).transpose();
    p[2] += r_i / kappa();
    p[5] += s * r_j / kappa();
    return p;
  }
  Eigen::Matrix<double, 1, 1> phi(const Local6& c, double) const {
    return Eigen::Matrix<double, 1, 1>(kappa() * std::sin(psi(c)));
  }
  Eigen::Matrix<double, 1, 6> jacobian(const Local6& c, double) const {
    return (kappa() * std::cos(psi(c)) * psi_c(c)).transpose();
  }
  void hessians(const Local6& c, double, Mat6* H) const {
    const Vec2 v = d(c);
    const double x = v.x(), y = v.y(), rho2 = v.squaredNorm(), rho4 = rho2 * rho2;
    const Vec2 g(-y / rho2, x / rho2);
    Mat2 Theta;
    Theta << 2 * x * y / rho4, (y * y - x * x) / rho4, (y * y - x * x) / rho4, -2 * x * y / rho4;
    const auto Dm = D(c);
    Mat6 theta_cc = Dm.transpose() * Theta * Dm;
    theta_cc(2, 2) += g.dot(rotation(c[2]) * c_i);
    theta_cc(5, 5) -= g.dot(rotation(c[5]) * c_j);
    const double p = psi(c);
    const Local6 pc = psi_c(c);
    H[0] = kappa() * (-std::cos(p) * theta_cc - std::sin(p) * pc * pc.transpose());
  }
  Mat2 axes(const Local6& c, double) const {
    const Vec2 e = d(c).normalized();
    Mat2 E;
    E << e, Vec2(-e.y(), e.x());
    return E;
  }
};

}  // namespace lagmb
