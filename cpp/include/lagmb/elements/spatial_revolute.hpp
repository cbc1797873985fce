// The spatial kind "spatial_revolute" (registry.hpp; its builder in cpp/src/elements/spatial_revolute.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

/// Revolute joint: d = 0 and the axis a_j of body j stays across f_i and
/// g_i of body i (Haug's dot-1 twice): 5 rows,
///   (A_i f_i) . (A_j a_j) = 0,  (A_i g_i) . (A_j a_j) = 0.
/// Its angle (drivers, rotational springs) turns f_j, body j's copy of f_i,
/// about a from f_i towards g_i.
struct SpatialRevoluteJoint : SpatialJointBase, spatial::TermJoint<SpatialRevoluteJoint, 5> {
  static constexpr const char* kind = "spatial_revolute";
  Vec3 a_j = Vec3::UnitZ(), f_j = Vec3::UnitX();  // the axis and f in body j's axes
  /// Its coordinate: the angle, f_j turned about a from f_i towards g_i.
  JointCoordinate coordinate() const { return joint_coordinate(true, false, f_j); }
  spatial::Terms<5> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want), aj = body_vector(c, kBodyJ, a_j, want);
    return {component(d, 0), component(d, 1), component(d, 2), dot(body_vector(c, kBodyI, f_i, want), aj, want),
            dot(body_vector(c, kBodyI, g_i, want), aj, want)};
  }
  /// Phi_c in closed form (the terms' gradients, without their general
  /// machinery: the revolute is most of a robot's rows). With x = r + A s,
  /// u = A_i f_i, v = A_i g_i, w = A_j a_j and P(p, s) = d(A(p) s)/dp:
  ///   d: [-I, -P(p_i, s_i), I, P(p_j, s_j)],
  ///   u.w: [0, w^T P(p_i, f_i), 0, u^T P(p_j, a_j)], v.w likewise.
  Eigen::Matrix<double, 5, 14> jacobian(const spatial::Loc& c, double) const {
    const Vec4 pi = c.segment<4>(3), pj = c.segment<4>(10);
    const Vec3 w = euler::rotate(pj, a_j);
    const Mat34 Pa = euler::point_jacobian(pj, a_j);
    Eigen::Matrix<double, 5, 14> J = Eigen::Matrix<double, 5, 14>::Zero();
    J.block<3, 3>(0, 0) = -Mat3::Identity();
    J.block<3, 4>(0, 3) = -euler::point_jacobian(pi, s_i);
    J.block<3, 3>(0, 7) = Mat3::Identity();
    J.block<3, 4>(0, 10) = euler::point_jacobian(pj, s_j);
    J.block<1, 4>(3, 3) = w.transpose() * euler::point_jacobian(pi, f_i);
    J.block<1, 4>(3, 10) = euler::rotate(pi, f_i).transpose() * Pa;
    J.block<1, 4>(4, 3) = w.transpose() * euler::point_jacobian(pi, g_i);
    J.block<1, 4>(4, 10) = euler::rotate(pi, g_i).transpose() * Pa;
    return J;
  }
  /// gamma = -c'^T Phi_cc c' in closed form: along the path (c'' = 0)
  /// (A s)'' = 2 A(p') s, so d'' = 2 (A(p_j') s_j - A(p_i') s_i) and
  /// (u.w)'' = u''.w + 2 u'.w' + u.w'' (u' = P(p_i, f_i) p_i').
  Eigen::Matrix<double, 5, 1> gamma(const spatial::Loc& c, const spatial::Loc& cd, double) const {
    const Vec4 pi = c.segment<4>(3), pj = c.segment<4>(10), pdi = cd.segment<4>(3), pdj = cd.segment<4>(10);
    const Vec3 w = euler::rotate(pj, a_j), w1 = euler::rotation_rate(pj, pdj, a_j), w2 = 2.0 * euler::rotate(pdj, a_j);
    auto dot_second = [&](const Vec3& s) {
      return 2.0 * euler::rotate(pdi, s).dot(w) + 2.0 * euler::rotation_rate(pi, pdi, s).dot(w1) +
             euler::rotate(pi, s).dot(w2);
    };
    Eigen::Matrix<double, 5, 1> g;
    g.head<3>() = -2.0 * (euler::rotate(pdj, s_j) - euler::rotate(pdi, s_i));
    g[3] = -dot_second(f_i);
    g[4] = -dot_second(g_i);
    return g;
  }
};

}  // namespace lagmb
