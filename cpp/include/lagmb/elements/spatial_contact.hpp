// Contact between two collision shapes in space: a geometry of the
// collision table (collision/pairs.hpp) gives the contact points, the
// contact law (contact_law.hpp) their forces.
#pragma once

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "lagmb/collision/pairs.hpp"
#include "lagmb/elements/contact_law.hpp"
#include "lagmb/spatial_terms.hpp"
#include "lagmb/model/event_group.hpp"

namespace lagmb {

/// Shape a on body i, shape b on body j (or the ground), paired by the
/// table's geometry into K contact points k, each with its gap g_k (< 0:
/// penetration d_k = -g_k), rate g_k', point P_k and normal n_k (out of b
/// towards a). At each point the law gives F_n,k = F_n(d_k, d_k', v_impact,k)
/// and, with the slip velocity v_t = (I - n n^T)(v_i(X) - v_j(X)) of body i's
/// material point over body j's at X (P, or an anchored pair's vertex
/// X = P + g n: acting_point),
///   F_k = F_n,k n_k - mu F_n,k v_t / sqrt(|v_t|^2 + v_s^2)
/// (the friction term left out while stuck: the rows below hold it all)
/// on body i at X_k and -F_k on body j. With F = sum F_k and the torques
/// tau_i = sum (X_k - r_i) x F_k, tau_j = sum (X_k - r_j) x F_k:
///   Q_ri = F,  Q_pi = 2 E(p_i)^T tau_i,  Q_rj = -F,  Q_pj = -2 E(p_j)^T tau_j
/// (a torque n acts on p through 2 E(p)^T n, spatial.hpp). Q_c and Q_cd
/// are exact: the same code over Dual<28> (c, cd; Dual<14> over body i's
/// where body j is the ground). Broad phase: while the
/// bounding spheres (a plane's half-space) are apart, Q = 0 and every event
/// function reads their gap, a lower bound of each point's. Each point is an
/// event function (its gap): onset (recording v_impact,k in the run's
/// state) and release restart the integrator. Narrow phase: forces and
/// events take the points within kNear of touching in full and the others'
/// gaps alone, the derivatives the pressing points alone (a hull of
/// hundreds of vertices resting on a few costs a height per vertex).
///
/// Stick (a pair whose points are material points of shape a, `anchored`,
/// with friction): the contact is also three constraint rows, open (left
/// out, as a stop's) until the event runner closes them. Closing records an
/// anchor in the run's state: the pressing vertices' F_n-weighted centre
/// (stick_hold) as s_a in body i's axes and s_b in body j's, and the
/// surface's tangents t1, t2 as u_1, u_2 in body i's axes; then, with t1,
/// t2, n = the plane's axes on body j and D = X_i(s_a) - X_j(s_b),
///   Phi = (t1 . D, t2 . D, (t2 . A_i u_1 - t1 . A_i u_2) / 2)
/// hold the anchor in the tangent plane and the turn about n: the third
/// is sum_k (n x e_k) . S e_k / 2 over (e_k) = (t1, t2, n), S the turn
/// of body i over body j since the stick, i.e. n . (S - S^T)^v / 2 = 2 s0
/// (s . n) for S's Euler parameters (s0, s): 0 where S is a swing about
/// an axis in the plane (a body rocking on its anchor), whatever the axis,
/// which t2 . A_i u_1 alone is not (it turned the body about n by the
/// misalignment of u_1 with the rocking axis times the rocking). Its
/// gradient at the stick is the turn about n. Its multipliers are the friction the contact holds:
/// the force -(lam_1 t1 + lam_2 t2) on body i at the anchor and the torque
/// -lam_3 about n. It is released where mu_s F_n - sqrt(lam_1^2 + lam_2^2 +
/// (lam_3 / rho)^2) turns negative (F_n the law's total normal force, rho
/// the pressing points' F_n-weighted mean distance from the anchor: the
/// torque the points' friction holds without a force, an elliptic limit
/// between the two), and closed where every pressing point slips slower
/// than v_s (stick_root) and the held friction is within that limit.
struct SpatialContact {
  using Space = Spatial;
  static constexpr bool state_dependent = true;
  static constexpr bool bounds_motion = false;  // g < 0 is contact, not a violation
  static constexpr bool reads_inputs = true;     // (the stick rows read their anchor in the run's state)
  static constexpr bool time_dependent = false;
  static constexpr bool stick_rows = true;
  static constexpr int rows = 3;
  static constexpr const char* kind = "spatial_contact";
  // run[run_state + k]: v_impact (m/s) of point k's contact in progress;
  // where the contact sticks, then its stick state (kArmed, kStuck,
  // kDisarmed) and the anchor (s_a, s_b, u_1, u_2: 12 numbers)
  static constexpr int run_state_size = 1;
  int run_state_count() const { return points + (sticks ? 13 : 0); }
  int run_state = -1;
  enum StickState { kArmed = 0, kStuck = 1, kDisarmed = -1 };

