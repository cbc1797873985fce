// A torque on a body in space, in global or body axes.
#pragma once

#include <array>

#include "lagmb/elements/spatial_force_base.hpp"

namespace lagmb {

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
