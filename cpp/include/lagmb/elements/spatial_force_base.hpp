// What the spatial force kinds share: their bodies, and the
// spring-damper-actuator on one scalar coordinate (spatial::add_spring_damper)
// that the translational and rotational spring-dampers are.
#pragma once

#include <string>

#include "lagmb/spatial_terms.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

struct SpatialForceBase {
  using Space = Spatial;
  static constexpr bool state_dependent = true;
  std::string name;
  int body_i = -1, body_j = -1;
};

/// A spring-damper-actuator on one scalar coordinate s(c) of the kind
/// (`coordinate(c, want, t)`): F = -k (s - s0) - c s' + f(t) along s
/// (spatial::add_spring_damper), potential k (s - s0)^2 / 2. Its effort
/// (Result.effort) is that F, the actuator's f(t) at the run's inputs
/// included.
template <class Kind>
struct ScalarSpringDamper : SpatialForceBase {
  double stiffness = 0.0, damping = 0.0, free_value = 0.0;  // k, c, s0
  Drive actuator;  // f(t); may be null
  static constexpr bool reads_inputs = true;

  double act(const Instant& t) const { return actuator ? actuator.at(t).f : 0.0; }
  double effort(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t) const {
    return spatial::spring_damper_force(self().coordinate(c, {}, t), cd, stiffness, damping, free_value, act(t));
  }
  spatial::Loc force(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t) const {
    spatial::Loc Q = spatial::Loc::Zero();
    spatial::add_spring_damper(self().coordinate(c, {}, t), cd, stiffness, damping, free_value, act(t), Q);
    return Q;
  }
  void derivatives(const spatial::Loc& c, const spatial::Loc& cd, const Instant& t, spatial::Mat14& dq,
                   spatial::Mat14& dv) const {
    spatial::Loc Q = spatial::Loc::Zero();
    dq.setZero();
    dv.setZero();
    spatial::add_spring_damper(self().coordinate(c, {true}, t), cd, stiffness, damping, free_value, act(t), Q, &dq,
                               &dv);
  }
  double potential(const spatial::Loc& c, const Instant& t) const {
    const double e = self().coordinate(c, {}, t).value - free_value;
    return 0.5 * stiffness * e * e;
  }

 private:
  const Kind& self() const { return static_cast<const Kind&>(*this); }
};

}  // namespace lagmb
