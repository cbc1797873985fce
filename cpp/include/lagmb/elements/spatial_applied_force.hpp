// A force at a point of a body in space, in global or body axes.
#pragma once

#include <array>

#include "lagmb/elements/spatial_force_base.hpp"

namespace lagmb {

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

}  // namespace lagmb
