// The Run: what simulate and a Simulator share of a dynamic run. Its jobs'
// parts have their own files: the options (run_options), the method choice
// of formulation "auto" (method_choice), the start (start), the outputs'
// recording (recording) and the sensitivities (sensitivities.cpp).
#pragma once

#include <memory>
#include <string>

#include "lagmb/events/event_runner.hpp"
#include "integrators/integrators.hpp"
#include "lagmb/analyses/redundancy.hpp"
#include "run/method_choice.hpp"
#include "run/recording.hpp"
#include "run/run_options.hpp"
#include "run/start.hpp"

namespace lagmb {

/// Everything one dynamic run changes, in one place (docs/design.md 2.8):
/// the model it runs (the one given, or built with the run's parameters),
/// its Data (the dropped rows, the input values, the elements' run state:
/// Data::RunValues, which every Data of the run shares), the augmented
/// system, the event runner, the watch over the rows left out as redundant,
/// the integration plan, the stepper and its loop, their counts and the
/// outputs recorded so far. simulate builds one and steps it to t_end; a
/// Simulator keeps one and steps it in chunks. Constructing it validates
/// nothing: the options are the caller's, checked (validate_run_options)
/// on `model`.
class Run {
 public:
  /// Starts the run of `given` (or of `with_parameters`, the model built
  /// from it with the run's parameters, when not null) at options.t0
  /// (dynamic_start, start_events): the consistent state is `start`;
  /// outputs holds none yet and there is no stepper until start_stepper.
  /// `stop_at_end`: the steps stop at plan.t_end (simulate) or may pass the
  /// time asked for (a Simulator: outputs interpolated, StepLoop).
  Run(const Model& given, std::shared_ptr<const Model> with_parameters, const SimulationOptions& options,
      const Method& method, bool stop_at_end);
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  const std::shared_ptr<const Model> with_parameters;  // null: the run is of the model given
  const Model& model;                                  // what the run integrates
  const SimulationOptions& options;
  const Method& method;  // the method asked for or chosen at the start (see current_method)
  Data data;  // the run's (plan.run): every other Data of the run is made of it
  AugmentedSystem kkt;
  ConsistentState start;
  std::unique_ptr<EventRunner> events;  // null without event elements
  IntegrationPlan plan;                 // outputs and breakpoints: the caller's
  std::unique_ptr<RedundancyWatch> watch;
  Trajectory outputs;  // n, m, p, dropped rows, the method's names and run_model set
  long input_changes = 0;  // a Simulator's restarts for new input values (Stats::input_changes)
  std::string method_choice = "given";  // Stats::method_choice

  /// Forward sensitivities to integrate (start_sensitivities; null: none).
  std::unique_ptr<SensitivityPlan> sensitivities;

  /// Appends the output (t, q, v) with the run's input values (and, with
  /// `solve`, its a and lam): record_output; with sensitivities, theirs.
  /// A method that drifts (Method::drifts: index1, projection-adams) is
  /// held to its constraints there first (check_held).
  void record(double t, const double* q, const double* v, bool solve);
  /// IntegratorFailure naming the row where |Phi(q, t)| exceeds
  /// 1e-2 (1 + |q|): a drifting method's steps have lost the motion (a
  /// spatial rod at 50 rad/s under Adams at rtol 1e-3 drifted 0.2 m in
  /// 0.44 s; without an event to restart at, the run reported success
  /// with |Phi| = 8 at its end).
  void check_held(double t, const double* q);
  /// Sets up forward sensitivities to the parameters `names`
  /// (Model::parameters' names) before the stepper starts: the models at
  /// p_i +- delta_i (delta_i = 1e-4 abs(p_i), 1e-4 where p_i = 0; the
  /// model at p_i for a side beyond a bound of its range: a one-sided
  /// difference), their GGL forms made of this run's Data, and the initial
  /// sensitivities from their consistent starts. ModelError for a method
  /// other than GGL with IDA, a model with events or joint friction, an
  /// unknown or repeated name, or a parameter with no sensitivity, each
  /// saying why: no other value of it nearby is allowed (a component of a
  /// universal joint's axis), a model with another value cannot start, or
  /// its change alters which rows are redundant.
  void start_sensitivities(const std::vector<std::string>& names);

  /// A new stepper of the run's method from the consistent state `from` at
  /// time t (plan.t0 = t, the scale of its first step), and a new loop; the
  /// counts of the one before are kept, and replacing it is a restart.
  void start_stepper(double t, const ConsistentState& from);
  /// The stepper restarted at order 1 from `from` at time t (the run's
  /// values changed there: an input); keeps its solver session.
  void restart_stepper(double t, const ConsistentState& from);
  /// A Simulator's new input values at the state the stepper reached: (t,
  /// q, v) its last step's end, which the new values leave on the
  /// constraints (no input moved a driver: |Phi| within 1e-12 (1 + |q|)).
  /// Nothing is projected: the events settle with the multipliers the
  /// stepper's formulation solves there (its next step's first stage),
  /// and the stepper resumes (from the events' consistent state where the
  /// active set changed). Returns that state, or false (nothing done) where
  /// the state is not the stepper's or the formulation has no multipliers
  /// to give: the caller restarts from a consistent state (restart_stepper).
  bool resume_in_place(double t, const VecX& q, const VecX& v, ConsistentState& now);
  /// Steps the stepper until the time reached is at least `target`,
  /// calling record(q, v) for t_out[k], k counting on: first for the times
  /// inside the step taken last (a Simulator's steps pass the time asked
  /// for), then as StepLoop::run. An IntegratorFailure leaves with the
  /// positions of the last accepted step (for the diagnosis).
  void step_to(double target, const std::vector<double>& t_out, size_t& k, const Record& record);
  /// Whether there is a stepper (start_stepper called).
  bool stepping() const { return bool(stepper_); }
  /// The method stepping now: `method`, or GGL after formulation "auto"
  /// gave up on the explicit method (step_to).
  const Method& current_method() const { return *current_; }
  /// Steps between outputs after which formulation "auto" takes the
  /// explicit method for too stiff and runs on with GGL.
  static constexpr long kAutoStiffSteps = 5000;

  /// The run's counts: every stepper's summed, the restarts (breakpoints,
  /// events, new steppers, input changes), the elements evaluated by the
  /// run's own Data and watch, the events; the method's names.
  Stats stats() const;

 private:
  /// Makes the initial sensitivities satisfy the constraints' linearization
  /// exactly (see run.cpp).
  void consistent_sensitivities(SensitivityPlan& sens);
  /// Formulation "auto" running the explicit method: after the failure
  /// `why` (its error test, kAutoStiffSteps or max_steps between outputs),
  /// GGL takes over from the last accepted step; false if that is not
  /// the case (or it happened before: the failure stands).
  bool switch_to_ggl(const IntegratorFailure& why);

  const Method* current_;
  std::unique_ptr<Stepper> stepper_;
  std::unique_ptr<StepLoop> loop_;
  bool stop_at_end_;
  Stats finished_;  // counts of the steppers before the current one
  long restarts_ = 0;  // new steppers and restarts from outside the loop
};

}  // namespace lagmb