  std::string name;
  int body_i = -1, body_j = -1;
  CollisionShape shape_a, shape_b;  // on body i, body j
  double radius_a = 0.0, radius_b = 0.0;  // their bounding_radius() (a hull's: over its vertices, found once)
  const collision::Pair* pair = nullptr;
  int points = 0;
  bool swapped = false;  // given as (b, a): readings are for the shape given first
  bool sticks = false;   // anchored pair with friction: has stick rows
  ContactLaw law;

  using Loc = spatial::Loc;

  template <class T>
  static void motions(const T* c, const T* cd, collision::Motion<T>& A, collision::Motion<T>& B) {
    A.r = {c[0], c[1], c[2]};
    A.rd = {cd[0], cd[1], cd[2]};
    B.r = {c[7], c[8], c[9]};
    B.rd = {cd[7], cd[8], cd[9]};
    for (int k = 0; k < 4; ++k) {
      A.p[k] = c[3 + k];
      A.pd[k] = cd[3 + k];
      B.p[k] = c[10 + k];
      B.pd[k] = cd[10 + k];
    }
  }

  /// The bounding spheres' gap (a plane: the sphere's height over it), a
  /// lower bound of every point's gap; > 0: the shapes are apart.
  double bounding_gap(const Loc& c) const {
    const Vec3 Xa = c.head<3>() + euler::rotate(c.segment<4>(3), shape_a.position);
    if (shape_b.kind == CollisionShape::kPlane) {
      const Vec4 pb = c.segment<4>(10);
      const Vec3 n = euler::rotate(pb, shape_b.axes.col(2));
      return n.dot(Xa - c.segment<3>(7) - euler::rotate(pb, shape_b.position)) - radius_a;
    }
    const Vec3 Xb = c.segment<3>(7) + euler::rotate(c.segment<4>(10), shape_b.position);
    return (Xa - Xb).norm() - radius_a - radius_b;
  }

  /// Whether a step from c0 to c1 whose gaps are open at both ends, the
  /// least of them `gap`, may have passed through the other shape and out
  /// (a fast ball across a small one: the signs at the ends do not show
  /// it): where the bounding spheres' centres, on the straight line between
  /// their ends' relative positions D(s) = (1 - s) D0 + s D1, come within
  /// the sum of the radii R_a + R_b, and a point of shape a may have moved
  /// further over shape b than `gap`: |D1 - D0| + theta_a R_a + theta_b
  /// (max |D| + R_a), theta the turn of each body over the step. A plane's
  /// half-space cannot be passed through.
  bool may_pass(const Loc& c0, const Loc& c1, double gap) const {
    if (shape_b.kind == CollisionShape::kPlane) return false;
    auto centres = [&](const Loc& c) {
      return Vec3(c.head<3>() + euler::rotate(c.segment<4>(3), shape_a.position) - c.segment<3>(7) -
                  euler::rotate(c.segment<4>(10), shape_b.position));
    };
    // the turn between two Euler parameter vectors: 2 acos |p0 . p1|
    auto turn = [](const Vec4& p0, const Vec4& p1) { return 2.0 * std::acos(std::min(1.0, std::abs(p0.dot(p1)))); };
    const Vec3 D0 = centres(c0), D1 = centres(c1), step = D1 - D0;
    const double Ra = radius_a, Rb = radius_b;
    const double s = step.squaredNorm() > 0.0 ? std::clamp(-D0.dot(step) / step.squaredNorm(), 0.0, 1.0) : 0.0;
    if (!((D0 + s * step).norm() < Ra + Rb)) return false;
    const double moved = step.norm() + turn(c0.segment<4>(3), c1.segment<4>(3)) * Ra +
                         turn(c0.segment<4>(10), c1.segment<4>(10)) * (std::max(D0.norm(), D1.norm()) + Ra);
    return moved > gap;
  }

