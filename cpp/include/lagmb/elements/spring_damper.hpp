// Translational spring-damper-actuator between a point of body i and a point
// of body j.
#pragma once

#include <string>

#include "lagmb/time_function.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// Along e = d / l, d = p_j - p_i, l = |d|: the force on body j is F e with
///   F = -k (l - l0) - c ldot + f_act(t)     (F > 0 pushes the points apart),
/// and -F e on body i. With D = dd/dc = [-I, -B_i s_i, I, B_j s_j] and
/// g = dl/dc = D^T e:
///   Q     = F g
///   Q_cd  = -c g g^T
///   Q_c   = g (-k g^T - c (L cd)^T) + F L,  L = d2l/dc2 = (D^T D + d_x H_x + d_y H_y - g g^T) / l
/// (H_k: second derivatives of d_k as in distance.hpp). Potential k (l - l0)^2 / 2.
/// Its effort (Result.effort) is F, the actuator's f_act(t) included.
struct SpringDamper {
  static constexpr bool state_dependent = true;
  static constexpr const char* kind = "spring_damper";
  static constexpr bool reads_inputs = true;

  std::string name;
  int body_i = -1, body_j = -1;
  Vec2 s_i = Vec2::Zero(), s_j = Vec2::Zero();
  double stiffness = 0.0, damping = 0.0, free_length = 0.0;
  Drive actuator;  // may be null

  struct Geometry {
    Vec2 d;
    double l;
    Eigen::Matrix<double, 2, 6> D;
    Local6 g;
  };
  Geometry geometry(const Local6& c) const {
    Geometry G;
    G.d = c.segment<2>(3) + rotation(c[5]) * s_j - c.segment<2>(0) - rotation(c[2]) * s_i;
    G.l = G.d.norm();
    G.D << -Mat2::Identity(), -rotation_derivative(c[2]) * s_i, Mat2::Identity(),
        rotation_derivative(c[5]) * s_j;
    G.g = G.D.transpose() * (G.d / G.l);
    return G;
  }
  double tension(const Geometry& G, const Local6& cd, const Instant& t) const {
    double F = -stiffness * (G.l - free_length) - damping * G.g.dot(cd);
    if (actuator) F += actuator.at(t).f;
    return F;
  }
  double effort(const Local6& c, const Local6& cd, const Instant& t) const { return tension(geometry(c), cd, t); }
  Local6 force(const Local6& c, const Local6& cd, const Instant& t) const {
    const Geometry G = geometry(c);
    return tension(G, cd, t) * G.g;
  }
  void derivatives(const Local6& c, const Local6& cd, const Instant& t, Mat6& Q_c, Mat6& Q_cd) const {
    const Geometry G = geometry(c);
    Mat6 L = G.D.transpose() * G.D - G.g * G.g.transpose();
    L(2, 2) += G.d.dot(rotation(c[2]) * s_i);
    L(5, 5) -= G.d.dot(rotation(c[5]) * s_j);
    L /= G.l;
    Q_cd = -damping * G.g * G.g.transpose();
    Q_c = G.g * (-stiffness * G.g - damping * (L * cd)).transpose() + tension(G, cd, t) * L;
  }
  double potential(const Local6& c, const Instant&) const {
    const double e = geometry(c).l - free_length;
    return 0.5 * stiffness * e * e;
  }
};

}  // namespace lagmb
