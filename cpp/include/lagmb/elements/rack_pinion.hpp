// Rack and pinion: the pinion's pitch circle rolls on the rack's pitch line.
#pragma once

#include <string>

#include "lagmb/projected_offset.hpp"

namespace lagmb {

/// Body i is the pinion (its centre of mass is the pinion centre), body j the
/// rack, with pitch-line direction u = A_j u' and the pinion on its left
/// (u turned +90 deg points from the rack to the pinion). Rolling without
/// slip: (v_pinion - v_rack) . u + radius (omega_i - omega_j) = 0, i.e.
///   Phi = u . (r_i - r_j - A_j s_j) + radius (phi_i - phi_j) - c0 = 0,
/// s_j = the pinion centre's initial position in the rack's axes. The first
/// term is a ProjectedOffset with the bodies swapped. The multiplier is the
/// tooth force (N). Joint axes: (u, n).
struct RackPinion {
  static constexpr int rows = 1;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "rack_pinion";
  static constexpr bool ties_motion = true;  // (is_tie)

  std::string name;
  int body_i = -1, body_j = -1;  // pinion, rack
  ProjectedOffset along;          // on swapped coordinates: w = u', s_i = s_j(rack), s_j = 0
  double radius = 1.0, c0 = 0.0;

  static Eigen::Matrix<double, 1, 6> unswap(const Eigen::Matrix<double, 1, 6>& g) {
    Eigen::Matrix<double, 1, 6> r;
    r << g.segment<3>(3), g.segment<3>(0);
    return r;
  }
  Eigen::Matrix<double, 1, 1> phi(const Local6& c, double) const {
    return Eigen::Matrix<double, 1, 1>(along.value(swap_bodies(c)) + radius * (c[2] - c[5]) - c0);
  }
  Eigen::Matrix<double, 1, 6> jacobian(const Local6& c, double) const {
    Eigen::Matrix<double, 1, 6> J = unswap(along.gradient(swap_bodies(c)));
    J(2) += radius;
    J(5) -= radius;
    return J;
  }
  void hessians(const Local6& c, double, Mat6* H) const {
    const Mat6 Hs = along.hessian(swap_bodies(c));
    Eigen::PermutationMatrix<6> P;
    P.indices() << 3, 4, 5, 0, 1, 2;
    H[0] = P.transpose() * Hs * P;
  }
  Mat2 axes(const Local6& c, double) const {
    const Vec2 u = rotation(c[5]) * along.w;
    Mat2 E;
    E << u, Vec2(-u.y(), u.x());
    return E;
  }
};

}  // namespace lagmb
