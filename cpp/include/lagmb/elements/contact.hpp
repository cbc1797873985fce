// Planar contact between a circle (on body i) and a line (on body j or the
// ground): the circle-line geometry of the contact law (contact_law.hpp).
#pragma once

#include <cmath>
#include <string>

#include "lagmb/dual.hpp"
#include "lagmb/elements/contact_law.hpp"
#include "lagmb/model/event_group.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// Circle: centre C = r_i + A_i s_c, radius R, on body i. Line: through
/// P0 = r_j + A_j s_p with direction u = A_j u' (unit) on body j; the circle
/// belongs on the side of n = u turned +90 deg. Signed distance of the centre
/// h = n . (C - P0), penetration d = R - h, its rate d' = -h'
/// (h' = n . (C' - P0') + omega_j (R90 n) . (C - P0)). The contact point is the
/// centre's projection on the line, P = C - h n; v_t = u . (v_i(P) - v_j(P))
/// is the slip velocity of the circle's material point there over the line's.
/// The law (ContactLaw: F_n, F_t from d, d', v_t) gives F = F_n n + F_t u on
/// body i at P and -F on body j at P:
///   Q_i = (F, (P - r_i) x F),  Q_j = (-F, -(P - r_j) x F).
/// v_impact is the approach speed -g' recorded by the onset event in the
/// run's state (a contact present at the start, or a force asked for
/// outside a run, uses ContactLaw::kMinImpactSpeed). Q_c and Q_cd are exact
/// (forward-mode derivatives of this same code, Dual<12>); where F_n is
/// clamped at 0 they are those of F_n = 0.
/// Event function: the gap g = h - R, both directions: onset (g' < 0: records
/// v_impact) and release restart the integrator (the force is not smooth there).
struct CircleLineContact {
  static constexpr bool state_dependent = true;
  static constexpr int roots = 1;
  static constexpr bool bounds_motion = false;  // g < 0 is contact, not a violation
  static constexpr const char* kind = "contact";

  std::string name;
  int body_i = -1, body_j = -1;
  Vec2 s_c = Vec2::Zero(), s_p = Vec2::Zero(), u = Vec2::UnitX();  // local
  double radius = 0.0;
  ContactLaw law;
  static constexpr int run_state_size = 1;  // run[run_state]: v_impact of the contact in progress (m/s)
  int run_state = -1;

  template <class T>
  struct Geometry {
    T Cx, Cy, nx, ny, ux, uy, h, hd, vt, Px, Py;
  };

  template <class T>
  Geometry<T> geometry(const T* c, const T* cd) const {
    using std::cos;
    using std::sin;
    Geometry<T> G;
    const T ci = cos(c[2]), si = sin(c[2]), cj = cos(c[5]), sj = sin(c[5]);
    // A s = (cos s_x - sin s_y, sin s_x + cos s_y)
    const T ax = ci * s_c.x() - si * s_c.y(), ay = si * s_c.x() + ci * s_c.y();  // A_i s_c
    const T bx = cj * s_p.x() - sj * s_p.y(), by = sj * s_p.x() + cj * s_p.y();  // A_j s_p
    G.ux = cj * u.x() - sj * u.y();
    G.uy = sj * u.x() + cj * u.y();
    G.nx = -G.uy;
    G.ny = G.ux;
    G.Cx = c[0] + ax;
    G.Cy = c[1] + ay;
    const T dx = G.Cx - c[3] - bx, dy = G.Cy - c[4] - by;  // C - P0
    G.h = G.nx * dx + G.ny * dy;
    // C' = rd_i + w_i R90 A_i s_c, P0' = rd_j + w_j R90 A_j s_p, n' = w_j R90 n
    const T Cdx = cd[0] - cd[2] * ay, Cdy = cd[1] + cd[2] * ax;
    const T Pdx = cd[3] - cd[5] * by, Pdy = cd[4] + cd[5] * bx;
    G.hd = G.nx * (Cdx - Pdx) + G.ny * (Cdy - Pdy) + cd[5] * (-G.ny * dx + G.nx * dy);
    G.Px = G.Cx - G.h * G.nx;
    G.Py = G.Cy - G.h * G.ny;
    // v_i(P) - v_j(P), material points of each body at P
    const T vx = cd[0] - cd[2] * (G.Py - c[1]) - (cd[3] - cd[5] * (G.Py - c[4]));
    const T vy = cd[1] + cd[2] * (G.Px - c[0]) - (cd[4] + cd[5] * (G.Px - c[3]));
    G.vt = G.ux * vx + G.uy * vy;
    return G;
  }

