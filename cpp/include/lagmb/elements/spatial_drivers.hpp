// Spatial drivers: prescribed motion of a revolute's angle, a translational
// or cylindrical joint's slide, or a body's coordinate. As in the plane, the
// effort is -lam, positive along the driven coordinate.
#pragma once

#include <cmath>
#include <string>

#include "lagmb/elements/spatial_terms.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

/// One row, time dependent through f.
struct SpatialDriverBase {
  using Space = Spatial;
  static constexpr int rows = 1;
  static constexpr bool time_dependent = true;
  using Row = Eigen::Matrix<double, 1, 1>;
  using Grad = Eigen::Matrix<double, 1, 14>;
  std::string name;
  int body_i = -1, body_j = -1;
  TimeFunctionPtr f;
  Mat3 axes(const spatial::Loc&, double) const { return Mat3::Identity(); }
};

/// The angle of a revolute (or cylindrical) joint: body j's copy f_j of the
/// joint's f_i, turned about a = f_i x g_i by theta, has u = f_j . g_i =
/// sin theta and w = f_j . f_i = cos theta (global vectors). The row
///   Phi = u cos f(t) - w sin f(t)   (= sin(theta - f) on the joint)
/// holds theta = f(t) with no jump at +-pi, and dPhi/dtheta = 1 there, so
/// lam is minus the torque about a on body j. With phi = f(t):
///   Phi_t  = -(u sin phi + w cos phi) f'
///   Phi_tc = -(u_c sin phi + w_c cos phi) f'
///   Phi_tt = -(u cos phi - w sin phi) f'^2 - (u sin phi + w cos phi) f''.
struct SpatialAngleDriver : SpatialDriverBase {
  static constexpr const char* kind = "spatial_angle_driver";
  Vec3 f_i = Vec3::UnitX(), g_i = Vec3::UnitY(), f_j = Vec3::UnitX();

  void sides(const spatial::Loc& c, const spatial::Want& want, spatial::ScalarTerm& u,
             spatial::ScalarTerm& w) const {
    using namespace spatial;
    const VectorTerm fj = body_vector(c, kBodyJ, f_j, want);
    u = dot(fj, body_vector(c, kBodyI, g_i, want), want);
    w = dot(fj, body_vector(c, kBodyI, f_i, want), want);
  }
  Row phi(const spatial::Loc& c, double t) const {
    spatial::ScalarTerm u, w;
    sides(c, {}, u, w);
    const double a = f->eval(t).f;
    return Row(u.value * std::cos(a) - w.value * std::sin(a));
  }
  Grad jacobian(const spatial::Loc& c, double t) const {
    spatial::ScalarTerm u, w;
    sides(c, {}, u, w);
    const double a = f->eval(t).f;
    return u.gradient * std::cos(a) - w.gradient * std::sin(a);
  }
  void hessians(const spatial::Loc& c, double t, spatial::Mat14* H) const {
    spatial::ScalarTerm u, w;
    sides(c, {true}, u, w);
    const double a = f->eval(t).f;
    H[0] = u.hessian * std::cos(a) - w.hessian * std::sin(a);
  }
  /// (H cd)^T, for gamma and the velocity Jacobian (TermJoint::rates).
  Grad rates(const spatial::Loc& c, const spatial::Loc& cd, double t) const {
    spatial::Want want;
    want.rate = &cd;
    spatial::ScalarTerm u, w;
    sides(c, want, u, w);
    const double a = f->eval(t).f;
    return u.gradient_rate * std::cos(a) - w.gradient_rate * std::sin(a);
  }
  Row phi_t(const spatial::Loc& c, double t) const {
    spatial::ScalarTerm u, w;
    sides(c, {}, u, w);
    const TimeValue v = f->eval(t);
    return Row(-(u.value * std::sin(v.f) + w.value * std::cos(v.f)) * v.df);
  }
  Grad phi_tc(const spatial::Loc& c, double t) const {
    spatial::ScalarTerm u, w;
    sides(c, {}, u, w);
    const TimeValue v = f->eval(t);
    return -(u.gradient * std::sin(v.f) + w.gradient * std::cos(v.f)) * v.df;
  }
  Row phi_tt(const spatial::Loc& c, double t) const {
    spatial::ScalarTerm u, w;
    sides(c, {}, u, w);
    const TimeValue v = f->eval(t);
    const double s = std::sin(v.f), co = std::cos(v.f);
    return Row(-(u.value * co - w.value * s) * v.df * v.df - (u.value * s + w.value * co) * v.ddf);
  }
};

/// Shared by drivers whose row is g(c) - f(t) with g a scalar term:
/// Phi_t = -f', Phi_tc = 0, Phi_tt = -f''.
template <class Kind>
struct SpatialCoordinateDriverBase : SpatialDriverBase {
  Row phi(const spatial::Loc& c, double t) const { return Row(self().coordinate(c, {}).value - f->eval(t).f); }
  Grad jacobian(const spatial::Loc& c, double) const { return self().coordinate(c, {}).gradient; }
  void hessians(const spatial::Loc& c, double, spatial::Mat14* H) const { H[0] = self().coordinate(c, {true}).hessian; }
  Grad rates(const spatial::Loc& c, const spatial::Loc& cd, double) const {
    spatial::Want want;
    want.rate = &cd;
    return self().coordinate(c, want).gradient_rate;
  }
  Row phi_t(const spatial::Loc&, double t) const { return Row(-f->eval(t).df); }
  Grad phi_tc(const spatial::Loc&, double) const { return Grad::Zero(); }
  Row phi_tt(const spatial::Loc&, double t) const { return Row(-f->eval(t).ddf); }

 private:
  const Kind& self() const { return static_cast<const Kind&>(*this); }
};

/// The slide of a translational or cylindrical joint: g = (A_i a_i) . d,
/// d from the joint point on body i to the one on body j (0 in the initial
/// configuration). Effort: the force along a on body j.
struct SpatialSlideDriver : SpatialCoordinateDriverBase<SpatialSlideDriver> {
  static constexpr const char* kind = "spatial_slide_driver";
  Vec3 s_i = Vec3::Zero(), s_j = Vec3::Zero(), a_i = Vec3::UnitZ();
  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want& want) const {
    using namespace spatial;
    return dot(body_vector(c, kBodyI, a_i, want),
               minus(body_point(c, kBodyJ, s_j, want), body_point(c, kBodyI, s_i, want)), want);
  }
};

/// A coordinate x, y or z (k = 0, 1, 2) of body j's centre of mass (body i
/// is the ground): g = r_j,k. Effort: the force along that axis on body j.
struct SpatialPositionDriver : SpatialCoordinateDriverBase<SpatialPositionDriver> {
  static constexpr const char* kind = "spatial_position_driver";
  int axis = 0;
  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want&) const {
    spatial::ScalarTerm g;
    g.value = c[7 + axis];
    g.gradient[7 + axis] = 1.0;
    g.hessian.setZero();
    return g;
  }
};

}  // namespace lagmb
