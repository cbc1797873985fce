// The time integrators lagmb drives, behind one call each.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "events/integrator_failure.hpp"
#include "formulations/dae.hpp"
#include "lagmb/integrators/methods.hpp"
#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/options.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

/// Forward sensitivities s_i = dy/dp_i of a run's solution y(t) to
/// parameters p_i (IDA on the GGL form only), integrated by IDAS beside y:
///   F_y s_i + F_y' s_i' + F_p_i = 0,
/// F_y s + F_y' s' from the formulation's exact blocks
/// (DaeFormulation::sensitivity_products) and F_p_i by central differences
/// of F between the models built with p_i +- delta_i (F of the same y, y').
struct SensitivityPlan {
  /// The models at p_i +- delta_i (first: the forms below refer to them).
  std::vector<std::shared_ptr<const Model>> models;
  std::vector<std::string> names;
  /// Half the span between the two models' values of p_i, by which F's
  /// differences divide: their step, or half of it at a bound of p_i's
  /// range (a damping of 0), where the model at p_i is the one beyond it
  std::vector<double> delta;
  std::vector<double> scale;  // IDAS' pbar: abs(p_i), 1 where p_i = 0
  /// The GGL forms of the models at p_i + delta_i and p_i - delta_i (Data of the run).
  std::vector<std::unique_ptr<DaeFormulation>> plus, minus;
  /// The sensitivities of y and y' at the start: central differences of the
  /// consistent starts of the models at p_i +- delta_i.
  std::vector<VecX> s0, sp0;
  int count() const { return int(names.size()); }
};

/// What every integrator is asked to do: the run's options (tolerances,
/// step bounds, progress) read where they are, and what the run derives.
struct IntegrationPlan {
  const SimulationOptions* options = nullptr;  // outlives the plan
  double t0 = 0.0, t_end = 0.0;  // of this stretch (a Simulator's advance moves them)
  VecX atol;                     // per coordinate: options->atol or options->atol_coordinates
  int max_order = 0;             // options->max_order, or the method's highest
  std::vector<double> t_out;
  std::vector<double> breakpoints;  // inside (t0, t_end): stop and restart there
  class EventRunner* events = nullptr;  // the model's event functions; null: none
  const Data* run = nullptr;  // the run's Data: each integrator's own Data is made of it (Data's constructor)
  /// Steps between outputs after which the method gives up as too stiff
  /// for it (IntegratorFailure::integrator_gave_up), so that formulation
  /// "auto" runs on with GGL; 0: none (only max_steps).
  long stiff_steps = 0;
  /// Forward sensitivities to integrate beside the state (null: none).
  SensitivityPlan* sensitivities = nullptr;
};

/// Smallest step an integrator may take: 100 ulps of the largest |t| of the
/// run. Below it the step cannot advance t.
inline double minimum_step(const IntegrationPlan& plan) {
  const double T = std::max({std::abs(plan.t0), std::abs(plan.t_end), 1.0});
  return 100.0 * std::numeric_limits<double>::epsilon() * T;
}

