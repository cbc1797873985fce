// The spatial kind "spatial_translational" (registry.hpp; its builder in cpp/src/elements/spatial_translational.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

/// Translational joint: the cylindrical joint's rows and no turn about the
/// axis, (A_i f_i) . (A_j g_j) = 0 with g_j body j's copy of g_i: 5 rows.
struct SpatialTranslationalJoint : SpatialJointBase, spatial::TermJoint<SpatialTranslationalJoint, 5> {
  static constexpr const char* kind = "spatial_translational";
  Vec3 a_j = Vec3::UnitZ(), g_j = Vec3::UnitY();
  /// Its coordinate: the slide along a, (A_i a_i) . d.
  JointCoordinate coordinate() const { return joint_coordinate(false, true, Vec3::UnitX()); }
  spatial::Terms<5> terms(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = offset(c, want), aj = body_vector(c, kBodyJ, a_j, want);
    const VectorTerm fi = body_vector(c, kBodyI, f_i, want), gi = body_vector(c, kBodyI, g_i, want);
    return {dot(fi, aj, want), dot(gi, aj, want), dot(fi, d, want), dot(gi, d, want),
            dot(fi, body_vector(c, kBodyJ, g_j, want), want)};
  }
  /// Phi_c in closed form (the terms' gradients without their general
  /// machinery, as the revolute's: a robot's finger slides). With u = A_i
  /// f_i, v = A_i g_i, w = A_j a_j, y = A_j g_j and P(p, s) = d(A(p) s)/dp:
  ///   u.w: [0, w^T P(p_i, f_i), 0, u^T P(p_j, a_j)]   (v.w, u.y alike),
  ///   u.d: [-u^T, d^T P(p_i, f_i) - u^T P(p_i, s_i), u^T, u^T P(p_j, s_j)]   (v.d alike).
  Eigen::Matrix<double, 5, 14> jacobian(const spatial::Loc& c, double) const {
    const Vec4 pi = c.segment<4>(3), pj = c.segment<4>(10);
    const Vec3 u = euler::rotate(pi, f_i), v = euler::rotate(pi, g_i), w = euler::rotate(pj, a_j),
               y = euler::rotate(pj, g_j);
    const Vec3 d = c.segment<3>(7) + euler::rotate(pj, s_j) - c.segment<3>(0) - euler::rotate(pi, s_i);
    const Mat34 Pf = euler::point_jacobian(pi, f_i), Pg = euler::point_jacobian(pi, g_i),
                Ps = euler::point_jacobian(pi, s_i), Pa = euler::point_jacobian(pj, a_j),
                Py = euler::point_jacobian(pj, g_j), Psj = euler::point_jacobian(pj, s_j);
    Eigen::Matrix<double, 5, 14> J = Eigen::Matrix<double, 5, 14>::Zero();
    J.block<1, 4>(0, 3) = w.transpose() * Pf;
    J.block<1, 4>(0, 10) = u.transpose() * Pa;
    J.block<1, 4>(1, 3) = w.transpose() * Pg;
    J.block<1, 4>(1, 10) = v.transpose() * Pa;
    J.block<1, 3>(2, 0) = -u.transpose();
    J.block<1, 4>(2, 3) = d.transpose() * Pf - u.transpose() * Ps;
    J.block<1, 3>(2, 7) = u.transpose();
    J.block<1, 4>(2, 10) = u.transpose() * Psj;
    J.block<1, 3>(3, 0) = -v.transpose();
    J.block<1, 4>(3, 3) = d.transpose() * Pg - v.transpose() * Ps;
    J.block<1, 3>(3, 7) = v.transpose();
    J.block<1, 4>(3, 10) = v.transpose() * Psj;
    J.block<1, 4>(4, 3) = y.transpose() * Pf;
    J.block<1, 4>(4, 10) = u.transpose() * Py;
    return J;
  }
  /// gamma = -c'^T Phi_cc c' in closed form: along the path (c'' = 0) a body
  /// vector x = A s has x' = P(p, s) p' and x'' = 2 A(p') s, d'' = x_j'' -
  /// x_i'' of the joint points, and (a.b)'' = a''.b + 2 a'.b' + a.b''.
  Eigen::Matrix<double, 5, 1> gamma(const spatial::Loc& c, const spatial::Loc& cd, double) const {
    const Vec4 pi = c.segment<4>(3), pj = c.segment<4>(10), pdi = cd.segment<4>(3), pdj = cd.segment<4>(10);
    struct Path {
      Vec3 x, x1, x2;  // the vector and its first and second derivatives along the path
    };
    auto along = [](const Vec4& p, const Vec4& pd, const Vec3& s) {
      return Path{euler::rotate(p, s), euler::rotation_rate(p, pd, s), 2.0 * euler::rotate(pd, s)};
    };
    const Path u = along(pi, pdi, f_i), v = along(pi, pdi, g_i), w = along(pj, pdj, a_j), y = along(pj, pdj, g_j);
    const Path si = along(pi, pdi, s_i), sj = along(pj, pdj, s_j);
    const Path d{c.segment<3>(7) + sj.x - c.segment<3>(0) - si.x, cd.segment<3>(7) + sj.x1 - cd.segment<3>(0) - si.x1,
                 sj.x2 - si.x2};
    auto second = [](const Path& a, const Path& b) { return a.x2.dot(b.x) + 2.0 * a.x1.dot(b.x1) + a.x.dot(b.x2); };
    Eigen::Matrix<double, 5, 1> g;
    g << -second(u, w), -second(v, w), -second(u, d), -second(v, d), -second(u, y);
    return g;
  }
};

}  // namespace lagmb
