// The collision table (collision/pairs.hpp): one geometry per pair of shape
// kinds, each a struct with points() and a collide() template over the
// number type, and one line per pair in table().
#include "lagmb/collision/pairs.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <type_traits>
#include <utility>

namespace lagmb::collision {

namespace {

/// A(p) s for a vector s of numbers T (Motion::rotate takes constants).
template <class T>
V3<T> rotate(const T* p, const V3<T>& s) {
  const V3<T> e(p[1], p[2], p[3]);
  return (p[0] * p[0] - dot(e, e)) * s + (T(2.0) * dot(e, s)) * e + (T(2.0) * p[0]) * cross(e, s);
}
/// A(p)^T s: A of the conjugate (e0, -e) is A(p)^T (the quadratic form).
template <class T>
V3<T> rotate_back(const T* p, const V3<T>& s) {
  const T q[4] = {p[0], -p[1], -p[2], -p[3]};
  return rotate(q, s);
}
template <class T>
V3<T> times(const Mat3& M, const V3<T>& v) {
  return {M(0, 0) * v.x + M(0, 1) * v.y + M(0, 2) * v.z, M(1, 0) * v.x + M(1, 1) * v.y + M(1, 2) * v.z,
          M(2, 0) * v.x + M(2, 1) * v.y + M(2, 2) * v.z};
}
template <class T>
T component(const V3<T>& v, int k) {
  return k == 0 ? v.x : k == 1 ? v.y : v.z;
}

/// A plane fixed in body B: a point P0 of its boundary, its outward unit
/// normal n (A(p) of the shape's z axis) and their rates.
template <class T>
struct PlaneFrame {
  V3<T> P0, P0d, n, nd;
  PlaneFrame(const CollisionShape& plane, const Motion<T>& B)
      : P0(B.point(plane.position)),
        P0d(B.point_velocity(plane.position)),
        n(B.rotate(plane.axes.col(2))),
        nd(B.rotate_rate(plane.axes.col(2))) {}
};

/// A sphere of radius rho about the point s of body A (rho = 0: a vertex)
/// against a plane: h = n . (X - P0), g = h - rho, g' = n' . (X - P0) +
/// n . (X' - P0'); P = X - h n, the centre's projection on the plane.
template <class T>
ContactPoint<T> ball_plane(const Vec3& s, double rho, const Motion<T>& A, const PlaneFrame<T>& pl) {
  const V3<T> X = A.point(s), Xd = A.point_velocity(s), D = X - pl.P0;
  const T h = dot(pl.n, D);
  ContactPoint<T> c;
  c.gap = h - T(rho);
  c.gap_rate = dot(pl.nd, D) + dot(pl.n, Xd - pl.P0d);
  c.point = X - h * pl.n;
  c.normal = pl.n;
  return c;
}

/// A sphere of radius rho about X (velocity Xd) of body A against the
/// point Y of body B's surface (Y' its velocity as a point that moves with
/// B; any sliding of Y on B's surface is across the normal): u = (X - Y) /
/// |X - Y|, g = |X - Y| - rho, g' = u . (X' - Y'), P = Y.
template <class T>
ContactPoint<T> ball_point(const V3<T>& X, const V3<T>& Xd, double rho, const V3<T>& Y, const V3<T>& Yd) {
  using std::sqrt;
  const V3<T> D = X - Y;
  const T dist = sqrt(dot(D, D) + T(1e-300));  // (coincident centres: no direction; the normal is then +z)
  ContactPoint<T> c;
  c.normal = value_of(dist) > 1e-150 ? (T(1.0) / dist) * D : V3<T>(T(0.0), T(0.0), T(1.0));
  c.gap = dist - T(rho);
  c.gap_rate = dot(c.normal, Xd - Yd);
  c.point = Y;
  return c;
}

// --- the geometries: a the moving shape, b the surface --------------------

struct SpherePlane {
  static constexpr bool anchored = false;
  static int points(const CollisionShape&, const CollisionShape&) { return 1; }
  template <class T>
  static void collide(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                      ContactPoint<T>* out, double /*reach*/) {
    out[0] = ball_plane(a.position, a.size[0], A, PlaneFrame<T>(b, B));
  }
};

/// A capsule's two end spheres (the segment's ends, radius R).
struct CapsulePlane {
  static constexpr bool anchored = false;
  // (of length 0, a sphere: one point)
  static int points(const CollisionShape& a, const CollisionShape&) { return a.size[1] > 0.0 ? 2 : 1; }
  template <class T>
  static void collide(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                      ContactPoint<T>* out, double /*reach*/) {
    const PlaneFrame<T> pl(b, B);
    const Vec3 half = 0.5 * a.size[1] * a.axes.col(2);
    out[0] = ball_plane<T>(a.position - half, a.size[0], A, pl);
    if (a.size[1] > 0.0) out[1] = ball_plane<T>(a.position + half, a.size[0], A, pl);
  }
};

/// A box's eight corners.
struct BoxPlane {
  static constexpr bool anchored = true;
  static int points(const CollisionShape&, const CollisionShape&) { return 8; }
  template <class T>
  static void collide(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                      ContactPoint<T>* out, double /*reach*/) {
    const PlaneFrame<T> pl(b, B);
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5);
      out[k] = ball_plane<T>(a.position + a.axes * corner.cwiseProduct(a.size), 0.0, A, pl);
    }
  }
};