/// One integrator as the shared stepping loop sees it.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// Sets the time the next steps must not pass (a breakpoint or t_end).
  virtual void set_stop(double stop) = 0;
  /// One step; returns the time reached and sets at_stop when that is the
  /// stop time. Throws IntegratorFailure (with the solver's diagnosis).
  virtual double step(bool& at_stop) = 0;
  /// q and v at time t inside the last step (interpolated).
  virtual void interpolate(double t, const double*& q, const double*& v) = 0;
  /// Restarts at order 1 from the current state at time t.
  virtual void restart(double t) = 0;
  /// Whether the loop stops the steps at the output times: a stepper whose
  /// interpolant is less accurate than its steps (an explicit Runge-Kutta
  /// method of order 7 with a quintic interpolant, whose long steps make the
  /// interpolant's O(h^6) error the larger one at outputs inside a step).
  virtual bool steps_to_outputs() const { return false; }
  /// Positions of the last accepted step.
  virtual const double* positions() const = 0;
  /// Counts so far, summed over restarts.
  virtual void fill_stats(Stats& stats) = 0;
  virtual const char* name() const = 0;

  // events (a stepper of a model without event elements never reports roots)
  /// Whether the last step stopped at a root of the event functions; then
  /// fired[i] != 0 for the event functions that crossed.
  virtual bool root_found(std::vector<int>& fired) { (void)fired; return false; }
  /// Velocities of the last accepted step (or of the root).
  virtual const double* velocities() const { return nullptr; }
  /// qdd and lam at (t, q, v) on the run's rows, as the stepper's own
  /// formulation solves them (remembered there: at a step's end the root
  /// functions, the output and the next step's first stage share one
  /// solve); false where it has none to give (the caller solves them).
  virtual bool motion_at(double t, const double* q, const double* v, const double*& qdd, const double*& lam) {
    (void)t, (void)q, (void)v, (void)qdd, (void)lam;
    return false;
  }
  /// Restarts at order 1 from a new consistent state at time t (after a
  /// velocity jump or a change of the equations).
  virtual void reset(double t, const ConsistentState& s) { (void)s; restart(t); }
  /// The same where only the equations jump (an input's new value) at the
  /// state reached: a stepper that needs no history may choose its first
  /// step there (ErkStepper); the others restart as reset() does.
  virtual void resume(double t, const ConsistentState& s) { reset(t, s); }
  /// The forward sensitivities at time t inside the last step (plan.sensitivities):
  /// s[i] of y and sp[i] of y' for each parameter, in the formulation's layout.
  virtual void sensitivities(double t, std::vector<VecX>& s, std::vector<VecX>& sp) {
    (void)t, (void)s, (void)sp;
    throw std::logic_error("lagmb: this integrator has no sensitivities");
  }
};

using Record = std::function<void(const double* q, const double* v)>;

/// The loop every run shares (simulate in one call, a Simulator in chunks):
/// outputs interpolated where asked (the steps are not stopped there, unless
/// the stepper's interpolant is the less accurate: steps_to_outputs), a
/// stop and restart at every breakpoint of the time functions, the events'
/// actions, the max_steps bound and progress reports.
class StepLoop {
 public:
  /// `stepper` starts at time t; the stop times are the breakpoints after t,
  /// then plan.t_end if `stop_at_end` (simulate), else none (a Simulator:
  /// the steps may pass the time asked for, outputs are interpolated).
  /// After each step the loop counts the turns of `model`'s spatial joints
  /// (model/joint_turns.hpp) in the run's state (plan.run).
  StepLoop(Stepper& stepper, const Model& model, const IntegrationPlan& plan, double t, bool stop_at_end = true);
  /// Steps until the time reached is at least `target`; calls record(q, v)
  /// for each t_out[k] up to the time reached, k counting on. At most
  /// options->max_steps steps between two outputs (IntegratorFailure beyond).
  /// Without stop_at_end, a breakpoint or event that ends a step past
  /// `target` is acted on when a later run has to step on: until then the
  /// step's interpolant holds the times before it, which a Simulator's next
  /// advances may ask for (a restart discards it).
  void run(double target, const std::vector<double>& t_out, size_t& k, const Record& record);
  /// The stepper was reset to time t from outside (a Simulator's input
  /// change): the breakpoints from there on (a pending action is void).
  void restarted(double t);
  /// Time the stepper reached (its last step's end).
  double t() const { return t_; }
  /// Up to which time the last step's interpolant holds: its end, or the
  /// crossing grazed() found in it beyond a Simulator's target (acted on
  /// when the next run passes it).
  double valid_until() const { return std::min(t_, graze_pending_); }
  /// Restarts at breakpoints and after events' actions so far.
  long restarts() const { return restarts_; }

