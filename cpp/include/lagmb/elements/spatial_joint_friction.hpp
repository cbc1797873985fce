// The spatial kind "spatial_joint_friction" (registry.hpp; its builder in
// cpp/src/elements/spatial_joint_friction.cpp): friction in a spatial
// revolute or translational joint, a force on the joint's coordinate.
#pragma once

#include <string>

#include "lagmb/elements/joint_friction.hpp"
#include "lagmb/model/joint_reading.hpp"
#include "lagmb/elements/spatial_force_base.hpp"

namespace lagmb {

/// Load-independent friction on a joint's coordinate s (a revolute's angle,
/// a translational's slide; spatial::JointReading), the planar law
/// (joint_friction.hpp) with mu = 0:
///   F = -F_0 sgn_s(s') - c s',   sgn_s(x) = x / sqrt(x^2 + v_s^2),
/// F_0 the preload (a URDF joint's <dynamics friction>), c the viscous
/// coefficient (its damping), s' = s_c cd. As a generalized force Q = F
/// s_c^T (power F s' <= 0), with
///   Q_c = F s_cc + F_s' s_c^T (s_cc cd)^T,   Q_cd = F_s' s_c^T s_c.
/// Its effort (Result.effort) is F, on the joint's second body.
struct SpatialJointFriction : SpatialForceBase {
  static constexpr const char* kind = "spatial_joint_friction";
  spatial::JointReading joint;
  JointFrictionLaw law;  // p.mu = 0

  double effort(const spatial::Loc& c, const spatial::Loc& cd, double) const {
    double dF_dN, dF_drate;
    return law.value(0.0, joint(c, {}).gradient.dot(cd), dF_dN, dF_drate);
  }
  spatial::Loc force(const spatial::Loc& c, const spatial::Loc& cd, double) const {
    const spatial::ScalarTerm s = joint(c, {});
    double dF_dN, dF_drate;
    return law.value(0.0, s.gradient.dot(cd), dF_dN, dF_drate) * s.gradient.transpose();
  }
  void derivatives(const spatial::Loc& c, const spatial::Loc& cd, double, spatial::Mat14& dq,
                   spatial::Mat14& dv) const {
    spatial::Want want;
    want.hessian = true;
    const spatial::ScalarTerm s = joint(c, want);
    double dF_dN, dF_drate;
    const double F = law.value(0.0, s.gradient.dot(cd), dF_dN, dF_drate);
    dq = F * s.hessian + dF_drate * s.gradient.transpose() * (s.hessian * cd).transpose();
    dv = dF_drate * s.gradient.transpose() * s.gradient;
  }
  double potential(const spatial::Loc&, double) const { return 0.0; }
};

}  // namespace lagmb
