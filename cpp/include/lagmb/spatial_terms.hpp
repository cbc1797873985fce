// The building blocks of spatial joints: vectors and points fixed in a body,
// their differences and dot products, each with its exact first and second
// derivatives in the element's local coordinates c = (r_i, p_i, r_j, p_j)
// (space.hpp). Every spatial joint is a few rows of these (Haug's "basic
// constraints": dot-1, dot-2, spherical; Haug, "Computer-Aided Kinematics and
// Dynamics of Mechanical Systems", sec. 9.4).
#pragma once

#include <array>
#include <cmath>

#include "lagmb/space.hpp"
#include "lagmb/spatial.hpp"

namespace lagmb::spatial {

using Loc = LocalVec<14>;
using Mat14 = LocalMat<14>;
using Row14 = Eigen::Matrix<double, 1, 14>;
using Jac3 = Eigen::Matrix<double, 3, 14>;

/// What a term is asked for beyond its value: the gradient (off for Phi
/// and gamma alone), the Hessians (the Newton matrix's sum_r w_r H_r, and
/// force derivatives), the rate of the gradient along cd, (H cd)^T =
/// d(grad)/dt (the velocity Jacobian), and/or the value's first two time
/// derivatives along a path c(t) with c' = cd and c'' = 0: u' = u_c cd and
/// u'' = cd^T u_cc cd, the convective term (gamma = -u''), carried through
/// the algebra as numbers, for a fraction of what a gradient costs.
/// (Kinds write Want{true} for the Hessians: that field stays first.)
struct Want {
  bool hessian = false;
  const Loc* rate = nullptr;  // cd, or null
  bool gradient = true;
  const Loc* path = nullptr;  // cd, or null
};

/// A vector function u(c): value, Jacobian du/dc and, as wanted, the
/// Hessian of each component and the Jacobian's rate along cd.
struct VectorTerm {
  Vec3 value = Vec3::Zero();
  bool first = false;  // jacobian set (want.gradient)
  Jac3 jacobian;
  bool second = false;
  std::array<Mat14, 3> hessian;
  bool rated = false;
  // d(du/dc)/dt along cd; set only where rated (zero-filled in every term,
  // it cost 3-5 % of a spatial run)
  Jac3 jacobian_rate;
  bool moving = false;  // along want.path: u' and u'' (c'' = 0)
  Vec3 velocity, convective;
};

/// A scalar function f(c): value, gradient and (as wanted) Hessian, the
/// gradient's rate (H cd)^T, and f' and f'' along the path (Want).
struct ScalarTerm {
  double value = 0.0;
  Row14 gradient = Row14::Zero();
  Mat14 hessian;
  Row14 gradient_rate = Row14::Zero();
  double velocity = 0.0, convective = 0.0;
};

/// The side of an element a body stands on: its r at 7 side, p at 7 side + 3.
enum Side { kBodyI = 0, kBodyJ = 1 };

/// A(p) a: the vector `a` fixed in the body on `side` (its axes), in
/// global axes. d/dp = point_jacobian(p, a), linear in p, so its rate along
/// p' is point_jacobian(p', a); d2/dp2 constant (spatial.hpp). Along the
/// path, u' = point_jacobian(p, a) p' and, A(p) a being the quadratic
/// rotate(p, a), u'' = 2 rotate(p', a).
inline VectorTerm body_vector(const Loc& c, Side side, const Vec3& a, const Want& want) {
  const int at = 7 * side + 3;
  const Vec4 p = c.segment<4>(at);
  VectorTerm u;
  u.value = euler::rotate(p, a);
  u.first = want.gradient || want.rate || want.hessian;
  if (u.first) {
    u.jacobian.setZero();
    u.jacobian.block<3, 4>(0, at) = euler::point_jacobian(p, a);
  }
  u.moving = want.path != nullptr;
  if (u.moving) {
    const Vec4 pd = want.path->segment<4>(at);
    u.velocity = euler::rotation_rate(p, pd, a);
    u.convective = 2.0 * euler::rotate(pd, a);
  }
  u.second = want.hessian;
  if (want.hessian)
    for (int k = 0; k < 3; ++k) {
      u.hessian[k].setZero();
      u.hessian[k].block<4, 4>(at, at) = euler::point_hessian(a, Vec3::Unit(k));
    }
  u.rated = want.rate != nullptr;
  if (u.rated) {
    u.jacobian_rate.setZero();
    u.jacobian_rate.block<3, 4>(0, at) = euler::point_jacobian(want.rate->segment<4>(at), a);
  }
  return u;
}

/// r + A(p) s: the point `s` (body axes) of the body on `side`, in global
/// coordinates.
inline VectorTerm body_point(const Loc& c, Side side, const Vec3& s, const Want& want) {
  VectorTerm u = body_vector(c, side, s, want);
  u.value += c.segment<3>(7 * side);
  if (u.first) u.jacobian.block<3, 3>(0, 7 * side).setIdentity();
  if (u.moving) u.velocity += want.path->segment<3>(7 * side);
  return u;
}

/// u - v.
inline VectorTerm minus(const VectorTerm& u, const VectorTerm& v) {
  VectorTerm w;
  w.value = u.value - v.value;
  w.first = u.first && v.first;
  if (w.first) w.jacobian = u.jacobian - v.jacobian;
  w.moving = u.moving && v.moving;
  if (w.moving) {
    w.velocity = u.velocity - v.velocity;
    w.convective = u.convective - v.convective;
  }
  w.second = u.second && v.second;
  if (w.second)
    for (int k = 0; k < 3; ++k) w.hessian[k] = u.hessian[k] - v.hessian[k];
  w.rated = u.rated && v.rated;
  if (w.rated) w.jacobian_rate = u.jacobian_rate - v.jacobian_rate;
  return w;
}

/// u . v: gradient u^T v_c + v^T u_c, Hessian u_c^T v_c + v_c^T u_c +
/// sum_k (u_k v_k,cc + v_k u_k,cc); the gradient's rate along cd
/// u'^T v_c + u^T v_c' + v'^T u_c + v^T u_c' (u' = u_c cd); along the path
/// f' = u'.v + u.v', f'' = u''.v + 2 u'.v' + u.v''.
inline ScalarTerm dot(const VectorTerm& u, const VectorTerm& v, const Want& want = {}) {
  ScalarTerm f;
  f.value = u.value.dot(v.value);
  if (u.first && v.first) f.gradient = u.value.transpose() * v.jacobian + v.value.transpose() * u.jacobian;
  if (u.moving && v.moving) {
    f.velocity = u.velocity.dot(v.value) + u.value.dot(v.velocity);
    f.convective = u.convective.dot(v.value) + 2.0 * u.velocity.dot(v.velocity) + u.value.dot(v.convective);
  }
  if (u.second && v.second) {
    const Mat14 cross = u.jacobian.transpose() * v.jacobian;
    f.hessian = cross + cross.transpose();
    for (int k = 0; k < 3; ++k) f.hessian += u.value[k] * v.hessian[k] + v.value[k] * u.hessian[k];
  }
  if (u.rated && v.rated && want.rate) {
    const Vec3 ud = u.jacobian * *want.rate, vd = v.jacobian * *want.rate;
    f.gradient_rate = ud.transpose() * v.jacobian + u.value.transpose() * v.jacobian_rate +
                      vd.transpose() * u.jacobian + v.value.transpose() * u.jacobian_rate;
  }
  return f;
}

/// ka a + kb b, term by term (the Hessian where want.hessian).
inline ScalarTerm combine(double ka, const ScalarTerm& a, double kb, const ScalarTerm& b, const Want& want) {
  ScalarTerm f;
  f.value = ka * a.value + kb * b.value;
  f.gradient = ka * a.gradient + kb * b.gradient;
  f.gradient_rate = ka * a.gradient_rate + kb * b.gradient_rate;
  f.velocity = ka * a.velocity + kb * b.velocity;
  f.convective = ka * a.convective + kb * b.convective;
  if (want.hessian) f.hessian = ka * a.hessian + kb * b.hessian;
  return f;
}

/// Component k of u as a scalar term.
inline ScalarTerm component(const VectorTerm& u, int k) {
  ScalarTerm f;
  f.value = u.value[k];
  if (u.first) f.gradient = u.jacobian.row(k);
  if (u.moving) {
    f.velocity = u.velocity[k];
    f.convective = u.convective[k];
  }
  if (u.second) f.hessian = u.hessian[k];
  if (u.rated) f.gradient_rate = u.jacobian_rate.row(k);
  return f;
}

/// |u| (u != 0): gradient u^T u_c / |u|, Hessian (u_c^T u_c + sum_k u_k
/// u_k,cc) / |u| - grad^T grad / |u|. (No rate: forces need the Hessian.)
/// Along the path, with s = u.u: l' = s' / 2l, l'' = s'' / 2l - l'^2 / l.
inline ScalarTerm length(const VectorTerm& u) {
  ScalarTerm f = dot(u, u);
  const double l = std::sqrt(f.value);
  f.value = l;
  f.gradient /= 2.0 * l;
  f.velocity /= 2.0 * l;
  f.convective = f.convective / (2.0 * l) - f.velocity * f.velocity / l;
  if (u.second) f.hessian = f.hessian / (2.0 * l) - f.gradient.transpose() * f.gradient / l;
  return f;
}

/// The angle atan2(u, w) in (-pi, pi]: with D = u^2 + w^2,
///   grad = (w u_c - u w_c) / D,
///   Hess = (u_c^T w_c - w_c^T u_c + w u_cc - u w_cc) / D - 2 grad^T (u u_c + w w_c) / D
/// (symmetric, though its parts are not), and along cd (u' = u_c cd)
///   (Hess cd)^T = (w' u_c - u' w_c + w (u_cc cd)^T - u (w_cc cd)^T) / D - 2 (u u' + w w') grad / D;
/// along the path f' = (w u' - u w') / D, f'' = (w u'' - u w'') / D - 2 (u u' + w w') f' / D.
inline ScalarTerm angle(const ScalarTerm& u, const ScalarTerm& w, const Want& want) {
  ScalarTerm f;
  const double D = u.value * u.value + w.value * w.value;
  f.value = std::atan2(u.value, w.value);
  f.gradient = (w.value * u.gradient - u.value * w.gradient) / D;
  if (want.path) {
    f.velocity = (w.value * u.velocity - u.value * w.velocity) / D;
    f.convective = (w.value * u.convective - u.value * w.convective) / D -
                   2.0 * (u.value * u.velocity + w.value * w.velocity) * f.velocity / D;
  }
  if (want.hessian) {
    const Mat14 cross = u.gradient.transpose() * w.gradient;
    f.hessian = (cross - cross.transpose() + w.value * u.hessian - u.value * w.hessian) / D -
                2.0 * f.gradient.transpose() * (u.value * u.gradient + w.value * w.gradient) / D;
  }
  if (want.rate) {
    const double ud = u.gradient.dot(*want.rate), wd = w.gradient.dot(*want.rate);
    f.gradient_rate = (wd * u.gradient - ud * w.gradient + w.value * u.gradient_rate - u.value * w.gradient_rate) / D -
                      2.0 * (u.value * ud + w.value * wd) / D * f.gradient;
  }
  return f;
}

/// A spring-damper-actuator on a scalar coordinate s(c) with rate s' = s_c cd:
///   F = -k (s - s0) - c s' + f,   Q = F s_c^T,
///   Q_c = s_c^T (-k s_c - c (s_cc cd)^T) + F s_cc,   Q_cd = -c s_c^T s_c,
/// added to Q (and, if given, to Q_c and Q_cd). Potential k (s - s0)^2 / 2.
/// F alone is spring_damper_force (what the force kinds' efforts read).
inline double spring_damper_force(const ScalarTerm& s, const Loc& cd, double k, double c, double s0, double f) {
  return -k * (s.value - s0) - c * s.gradient.dot(cd) + f;
}
inline void add_spring_damper(const ScalarTerm& s, const Loc& cd, double k, double c, double s0, double f, Loc& Q,
                              Mat14* Q_c = nullptr, Mat14* Q_cd = nullptr) {
  const double F = spring_damper_force(s, cd, k, c, s0, f);
  Q += F * s.gradient.transpose();
  if (Q_c) *Q_c += s.gradient.transpose() * (-k * s.gradient - c * (s.hessian * cd).transpose()) + F * s.hessian;
  if (Q_cd) *Q_cd -= c * s.gradient.transpose() * s.gradient;
}

/// Rows of a joint as scalar terms, for the kinds' phi, jacobian and
/// hessians: each kind lists its rows once (terms(c, second)) and these give
/// the three views of them.
template <int R>
using Terms = std::array<ScalarTerm, R>;

template <int R>
Eigen::Matrix<double, R, 1> values(const Terms<R>& t) {
  Eigen::Matrix<double, R, 1> v;
  for (int r = 0; r < R; ++r) v[r] = t[r].value;
  return v;
}

template <int R>
Eigen::Matrix<double, R, 14> gradients(const Terms<R>& t) {
  Eigen::Matrix<double, R, 14> J;
  for (int r = 0; r < R; ++r) J.row(r) = t[r].gradient;
  return J;
}

template <int R>
void hessians(const Terms<R>& t, Mat14* H) {
  for (int r = 0; r < R; ++r) H[r] = t[r].hessian;
}

template <int R>
Eigen::Matrix<double, R, 1> convectives(const Terms<R>& t) {
  Eigen::Matrix<double, R, 1> v;
  for (int r = 0; r < R; ++r) v[r] = t[r].convective;
  return v;
}

template <int R>
Eigen::Matrix<double, R, 14> gradient_rates(const Terms<R>& t) {
  Eigen::Matrix<double, R, 14> V;
  for (int r = 0; r < R; ++r) V.row(r) = t[r].gradient_rate;
  return V;
}

/// The spatial joint kinds' views of their rows, from the kind's
///   Terms<rows> terms(const Loc& c, const Want& want) const;
/// (a base by CRTP: each kind states its rows once). rates(c, cd) gives
/// the rows (H_r cd)^T, for the velocity Jacobian, and gamma(c, cd) =
/// -cd^T H_r cd from the convective terms, neither forming the Hessians
/// nor (gamma) a gradient (constraint_group.hpp).
template <class Kind, int R>
struct TermJoint {
  using Space = Spatial;
  static constexpr int rows = R;
  Eigen::Matrix<double, R, 1> phi(const Loc& c, double) const {
    Want want;
    want.gradient = false;
    return values<R>(self().terms(c, want));
  }
  Eigen::Matrix<double, R, 1> gamma(const Loc& c, const Loc& cd, double) const {
    Want want;
    want.gradient = false;
    want.path = &cd;
    return -convectives<R>(self().terms(c, want));
  }
  Eigen::Matrix<double, R, 14> jacobian(const Loc& c, double) const { return gradients<R>(self().terms(c, {})); }
  void hessians(const Loc& c, double, Mat14* H) const { spatial::hessians<R>(self().terms(c, {true}), H); }
  Eigen::Matrix<double, R, 14> rates(const Loc& c, const Loc& cd, double) const {
    Want want;
    want.rate = &cd;
    return gradient_rates<R>(self().terms(c, want));
  }

 private:
  const Kind& self() const { return static_cast<const Kind&>(*this); }
};

}  // namespace lagmb::spatial