  /// How near touching (m) a point is evaluated in full where only the
  /// pressing ones and the gaps matter (forces, events): a point farther
  /// may carry its gap alone (collision::Pair; a hull's vertices). Above
  /// the gaps' rounding and the events' 1e-9 m band.
  static constexpr double kNear = 1e-6;
  static constexpr double kAll = std::numeric_limits<double>::infinity();

  /// The contact points at (c, cd), those farther than `reach` perhaps their gaps alone.
  std::vector<collision::ContactPoint<double>> contact_points(const Loc& c, const Loc& cd, double reach) const {
    collision::Motion<double> A, B;
    motions(c.data(), cd.data(), A, B);
    std::vector<collision::ContactPoint<double>> out(points);
    pair->at(shape_a, shape_b, A, B, out.data(), reach);
    return out;
  }

  /// Where point p's force acts and its slip is measured: an anchored
  /// pair's vertex itself, X = P + g n (a body rocking on a corner does not
  /// slip there), else P on the surface (a rolling sphere's point).
  template <class T>
  collision::V3<T> acting_point(const collision::ContactPoint<T>& p) const {
    return pair->anchored ? p.point + p.gap * p.normal : p.point;
  }

  /// Q at (c, cd) from the contact points `pts` (evaluated with the same
  /// numbers): pts[j] is point which[j] for j < count (which null: pts[k]
  /// is point k, k < points).
  template <class T>
  void generalized_force(const T* c, const T* cd, const collision::ContactPoint<T>* pts, const int* which,
                         int count, const double* run, T* Q) const {
    using collision::V3;
    collision::Motion<T> A, B;
    motions(c, cd, A, B);
    V3<T> F, tau_i, tau_j;
    const bool slides = law.friction > 0.0 && !stuck(run);  // (stuck, the rows hold all the friction)
    for (int j = 0; j < count; ++j) {
      const collision::ContactPoint<T>& p = pts[j];
      const int k = which ? which[j] : j;
      if (!(value_of(p.gap) < 0.0)) continue;  // (apart: no force, and a far point has its gap alone)
      const T Fn = law.normal_force(-p.gap, -p.gap_rate, run[run_state + k]);
      if (!(value_of(Fn) > 0.0)) continue;
      V3<T> Fk = Fn * p.normal;
      if (slides) {
        const V3<T> v = A.velocity_at(acting_point(p)) - B.velocity_at(acting_point(p));
        const V3<T> vt = v - dot(v, p.normal) * p.normal;
        Fk = Fk + law.friction_force(Fn, T(1.0), dot(vt, vt)) * vt;
      }
      F = F + Fk;
      tau_i = tau_i + cross(acting_point(p) - A.r, Fk);
      tau_j = tau_j + cross(acting_point(p) - B.r, Fk);
    }
    // 2 E(p)^T tau = 2 (-e . tau, e0 tau - e x tau)
    auto torque = [](const T* p, const V3<T>& n, T sign, T* out) {
      const V3<T> e(p[1], p[2], p[3]);
      const V3<T> w = p[0] * n - cross(e, n);
      out[0] = T(-2.0) * sign * dot(e, n);
      out[1] = T(2.0) * sign * w.x;
      out[2] = T(2.0) * sign * w.y;
      out[3] = T(2.0) * sign * w.z;
    };
    Q[0] = F.x, Q[1] = F.y, Q[2] = F.z;
    torque(A.p, tau_i, T(1.0), Q + 3);
    Q[7] = -F.x, Q[8] = -F.y, Q[9] = -F.z;
    torque(B.p, tau_j, T(-1.0), Q + 10);
  }

