// Functions of time with exact first and second derivatives (drivers, actuators).
#pragma once

#include <iosfwd>
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
  /// The function as text that time_function_from_text reads back exactly
  /// ("harmonic 0.5 6.28 0 0"); "" for one that has none (a Python callable).
  virtual std::string text() const { return ""; }
  /// Whether f changes with t (false: a constant, or an input, which holds
  /// its value between the jumps a Simulator makes).
  virtual bool varies() const { return true; }
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

/// Reads one function written by TimeFunction::text from `in`; ModelError
/// naming what is wrong.
TimeFunctionPtr time_function_from_text(std::istream& in);

/// A value set from outside while the model runs (Simulator::set_input): a
/// force, torque or driver value given as an input instead of a function of
/// time. It holds its value between changes (f' = f'' = 0); a change is a
/// jump, where the integrator restarts. The Model lists the inputs of its
/// elements (Model::inputs) and each element reads its input's value from
/// the run (Data::run, Instant::inputs), so one Model runs with different
/// inputs on several threads. A run starts with the initial values; only a
/// Simulator changes them. eval() outside a run gives the initial value.
class Input final : public TimeFunction {
 public:
  /// `name` "": named after the element it feeds (Model::inputs).
  explicit Input(double initial, std::string name = "") : initial_(initial), name_(std::move(name)) {}
  TimeValue eval(double) const override { return {initial_, 0.0, 0.0}; }
  std::string text() const override;
  bool varies() const override { return false; }
  double initial() const { return initial_; }
  const std::string& name() const { return name_; }

 private:
  double initial_;
  std::string name_;
};
std::shared_ptr<Input> input(double initial, std::string name = "");

/// When a kernel evaluates the model: the time, the run's input values
/// (Model::inputs order) and the run's element state (Data::RunValues::state:
/// e.g. the turns a spatial joint has made, model/joint_turns.hpp); Data::at
/// makes one. Kernels pass it down to the elements that follow a function of
/// time or an input, or read the run's state; nothing is bound to a thread.
struct Instant {
  double t = 0.0;
  const double* inputs = nullptr;
  const double* state = nullptr;  // null: outside a run (every element at its initial state)
};

/// What an element follows: a function of time, or an input of the model
/// (its slot in the run's input values, set when the element is built).
struct Drive {
  TimeFunctionPtr f;  // null: none (an optional actuator)
  int input = -1;     // >= 0: the slot in Instant::inputs that replaces f
  TimeValue at(const Instant& now) const {
    if (input >= 0) return {now.inputs[input], 0.0, 0.0};
    return f->eval(now.t);
  }
  explicit operator bool() const { return bool(f); }
};

}  // namespace lagmb
