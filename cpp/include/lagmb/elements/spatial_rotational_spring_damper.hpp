// A torsion spring-damper-actuator on a revolute's (or cylindrical joint's)
// angle.
#pragma once

#include "lagmb/model/joint_reading.hpp"
#include "lagmb/elements/spatial_force_base.hpp"

namespace lagmb {

/// Rotational spring-damper-actuator on a revolute's (or cylindrical
/// joint's) angle theta, continuous through the joint's turns in a run
/// (spatial::JointReading; s0: the free angle): the torque on body j about
/// the axis is T = -k (theta - theta0) - c theta' + tau(t).
struct SpatialRotationalSpringDamper : ScalarSpringDamper<SpatialRotationalSpringDamper> {
  static constexpr const char* kind = "spatial_rotational_spring_damper";
  spatial::JointReading joint;

  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want& want, const Instant& t) const {
    return joint(c, want, t);
  }
};

}  // namespace lagmb
