// The two spaces an element kind lives in: the plane and space. A kind says
// which with `using Space = Spatial;` (planar when it says nothing); its
// group (constraint_group.hpp, force_group.hpp) takes from the Space how many
// local coordinates it has, what the ground reads there and how a reaction
// is reported. Assembly sees neither.
#pragma once

#include <type_traits>

#include "lagmb/spatial.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// Planar elements: c = (x_i, y_i, phi_i, x_j, y_j, phi_j); the ground (and
/// a particle's missing angle) reads 0. Reactions (k, 3): force (x, y) and
/// torque about body j's centre of mass.
struct Planar {
  static constexpr int dimension = 2;
  static constexpr int local = 6;
  static constexpr int bodies = 2;
  using Axes = Mat2;
  using Point = Vec2;
  static double ground_coordinate(int) { return 0.0; }
  /// The reaction on body j from the generalized force g = -Phi_c^T lam: the
  /// last three of g; with `about` a point P, the torque about P instead of
  /// about body j's centre of mass r_j, M_P = M_G + (r_j - P) x F (the ground
  /// as body j reads r_j = 0); with `axes`, the force in those axes (A^T F).
  static VecX reaction(const Local6& g, const Local6& c, const Axes* axes, const Point* about = nullptr) {
    VecX w = g.tail<3>();
    if (about) w[2] += cross(Vec2(c.segment<2>(3) - *about), Vec2(w.head<2>()));
    if (axes) w.head<2>() = axes->transpose() * w.head<2>();
    return w;
  }
};

/// Spatial elements: c = (r_i, p_i, r_j, p_j), 3 + 4 per body (centre of
/// mass and Euler parameters, spatial.hpp); the ground reads r = 0, p = (1,
/// 0, 0, 0). Reactions (k, 6): force and torque about body j's centre of
/// mass, global axes: F = g_rj, n = E(p_j) g_pj / 2 (the generalized force
/// of a torque n on p is 2 E(p)^T n).
struct Spatial {
  static constexpr int dimension = 3;
  static constexpr int local = 14;
  static constexpr int bodies = 2;
  using Axes = Mat3;
  using Point = Vec3;
  static double ground_coordinate(int a) { return a == 3 || a == 10 ? 1.0 : 0.0; }
  /// With `about` a point P: the torque about P, n_P = n + (r_j - P) x F.
  static VecX reaction(const Eigen::Matrix<double, 14, 1>& g, const Eigen::Matrix<double, 14, 1>& c,
                       const Axes* axes, const Point* about = nullptr) {
    VecX w(6);
    w.head<3>() = g.segment<3>(7);
    w.tail<3>() = 0.5 * euler::E(c.segment<4>(10)) * g.segment<4>(10);
    if (about) w.tail<3>() += Vec3(c.segment<3>(7) - *about).cross(Vec3(w.head<3>()));
    if (axes) {
      w.head<3>() = axes->transpose() * w.head<3>();
      w.tail<3>() = axes->transpose() * w.tail<3>();
    }
    return w;
  }
};

/// Elements that relate two spatial joints (joint_coupling.hpp): c = (c_a,
/// c_b), each the 14 coordinates (r_i, p_i, r_j, p_j) of one joint's two
/// bodies (a body both joints share appears twice; its group adds the
/// columns). Reactions (k, 6): as Spatial, on the second joint's body j.
struct SpatialJointPair {
  static constexpr int dimension = 3;
  static constexpr int local = 28;
  static constexpr int bodies = 4;
  using Axes = Mat3;
  using Point = Vec3;
  static double ground_coordinate(int a) { return a % 7 == 3 ? 1.0 : 0.0; }
  static VecX reaction(const Eigen::Matrix<double, 28, 1>& g, const Eigen::Matrix<double, 28, 1>& c,
                       const Axes* axes, const Point* about = nullptr) {
    return Spatial::reaction(g.tail<14>(), c.tail<14>(), axes, about);
  }
};

/// The Space of an element kind: Kind::Space, or Planar.
template <class Kind, class = void>
struct space_of {
  using type = Planar;
};
template <class Kind>
struct space_of<Kind, std::void_t<typename Kind::Space>> {
  using type = typename Kind::Space;
};
template <class Kind>
using space_of_t = typename space_of<Kind>::type;

template <int L>
using LocalVec = Eigen::Matrix<double, L, 1>;
template <int L>
using LocalMat = Eigen::Matrix<double, L, L>;

/// An element's local coordinates from the global q: the ground's (and a
/// missing angle's) value where coord is -1.
template <class S>
LocalVec<S::local> gather_q(const double* q, const LocalCoords& coord) {
  LocalVec<S::local> c;
  for (int a = 0; a < S::local; ++a) c[a] = coord[a] >= 0 ? q[coord[a]] : S::ground_coordinate(a);
  return c;
}

/// An element's local velocities (or any vector over q) from the global one:
/// 0 where coord is -1 (the ground does not move).
template <int L>
LocalVec<L> gather_v(const double* v, const LocalCoords& coord) {
  LocalVec<L> c;
  for (int a = 0; a < L; ++a) c[a] = coord[a] >= 0 ? v[coord[a]] : 0.0;
  return c;
}

}  // namespace lagmb