/// The vertices of a convex hull (every vertex of it: the deepest point of
/// a convex shape below a plane is one of them). Each vertex's height over
/// the plane first, in doubles: h_k = h_0 + m . v_k, with m the normal in
/// the hull's own axes and h_0 its centre's height (three multiply-adds a
/// vertex); a vertex within `reach` is then a ball_plane point of radius 0,
/// one beyond it its gap h_k alone (rate and point NaN); over Dual numbers
/// (`some`) only the vertices asked for: a hull of hundreds of vertices
/// resting on a few costs little more than the few.
struct ConvexPlane {
  static constexpr bool anchored = true;
  static int points(const CollisionShape& a, const CollisionShape&) { return int(a.vertices.size()); }
  template <class T>
  static void collide(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                      ContactPoint<T>* out, double reach) {
    const PlaneFrame<T> pl(b, B);
    const double h0 = value_of(dot(pl.n, A.point(a.position) - pl.P0));
    const Vec3 n = pl.n.value(), m = a.axes.transpose() * rotate_back(A.p, pl.n).value();
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    for (size_t k = 0; k < a.vertices.size(); ++k) {
      const double h = h0 + m.dot(a.vertices[k]);
      if (h <= reach) {
        out[k] = ball_plane<T>(a.position + a.axes * a.vertices[k], 0.0, A, pl);
      } else {
        out[k].gap = T(h), out[k].gap_rate = T(nan);
        out[k].point = V3<T>(Vec3::Constant(nan)), out[k].normal = V3<T>(n);
      }
    }
  }
  template <class T>
  static void some(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                   const int* which, int count, ContactPoint<T>* out) {
    const PlaneFrame<T> pl(b, B);
    for (int j = 0; j < count; ++j) out[j] = ball_plane<T>(a.position + a.axes * a.vertices[which[j]], 0.0, A, pl);
  }
};

/// A cylinder's two rims, four points each: the rim's point deepest
/// below the plane, X + R m (m the unit vector in the rim's plane most
/// against n: -(n - (n . w) w) normalized, w the axis; the cylinder's own x
/// axis where the axis is along n), and the rim's points at 90, 180 and 270
/// degrees from it. Lying on its side it touches at the two deepest points
/// (it rolls exactly); standing on an end it rests on the four points of
/// that rim. The points move along the rims: not material points.
struct CylinderPlane {
  static constexpr bool anchored = false;
  static int points(const CollisionShape&, const CollisionShape&) { return 8; }
  template <class T>
  static void collide(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                      ContactPoint<T>* out, double /*reach*/) {
    using std::sqrt;
    const PlaneFrame<T> pl(b, B);
    const V3<T> w = A.rotate(a.axes.col(2)), wd = A.rotate_rate(a.axes.col(2));
    V3<T> m = pl.n - dot(pl.n, w) * w;
    T norm = sqrt(dot(m, m));
    if (!(value_of(norm) > 1e-12)) {  // (standing on an end: the rim's points start at its own x axis)
      m = -A.rotate(a.axes.col(0));
      norm = T(1.0);
    }
    m = T(-1.0) / norm * m;      // towards the plane, in the rim's plane
    const V3<T> e = cross(w, m);  // the rim's plane's second direction
    const V3<T> omega = A.angular_velocity();
    for (int rim = 0; rim < 2; ++rim) {
      const Vec3 centre = a.position + (rim ? 0.5 : -0.5) * a.size[1] * a.axes.col(2);
      const V3<T> X = A.point(centre), Xd = A.point_velocity(centre);
      for (int k = 0; k < 4; ++k) {
        // the point X + R u on the rim, u = m, e, -m, -e; its gap's rate
        // as the rim point moving with the body (its sliding along the
        // rim is across n where it is deepest, and counted as the body's
        // motion elsewhere: u' = omega x u)
        const V3<T> u = k == 0 ? m : k == 1 ? e : k == 2 ? -m : -e;
        const V3<T> Y = X + T(a.size[0]) * u, Yd = Xd + T(a.size[0]) * cross(omega, u), D = Y - pl.P0;
        ContactPoint<T>& c = out[4 * rim + k];
        c.gap = dot(pl.n, D);
        c.gap_rate = dot(pl.nd, D) + dot(pl.n, Yd - pl.P0d);
        c.point = Y - c.gap * pl.n;
        c.normal = pl.n;
      }
    }
    (void)wd;
  }
};

