// Orientation in space by Euler parameters (a unit quaternion), as in
// Nikravesh, "Computer-Aided Analysis of Mechanical Systems" (ch. 6) and Haug,
// "Computer-Aided Kinematics and Dynamics of Mechanical Systems" (ch. 9).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "lagmb/types.hpp"

namespace lagmb {

using Mat34 = Eigen::Matrix<double, 3, 4>;
using Mat4 = Eigen::Matrix4d;

/// skew(a) b = a x b.
inline Mat3 skew(const Vec3& a) {
  Mat3 S;
  S << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return S;
}

namespace euler {

/// Euler parameters p = (e0, e), e = (e1, e2, e3): (w, x, y, z) of the unit
/// quaternion turning body axes into global axes, p^T p = 1. With
///   G(p) = [-e, -skew(e) + e0 I],   E(p) = [-e, skew(e) + e0 I]   (3 x 4)
/// the angular velocity is omega = 2 E(p) p' (global axes) = A omega',
/// omega' = 2 G(p) p' (body axes), and A(p) = E(p) G(p)^T. For unit p:
/// G p = E p = 0, G G^T = E E^T = I, G^T G = E^T E = I - p p^T, and
/// G(p) x = -G(x) p for any x (likewise E). A(p) s here is the homogeneous
/// quadratic (e0^2 - e.e) s + 2 (e.s) e + 2 e0 e x s, the rotation of s
/// scaled by p^T p.
inline Mat34 G(const Vec4& p) {
  Mat34 g;
  g.col(0) = -p.tail<3>();
  g.rightCols<3>() = -skew(p.tail<3>()) + p[0] * Mat3::Identity();
  return g;
}

inline Mat34 E(const Vec4& p) {
  Mat34 g;
  g.col(0) = -p.tail<3>();
  g.rightCols<3>() = skew(p.tail<3>()) + p[0] * Mat3::Identity();
  return g;
}

/// The rotation matrix A(p) = E G^T (body axes into global axes).
inline Mat3 A(const Vec4& p) { return E(p) * G(p).transpose(); }

/// A(p) s.
inline Vec3 rotate(const Vec4& p, const Vec3& s) {
  const double e0 = p[0];
  const Vec3 e = p.tail<3>();
  return (e0 * e0 - e.dot(e)) * s + 2.0 * e.dot(s) * e + 2.0 * e0 * e.cross(s);
}

/// d(A(p) s)/dp (3 x 4) = 2 [e0 s + e x s,  (e.s) I + e s^T - s e^T - e0 skew(s)];
/// linear in p, and point_jacobian(p, s) p = 2 A(p) s.
inline Mat34 point_jacobian(const Vec4& p, const Vec3& s) {
  const double e0 = p[0];
  const Vec3 e = p.tail<3>();
  Mat34 J;
  J.col(0) = 2.0 * (e0 * s + e.cross(s));
  J.rightCols<3>() = 2.0 * (e.dot(s) * Mat3::Identity() + e * s.transpose() - s * e.transpose() - e0 * skew(s));
  return J;
}

/// d(A(p) s)/dt = point_jacobian(p, s) p', without forming the matrix:
/// 2 [p0' (e0 s + e x s) + (e.s) e' + (s.e') e - (e.e') s - e0 s x e'].
inline Vec3 rotation_rate(const Vec4& p, const Vec4& pd, const Vec3& s) {
  const double e0 = p[0];
  const Vec3 e = p.tail<3>(), ed = pd.tail<3>();
  return 2.0 * (pd[0] * (e0 * s + e.cross(s)) + e.dot(s) * ed + s.dot(ed) * e - e.dot(ed) * s - e0 * s.cross(ed));
}

/// d2(A(p) s)_k / dp2 (4 x 4, constant: A s is quadratic in p), for the
/// weighted sum over k with weights w: sum_k w_k d2(A s)_k/dp2.
inline Mat4 point_hessian(const Vec3& s, const Vec3& w) {
  Mat4 H;
  for (int b = 0; b < 4; ++b) H.col(b) = point_jacobian(Vec4::Unit(b), s).transpose() * w;
  return H;
}

/// W(y) with G(x)^T y = W(y) x for every x: [[0, -y^T], [y, -skew(y)]].
inline Mat4 W(const Vec3& y) {
  Mat4 w;
  w(0, 0) = 0.0;
  w.block<1, 3>(0, 1) = -y.transpose();
  w.block<3, 1>(1, 0) = y;
  w.block<3, 3>(1, 1) = -skew(y);
  return w;
}

/// Euler parameters of a rotation matrix (Shepperd's method: the largest of
/// the four squares first), with e0 >= 0.
inline Vec4 from_matrix(const Mat3& R) {
  const double t = R.trace();
  Vec4 p;
  if (t >= R(0, 0) && t >= R(1, 1) && t >= R(2, 2)) {
    const double s = std::sqrt(1.0 + t) * 2.0;  // 4 e0
    p << 0.25 * s, (R(2, 1) - R(1, 2)) / s, (R(0, 2) - R(2, 0)) / s, (R(1, 0) - R(0, 1)) / s;
  } else if (R(0, 0) >= R(1, 1) && R(0, 0) >= R(2, 2)) {
    const double s = std::sqrt(1.0 + R(0, 0) - R(1, 1) - R(2, 2)) * 2.0;  // 4 e1
    p << (R(2, 1) - R(1, 2)) / s, 0.25 * s, (R(0, 1) + R(1, 0)) / s, (R(0, 2) + R(2, 0)) / s;
  } else if (R(1, 1) >= R(2, 2)) {
    const double s = std::sqrt(1.0 + R(1, 1) - R(0, 0) - R(2, 2)) * 2.0;  // 4 e2
    p << (R(0, 2) - R(2, 0)) / s, (R(0, 1) + R(1, 0)) / s, 0.25 * s, (R(1, 2) + R(2, 1)) / s;
  } else {
    const double s = std::sqrt(1.0 + R(2, 2) - R(0, 0) - R(1, 1)) * 2.0;  // 4 e3
    p << (R(1, 0) - R(0, 1)) / s, (R(0, 2) + R(2, 0)) / s, (R(1, 2) + R(2, 1)) / s, 0.25 * s;
  }
  if (p[0] < 0.0) p = -p;
  return p.normalized();
}

/// Two unit vectors f, g completing a unit vector a to a right-handed
/// orthonormal triple (f, g, a).
inline void complete_basis(const Vec3& a, Vec3& f, Vec3& g) {
  const Vec3 other = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  f = a.cross(other).normalized();
  g = a.cross(f);
}

}  // namespace euler
}  // namespace lagmb