  template <class T>
  void evaluate(const T* c, const T* cd, double impact_speed, T* Q) const {
    for (int a = 0; a < 6; ++a) Q[a] = T(0.0);
    const Geometry<T> G = geometry(c, cd);
    const T Fn = law.normal_force(T(radius) - G.h, -G.hd, impact_speed);
    if (!(value_of(Fn) > 0.0)) return;
    const T Ft = law.friction_force(Fn, G.vt, G.vt * G.vt);
    const T Fx = Fn * G.nx + Ft * G.ux, Fy = Fn * G.ny + Ft * G.uy;
    Q[0] = Fx;
    Q[1] = Fy;
    Q[2] = (G.Px - c[0]) * Fy - (G.Py - c[1]) * Fx;
    Q[3] = -Fx;
    Q[4] = -Fy;
    Q[5] = -((G.Px - c[3]) * Fy - (G.Py - c[4]) * Fx);
  }

  Local6 force(const Local6& c, const Local6& cd, double, const double* run) const {
    double Q[6];
    evaluate(c.data(), cd.data(), run[run_state], Q);
    return Eigen::Map<const Local6>(Q);
  }
  void derivatives(const Local6& c, const Local6& cd, double, const double* run, Mat6& Q_c, Mat6& Q_cd) const {
    using D = Dual<12>;
    D x[6], xd[6], Q[6];
    for (int a = 0; a < 6; ++a) {
      x[a] = D(c[a]);
      x[a].d[a] = 1.0;
      xd[a] = D(cd[a]);
      xd[a].d[6 + a] = 1.0;
    }
    evaluate(x, xd, run[run_state], Q);
    for (int b = 0; b < 6; ++b) {
      Q_c.row(b) = Q[b].d.head<6>().transpose();
      Q_cd.row(b) = Q[b].d.tail<6>().transpose();
    }
  }
  /// The contact at (c, cd), v_impact from the run's state (ContactReading;
  /// the state is slip while in contact: the regularized friction never sticks).
  ContactReading reading(const Local6& c, const Local6& cd, const double* run) const {
    const Geometry<double> G = geometry(c.data(), cd.data());
    ContactReading r;
    r.penetration = radius - G.h;
    r.normal = Vec3(G.nx, G.ny, 0.0);
    r.point = Vec3(G.Px, G.Py, 0.0);
    r.slip_speed = std::abs(G.vt);
    r.normal_force = law.normal_force(r.penetration, -G.hd, run[run_state]);
    if (!(r.normal_force > 0.0)) return r;
    r.state = ContactReading::kSlip;
    const double Ft = law.friction_force(r.normal_force, G.vt, G.vt * G.vt);
    r.friction_force = Vec3(Ft * G.ux, Ft * G.uy, 0.0);
    return r;
  }
  double potential(const Local6& c, double) const {
    const Local6 zero = Local6::Zero();
    return law.potential(radius - geometry(c.data(), zero.data()).h);
  }

  // event: the gap
  double root(int, const Local6& c, const Local6& cd, double) const {
    const double g = geometry(c.data(), cd.data()).h - radius;
    return g != 0.0 ? g : -1e-300;
  }
  int direction(int) const { return 0; }
  EventAction crossing(int, const Local6& c, const Local6& cd, double, double* run, int direction) const {
    EventAction a;
    a.type = EventAction::kRestart;
    a.speed = geometry(c.data(), cd.data()).hd;
    // (labelled by the way the gap crossed where that is known: touching at rest, its rate is rounding)
    if (direction < 0 || (direction == 0 && a.speed < 0.0)) {
      run[run_state] = std::max(0.0, -a.speed);
      a.label = "onset";
    } else {
      a.label = "release";
    }
    return a;
  }
};

}  // namespace lagmb
