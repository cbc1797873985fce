// The contact law every contact geometry shares: a compliant normal force
// with Hunt-Crossley damping whose rebound is exactly the restitution
// coefficient, and regularized Coulomb friction. A geometry (a shape pair:
// circle-line in the plane) gives the law its penetration, penetration rate
// and slip velocity at the contact point, and applies the force the law
// returns there.
#pragma once

#include <algorithm>
#include <cmath>

#include "lagmb/dual.hpp"
#include "lagmb/model/contact_reading.hpp"

namespace lagmb {

/// At one contact point with penetration d (m; > 0 in contact), its rate d'
/// (m/s) and the slip velocity v_t of body i's material point over body j's
/// (tangent to the contact), for d > 0:
///   F_n = k d^1.5 (1 + c d' / v_impact)   (0 where it would pull)
///   F_t = -mu F_n v_t / sqrt(|v_t|^2 + v_s^2)
/// on body i along the outward normal of body j's surface (and along v_t),
/// the opposite on body j. v_impact is the approach speed recorded at the
/// contact's onset (at least kMinImpactSpeed); c = damping_for(e), the
/// damping whose rebound is exactly e (Hunt and Crossley's 1975 form of the
/// force; Flores et al. 2011's c = 8 (1 - e) / (5 e) approximates it). Potential (the
/// elastic part): k d^2.5 / 2.5. Written once for doubles and Dual numbers
/// (the geometries' exact Jacobians).
struct ContactLaw {
  static constexpr double kExponent = 1.5;
  static constexpr double kMinImpactSpeed = 1e-3;  // m/s

  double stiffness = 0.0;      // k, N/m^1.5
  double restitution = 1.0;    // e in (0, 1]
  double damping = 0.0;        // c = damping_for(restitution), set with it (build::contact_law)
  double friction = 0.0;       // mu
  double static_friction = 0.0;  // mu_s: what a stuck contact holds (spatial_contact.hpp; >= mu)
  double slip_velocity = 1e-4;  // v_s, m/s

  /// The damping c whose rebound is exactly e. Two bodies meeting at the
  /// speed v with the contact force alone between them (effective mass m
  /// along the normal): m d'' = -k d^n (1 + c d'/v), d(0) = 0, d'(0) = v.
  /// With w = d'/v the phase plane separates,
  ///   w dw / (1 + c w) = -(k / (m v^2)) d^n dd,
  /// and the approach (w from 1 to 0) and the restitution (w from 0 to -e)
  /// run between the same d = 0 and d_max, so their integrals
  /// w / c - ln(1 + c w) / c^2 are equal and opposite:
  ///   c (1 + e) = ln((1 + c) / (1 - c e)),
  /// whatever k, m, v and n (1 + c w stays above 1 - c e > 0: the clamp
  /// never acts in such an impact).
  /// Its root c in (0, 1/e) is found by bisection on
  ///   G(c) = (ln(1 + c) - ln(1 - c e) - c (1 + e)) / c^2
  ///        = sum_{j>=2} c^(j-2) ((-1)^(j+1) + e^j) / j,
  /// negative at c -> 0 (-(1 - e^2)/2) and +infinity at c = 1/e; the series
  /// (with 1 - e^j = -expm1(j ln e)) below c = 0.5, where the logarithms
  /// cancel, and c^2 G above (only its sign is needed, and c^2 overflows).
  /// e = 1: c = 0. As e -> 0, c -> 1/e (c e = 1 - (1 + c) exp(-(1 + c)) to
  /// first order): no finite damping gives e = 0.
  static double damping_for(double e) {
    if (!(e > 0.0 && e < 1.0)) return 0.0;  // (e = 1; e outside (0, 1] is refused where the law is built)
    if (!std::isfinite(1.0 / e)) return 1.0 / e;  // (infinite: refused there too)
    const double log_e = std::log(e);
    auto G = [&](double c) {
      if (c >= 0.5) return std::log1p(c) - std::log1p(-c * e) - c * (1.0 + e);  // (its sign: c^2 G)
      double sum = 0.0, power = 1.0;  // c^(j-2)
      for (int j = 2; j < 80 && power > 1e-20; ++j, power *= c)
        sum += power * (j % 2 ? 1.0 + std::exp(j * log_e) : std::expm1(j * log_e)) / j;
      return sum;
    };
    double lo = 0.0, hi = 1.0 / e;  // G(lo) < 0 <= G(hi)
    for (int k = 0; k < 2000; ++k) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;
      (G(mid) < 0.0 ? lo : hi) = mid;
    }
    return lo;
  }

  /// F_n at penetration d and rate d' (0 out of contact, or where the damping would pull).
  template <class T>
  T normal_force(const T& d, const T& d_rate, double impact_speed) const {
    using std::pow;
    if (!(value_of(d) > 0.0)) return T(0.0);
    const double chi = damping / std::max(impact_speed, kMinImpactSpeed);
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