  Loc force(const Loc& c, const Loc& cd, const Instant&, const double* run) const {
    Loc Q = Loc::Zero();
    if (bounding_gap(c) > 0.0) return Q;
    const auto pts = contact_points(c, cd, kNear);
    generalized_force(c.data(), cd.data(), pts.data(), nullptr, points, run, Q.data());
    return Q;
  }

  void derivatives(const Loc& c, const Loc& cd, const Instant&, const double* run, spatial::Mat14& Q_c,
                   spatial::Mat14& Q_cd) const {
    Q_c.setZero();
    Q_cd.setZero();
    if (bounding_gap(c) > 0.0) return;
    // over dual numbers, the pressing points alone (the others' force is 0)
    const auto values = contact_points(c, cd, kNear);
    std::vector<int> which;
    for (int k = 0; k < points; ++k)
      if (values[k].gap < 0.0) which.push_back(k);
    const int count = int(which.size());
    if (!count) return;
    if (body_j < 0) {  // (the ground: derivatives in body i's 7 + 7 only)
      using D = collision::OneBodyDual;
      D x[14], xd[14], Q[14];
      for (int a = 0; a < 14; ++a) {
        x[a] = D(c[a]);
        xd[a] = D(cd[a]);
        if (a < 7) x[a].d[a] = 1.0, xd[a].d[7 + a] = 1.0;
      }
      collision::Motion<D> A, B;
      motions(x, xd, A, B);
      std::vector<collision::ContactPoint<D>> pts(count);
      pair->one_body(shape_a, shape_b, A, B, which.data(), count, pts.data());
      generalized_force(x, xd, pts.data(), which.data(), count, run, Q);
      for (int b = 0; b < 14; ++b) {
        Q_c.block<1, 7>(b, 0) = Q[b].d.head<7>().transpose();
        Q_cd.block<1, 7>(b, 0) = Q[b].d.tail<7>().transpose();
      }
      return;
    }
    using D = collision::ContactDual;
    D x[14], xd[14], Q[14];
    for (int a = 0; a < 14; ++a) {
      x[a] = D(c[a]);
      x[a].d[a] = 1.0;
      xd[a] = D(cd[a]);
      xd[a].d[14 + a] = 1.0;
    }
    collision::Motion<D> A, B;
    motions(x, xd, A, B);
    std::vector<collision::ContactPoint<D>> pts(count);
    pair->derivative(shape_a, shape_b, A, B, which.data(), count, pts.data());
    generalized_force(x, xd, pts.data(), which.data(), count, run, Q);
    for (int b = 0; b < 14; ++b) {
      Q_c.row(b) = Q[b].d.head<14>().transpose();
      Q_cd.row(b) = Q[b].d.tail<14>().transpose();
    }
  }

  double potential(const Loc& c, const Instant&) const {
    if (bounding_gap(c) > 0.0) return 0.0;
    double V = 0.0;
    for (const auto& p : contact_points(c, Loc::Zero(), kNear)) V += law.potential(-p.gap);
    return V;
  }

