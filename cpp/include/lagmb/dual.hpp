// Forward-mode dual numbers: first derivatives computed beside a value, for
// the Jacobians of forces written once as templates over their number type.
#pragma once

#include <cmath>

#include "lagmb/types.hpp"

namespace lagmb {

/// A number with its first derivatives with respect to N inputs (forward
/// mode): a force written once, as a template over its number type, is
/// evaluated with doubles for its value and with Dual<N> over its N inputs
/// for its derivatives, which are then exact to rounding (the contact force
/// takes Dual<12> over (c, cd) for Q_c and Q_cd).
template <int N>
struct Dual {
  double v = 0.0;
  Eigen::Matrix<double, N, 1> d = Eigen::Matrix<double, N, 1>::Zero();
  Dual() = default;
  Dual(double x) : v(x) {}  // NOLINT: constants convert
  friend Dual operator+(Dual a, const Dual& b) { a.v += b.v; a.d += b.d; return a; }
  friend Dual operator-(Dual a, const Dual& b) { a.v -= b.v; a.d -= b.d; return a; }
  friend Dual operator-(Dual a) { a.v = -a.v; a.d = -a.d; return a; }
  friend Dual operator*(const Dual& a, const Dual& b) {
    Dual r;
    r.v = a.v * b.v;
    r.d = a.d * b.v + b.d * a.v;
    return r;
  }
  friend Dual operator/(const Dual& a, const Dual& b) {
    Dual r;
    r.v = a.v / b.v;
    r.d = (a.d - b.d * r.v) / b.v;
    return r;
  }
  friend Dual sqrt(const Dual& a) {
    Dual r;
    r.v = std::sqrt(a.v);
    r.d = a.d / (2.0 * r.v);
    return r;
  }
  friend Dual pow(const Dual& a, double p) {
    Dual r;
    r.v = std::pow(a.v, p);
    r.d = a.d * (p * std::pow(a.v, p - 1.0));
    return r;
  }
  friend Dual cos(const Dual& a) {
    Dual r;
    r.v = std::cos(a.v);
    r.d = -std::sin(a.v) * a.d;
    return r;
  }
  friend Dual sin(const Dual& a) {
    Dual r;
    r.v = std::sin(a.v);
    r.d = std::cos(a.v) * a.d;
    return r;
  }
};
/// The value of a number, without its derivatives (for a branch on it).
inline double value_of(double x) { return x; }
template <int N>
double value_of(const Dual<N>& x) { return x.v; }

}  // namespace lagmb