 private:
  double stop_time() const;
  /// Whether a step that ended at t stopped at the next breakpoint (and not
  /// at an output time, steps_to_outputs).
  bool at_breakpoint(double t, bool at_stop) const;
  /// After a step to t: an event's action, or the restart at a breakpoint
  /// (at_stop). True if the stepper was restarted.
  bool act(double t, bool at_stop);
  /// After a step of length h to t: the joints' turns (count_turns);
  /// IntegratorFailure if the step turned a joint whose angle the equations
  /// read by half a turn or more.
  void count_joint_turns(double t, double h);
  /// The actions of the crossings flagged in fired_ at (t, q, v) and the
  /// stepper restarted from the state they leave; false if nothing acted.
  bool act_on_crossings(double t, const double* q, const double* v);
  /// After a step from t0 to t1 without a root: the time a stop's limit was
  /// crossed and left inside it (EventRunner::grazed), or infinity.
  double grazed(double t0, double t1);
  /// The multipliers at (t, q, v) the stepper's formulation has (null: none).
  const double* multipliers(double t, const double* q, const double* v);
  /// The crossing grazed() found at t, h after the step's start (flagged in
  /// fired_): the impact there and the stepper restarted from it (the rest
  /// of the step dropped). False if nothing happened there (the step stands).
  bool act_at_graze(double t, double h);
  Stepper& stepper_;
  const Model& model_;
  const IntegrationPlan& plan_;
  double t_;
  bool stop_at_end_;
  size_t next_break_ = 0;
  long restarts_ = 0;
  bool pending_ = false, pending_at_stop_ = false;  // act() deferred to the next run
  double graze_pending_ = INFINITY, graze_step_start_ = NAN;  // a crossing grazed() found beyond the target, and its step's start
  bool bounded_ = false;  // the stop last set was the events' step bound (EventRunner::step_bound)
  std::vector<int> fired_;
  VecX q_event_, v_event_;
};

/// The steppers of the integrators, each started at `start` at time plan.t0
/// and owning its solver session; `plan` must outlive the stepper (its
/// tolerances, bounds and event functions are read from there, and its t0
/// and t_end set the scale of the first step after a reset).
///
/// IDA (ida_integrator.cpp) on a DAE formulation.
std::unique_ptr<Stepper> make_ida_stepper(std::unique_ptr<DaeFormulation> dae, const ConsistentState& start,
                                          const IntegrationPlan& plan);
/// CVODE (cvode_integrator.cpp) on the ODE in accelerations (qdd, lam from
/// the augmented system at every right-hand side). BDF: q and v are
/// projected onto Phi = 0 and Phi_q v + Phi_t = 0 after every step.
/// Adams-Moulton: CVODE cannot project, so only Baumgarte terms (alpha,
/// beta) hold the constraints.
std::unique_ptr<Stepper> make_cvode_stepper(const Model& model, bool adams, double alpha, double beta,
                                            const ConsistentState& start, const IntegrationPlan& plan);
/// ARKODE's explicit Runge-Kutta methods (erk_integrator.cpp; ERKStep, order
/// plan.max_order: 2 to 6 or 8) on the ODE in accelerations, q and v
/// projected onto Phi = 0 and Phi_q v + Phi_t = 0 after every accepted step.
std::unique_ptr<Stepper> make_erk_stepper(const Model& model, const ConsistentState& start,
                                          const IntegrationPlan& plan);
/// ALI3-P (ali3p_integrator.cpp): index-3 equations, trapezoidal rule with
/// the fixed step options->max_step, Newton on (q, lam) with a regularized
/// multiplier block to options->newton_rtol and newton_atol, mass-orthogonal
/// projections of v and a.
std::unique_ptr<Stepper> make_ali3p_stepper(const Model& model, const ConsistentState& start,
                                            const IntegrationPlan& plan);

/// The stepper of a method of the table (methods.cpp), started at `start`.
std::unique_ptr<Stepper> make_stepper(const Method& method, const Model& model, const ConsistentState& start,
                                      const IntegrationPlan& plan);

}  // namespace lagmb
