// A run driven from outside: advanced in chunks, its inputs set between
// them, saved and restored (a controller in the loop, a co-simulation step,
// what-if runs).
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "lagmb/integrators/methods.hpp"
#include "lagmb/run/simulate.hpp"

namespace lagmb {

class Run;

/// Where a Simulator was, to go back to: time, state, inputs and the
/// elements' run state. Opaque beyond t, q and v.
struct SimulatorState {
  double t = 0.0;
  VecX q, v;
  VecX inputs;     // one per Model::inputs()
  VecX run_state;  // Data::run->state (a contact's impact speed, the joints' turns)
  std::vector<int> closed_rows;  // the stops held on their limits (Data::closed_rows)
  long events = 0;  // event records up to t
  std::uint64_t model_id = 0;  // Model::id() of the model it belongs to
};

/// A dynamic run of `model` (the DAE integrated by the method of the
/// options, as simulate does) that advances when asked:
///
///   Simulator sim(model, options);
///   sim.set_input("push", 2.0);  // takes effect from sim.t() on
///   sim.advance(0.01);           // integrate to t = 0.01
///   sim.q(), sim.v(), sim.a(), sim.lam()
///
/// The integrator keeps its steps and history from one advance to the next:
/// its steps may pass the time asked for, and the state there is its
/// interpolant (consistent to the tolerance), so many short advances take
/// the steps one long one takes. It restarts at order 1 where the motion
/// needs it: at breakpoints of the time functions and events (as in
/// simulate), at a change of an input (a jump in a force or a driver's
/// value; a driver's positions are then assembled anew), and from a state
/// saved or restored. The options are simulate's, without the outputs
/// (t_end, t_out, n_out), the analysis (always the dynamic one) and the
/// progress report; max_steps bounds the steps between two outputs.
///
/// Outputs: the state at t0, at the end of every advance and, with
/// output_interval > 0, at every multiple of it after t0 (result()).
/// The model must outlive the simulator.
///
/// Calls from several threads are taken one at a time (a call waits for the
/// one in progress); a call from inside the simulator's own run (a force or
/// driver function calling advance) is a ModelError.
class Simulator {
 public:
  /// `parameters`: run `model` with other parameter values (parameters.hpp;
  /// the simulator keeps the model built with them, model()).
  Simulator(const Model& model, const SimulationOptions& options = {}, double output_interval = 0.0,
            const ParameterValues& parameters = {});
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  /// The model it runs: the one given, or that model with the parameters given.
  const Model& model() const;

  double t() const;
  VecX q() const;
  VecX v() const;
  /// Accelerations and multipliers at (t, q, v), from the augmented system.
  VecX a();
  VecX lam();

  /// Integrates to time t (>= t(); equal: nothing to do). ModelError for a
  /// time before t() or not finite; SimulationError if the integrator fails
  /// (the outputs reached stay in result(), the simulator stays at the last
  /// time it reached in full and refuses to go on until set_state).
  void advance(double t);

  /// Sets an input (Model::inputs) from t() on. ModelError naming the
  /// inputs for an unknown name, an element that is not an input, or a value
  /// that is not finite.
  void set_input(const std::string& name, double value);
  double input(const std::string& name) const;
  VecX inputs() const;
  /// The run's element state now (joints' turn counts, contacts' impact
  /// speeds: what Result's run_state holds at each output).
  VecX run_state() const;

  /// The state to come back to. The integrator restarts here on the next
  /// advance, so that advancing from a restored copy repeats the run from
  /// here bit for bit.
  SimulatorState state();
  /// Goes back (or forward) to a saved state: the outputs after its time
  /// are dropped, the integrator restarts there. Clears a failure.
  void set_state(const SimulatorState& s);

  /// The outputs so far (a and lam solved at each), the events handled and
  /// the solver counts summed over every restart (a copy); wall_time: the
  /// seconds spent in advance, summed.
  Trajectory result() const;
  Stats stats() const;
  /// Why the last advance failed ("" if it did not).
  std::string failure() const;

 private:
  /// Holds the simulator for one call: waits for a call in progress on
  /// another thread; refuses one from inside a run on this thread.
  class Call {
   public:
    Call(const Simulator& s, const char* what);
    ~Call();

   private:
    const Simulator& s_;
    std::unique_lock<std::recursive_mutex> lock_;
    bool outer_;
  };
  const VecX& solved_a();
  Trajectory result_now() const;
  Stats stats_now() const;
  /// The state at t_ made consistent, with the stops settled (released or captured) under the inputs now.
  ConsistentState consistent_start();
  void new_stepper();
  void restart_for_inputs();
  void check_usable(const char* what) const;
  int input_slot(const std::string& name) const;

  SimulationOptions options_;
  double output_interval_;
  const Method* method_;
  /// What the run changes: the model with its parameters, Data and its run
  /// values, events, plan, stepper and loop, counts, outputs.
  std::unique_ptr<Run> run_;

  double t_ = 0.0;
  VecX q_, v_, a_, lam_;
  bool solved_ = false;  // a_, lam_ at t_
  VecX inputs_, inputs_integrated_;  // set, and what the integrator runs with
  bool fresh_ = true;  // a new stepper at the next advance
  double wall_ = 0.0;  // s spent in advance, summed (the stats' wall_time)
  std::string failure_;
  mutable std::recursive_mutex busy_;
  mutable bool running_ = false;  // inside a call that runs model functions
};

}  // namespace lagmb