  /// The resultant of the points at (c, cd) (ContactReading; state slip
  /// while any point presses: the regularized friction never sticks): the
  /// normal force along the mean normal of the pressing points, the rest
  /// of the force as friction, the point their centre of pressure
  /// (sum F_n,k P_k / sum F_n,k), the deepest penetration and the fastest
  /// slip among them; while open, the nearest point's gap and position.
  ContactReading reading(const Loc& c, const Loc& cd, const double* run) const {
    const auto pts = contact_points(c, cd, kAll);
    collision::Motion<double> A, B;
    motions(c.data(), cd.data(), A, B);
    ContactReading r;
    int nearest = 0;
    for (int k = 1; k < points; ++k)
      if (pts[k].gap < pts[nearest].gap) nearest = k;
    r.penetration = -pts[nearest].gap;
    r.point = pts[nearest].point.value();
    r.normal = pts[nearest].normal.value();
    Vec3 F = Vec3::Zero(), normal = Vec3::Zero(), centre = Vec3::Zero();
    double pressing = 0.0, slip = 0.0;
    for (int k = 0; k < points; ++k) {
      const auto& p = pts[k];
      const double Fn = law.normal_force(-p.gap, -p.gap_rate, run[run_state + k]);
      if (!(Fn > 0.0)) continue;
      const Vec3 n = p.normal.value();
      const Vec3 v = (A.velocity_at(acting_point(p)) - B.velocity_at(acting_point(p))).value();
      const Vec3 vt = v - v.dot(n) * n;
      F += Fn * n;
      if (!stuck(run)) F += law.friction_force(Fn, 1.0, vt.squaredNorm()) * vt;
      normal += Fn * n;
      centre += Fn * p.point.value();
      pressing += Fn;
      slip = std::max(slip, vt.norm());
    }
    if (pressing > 0.0) {
      r.normal = normal.normalized();
      r.normal_force = F.dot(r.normal);
      r.friction_force = F - r.normal_force * r.normal;
      r.point = centre / pressing;
      r.slip_speed = slip;
      r.state = ContactReading::kSlip;
    } else {
      const auto X = acting_point(pts[nearest]);
      const Vec3 n = r.normal, v = (A.velocity_at(X) - B.velocity_at(X)).value();
      r.slip_speed = (v - v.dot(n) * n).norm();
    }
    if (swapped) {  // for the shape given first: the force on it, the normal towards it
      r.normal = -r.normal;
      r.friction_force = -r.friction_force;
    }
    return r;
  }

  // events: each point's gap
  int root_count() const { return points; }
  void root_values(const Loc& c, const Loc& cd, double, double* g) const {
    const double apart = bounding_gap(c);
    if (apart > 0.0) {
      std::fill(g, g + points, apart);
      return;
    }
    // a gap within 1e-9 m of 0 reads by its rate: approaching, inside
    // (-1e-9: an onset just found, the restart's state back on the open
    // side by the projection's rounding, is not found again), leaving or at
    // rest, outside (+1e-9: a release likewise; a corner touching down at
    // rest is not an onset until it presses)
    constexpr double at_surface = 1e-9;
    const auto pts = contact_points(c, cd, kNear);
    for (int k = 0; k < points; ++k)
      g[k] = std::abs(pts[k].gap) > at_surface ? pts[k].gap : pts[k].gap_rate < 0.0 ? -at_surface : at_surface;
  }
  int direction(int) const { return 0; }
  EventAction crossing(int k, const Loc& c, const Loc& cd, double, double* run, int direction) const {
    EventAction a;
    a.type = EventAction::kRestart;
    a.speed = contact_points(c, cd, kAll)[k].gap_rate;
    // (labelled by the way the function crossed where that is known: at a
    // point touching at rest its rate is rounding, of either sign)
    if (direction < 0 || (direction == 0 && a.speed < 0.0)) {
      run[run_state + k] = std::max(0.0, -a.speed);
      a.label = "onset";
    } else {
      a.label = "release";
    }
    return a;
  }
  // --- stick: three rows (see above) -------------------------------------