struct SphereSphere {
  static constexpr bool anchored = false;
  static int points(const CollisionShape&, const CollisionShape&) { return 1; }
  template <class T>
  static void collide(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                      ContactPoint<T>* out, double /*reach*/) {
    // b's surface point on the line of centres, moving with b: Y = Y_b + R_b u
    ContactPoint<T> c = ball_point(A.point(a.position), A.point_velocity(a.position), a.size[0] + b.size[0],
                                   B.point(b.position), B.point_velocity(b.position));
    c.point = c.point + T(b.size[0]) * c.normal;
    out[0] = c;
  }
};

/// A sphere against a capsule: the point of the capsule's segment nearest
/// the sphere's centre (its parameter clamped to the segment) as a sphere
/// of the capsule's radius.
struct SphereCapsule {
  static constexpr bool anchored = false;
  static int points(const CollisionShape&, const CollisionShape&) { return 1; }
  template <class T>
  static void collide(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                      ContactPoint<T>* out, double /*reach*/) {
    const Vec3 half = 0.5 * b.size[1] * b.axes.col(2);
    const V3<T> E0 = B.point(b.position - half), E1 = B.point(b.position + half);
    const V3<T> E0d = B.point_velocity(b.position - half), E1d = B.point_velocity(b.position + half);
    const V3<T> X = A.point(a.position), seg = E1 - E0;
    const T length2 = dot(seg, seg);  // (0: a capsule of length 0, a sphere)
    T s = value_of(length2) > 0.0 ? dot(X - E0, seg) / length2 : T(0.0);
    if (value_of(s) < 0.0) s = T(0.0);
    if (value_of(s) > 1.0) s = T(1.0);
    // Y moves as b's material point plus s' along the segment, across the normal
    ContactPoint<T> c = ball_point(X, A.point_velocity(a.position), a.size[0] + b.size[0],
                                   E0 + s * seg, E0d + s * (E1d - E0d));
    c.point = c.point + T(b.size[0]) * c.normal;
    out[0] = c;
  }
};

/// Two capsules: the nearest points X (on a's segment) and Y (on b's),
/// each segment's parameter clamped to it (Ericson, "Real-Time Collision
/// Detection", 5.1.9), as spheres of the radii about them. Parallel
/// segments (a line of contact) take a's parameter 0 or the end that
/// overlaps: one point of the line.
struct CapsuleCapsule {
  static constexpr bool anchored = false;
  static int points(const CollisionShape&, const CollisionShape&) { return 1; }
  template <class T>
  static void collide(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                      ContactPoint<T>* out, double /*reach*/) {
    const Vec3 ha = 0.5 * a.size[1] * a.axes.col(2), hb = 0.5 * b.size[1] * b.axes.col(2);
    const V3<T> P0 = A.point(a.position - ha), P1 = A.point(a.position + ha);
    const V3<T> Q0 = B.point(b.position - hb), Q1 = B.point(b.position + hb);
    const V3<T> d1 = P1 - P0, d2 = Q1 - Q0, r = P0 - Q0;
    const T aa = dot(d1, d1), ee = dot(d2, d2), f = dot(d2, r), c = dot(d1, r), bb = dot(d1, d2);
    const T denom = aa * ee - bb * bb;
    auto clamp01 = [](T x) { return value_of(x) < 0.0 ? T(0.0) : value_of(x) > 1.0 ? T(1.0) : x; };
    T s = value_of(denom) > 1e-12 * value_of(aa) * value_of(ee) && value_of(denom) > 0.0
              ? clamp01((bb * f - c * ee) / denom) : T(0.0);
    // (a capsule of length 0 is a sphere: its segment's parameter 0)
    T t = value_of(ee) > 0.0 ? (bb * s + f) / ee : T(0.0);
    if (value_of(t) < 0.0) {
      t = T(0.0);
      s = value_of(aa) > 0.0 ? clamp01(-c / aa) : T(0.0);
    } else if (value_of(t) > 1.0) {
      t = T(1.0);
      s = value_of(aa) > 0.0 ? clamp01((bb - c) / aa) : T(0.0);
    }
    const V3<T> X = P0 + s * d1, Y = Q0 + t * d2;
    const V3<T> Xd = A.point_velocity(a.position - ha) + s * (A.point_velocity(a.position + ha) -
                                                             A.point_velocity(a.position - ha));
    const V3<T> Yd = B.point_velocity(b.position - hb) + t * (B.point_velocity(b.position + hb) -
                                                             B.point_velocity(b.position - hb));
    ContactPoint<T> contact = ball_point(X, Xd, a.size[0] + b.size[0], Y, Yd);
    contact.point = contact.point + T(b.size[0]) * contact.normal;
    out[0] = contact;
  }
};

