// Spatial force elements: spring-damper-actuators on a distance, on a
// revolute's angle and on the six relative coordinates of a bushing (all
// spatial::add_spring_damper on a scalar term), and applied forces and
// torques.
#pragma once

#include <array>
#include <string>

#include "lagmb/elements/spatial_drivers.hpp"
#include "lagmb/elements/spatial_terms.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

struct SpatialForceBase {
  using Space = Spatial;
  static constexpr bool state_dependent = true;
  std::string name;
  int body_i = -1, body_j = -1;
};

/// A spring-damper-actuator on one scalar coordinate s(c) of the kind
/// (`coordinate(c, want, t)`): F = -k (s - s0) - c s' + f(t) along s
/// (spatial::add_spring_damper), potential k (s - s0)^2 / 2. Its effort
/// (Result.effort) is that F, the actuator's f(t) at the run's inputs
/// included.
template <class Kind>
struct ScalarSpringDamper : SpatialForceBase {
  double stiffness = 0.0, damping = 0.0, free_value = 0.0;  // k, c, s0
  Drive actuator;  // f(t); may be null
  static constexpr bool reads_inputs = true;

  double act(const Instant& t) const { return actuator ? actuator.at(t).f : 0.0; }
  double effort(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t) const {
    return spatial::spring_damper_force(self().coordinate(c, {}, t), cd, stiffness, damping, free_value, act(t));
  }
  spatial::Loc force(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t) const {
    spatial::Loc Q = spatial::Loc::Zero();
    spatial::add_spring_damper(self().coordinate(c, {}, t), cd, stiffness, damping, free_value, act(t), Q);
    return Q;
  }
  void derivatives(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t, spatial::Mat14& dq,
                   spatial::Mat14& dv) const {
    spatial::Loc Q = spatial::Loc::Zero();
    dq.setZero();
    dv.setZero();
    spatial::add_spring_damper(self().coordinate(c, {true}, t), cd, stiffness, damping, free_value, act(t), Q, &dq,
                               &dv);
  }
  double potential(const spatial::Loc& c, const Instant& t) const {
    const double e = self().coordinate(c, {}, t).value - free_value;
    return 0.5 * stiffness * e * e;
  }

 private:
  const Kind& self() const { return static_cast<const Kind&>(*this); }
};

/// Translational spring-damper-actuator between the points s_i and s_j, on
/// l = |d| (s0: the free length): F > 0 pushes the points apart.
struct SpatialSpringDamper : ScalarSpringDamper<SpatialSpringDamper> {
  static constexpr const char* kind = "spatial_spring_damper";
  Vec3 s_i = Vec3::Zero(), s_j = Vec3::Zero();

  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want& want, const Instant&) const {
    using namespace spatial;
    return length(minus(body_point(c, kBodyJ, s_j, want), body_point(c, kBodyI, s_i, want)));
  }
};

/// Rotational spring-damper-actuator on a revolute's (or cylindrical
/// joint's) angle theta, continuous through the joint's turns in a run
/// (spatial::JointReading; s0: the free angle): the torque on body j about
/// the axis is T = -k (theta - theta0) - c theta' + tau(t).
struct SpatialRotationalSpringDamper : ScalarSpringDamper<SpatialRotationalSpringDamper> {
  static constexpr const char* kind = "spatial_rotational_spring_damper";
  spatial::JointReading joint;

  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want& want, const Instant& t) const {
    return joint(c, want, t);
  }
};

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

/// A force F at the point s of body i (body j: the ground), given by its
/// components as functions of time, in global axes or (local) in the
/// body's axes, turning with it (F = A(p) F'). Virtual work F . d(r + A s):
///   Q_r = F,  Q_p = point_jacobian(p, s)^T F,
/// and for a local force Q_p also depends on p through F = A(p) F'.
/// Its effort (Result.effort) is F in global axes, as applied at the run's
/// inputs.
struct SpatialAppliedForce : SpatialForceBase {
  static constexpr const char* kind = "spatial_force";
  Vec3 s = Vec3::Zero();
  std::array<Drive, 3> components;
  static constexpr bool reads_inputs = true;
  bool local = false;

