// Bodies: a planar rigid body (x, y, phi) or a particle (x, y).
#pragma once

#include <string>

#include "lagmb/types.hpp"

namespace lagmb {

/// A planar rigid body (3 coordinates: x, y of the centre of mass and the
/// angle phi) or a particle (2 coordinates: x, y). SI units. Each adds a
/// constant diagonal block to the mass matrix M: diag(m, m, J) for a rigid
/// body, diag(m, m) for a particle.
struct Body {
  std::string name;
  double mass = 1.0;     // kg
  double inertia = 1.0;  // kg m^2 about the centre of mass (0 for particles)
  Vec2 position = Vec2::Zero();
  double angle = 0.0;
  Vec2 velocity = Vec2::Zero();
  double angular_velocity = 0.0;
  bool particle = false;
  int first_coord = -1;  // set by finalize()

  int n_coordinates() const { return particle ? 2 : 3; }
  /// Index of the angle coordinate in q, or -1 for a particle.
  int angle_coord() const { return particle ? -1 : first_coord + 2; }
};

}  // namespace lagmb
