// What a contact force kind reports of itself at one instant (its readers:
// Result.contact, outputs.hpp contacts()).
#pragma once

#include "lagmb/types.hpp"

namespace lagmb {

/// What a contact does at one instant, for its readers (Result.contact):
/// the normal force F_n (N, >= 0) on body i along the normal n (the outward
/// normal of body j's surface), the friction force on body i (N), the
/// contact point P (m), the penetration d (m, < 0: the gap while open), the
/// slip speed |v_t| (m/s) and the state. Vectors in global axes, their
/// first `dimension` components used (2 in the plane, 3 in space).
struct ContactReading {
  enum State { kOpen = 0, kSlip = 1, kStick = 2 };
  double normal_force = 0.0;
  Vec3 friction_force = Vec3::Zero(), point = Vec3::Zero(), normal = Vec3::Zero();
  double penetration = 0.0, slip_speed = 0.0;
  State state = kOpen;
};

}  // namespace lagmb
