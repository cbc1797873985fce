// How spatial elements read a joint's coordinate: a revolute's (or
// cylindrical joint's) angle, a translational's slide, and JointReading,
// which keeps the angle continuous through the joint's turns in a run.
#pragma once

#include <cmath>

#include "lagmb/spatial_terms.hpp"
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

}  // namespace lagmb
