// The failure of a run's integration, thrown by the event runner (the
// lowest layer that gives up on a run) and the steppers above it; the run
// turns it into a SimulationError with its diagnosis (run/simulate.cpp).
#pragma once

#include <stdexcept>
#include <string>

#include "lagmb/types.hpp"

namespace lagmb {

/// The integrator gave up at time t; what() carries its diagnosis.
struct IntegratorFailure : std::runtime_error {
  IntegratorFailure(const std::string& what, double t_reached)
      : std::runtime_error(what), t(t_reached) {}
  double t;
  VecX q;  // positions at t (the last accepted step), for the diagnosis
  bool diagnose = true;  // false: the message is complete (no Jacobian diagnosis)
  /// The integrator itself gave up (its error test or step count), not a
  /// user function or an event: another method may still get through
  /// (formulation "auto" then runs on with GGL: Run::step_to).
  bool integrator_gave_up = false;
};

/// A failure whose message is complete: no Jacobian diagnosis follows.
inline IntegratorFailure plain_failure(const std::string& message, double t) {
  IntegratorFailure f(message, t);
  f.diagnose = false;
  return f;
}

}  // namespace lagmb
