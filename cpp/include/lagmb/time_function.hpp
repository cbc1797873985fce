// Functions of time with exact first and second derivatives (drivers, actuators).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagmb {

/// f(t), f'(t), f''(t).
struct TimeValue {
  double f = 0.0, df = 0.0, ddf = 0.0;
};

class TimeFunction {
 public:
  virtual ~TimeFunction() = default;
  virtual TimeValue eval(double t) const = 0;
  /// Times where a derivative of f jumps (smooth-step ends, spline knots).
  /// The integrator stops and restarts there instead of stepping across.
  virtual std::vector<double> breakpoints() const { return {}; }
};
using TimeFunctionPtr = std::shared_ptr<TimeFunction>;

/// A user-supplied function failed; the run stops with this message.
struct UserFunctionError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// c
TimeFunctionPtr constant(double c);
/// start + rate t
TimeFunctionPtr linear(double rate, double start = 0.0);
/// c0 + c1 t + c2 t^2 + ...
TimeFunctionPtr polynomial(std::vector<double> coeffs);
/// offset + amplitude sin(omega t + phase)
TimeFunctionPtr harmonic(double amplitude, double omega, double phase = 0.0, double offset = 0.0);
/// y0 before t0, y1 after t1, y0 + (y1 - y0)(10 s^3 - 15 s^4 + 6 s^5) between,
/// s = (t - t0)/(t1 - t0): zero velocity and acceleration at both ends.
TimeFunctionPtr smooth_step(double t0, double t1, double y0, double y1);
/// Natural cubic spline through (times, values), C2; linear beyond the ends.
TimeFunctionPtr spline(std::vector<double> times, std::vector<double> values);

}  // namespace lagmb
