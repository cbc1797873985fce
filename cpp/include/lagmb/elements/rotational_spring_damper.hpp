// Rotational spring-damper-actuator between two bodies.
#pragma once

#include <string>

#include "lagmb/time_function.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// theta = phi_j - phi_i; the torque on body j is
///   tau = -k (theta - theta0) - c thetadot + tau_act(t),
/// body i gets -tau. Q_c and Q_cd are constant: +-k and +-c on the angles.
/// Potential k (theta - theta0)^2 / 2. Its effort (Result.effort) is tau.
struct RotationalSpringDamper {
  static constexpr bool state_dependent = true;
  static constexpr const char* kind = "rotational_spring_damper";
  static constexpr bool reads_inputs = true;

  std::string name;
  int body_i = -1, body_j = -1;
  double stiffness = 0.0, damping = 0.0, free_angle = 0.0;
  Drive actuator;  // may be null

  double effort(const Local6& c, const Local6& cd, const Instant& t) const {
    const double tau = -stiffness * (c[5] - c[2] - free_angle) - damping * (cd[5] - cd[2]);
    return actuator ? tau + actuator.at(t).f : tau;
  }
  Local6 force(const Local6& c, const Local6& cd, const Instant& t) const {
    const double tau = effort(c, cd, t);
    Local6 Q = Local6::Zero();
    Q[2] = -tau;
    Q[5] = tau;
    return Q;
  }
  void derivatives(const Local6&, const Local6&, const Instant&, Mat6& Q_c, Mat6& Q_cd) const {
    Q_c.setZero();
    Q_cd.setZero();
    for (auto [M, k] : {std::pair<Mat6*, double>{&Q_c, stiffness}, {&Q_cd, damping}}) {
      (*M)(2, 2) = (*M)(5, 5) = -k;
      (*M)(2, 5) = (*M)(5, 2) = k;
    }
  }
  double potential(const Local6& c, const Instant&) const {
    const double e = c[5] - c[2] - free_angle;
    return 0.5 * stiffness * e * e;
  }
};

}  // namespace lagmb
