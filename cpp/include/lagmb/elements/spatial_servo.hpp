// A joint servo: an actuator that drives a joint's coordinate toward a
// target with a PD law, inside the integrator (MuJoCo's position actuator
// with its velocity gain, plus a feed-forward and a torque limit).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "lagmb/model/joint_reading.hpp"
#include "lagmb/elements/spatial_force_base.hpp"
#include "lagmb/spatial_terms.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

/// On the joint's coordinate theta (a revolute's or cylindrical joint's
/// angle, counting whole turns, or a translational joint's slide:
/// spatial::JointReading), the generalized force along theta on body j
///   tau = sat(kp (theta*(t) - theta) + kd (theta*'(t) - theta') + tau_ff(t))
/// with sat clamping to [-tau_max, tau_max] (N m, or N for a slide). The
/// target theta* is a function of time or an mb.Input (then theta*' = 0,
/// and a new value steps the target); tau_ff likewise. Unsaturated it is
/// the spring-damper -kp (theta - theta*) - kd theta' + (kd theta*' +
/// tau_ff) (spatial::add_spring_damper, exact Q_c and Q_cd); saturated, a
/// constant +-tau_max along theta (Q_c = tau H_theta, Q_cd = 0). No
/// potential: it is an actuator, its work enters r.energy as work done.
/// Its effort (Result.effort) is tau as applied, after the clamp.
struct SpatialJointServo : SpatialForceBase {
  static constexpr const char* kind = "spatial_joint_servo";
  static constexpr bool reads_inputs = true;
  spatial::JointReading joint;
  double kp = 0.0, kd = 0.0;  // N m/rad, N m s/rad (N/m, N s/m)
  double limit = std::numeric_limits<double>::infinity();
  Drive target, feedforward;  // theta*(t); tau_ff(t), may be null

  /// The law's parts at t: the target's value and rate, and the force added
  /// to the spring-damper (kd theta*' + tau_ff).
  struct Set {
    double value, rate, added;
  };
  Set at(const Instant& t) const {
    const TimeValue s = target.at(t);
    return {s.f, s.df, kd * s.df + (feedforward ? feedforward.at(t).f : 0.0)};
  }
  /// tau before the clamp.
  double demand(const spatial::ScalarTerm& s, const spatial::Loc& cd, const Set& set) const {
    return -kp * (s.value - set.value) - kd * s.gradient.dot(cd) + set.added;
  }
  double effort(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t) const {
    const double tau = demand(joint(c, {}, t), cd, at(t));
    return std::abs(tau) <= limit ? tau : std::copysign(limit, tau);
  }
  void add(const spatial::ScalarTerm& s, const spatial::Loc& cd, const Instant& t, spatial::Loc& Q,
           spatial::Mat14* Q_c, spatial::Mat14* Q_cd) const {
    const Set set = at(t);
    const double tau = demand(s, cd, set);
    if (std::abs(tau) <= limit)
      spatial::add_spring_damper(s, cd, kp, kd, set.value, set.added, Q, Q_c, Q_cd);
    else
      spatial::add_spring_damper(s, cd, 0.0, 0.0, 0.0, std::copysign(limit, tau), Q, Q_c, Q_cd);
  }
  spatial::Loc force(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t) const {
    spatial::Loc Q = spatial::Loc::Zero();
    add(joint(c, {}, t), cd, t, Q, nullptr, nullptr);
    return Q;
  }
  void derivatives(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t, spatial::Mat14& dq,
                   spatial::Mat14& dv) const {
    spatial::Loc Q = spatial::Loc::Zero();
    dq.setZero();
    dv.setZero();
    add(joint(c, {true}, t), cd, t, Q, &dq, &dv);
  }
  double potential(const spatial::Loc&, const Instant&) const { return 0.0; }
};

}  // namespace lagmb
