// Bodies: a planar rigid body (x, y, phi), a particle (x, y), or a spatial
// rigid body (r, p).
#pragma once

#include <string>

#include "lagmb/types.hpp"

namespace lagmb {

/// A planar rigid body (3 coordinates: x, y of the centre of mass and the
/// angle phi), a particle (2 coordinates: x, y), or a spatial rigid body (7:
/// its centre of mass r and Euler parameters p, elements/spatial_body.hpp).
/// SI units. Each adds a block to the mass matrix M: diag(m, m, J) for a
/// planar rigid body, diag(m, m) for a particle (both constant), and
/// diag(m, m, m, M_p(p)) for a spatial one.
struct Body {
  std::string name;
  double mass = 1.0;     // kg
  double inertia = 1.0;  // kg m^2 about the centre of mass (0 for particles)
  Vec2 position = Vec2::Zero();
  double angle = 0.0;
  Vec2 velocity = Vec2::Zero();
  double angular_velocity = 0.0;
  bool particle = false;
  // a spatial rigid body (spatial = true): the initial state in global axes,
  // and the inertia tensor J' about the centre of mass in body axes
  bool spatial = false;
  Vec3 r0 = Vec3::Zero(), rdot0 = Vec3::Zero(), omega0 = Vec3::Zero();
  Vec4 p0 = Vec4::UnitX();  // (1, 0, 0, 0): body axes along the global ones
  Mat3 inertia_tensor = Mat3::Identity();
  int first_coord = -1;  // set by finalize()

  int n_coordinates() const { return spatial ? 7 : particle ? 2 : 3; }
  /// Index of the planar angle coordinate in q, or -1 (particle, spatial body).
  int angle_coord() const { return particle || spatial ? -1 : first_coord + 2; }
  /// Whether its motion has mass and (unless a particle) inertia in every
  /// direction: m > 0, and J > 0 in the plane or every principal moment of
  /// J' > 1e-12 of the largest in space (a zero moment of a tensor turned to
  /// other axes reads as +-1e-17, and its inverse would be 1e17). A body
  /// without runs on the augmented system's LU, never on M^-1.
  bool has_mass_and_inertia() const;
};

}  // namespace lagmb
