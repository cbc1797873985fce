// The collision table: one geometry per pair of shape kinds, each giving
// the contact points of two shapes from the motion of their bodies, written
// once over the number type (doubles for values, Dual numbers for exact
// Jacobians), as MuJoCo's table of collision functions is one function per
// pair of geometry types. A new pair is one geometry struct and one line of
// the table (cpp/src/collision/pairs.cpp).
#pragma once

#include <cmath>

#include "lagmb/collision/shape.hpp"
#include "lagmb/dual.hpp"

namespace lagmb::collision {

/// A 3-vector of numbers of type T (double or Dual<N>).
template <class T>
struct V3 {
  T x, y, z;
  V3() : x(0.0), y(0.0), z(0.0) {}
  V3(T a, T b, T c) : x(std::move(a)), y(std::move(b)), z(std::move(c)) {}
  explicit V3(const Vec3& v) : x(v.x()), y(v.y()), z(v.z()) {}
  friend V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend V3 operator-(const V3& a) { return {-a.x, -a.y, -a.z}; }
  friend V3 operator*(const T& s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
  Vec3 value() const { return Vec3(value_of(x), value_of(y), value_of(z)); }
};
template <class T>
T dot(const V3<T>& a, const V3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T>
V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// A body's position and velocity as an element's local coordinates hold
/// them (space.hpp): centre of mass r, Euler parameters p = (e0, e), and
/// their rates.
template <class T>
struct Motion {
  V3<T> r, rd;
  T p[4], pd[4];

  /// A(p) s (spatial.hpp: the quadratic (e0^2 - e.e) s + 2 (e.s) e + 2 e0 e x s).
  V3<T> rotate(const Vec3& s) const {
    const V3<T> e(p[1], p[2], p[3]), S(s);
    return (p[0] * p[0] - dot(e, e)) * S + (T(2.0) * dot(e, S)) * e + (T(2.0) * p[0]) * cross(e, S);
  }
  /// d(A(p) s)/dt: the derivative of rotate along p'.
  V3<T> rotate_rate(const Vec3& s) const {
    const V3<T> e(p[1], p[2], p[3]), ed(pd[1], pd[2], pd[3]), S(s);
    return (T(2.0) * (p[0] * pd[0] - dot(e, ed))) * S + (T(2.0) * dot(ed, S)) * e + (T(2.0) * dot(e, S)) * ed +
           (T(2.0) * pd[0]) * cross(e, S) + (T(2.0) * p[0]) * cross(ed, S);
  }
  /// The point s fixed in the body (body axes from its centre of mass), and its velocity.
  V3<T> point(const Vec3& s) const { return r + rotate(s); }
  V3<T> point_velocity(const Vec3& s) const { return rd + rotate_rate(s); }
  /// omega = 2 E(p) p' (global axes).
  V3<T> angular_velocity() const {
    const V3<T> e(p[1], p[2], p[3]), ed(pd[1], pd[2], pd[3]);
    return T(2.0) * (p[0] * ed - pd[0] * e + cross(e, ed));
  }
  /// The velocity of the body's material point at the global point P: r' + omega x (P - r).
  V3<T> velocity_at(const V3<T>& P) const { return rd + cross(angular_velocity(), P - r); }
};

/// One contact point of a pair: the gap g (m; < 0: penetration d = -g) and
/// its rate g', the point P (m, global) and the unit normal n (global, out
/// of shape b towards shape a) there. Shape a's body is the element's body i.
template <class T>
struct ContactPoint {
  T gap, gap_rate;
  V3<T> point, normal;
};

/// The numbers the table is written for: values, and Dual over an element's
/// 14 coordinates and 14 velocities (elements/spatial_contact.hpp), or over
/// its first body's 7 and 7 where the second is the ground (half the work).
using ContactDual = Dual<28>;
using OneBodyDual = Dual<14>;

/// One line of the table: shapes of kinds (a, b), how many contact points
/// they have (fixed for the pair: each is an event function) and the
/// geometry that gives them, for both number types. `at` fills out[0 ..
/// points) and may give a point whose gap exceeds `reach` (m) its gap alone
/// (its rate and point NaN: the law's force is 0 there; +infinity: every
/// point in full); the Dual versions fill out[j] with point which[j], j <
/// count (the pressing ones): a geometry of many points (a hull's vertices)
/// evaluates in full only the few near touching.
struct Pair {
  CollisionShape::Kind a, b;
  /// Whether each contact point is a material point of shape a (a vertex:
  /// box corners, hull vertices), so that a stuck contact is held in place
  /// by rows on positions; a round shape rolls over its points instead.
  bool anchored;
  int (*points)(const CollisionShape& a, const CollisionShape& b);
  void (*at)(const CollisionShape& a, const CollisionShape& b, const Motion<double>& A, const Motion<double>& B,
             ContactPoint<double>* out, double reach);
  void (*derivative)(const CollisionShape& a, const CollisionShape& b, const Motion<ContactDual>& A,
                     const Motion<ContactDual>& B, const int* which, int count, ContactPoint<ContactDual>* out);
  void (*one_body)(const CollisionShape& a, const CollisionShape& b, const Motion<OneBodyDual>& A,
                   const Motion<OneBodyDual>& B, const int* which, int count, ContactPoint<OneBodyDual>* out);
};

/// The table's line for shapes of kinds (a, b), or null: the pairs are
/// written one way round (a the moving shape, b the surface: sphere against
/// plane), and a contact given the other way round swaps its shapes.
const Pair* find_pair(CollisionShape::Kind a, CollisionShape::Kind b);
/// "sphere-plane, box-plane, ...": the pairs the table has, for messages.
std::string known_pairs();

}  // namespace lagmb::collision