/// A sphere against a box: the box's point nearest the sphere's centre
/// (the centre clamped to the box in the box's axes); a centre inside the
/// box is pushed out through the nearest face.
struct SphereBox {
  static constexpr bool anchored = false;
  static int points(const CollisionShape&, const CollisionShape&) { return 1; }
  template <class T>
  static void collide(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B,
                      ContactPoint<T>* out, double /*reach*/) {
    const V3<T> X = A.point(a.position), Xd = A.point_velocity(a.position);
    const V3<T> local = times<T>(b.axes.transpose(), rotate_back(B.p, X - B.r) - V3<T>(b.position));  // box axes
    const Vec3 h = 0.5 * b.size;
    V3<T> y = local;
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
      T& yk = k == 0 ? y.x : k == 1 ? y.y : y.z;
      if (value_of(yk) > h[k]) yk = T(h[k]), inside = false;
      if (value_of(yk) < -h[k]) yk = T(-h[k]), inside = false;
    }
    if (!inside) {
      const V3<T> Y = B.r + rotate(B.p, V3<T>(b.position) + times<T>(b.axes, y));
      out[0] = ball_point(X, Xd, a.size[0], Y, B.velocity_at(Y));
      return;
    }
    int face = 0;  // the face nearest the centre: the least h_k - |y_k|
    double least = h[0] - std::abs(value_of(local.x));
    for (int k = 1; k < 3; ++k)
      if (h[k] - std::abs(value_of(component(local, k))) < least) least = h[k] - std::abs(value_of(component(local, k))), face = k;
    const double sign = value_of(component(local, face)) >= 0.0 ? 1.0 : -1.0;
    CollisionShape plane;
    plane.position = b.position + sign * h[face] * b.axes.col(face);
    plane.axes.col(2) = sign * b.axes.col(face);
    out[0] = ball_plane(a.position, a.size[0], A, PlaneFrame<T>(plane, B));
  }
};

/// Whether a geometry gives some of its points alone (Geometry::some).
template <class Geometry, class = void>
struct GivesSome : std::false_type {};
template <class Geometry>
struct GivesSome<Geometry, std::void_t<decltype(&Geometry::template some<double>)>> : std::true_type {};

/// The points which[0 .. count) of a geometry over T: its `some`, or all
/// its points (a few) computed and those picked.
template <class Geometry, class T>
void some(const CollisionShape& a, const CollisionShape& b, const Motion<T>& A, const Motion<T>& B, const int* which,
          int count, ContactPoint<T>* out) {
  if constexpr (GivesSome<Geometry>::value) {
    Geometry::some(a, b, A, B, which, count, out);
  } else {
    std::vector<ContactPoint<T>> all(Geometry::points(a, b));
    Geometry::collide(a, b, A, B, all.data(), std::numeric_limits<double>::infinity());
    for (int j = 0; j < count; ++j) out[j] = all[which[j]];
  }
}

template <class Geometry>
Pair line(CollisionShape::Kind a, CollisionShape::Kind b) {
  return {a, b, Geometry::anchored, &Geometry::points, &Geometry::template collide<double>,
          &some<Geometry, ContactDual>, &some<Geometry, OneBodyDual>};
}

const std::vector<Pair>& table() {
  using S = CollisionShape;
  static const std::vector<Pair> pairs = {
      line<SpherePlane>(S::kSphere, S::kPlane),     line<CapsulePlane>(S::kCapsule, S::kPlane),
      line<BoxPlane>(S::kBox, S::kPlane),           line<ConvexPlane>(S::kConvex, S::kPlane),
      line<SphereSphere>(S::kSphere, S::kSphere),   line<SphereCapsule>(S::kSphere, S::kCapsule),
      line<SphereBox>(S::kSphere, S::kBox),         line<CylinderPlane>(S::kCylinder, S::kPlane),
      line<CapsuleCapsule>(S::kCapsule, S::kCapsule),
  };
  return pairs;
}

}  // namespace

const Pair* find_pair(CollisionShape::Kind a, CollisionShape::Kind b) {
  for (const Pair& p : table())
    if (p.a == a && p.b == b) return &p;
  return nullptr;
}

std::string known_pairs() {
  std::string out;
  for (const Pair& p : table())
    out += (out.empty() ? "" : ", ") + std::string(shape_kind_name(p.a)) + "-" + shape_kind_name(p.b);
  return out;
}

}  // namespace lagmb::collision