  int stick_state(const double* run) const { return int(run[run_state + points]); }
  bool stuck(const double* run) const { return sticks && stick_state(run) == kStuck; }
  const double* anchor(const Instant& at) const {
    static const double none[12] = {0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0};  // (outside a run: an anchor at the centres)
    return at.state ? at.state + run_state + points + 1 : none;
  }
  spatial::Terms<3> stick_terms(const Loc& c, const spatial::Want& want, const Instant& at) const {
    using namespace spatial;
    const double* x = anchor(at);
    const Vec3 s_a(x[0], x[1], x[2]), s_b(x[3], x[4], x[5]), u_1(x[6], x[7], x[8]), u_2(x[9], x[10], x[11]);
    const VectorTerm D = minus(body_point(c, kBodyI, s_a, want), body_point(c, kBodyJ, s_b, want));
    const VectorTerm t1 = body_vector(c, kBodyJ, shape_b.axes.col(0), want);
    const VectorTerm t2 = body_vector(c, kBodyJ, shape_b.axes.col(1), want);
    return {dot(t1, D, want), dot(t2, D, want),
            combine(0.5, dot(t2, body_vector(c, kBodyI, u_1, want), want), -0.5,
                    dot(t1, body_vector(c, kBodyI, u_2, want), want), want)};
  }
  Eigen::Matrix<double, 3, 1> phi(const Loc& c, const Instant& at) const {
    spatial::Want want;
    want.gradient = false;
    return spatial::values<3>(stick_terms(c, want, at));
  }
  Eigen::Matrix<double, 3, 1> gamma(const Loc& c, const Loc& cd, const Instant& at) const {
    spatial::Want want;
    want.gradient = false;
    want.path = &cd;
    return -spatial::convectives<3>(stick_terms(c, want, at));
  }
  Eigen::Matrix<double, 3, 14> jacobian(const Loc& c, const Instant& at) const {
    return spatial::gradients<3>(stick_terms(c, {}, at));
  }
  void hessians(const Loc& c, const Instant& at, spatial::Mat14* H) const {
    spatial::hessians<3>(stick_terms(c, {true}, at), H);
  }
  Eigen::Matrix<double, 3, 14> rates(const Loc& c, const Loc& cd, const Instant& at) const {
    spatial::Want want;
    want.rate = &cd;
    return spatial::gradient_rates<3>(stick_terms(c, want, at));
  }
  /// The rows' axes: the surface's (t1, t2, n) on body j.
  Mat3 axes(const Loc& c, const Instant&) const {
    Mat3 E;
    for (int k = 0; k < 3; ++k) E.col(k) = euler::rotate(c.segment<4>(10), shape_b.axes.col(k));
    return E;
  }

