// Spatial drivers: prescribed motion of a revolute's angle, a translational
// or cylindrical joint's slide, or a body's coordinate. As in the plane, the
// effort is -lam, positive along the driven coordinate.
#pragma once

#include <cmath>
#include <string>

#include "lagmb/elements/spatial_terms.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

namespace spatial {

/// The angle of a revolute (or cylindrical) joint: body j's copy f_j of the
/// joint's f_i, turned about a = f_i x g_i by theta, has f_j . g_i =
/// sin theta and f_j . f_i = cos theta (global vectors), so
///   theta = atan2(f_j . g_i, f_j . f_i)   in (-pi, pi]   (spatial_terms.hpp, angle).
/// What its drivers, stops and springs act on.
inline ScalarTerm joint_angle(const Loc& c, const Vec3& f_i, const Vec3& g_i, const Vec3& f_j, const Want& want) {
  const VectorTerm fj = body_vector(c, kBodyJ, f_j, want);
  return angle(dot(fj, body_vector(c, kBodyI, g_i, want), want), dot(fj, body_vector(c, kBodyI, f_i, want), want),
               want);
}

/// The slide of a translational or cylindrical joint: (A_i a_i) . d, d from
/// the joint point on body i to the one on body j (0 in the initial
/// configuration).
inline ScalarTerm joint_slide(const Loc& c, const Vec3& s_i, const Vec3& s_j, const Vec3& a_i, const Want& want) {
  return dot(body_vector(c, kBodyI, a_i, want), minus(body_point(c, kBodyJ, s_j, want), body_point(c, kBodyI, s_i, want)),
             want);
}

/// A joint's coordinate as springs, couplings and stops read it: a
/// revolute's angle (joint_angle) taken within pi of a center, so that the
/// reading does not wrap where the element acts, or a translational's slide
/// (joint_slide). The center is `center` (the angle in the initial
/// configuration; a stop's: the middle of its range) and, in a run, moves
/// with the joint: `turns` >= 0 is the joint's slots in the run's state,
/// whose first holds how far the run has moved it (count_turns,
/// model/joint_turns.hpp: the angle at the last step), so an angle read in a
/// run is continuous however many turns the joint makes. The shift by a
/// whole number of turns is constant where the reading is smooth: the
/// derivatives are joint_angle's.
struct JointReading {
  bool slide = false;
  Vec3 f_i = Vec3::UnitX(), g_i = Vec3::UnitY(), f_j = Vec3::UnitX();  // the angle's (joint_coordinate.hpp)
  Vec3 s_i = Vec3::Zero(), s_j = Vec3::Zero(), a_i = Vec3::UnitZ();    // the slide's
  double center = 0.0;                                                  // rad
  int turns = -1;  // the joint's slots in Instant::state (-1: the center stays where it is)

  /// The center at an instant of a run (outside a run, at.state null: `center`).
  double center_at(const Instant& at) const { return turns >= 0 && at.state ? center + at.state[turns] : center; }
  /// The coordinate with the angle read within pi of `around`.
  ScalarTerm read(const Loc& c, const Want& want, double around) const {
    if (slide) return joint_slide(c, s_i, s_j, a_i, want);
    ScalarTerm s = joint_angle(c, f_i, g_i, f_j, want);
    s.value = around + std::remainder(s.value - around, 2.0 * kPi);
    return s;
  }
  ScalarTerm operator()(const Loc& c, const Want& want, const Instant& at) const {
    return read(c, want, center_at(at));
  }
  /// Within pi of the fixed center.
  ScalarTerm operator()(const Loc& c, const Want& want) const { return read(c, want, center); }
};

}  // namespace spatial

/// One row, time dependent through f.
struct SpatialDriverBase {
  using Space = Spatial;
  static constexpr int rows = 1;
  static constexpr bool time_dependent = true;
  using Row = Eigen::Matrix<double, 1, 1>;
  using Grad = Eigen::Matrix<double, 1, 14>;
  std::string name;
  int body_i = -1, body_j = -1;
  Drive f;  // the prescribed value
  static constexpr bool reads_inputs = true;
  static constexpr bool ties_motion = true;  // (is_tie)
  Mat3 axes(const spatial::Loc&, const Instant&) const { return Mat3::Identity(); }
};

/// Shared by drivers whose row is g(c) - f(t) with g a scalar term:
/// Phi_t = -f', Phi_tc = 0, Phi_tt = -f''. A kind whose g is an angle
/// (periodic = true) takes the difference into (-pi, pi]: g and g + 2 pi are
/// one configuration, and the row then has the one root g = f (mod 2 pi),
/// whatever f's start and however far it jumps; the wrap is constant near
/// the root, so the derivatives are those of g - f.
template <class Kind>
struct SpatialCoordinateDriverBase : SpatialDriverBase {
  static constexpr bool periodic = false;
  Row phi(const spatial::Loc& c, const Instant& t) const {
    const double difference = self().coordinate(c, {}).value - f.at(t).f;
    return Row(Kind::periodic ? std::remainder(difference, 2.0 * kPi) : difference);
  }
  Grad jacobian(const spatial::Loc& c, const Instant&) const { return self().coordinate(c, {}).gradient; }
  void hessians(const spatial::Loc& c, const Instant&, spatial::Mat14* H) const { H[0] = self().coordinate(c, {true}).hessian; }
  Grad rates(const spatial::Loc& c, const spatial::Loc& cd, const Instant&) const {
    spatial::Want want;
    want.rate = &cd;
    return self().coordinate(c, want).gradient_rate;
  }
  Row phi_t(const spatial::Loc&, const Instant& t) const { return Row(-f.at(t).df); }
  Grad phi_tc(const spatial::Loc&, const Instant&) const { return Grad::Zero(); }
  Row phi_tt(const spatial::Loc&, const Instant& t) const { return Row(-f.at(t).ddf); }

 private:
  const Kind& self() const { return static_cast<const Kind&>(*this); }
};

/// The angle of a revolute (or cylindrical) joint, g = theta
/// (spatial::joint_angle); the row theta - f(t), wrapped (periodic), holds
/// theta = f(t) mod 2 pi. dPhi/dtheta = 1, so lam is minus the torque about
/// a on body j.
struct SpatialAngleDriver : SpatialCoordinateDriverBase<SpatialAngleDriver> {
  static constexpr const char* kind = "spatial_angle_driver";
  static constexpr bool periodic = true;
  Vec3 f_i = Vec3::UnitX(), g_i = Vec3::UnitY(), f_j = Vec3::UnitX();

  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want& want) const {
    return spatial::joint_angle(c, f_i, g_i, f_j, want);
  }
};

/// The slide of a translational or cylindrical joint, g = (A_i a_i) . d
/// (spatial::joint_slide). Effort: the force along a on body j.
struct SpatialSlideDriver : SpatialCoordinateDriverBase<SpatialSlideDriver> {
  static constexpr const char* kind = "spatial_slide_driver";
  Vec3 s_i = Vec3::Zero(), s_j = Vec3::Zero(), a_i = Vec3::UnitZ();
  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want& want) const {
    return spatial::joint_slide(c, s_i, s_j, a_i, want);
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
