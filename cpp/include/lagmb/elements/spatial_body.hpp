// A spatial rigid body's own equations: the rotational block of M, the
// normalization of its Euler parameters, and its quadratic-velocity
// (gyroscopic) force. Its builder (cpp/src/elements/spatial_body.cpp) adds the
// body and the last two as elements of their own.
#pragma once

#include <string>

#include "lagmb/space.hpp"
#include "lagmb/spatial.hpp"

namespace lagmb {

/// The rotational part of a spatial body's mass matrix. With omega' =
/// 2 G(p) p' (body axes) the kinetic energy is T = m r'.r' / 2 + 2 p'^T G^T
/// J' G p', so Lagrange's equation gives M_p = 4 G^T J' G, singular along p
/// (G p = 0) and state dependent, and the quadratic-velocity force
/// 8 G(p')^T J' G(p') p (Nikravesh; Haug, as cited in spatial.hpp). lagmb uses
///   M_p(p) = 4 G^T J' G + 4 jbar p p^T,   jbar = trace(J') / 3,
/// which adds jbar (2 p p^T) (p^T p'' + p'^T p') = jbar Phi_N,q^T Phi_N'' to
/// the equations: zero wherever the normalization Phi_N = (p^T p - 1) / 2
/// holds, so the motion is the same, and M_p is then definite, with the
/// inverse below (P = [G; p^T] has P P^T = |p|^2 I):
///   M_p^-1 = P^T diag(J'^-1 / 4, 1 / (4 jbar)) P / |p|^4.
/// The force side takes the matching -4 jbar p (p'^T p') (GyroscopicForce).
namespace rotational_mass {

inline double mean_inertia(const Mat3& J) { return J.trace() / 3.0; }

inline Mat4 block(const Vec4& p, const Mat3& J) {
  const Mat34 g = euler::G(p);
  return 4.0 * g.transpose() * J * g + 4.0 * mean_inertia(J) * p * p.transpose();
}

inline Mat4 inverse(const Vec4& p, const Mat3& J_inverse, double jbar) {
  Mat4 P;
  P.topRows<3>() = euler::G(p);
  P.row(3) = p.transpose();
  Mat4 D = Mat4::Zero();
  D.topLeftCorner<3, 3>() = 0.25 * J_inverse;
  D(3, 3) = 0.25 / jbar;
  const double p2 = p.squaredNorm();
  return P.transpose() * D * P / (p2 * p2);
}

/// d(M_p(p) a)/dp = 4 [W(J' G(p) a) - G(p)^T J' G(a)] + 4 jbar (p a^T + (p.a) I),
/// from G(p)^T y = W(y) p and G(p) a = -G(a) p.
inline Mat4 derivative(const Vec4& p, const Mat3& J, const Vec4& a) {
  const Mat34 g = euler::G(p);
  return 4.0 * (euler::W(J * g * a) - g.transpose() * J * euler::G(a)) +
         4.0 * mean_inertia(J) * (p * a.transpose() + p.dot(a) * Mat4::Identity());
}

/// omega'^T J' omega' / 2 with omega' = 2 G(p) p' (the exact rotational
/// kinetic energy, without the jbar term, which is 0 on the manifold).
inline double kinetic_energy(const Vec4& p, const Vec4& pd, const Mat3& J) {
  const Vec3 w = 2.0 * euler::G(p) * pd;
  return 0.5 * w.dot(J * w);
}

}  // namespace rotational_mass

/// Normalization of a spatial body's Euler parameters, one row:
///   Phi = (p^T p - 1) / 2,  Phi_p = p^T,  d2Phi/dp2 = I,  gamma = -p'^T p'.
/// Added with every spatial body (body_i; body_j is the ground). Its
/// multiplier has no physical meaning beyond keeping |p| = 1.
struct EulerParameterNorm {
  using Space = Spatial;
  static constexpr int rows = 1;
  static constexpr bool time_dependent = false;
  static constexpr const char* kind = "euler_parameter_norm";

  std::string name;
  int body_i = -1, body_j = -1;

  Eigen::Matrix<double, 1, 1> phi(const LocalVec<14>& c, double) const {
    return Eigen::Matrix<double, 1, 1>(0.5 * (c.segment<4>(3).squaredNorm() - 1.0));
  }
  Eigen::Matrix<double, 1, 14> jacobian(const LocalVec<14>& c, double) const {
    Eigen::Matrix<double, 1, 14> J = Eigen::Matrix<double, 1, 14>::Zero();
    J.segment<4>(3) = c.segment<4>(3).transpose();
    return J;
  }
  void hessians(const LocalVec<14>&, double, LocalMat<14>* H) const {
    H[0].setZero();
    H[0].block<4, 4>(3, 3).setIdentity();
  }
  Eigen::Matrix<double, 1, 1> gamma(const LocalVec<14>&, const LocalVec<14>& cd, double) const {
    return Eigen::Matrix<double, 1, 1>(-cd.segment<4>(3).squaredNorm());
  }
  Mat3 axes(const LocalVec<14>&, double) const { return Mat3::Identity(); }
};

/// The quadratic-velocity force of a spatial body on its Euler parameters,
/// with the term of the definite M_p (rotational_mass):
///   Q_p = 8 G(p')^T J' G(p') p - 4 jbar p (p'^T p')
/// (in body axes 8 G(p')^T J' G(p') p = -4 G(p')^T J' omega', the
/// gyroscopic moment). With y = J' G(p) p' and G(p') p = -G(p) p':
///   dQ_p/dp  = 8 G(p')^T J' G(p') - 4 jbar (p'^T p') I
///   dQ_p/dp' = -8 [W(y) + G(p')^T J' G(p)] - 8 jbar p p'^T
/// Added with every spatial body; no potential.
struct GyroscopicForce {
  using Space = Spatial;
  static constexpr bool state_dependent = true;
  static constexpr const char* kind = "gyroscopic_force";

  std::string name;
  int body_i = -1, body_j = -1;
  Mat3 J = Mat3::Identity();
  double jbar = 1.0;

  LocalVec<14> force(const LocalVec<14>& c, const LocalVec<14>& cd, double) const {
    const Vec4 p = c.segment<4>(3), pd = cd.segment<4>(3);
    const Mat34 gd = euler::G(pd);
    LocalVec<14> f = LocalVec<14>::Zero();
    f.segment<4>(3) = 8.0 * gd.transpose() * (J * (gd * p)) - 4.0 * jbar * pd.squaredNorm() * p;
    return f;
  }
  void derivatives(const LocalVec<14>& c, const LocalVec<14>& cd, double, LocalMat<14>& dq,
                   LocalMat<14>& dv) const {
    const Vec4 p = c.segment<4>(3), pd = cd.segment<4>(3);
    const Mat34 g = euler::G(p), gd = euler::G(pd);
    dq.setZero();
    dv.setZero();
    dq.block<4, 4>(3, 3) = 8.0 * gd.transpose() * J * gd - 4.0 * jbar * pd.squaredNorm() * Mat4::Identity();
    dv.block<4, 4>(3, 3) =
        -8.0 * (euler::W(J * g * pd) + gd.transpose() * J * g) - 8.0 * jbar * p * pd.transpose();
  }
  double potential(const LocalVec<14>&, double) const { return 0.0; }
};

}  // namespace lagmb