  /// The pressing points at (c, cd): their total normal force, the
  /// largest slip speed among them, their centre of pressure C = sum F_n,k
  /// P_k / F_n and F_n-weighted mean distance rho from it, the same mean
  /// of the pressing material points X_k = P_k + g_k n_k (an anchored
  /// pair's vertices), and the deepest.
  struct Pressing {
    double normal_force = 0.0, slip = 0.0, radius = 0.0;
    Vec3 centre = Vec3::Zero(), material = Vec3::Zero();
    int deepest = -1;
  };
  Pressing pressing(const Loc& c, const Loc& cd, const double* run) const {
    Pressing out;
    if (bounding_gap(c) > 0.0) return out;
    const auto pts = contact_points(c, cd, kNear);
    collision::Motion<double> A, B;
    motions(c.data(), cd.data(), A, B);
    std::vector<double> Fn(points, 0.0);
    for (int k = 0; k < points; ++k) {
      const auto& p = pts[k];
      if (!(p.gap < 0.0)) continue;  // (apart: no force)
      Fn[k] = law.normal_force(-p.gap, -p.gap_rate, run[run_state + k]);
      if (!(Fn[k] > 0.0)) continue;
      const Vec3 n = p.normal.value(), v = (A.velocity_at(acting_point(p)) - B.velocity_at(acting_point(p))).value();
      out.normal_force += Fn[k];
      out.centre += Fn[k] * p.point.value();
      out.material += Fn[k] * acting_point(p).value();
      out.slip = std::max(out.slip, (v - v.dot(n) * n).norm());
      if (out.deepest < 0 || p.gap < pts[out.deepest].gap) out.deepest = k;
    }
    if (!(out.normal_force > 0.0)) return out;
    out.centre /= out.normal_force;
    out.material /= out.normal_force;
    for (int k = 0; k < points; ++k)
      if (Fn[k] > 0.0) out.radius += Fn[k] * (pts[k].point.value() - out.centre).norm() / out.normal_force;
    return out;
  }
  /// The event runner's function of the stick state: stuck, the friction
  /// margin mu_s F_n - sqrt(|F_r|^2 + (tau_C / rho)^2) with F_r = -(lam_1
  /// t1 + lam_2 t2) the force the rows hold at the anchor and tau_C their
  /// torque about n at the centre of pressure C (rho: the points' mean
  /// distance from C, at least 1e-3 of shape a's bounding radius: a single
  /// point holds next to no spin); -1 when nothing presses; armed, the
  /// largest slip of the pressing points less v_s (1 while none presses),
  /// stuck where it turns negative; disarmed (released, or found unable
  /// to hold), that slip less 2 v_s, armed again where it turns positive.
  double stick_root(const Loc& c, const Loc& cd, const Instant& at, const double* lam) const {
    const double* run = at.state;
    const int state = stick_state(run);
    const Pressing now = pressing(c, cd, run);
    if (state == kStuck) {
      if (now.deepest < 0) return -1.0;
      const double* x = anchor(at);
      const Vec4 pi = c.segment<4>(3), pj = c.segment<4>(10);
      const Vec3 X = c.head<3>() + euler::rotate(pi, Vec3(x[0], x[1], x[2]));
      const Vec3 t1 = euler::rotate(pj, shape_b.axes.col(0)), t2 = euler::rotate(pj, shape_b.axes.col(1));
      const Vec3 n = t1.cross(t2), u1 = euler::rotate(pi, Vec3(x[6], x[7], x[8])),
                 u2 = euler::rotate(pi, Vec3(x[9], x[10], x[11]));
      const Vec3 F = -(lam[0] * t1 + lam[1] * t2);
      // (the third row's torque about n: its gradient along a turn about n)
      const double torque = -lam[2] * 0.5 * (t2.dot(n.cross(u1)) - t1.dot(n.cross(u2))) + n.dot((X - now.centre).cross(F));
      const double rho = std::max(now.radius, 1e-3 * radius_a);
      return law.static_friction * now.normal_force - std::sqrt(F.squaredNorm() + (torque / rho) * (torque / rho));
    }
    if (now.deepest < 0) return 1.0;
    return now.slip - (state == kDisarmed ? 2.0 : 1.0) * law.slip_velocity;
  }
  /// Anchors the contact at the pressing vertices' F_n-weighted centre
  /// (below the centre of pressure by their mean depth: a body rocking
  /// about its pressing edge keeps that edge's vertices, not the point
  /// above them, in place) and marks it stuck (false: no point presses).
  bool stick_hold(const Loc& c, const Loc& cd, double* run) const {
    const Pressing now = pressing(c, cd, run);
    if (now.deepest < 0) return false;
    const Vec4 pi = c.segment<4>(3), pj = c.segment<4>(10);
    const Vec3 t1 = euler::rotate(pj, shape_b.axes.col(0)), t2 = euler::rotate(pj, shape_b.axes.col(1));
    double* x = run + run_state + points;
    x[0] = kStuck;
    // (A(p)^T undoes A(p) for unit p: the anchor and the tangent in each body's axes)
    Eigen::Map<Vec3>(x + 1) = euler::A(pi).transpose() * (now.material - c.head<3>());
    Eigen::Map<Vec3>(x + 4) = euler::A(pj).transpose() * (now.material - c.segment<3>(7));
    Eigen::Map<Vec3>(x + 7) = euler::A(pi).transpose() * t1;
    Eigen::Map<Vec3>(x + 10) = euler::A(pi).transpose() * t2;
    return true;
  }
  void stick_set(double* run, StickState state) const { run[run_state + points] = state; }
  /// A stuck contact's reading (reading()) with the friction its rows hold
  /// (lam: the rows' multipliers): -(lam_1 t1 + lam_2 t2) on body i, state stick.
  void stick_reading(const Loc& c, const double* run, const double* lam, ContactReading& r) const {
    if (stick_state(run) != kStuck || r.state == ContactReading::kOpen) return;
    const Vec4 pj = c.segment<4>(10);
    const Vec3 held = -(lam[0] * euler::rotate(pj, shape_b.axes.col(0)) + lam[1] * euler::rotate(pj, shape_b.axes.col(1)));
    r.friction_force += swapped ? Vec3(-held) : held;
    r.state = ContactReading::kStick;
  }
};


}  // namespace lagmb
