// Formulation "auto": which method a run takes, and why.
#pragma once

#include <string>

#include "lagmb/integrators/methods.hpp"
#include "lagmb/model/model.hpp"
#include "lagmb/options.hpp"

namespace lagmb {

/// What formulation "auto" runs, and why (Stats::method_choice):
///   - GGL where the forces switch faster than any step can follow: a
///     contact (its onset and release; an explicit step could pass a whole
///     contact) or joint friction from the joints' loads;
///   - GGL where the applied forces are stiff: their fastest rate rho
///     (force_rates at the initial state: springs, bushings, dampers, the
///     smoothed sign of joint friction) times the run's span above
///     kStiffSpan, where an explicit method would take more than about
///     kStiffSpan / 5 steps for stability alone;
///   - else the explicit projection-erk (Prince-Dormand 8(7) with projections),
///     which on non-stiff mechanisms reaches an error in a fraction of the
///     implicit methods' time (bench/accuracy/auto_method.py); should it give up
///     (its error test, or kAutoStiffSteps between two outputs), GGL takes
///     over from its last step (Run::switch_to_ggl).
struct MethodChoice {
  const Method* method = nullptr;
  std::string why;
};
constexpr double kStiffSpan = 1000.0;
MethodChoice choose_method(const Model& model, const SimulationOptions& o);

}  // namespace lagmb
