// f = (A_i w) . (r_j + A_j s_j - r_i - A_i s_i): the offset of a point of
// body j from a point of body i, projected on a direction fixed in body i.
// Translational joints, pin-in-slot joints, slide drivers and racks share it.
#pragma once

#include "lagmb/types.hpp"

namespace lagmb {

struct ProjectedOffset {
  Vec2 w = Vec2::UnitX();  // direction in body i's axes
  Vec2 s_i = Vec2::Zero(), s_j = Vec2::Zero();

  double value(const Local6& c) const { return (rotation(c[2]) * w).dot(offset(c)); }

  /// With a = A_i w and d the offset:
  ///   df/dr_i = -a, df/dr_j = a, df/dphi_i = (B_i w).d - a.(B_i s_i), df/dphi_j = a.(B_j s_j).
  Eigen::Matrix<double, 1, 6> gradient(const Local6& c) const {
    const Vec2 a = rotation(c[2]) * w, bw = rotation_derivative(c[2]) * w;
    Eigen::Matrix<double, 1, 6> g;
    g << -a.transpose(), bw.dot(offset(c)) - a.dot(rotation_derivative(c[2]) * s_i), a.transpose(),
        a.dot(rotation_derivative(c[5]) * s_j);
    return g;
  }

  /// d2f/dr_i dphi_i = -B_i w, d2f/dr_j dphi_i = B_i w,
  /// d2f/dphi_i2 = -a.d - w.s_i, d2f/dphi_i dphi_j = (B_i w).(B_j s_j),
  /// d2f/dphi_j2 = -a.(A_j s_j); all others zero (d2A/dphi2 = -A, B^T B = I).
  Mat6 hessian(const Local6& c) const {
    const Vec2 a = rotation(c[2]) * w, bw = rotation_derivative(c[2]) * w;
    Mat6 H = Mat6::Zero();
    H.block<2, 1>(0, 2) = -bw;
    H.block<2, 1>(3, 2) = bw;
    H.block<1, 2>(2, 0) = -bw.transpose();
    H.block<1, 2>(2, 3) = bw.transpose();
    H(2, 2) = -a.dot(offset(c)) - w.dot(s_i);
    H(2, 5) = H(5, 2) = bw.dot(rotation_derivative(c[5]) * s_j);
    H(5, 5) = -a.dot(rotation(c[5]) * s_j);
    return H;
  }

  /// For w the normal of a line (w = u' turned +90 deg): the line's axes
  /// (u, n) = (A_i u', A_i w) as columns.
  Mat2 line_axes(const Local6& c) const {
    const Mat2 A = rotation(c[2]);
    Mat2 E;
    E << A * Vec2(w.y(), -w.x()), A * w;
    return E;
  }
  /// The line's direction u' in body i's axes (w turned -90 deg).
  Vec2 line_direction() const { return {w.y(), -w.x()}; }

  /// The point s_j of body j, global.
  Vec2 point_j(const Local6& c) const { return c.segment<2>(3) + rotation(c[5]) * s_j; }

  Vec2 offset(const Local6& c) const {
    return c.segment<2>(3) + rotation(c[5]) * s_j - c.segment<2>(0) - rotation(c[2]) * s_i;
  }
};

/// The same, with the roles of the bodies swapped (direction fixed in body j).
inline Local6 swap_bodies(const Local6& c) {
  Local6 s;
  s << c.segment<3>(3), c.segment<3>(0);
  return s;
}

}  // namespace lagmb
