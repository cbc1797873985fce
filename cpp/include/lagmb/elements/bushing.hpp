// A bushing: six spring-dampers on the relative translations and rotations
// of two frames, one fixed in each body.
#pragma once

#include <array>

#include "lagmb/elements/spatial_force_base.hpp"

namespace lagmb {

/// Bushing: six spring-dampers between a frame fixed in body i and one fixed
/// in body j, both at the point `at` with the global axes of the initial
/// configuration. With d from the point on body i to the one on body j and
/// (x, y, z)_i, (x, y, z)_j the frames' axes in global components:
///   translations  delta = (x_i . d, y_i . d, z_i . d)
///   rotations     rho = ((z_i . y_j - y_i . z_j) / 2, (x_i . z_j - z_i . x_j) / 2,
///                        (y_i . x_j - x_i . y_j) / 2)
/// (rho is the rotation vector for small turns, sin(angle) for a turn about
/// one axis); each gets F = -k s - c s'. Potential sum k s^2 / 2.
/// Its effort (Result.effort) is the six F: the force on body j along the
/// axes of body i's frame (N) and the torque about them (N m; for small
/// relative turns, where rho is the rotation vector).
struct Bushing : SpatialForceBase {
  static constexpr const char* kind = "bushing";
  Vec3 s_i = Vec3::Zero(), s_j = Vec3::Zero();
  std::array<Vec3, 3> axes_i, axes_j;  // the frames' axes in each body's axes
  Vec3 stiffness = Vec3::Zero(), damping = Vec3::Zero();
  Vec3 rotational_stiffness = Vec3::Zero(), rotational_damping = Vec3::Zero();

  std::array<spatial::ScalarTerm, 6> coordinates(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    const VectorTerm d = minus(body_point(c, kBodyJ, s_j, want), body_point(c, kBodyI, s_i, want));
    std::array<VectorTerm, 3> ei, ej;
    for (int k = 0; k < 3; ++k) {
      ei[k] = body_vector(c, kBodyI, axes_i[k], want);
      ej[k] = body_vector(c, kBodyJ, axes_j[k], want);
    }
    std::array<ScalarTerm, 6> s;
    for (int k = 0; k < 3; ++k) {
      s[k] = dot(ei[k], d);
      const int a = (k + 1) % 3, b = (k + 2) % 3;  // rho_x from (y, z), rho_y from (z, x), rho_z from (x, y)
      ScalarTerm p = dot(ei[b], ej[a]), m = dot(ei[a], ej[b]);
      s[3 + k].value = 0.5 * (p.value - m.value);
      s[3 + k].gradient = 0.5 * (p.gradient - m.gradient);
      if (want.hessian) s[3 + k].hessian = 0.5 * (p.hessian - m.hessian);
    }
    return s;
  }
  double k(int a) const { return a < 3 ? stiffness[a] : rotational_stiffness[a - 3]; }
  double c(int a) const { return a < 3 ? damping[a] : rotational_damping[a - 3]; }
  Eigen::Matrix<double, 6, 1> effort(const spatial::Loc& q, const spatial::Loc& qd, double) const {
    const auto s = coordinates(q, {});
    Eigen::Matrix<double, 6, 1> F;
    for (int a = 0; a < 6; ++a) F[a] = spatial::spring_damper_force(s[a], qd, k(a), c(a), 0.0, 0.0);
    return F;
  }
  spatial::Loc force(const spatial::Loc& q, const spatial::Loc& qd, double) const {
    spatial::Loc Q = spatial::Loc::Zero();
    const auto s = coordinates(q, {});
    for (int a = 0; a < 6; ++a) spatial::add_spring_damper(s[a], qd, k(a), c(a), 0.0, 0.0, Q);
    return Q;
  }
  void derivatives(const spatial::Loc& q, const spatial::Loc& qd, double, spatial::Mat14& dq,
                   spatial::Mat14& dv) const {
    spatial::Loc Q = spatial::Loc::Zero();
    dq.setZero();
    dv.setZero();
    const auto s = coordinates(q, {true});
    for (int a = 0; a < 6; ++a) spatial::add_spring_damper(s[a], qd, k(a), c(a), 0.0, 0.0, Q, &dq, &dv);
  }
  double potential(const spatial::Loc& q, double) const {
    const auto s = coordinates(q, {});
    double V = 0.0;
    for (int a = 0; a < 6; ++a) V += 0.5 * k(a) * s[a].value * s[a].value;
    return V;
  }
};

}  // namespace lagmb
