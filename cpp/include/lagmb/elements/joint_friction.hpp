// Joint friction: Coulomb (load from the joint's own reaction) + viscous, in
// revolute and translational joints.
#pragma once

#include <cmath>
#include <string>

#include "lagmb/projected_offset.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// Parameters of a joint's friction (SI units).
struct JointFrictionParameters {
  double mu = 0.0;              // Coulomb coefficient (-)
  double viscous = 0.0;         // c: N m s/rad (revolute) or N s/m (translational)
  double preload = 0.0;         // load-independent Coulomb part: N m or N
  double pin_radius = 0.0;      // revolute: friction arm r_pin of the load (m)
  double bearing_length = 0.0;  // translational: L in |N| + |M|/L (m); 0: moment ignored
  double slip_velocity = 1e-3;  // v_s of the regularized sign (rad/s or m/s)
  double load_smoothing = 1e-6; // F_s of the smoothed |.| of the reaction (N, or N m for M)
};

/// The friction law, shared by both joint kinds. With s the joint's relative
/// coordinate (revolute: theta = phi_j - phi_i; translational: the slide
/// u_i . (p_j - p_i)), sd = ds/dt its rate and N >= 0 the joint's load:
///
///   F = -(mu rho N + F_0) sgn_s(sd) - c sd,   sgn_s(x) = x / sqrt(x^2 + v_s^2)
///
/// with rho = r_pin (revolute) or 1 (translational). F is a torque on body j
/// about the pin (revolute) or a force along u_i on body j (translational);
/// body i gets the opposite. As a generalized force: Q = F (ds/dc)^T, so its
/// power is exactly F sd <= 0.
struct JointFrictionLaw {
  JointFrictionParameters p;
  double arm = 1.0;  // rho

  /// F at load N and rate sd, with dF/dN and dF/dsd.
  double value(double N, double sd, double& dF_dN, double& dF_dsd) const {
    const double vs2 = p.slip_velocity * p.slip_velocity;
    const double root = std::sqrt(sd * sd + vs2);
    const double sgn = sd / root, dsgn = vs2 / (root * root * root);
    const double coulomb = p.mu * arm * N + p.preload;
    dF_dN = -p.mu * arm * sgn;
    dF_dsd = -coulomb * dsgn - p.viscous;
    return -coulomb * sgn - p.viscous * sd;
  }

  /// |x| smoothed near 0: sqrt(x^2 + F_s^2) - F_s (exact at 0, within F_s of
  /// |x| everywhere, with a continuous derivative).
  double smooth_abs(double x, double& dx) const {
    const double fs = p.load_smoothing, root = std::sqrt(x * x + fs * fs);
    dx = x / root;
    return root - fs;
  }
};

/// Revolute friction. Load N = |F_reaction| = |lam| (the revolute's two
/// multipliers are the joint force in global axes), smoothed:
/// N = sqrt(lam_1^2 + lam_2^2 + F_s^2) - F_s. s = phi_j - phi_i, so
/// ds/dc = (0, 0, -1, 0, 0, 1), constant.
struct RevoluteFriction {
  static constexpr int rows = 2;  // the joint's rows
  static constexpr const char* kind = "revolute_friction";
  std::string name;
  int body_i = -1, body_j = -1;
  int joint_group = -1, joint_index = -1;  // the joint, in the model's constraint groups
  JointFrictionLaw law;

  static constexpr bool constant_direction = true;
  Local6 direction(const Local6&) const {
    Local6 g;
    g << 0, 0, -1, 0, 0, 1;
    return g;
  }
  Mat6 direction_derivative(const Local6&) const { return Mat6::Zero(); }
  /// N and dN/dlam of the joint's rows.
  double load(const double* lam, double* dN) const {
    const double fs = law.p.load_smoothing;
    const double root = std::sqrt(lam[0] * lam[0] + lam[1] * lam[1] + fs * fs);
    dN[0] = lam[0] / root;
    dN[1] = lam[1] / root;
    return root - fs;
  }
};

/// Translational friction. The joint's rows are the offset across the axis
/// (multiplier lam_1: |lam_1| is the normal force N, the row's gradient has
/// unit length in r_j) and the relative angle (lam_2: the reaction moment M
/// about the joint point of body j). Load:
///   N = |lam_1|_s + |lam_2|_s / L   (L = bearing_length; without L: |lam_1|_s)
/// s = u_i . (p_j - p_i), the slide; ds/dc and d2s/dc2 from ProjectedOffset.
struct TranslationalFriction {
  static constexpr int rows = 2;
  static constexpr const char* kind = "translational_friction";
  std::string name;
  int body_i = -1, body_j = -1;
  int joint_group = -1, joint_index = -1;
  JointFrictionLaw law;
  ProjectedOffset along;  // w = u', the axis in body i's axes

  static constexpr bool constant_direction = false;
  Local6 direction(const Local6& c) const { return along.gradient(c).transpose(); }
  Mat6 direction_derivative(const Local6& c) const { return along.hessian(c); }
  double load(const double* lam, double* dN) const {
    double N = law.smooth_abs(lam[0], dN[0]);
    dN[1] = 0.0;
    if (law.p.bearing_length > 0.0) {
      N += law.smooth_abs(lam[1], dN[1]) / law.p.bearing_length;
      dN[1] /= law.p.bearing_length;
    }
    return N;
  }
};

}  // namespace lagmb