  Vec3 given(const Instant& t) const {
    return Vec3(components[0].at(t).f, components[1].at(t).f, components[2].at(t).f);
  }
  Vec3 effort(const spatial::Loc& c, const spatial::Loc&, const Instant& t) const {
    return local ? euler::rotate(c.segment<4>(3), given(t)) : given(t);
  }
  spatial::Loc force(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t) const {
    const Vec4 p = c.segment<4>(3);
    const Vec3 F = effort(c, cd, t);
    spatial::Loc Q = spatial::Loc::Zero();
    Q.head<3>() = F;
    Q.segment<4>(3) = euler::point_jacobian(p, s).transpose() * F;
    return Q;
  }
  /// dQ/dp: point_hessian(s, F) for a global F; for a local one F = A(p) F'
  /// adds F_p = point_jacobian(p, F') to both parts.
  void derivatives(const spatial::Loc& c, const spatial::Loc&, const Instant& t, spatial::Mat14& dq,
                   spatial::Mat14& dv) const {
    dq.setZero();
    dv.setZero();
    const Vec4 p = c.segment<4>(3);
    const Vec3 Fl = given(t);
    const Vec3 F = local ? euler::rotate(p, Fl) : Fl;
    dq.block<4, 4>(3, 3) = euler::point_hessian(s, F);
    if (local) {
      const Mat34 F_p = euler::point_jacobian(p, Fl);
      dq.block<3, 4>(0, 3) = F_p;
      dq.block<4, 4>(3, 3) += euler::point_jacobian(p, s).transpose() * F_p;
    }
  }
  double potential(const spatial::Loc&, const Instant&) const { return 0.0; }
};

/// A torque n on body i, global or (local) in the body's axes: Q_p =
/// 2 E(p)^T n, or 2 G(p)^T n' (lagmb/spatial.hpp); linear in p:
///   E(p)^T n = X(n) p, X(n) = [[0, -n^T], [n, skew(n)]];  G(p)^T n' = W(n') p.
/// Its effort (Result.effort) is n in global axes (A(p) n' for a local one).
struct SpatialAppliedTorque : SpatialForceBase {
  static constexpr const char* kind = "spatial_torque";
  std::array<Drive, 3> components;
  static constexpr bool reads_inputs = true;
  bool local = false;

  Vec3 given(const Instant& t) const {
    return Vec3(components[0].at(t).f, components[1].at(t).f, components[2].at(t).f);
  }
  Mat4 operator_of(const Vec3& n) const {
    if (local) return euler::W(n);
    Mat4 X;
    X(0, 0) = 0.0;
    X.block<1, 3>(0, 1) = -n.transpose();
    X.block<3, 1>(1, 0) = n;
    X.block<3, 3>(1, 1) = skew(n);
    return X;
  }
  Vec3 effort(const spatial::Loc& c, const spatial::Loc&, const Instant& t) const {
    return local ? euler::rotate(c.segment<4>(3), given(t)) : given(t);
  }
  spatial::Loc force(const spatial::Loc& c, const spatial::Loc&, const Instant& t) const {
    spatial::Loc Q = spatial::Loc::Zero();
    Q.segment<4>(3) = 2.0 * operator_of(given(t)) * c.segment<4>(3);
    return Q;
  }
  void derivatives(const spatial::Loc&, const spatial::Loc&, const Instant& t, spatial::Mat14& dq, spatial::Mat14& dv) const {
    dq.setZero();
    dv.setZero();
    dq.block<4, 4>(3, 3) = 2.0 * operator_of(given(t));
  }
  double potential(const spatial::Loc&, const Instant&) const { return 0.0; }
};

}  // namespace lagmb
