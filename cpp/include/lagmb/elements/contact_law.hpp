// The contact law every contact geometry shares: a compliant normal force
// with Hunt-Crossley damping calibrated to a restitution coefficient, and
// regularized Coulomb friction. A geometry (a shape pair: circle-line in the
// plane) gives the law its penetration, penetration rate and slip velocity
// at the contact point, and applies the force the law returns there.
#pragma once

#include <algorithm>
#include <cmath>

#include "lagmb/dual.hpp"
#include "lagmb/model/contact_reading.hpp"

namespace lagmb {

/// At one contact point with penetration d (m; > 0 in contact), its rate d'
/// (m/s) and the slip velocity v_t of body i's material point over body j's
/// (tangent to the contact), for d > 0 (Flores, Machado, Silva, Martins 2011,
/// Multibody Syst Dyn 25):
///   F_n = k d^1.5 (1 + 8 (1 - e) / (5 e) d' / v_impact)   (0 where it would pull)
///   F_t = -mu F_n v_t / sqrt(|v_t|^2 + v_s^2)
/// on body i along the outward normal of body j's surface (and along v_t),
/// the opposite on body j. v_impact is the approach speed recorded at the
/// contact's onset (at least kMinImpactSpeed). Potential (the elastic part):
/// k d^2.5 / 2.5. Written once for doubles and Dual numbers (the geometries'
/// exact Jacobians).
struct ContactLaw {
  static constexpr double kExponent = 1.5;
  static constexpr double kMinImpactSpeed = 1e-3;  // m/s

  double stiffness = 0.0;      // k, N/m^1.5
  double restitution = 1.0;    // e in (0, 1]
  double friction = 0.0;       // mu
  double static_friction = 0.0;  // mu_s: what a stuck contact holds (spatial_contact.hpp; >= mu)
  double slip_velocity = 1e-4;  // v_s, m/s

  /// F_n at penetration d and rate d' (0 out of contact, or where the damping would pull).
  template <class T>
  T normal_force(const T& d, const T& d_rate, double impact_speed) const {
    using std::pow;
    if (!(value_of(d) > 0.0)) return T(0.0);
    const double v_imp = std::max(impact_speed, kMinImpactSpeed);
    const double chi = 8.0 * (1.0 - restitution) / (5.0 * restitution * v_imp);
    const T Fn = stiffness * pow(d, kExponent) * (T(1.0) + chi * d_rate);
    return value_of(Fn) > 0.0 ? Fn : T(0.0);
  }
  /// The friction force's component along a direction in which v_t has
  /// the component v: -mu F_n v / sqrt(|v_t|^2 + v_s^2) (slip_squared = |v_t|^2).
  template <class T>
  T friction_force(const T& Fn, const T& v, const T& slip_squared) const {
    using std::sqrt;
    if (!(friction > 0.0)) return T(0.0);
    return -friction * Fn * v / sqrt(slip_squared + T(slip_velocity * slip_velocity));
  }
  /// The elastic part's potential at penetration d (J).
  double potential(double d) const { return d > 0.0 ? stiffness * std::pow(d, kExponent + 1.0) / (kExponent + 1.0) : 0.0; }
};

}  // namespace lagmb
