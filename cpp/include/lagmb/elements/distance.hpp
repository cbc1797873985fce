// Distance constraint: a massless rigid link between a point of body i and a
// point of body j.
#pragma once

#include <string>

#include "lagmb/types.hpp"

namespace lagmb {

/// Phi = (d.d - L^2) / (2 L), d = r_j + A_j s_j - r_i - A_i s_i.
/// Scaled so that lam is the link force: the force on body j is -lam d / L,
/// so lam > 0 is tension. With D = dd/dc = [-I, -B_i s_i, I, B_j s_j]:
///   Phi_c = d^T D / L,  Phi_cc = (D^T D + d_x H_x + d_y H_y) / L,
/// H_k the second derivatives of d_k (at phi_i phi_i: (A_i s_i)_k, at
/// phi_j phi_j: -(A_j s_j)_k). Joint axes: (d / |d|, turned +90 deg).
struct DistanceJoint {
  static constexpr int rows = 1;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "distance";

  std::string name;
  int body_i = -1, body_j = -1;
  Vec2 s_i = Vec2::Zero(), s_j = Vec2::Zero();
  double length = 1.0;

  Vec2 d(const Local6& c) const {
    return c.segment<2>(3) + rotation(c[5]) * s_j - c.segment<2>(0) - rotation(c[2]) * s_i;
  }
  Eigen::Matrix<double, 2, 6> D(const Local6& c) const {
    Eigen::Matrix<double, 2, 6> M;
    M << -Mat2::Identity(), -rotation_derivative(c[2]) * s_i, Mat2::Identity(),
        rotation_derivative(c[5]) * s_j;
    return M;
  }
  /// The link's end on body j (reactions about the joint).
  Vec2 origin(const Local6& c, double) const { return c.segment<2>(3) + rotation(c[5]) * s_j; }
  Eigen::Matrix<double, 1, 1> phi(const Local6& c, double) const {
    const Vec2 v = d(c);
    return Eigen::Matrix<double, 1, 1>((v.squaredNorm() - length * length) / (2.0 * length));
  }
  Eigen::Matrix<double, 1, 6> jacobian(const Local6& c, double) const {
    return d(c).transpose() * D(c) / length;
  }
  void hessians(const Local6& c, double, Mat6* H) const {
    const auto Dm = D(c);
    const Vec2 v = d(c), ai = rotation(c[2]) * s_i, aj = rotation(c[5]) * s_j;
    H[0] = Dm.transpose() * Dm;
    H[0](2, 2) += v.dot(ai);
    H[0](5, 5) -= v.dot(aj);
    H[0] /= length;
  }
  Mat2 axes(const Local6& c, double) const {
    Vec2 e = d(c);
    const double n = e.norm();
    e = n > 0 ? Vec2(e / n) : Vec2::UnitX();
    Mat2 E;
    E << e, Vec2(-e.y(), e.x());
    return E;
  }
};

}  // namespace lagmb
