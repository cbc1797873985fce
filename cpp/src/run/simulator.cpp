#include "lagmb/run/simulator.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "integrators/integrators.hpp"
#include "lagmb/analyses/diagnosis.hpp"
#include "lagmb/interrupt.hpp"
#include "lagmb/analyses/kinematics.hpp"
#include "lagmb/integrators/methods.hpp"
#include "run/run.hpp"

namespace lagmb {

Simulator::Simulator(const Model& given, const SimulationOptions& options, double output_interval,
                     const ParameterValues& parameters)
    : options_(options), output_interval_(output_interval) {
  std::shared_ptr<const Model> with = lagmb::with_parameters(given, parameters);
  const Model& model = with ? *with : given;
  method_ = &validate_run_options(model, options_, "Simulator");
  if (!(std::isfinite(output_interval) && output_interval >= 0.0))
    throw ModelError("Simulator: output_interval must be finite and >= 0 (0: outputs at the ends of advances), got " +
                     to_text(output_interval));
  if (options_.analysis != Analysis::kAuto && options_.analysis != Analysis::kDynamic)
    throw ModelError(std::string("Simulator: a simulator integrates the equations of motion (analysis 'dynamic'); ") +
                     "for a '" + name_of(options_.analysis) + "' analysis call simulate");
  require_determined_motion(model, model.initial_q(), options_.t0, "Simulator");
  const int n = model.n_coordinates(), m = model.n_constraints();
  run_ = std::make_unique<Run>(given, std::move(with), options_, *method_, /*stop_at_end=*/false);
  run_->plan.breakpoints = model.breakpoints();  // the loop takes those after its start
  inputs_ = run_->data.run->inputs;  // the initial values
  inputs_integrated_ = inputs_;

  const ConsistentState& start = run_->start;
  t_ = options_.t0;
  q_ = start.q, v_ = start.v, a_ = start.qdd, lam_ = start.lam;
  solved_ = true;
  Trajectory& record = run_->outputs;
  record.inputs.assign(inputs_.data(), inputs_.data() + inputs_.size());
  const VecX& state = run_->data.run->state;
  record.run_state.assign(state.data(), state.data() + state.size());
  record.t.push_back(t_);
  record.q.insert(record.q.end(), q_.data(), q_.data() + n);
  record.v.insert(record.v.end(), v_.data(), v_.data() + n);
  record.a.insert(record.a.end(), a_.data(), a_.data() + n);
  record.lam.insert(record.lam.end(), lam_.data(), lam_.data() + m);
}

Simulator::~Simulator() = default;

const Model& Simulator::model() const { return run_->model; }

Simulator::Call::Call(const Simulator& s, const char* what) : s_(s), lock_(s.busy_), outer_(!s.running_) {
  if (!outer_)
    throw ModelError(std::string("Simulator.") + what +
                     ": called from inside the simulator's own run (a force, torque or driver function?); a "
                     "simulator's functions are called between its calls, not from them");
  s_.running_ = true;
}

Simulator::Call::~Call() { s_.running_ = false; }

double Simulator::t() const {
  Call call(*this, "t");
  return t_;
}

VecX Simulator::q() const {
  Call call(*this, "q");
  return q_;
}

VecX Simulator::v() const {
  Call call(*this, "v");
  return v_;
}

VecX Simulator::inputs() const {
  Call call(*this, "inputs");
  return inputs_;
}

VecX Simulator::run_state() const {
  Call call(*this, "run_state");
  return run_->data.run->state;
}

std::string Simulator::failure() const {
  Call call(*this, "failure");
  return failure_;
}

void Simulator::check_usable(const char* what) const {
  if (!failure_.empty())
    throw SimulationError(std::string("Simulator.") + what + ": the simulator failed at t = " + to_text(t_) +
                              " and cannot go on (" + failure_ + "); set_state goes back to a saved state",
                          t_);
}

VecX Simulator::a() {
  Call call(*this, "a");
  return solved_a();
}

const VecX& Simulator::solved_a() {
  if (!solved_) {
    run_->data.run->inputs = inputs_;
    a_.resize(q_.size());
    lam_.resize(model().n_constraints());
    solve_accelerations(model(), run_->data, run_->kkt, q_.data(), v_.data(), t_, a_.data(), lam_.data());
    solved_ = true;
  }
  return a_;
}

VecX Simulator::lam() {
  Call call(*this, "lam");
  solved_a();
  return lam_;
}

int Simulator::input_slot(const std::string& name) const {
  const int k = model().input_index(name);
  if (k >= 0) return k;
  std::string names;
  for (const InputInfo& in : model().inputs()) names += (names.empty() ? "'" : ", '") + in.name + "'";
  const std::string theirs = names.empty() ? "the model has no inputs (give a force, torque or driver value as an "
                                             "Input to make one)"
                                           : "the inputs are " + names;
  if (model().has(name))
    throw ModelError("Simulator: '" + name + "' is " + model().describe(name) + ", not an input; " + theirs);
  throw ModelError("Simulator: no input called '" + name + "'; " + theirs);
}

void Simulator::set_input(const std::string& name, double value) {
  Call call(*this, "set_input");
  check_usable("set_input");
  const int k = input_slot(name);
  if (!std::isfinite(value))
    throw ModelError("Simulator: input '" + name + "' must be finite, got " + to_text(value));
  if (!(std::abs(value) <= kLargestGiven))
    throw ModelError("Simulator: input '" + name + "' = " + to_text(value) + " is beyond " + to_text(kLargestGiven) +
                     ", the largest lagmb takes for a gain or an input: " + largest_given_reason());
  inputs_[k] = value;
  solved_ = solved_ && inputs_ == inputs_integrated_;
}

double Simulator::input(const std::string& name) const {
  Call call(*this, "input");
  return inputs_[input_slot(name)];
}

ConsistentState Simulator::consistent_start() {
  ConsistentState start = make_consistent(model(), run_->data, run_->kkt, q_, v_, t_);
  // a stop held under the old input values may let go (or a joint at its limit be pressed on) under the new
  if (run_->events && run_->events->settle(t_, start.q, start.v, false, start.lam.data(), start.qdd.data()))
    start = run_->events->consistent(t_, start.q, start.v);
  return start;
}

void Simulator::new_stepper() {
  const ConsistentState start = consistent_start();
  run_->start_stepper(t_, start);
  q_ = start.q, v_ = start.v, a_ = start.qdd, lam_ = start.lam;
  solved_ = true;
  inputs_integrated_ = inputs_;
  fresh_ = false;
}

void Simulator::restart_for_inputs() {
  // a jump in a force (the state the steps reached goes on, unprojected),
  // or in a driver's value (positions assembled anew)
  ConsistentState start;
  if (!run_->resume_in_place(t_, q_, v_, start)) {
    start = consistent_start();
    run_->restart_stepper(t_, start);
  }
  ++run_->input_changes;
  q_ = start.q, v_ = start.v, a_ = start.qdd, lam_ = start.lam;
  solved_ = true;
  inputs_integrated_ = inputs_;
}

void Simulator::advance(double target) {
  Call call(*this, "advance");
  check_usable("advance");
  if (!std::isfinite(target)) throw ModelError("Simulator.advance: t is not finite (" + to_text(target) + ")");
  if (target < t_)
    throw ModelError("Simulator.advance: t = " + to_text(target) + " is before the simulator's time " + to_text(t_) +
                     "; a simulator only goes forward (set_state goes back to a saved state)");
  if (target == t_) return;
  check_time(target, "Simulator.advance", "t");
  // a span time cannot resolve is no step an integrator can take
  if (const double shortest = shortest_span(t_, target); target - t_ < shortest)
    throw ModelError("Simulator.advance: t = " + to_text(target) + " is within " + to_text(shortest) +
                     " s of the simulator's time " + to_text(t_) + ", below the time resolution there (" +
                     to_text(kTimeResolution) + " max(|t|, 1 s)): advance further");
  // the outputs: the multiples of output_interval after t_, then target
  std::vector<double> t_out;
  if (output_interval_ > 0.0) {
    const double t0 = options_.t0, dt = output_interval_;
    // outputs closer than time can resolve would repeat one time
    if (dt < shortest_span(t_, target))
      throw ModelError("Simulator.advance: the output_interval of " + to_text(dt) + " s is below the time "
                       "resolution near t = " + to_text(target) + " (" + to_text(shortest_span(t_, target)) +
                       " s): record less often");
    // kept in memory: refuse what cannot fit rather than fail half way
    if ((target - t_) / dt > 1e7)
      throw ModelError("Simulator.advance: from t = " + to_text(t_) + " to " + to_text(target) +
                       " the output_interval of " + to_text(dt) + " s asks for " + to_text((target - t_) / dt) +
                       " outputs (at most 1e7 per advance): advance in shorter steps or record less often");
    for (double k = std::floor((t_ - t0) / dt) + 1;; ++k) {
      const double tk = t0 + k * dt;
      if (!(tk < target - 1e-9 * dt)) break;
      if (tk > t_ && (t_out.empty() || tk > t_out.back())) t_out.push_back(tk);
    }
  }
  if (t_out.empty() || target > t_out.back()) t_out.push_back(target);

  run_->data.run->inputs = inputs_;  // what the run's kernels read from here on
  const int first_new = run_->outputs.size();
  // the wall time of this advance into the stats' sum, however it ends
  struct Timed {
    double& sum;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    ~Timed() { sum += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }
  } timed{wall_};
  size_t k = 0;
  auto record = [&](const double* q, const double* v) {
    run_->record(t_out[k], q, v, true);
  };
  try {
    run_->plan.t_end = target;  // the steppers' tout, and the scale of a first step
    if (fresh_ || !run_->stepping())
      new_stepper();
    else if (inputs_ != inputs_integrated_)
      restart_for_inputs();
    run_->step_to(target, t_out, k, record);
  } catch (const IntegratorFailure& e) {
    std::ostringstream msg;
    msg << e.what();
    if (e.q.size() && e.diagnose) msg << diagnose_failure(model(), e.q, e.t, run_->outputs.dropped_rows);
    failure_ = msg.str();
  } catch (const UserFunctionError& e) {
    failure_ = e.what();
  } catch (const SimulationError& e) {  // a solve inside a step or restart
    failure_ = e.what();
  } catch (Interrupted&) {  // Ctrl-C: the outputs of this advance are dropped, the run can go on
    run_->outputs.truncate(first_new);
    fresh_ = true;
    throw;
  }
  // the state: the last output (at target; after a failure, the last one reached)
  const int last = run_->outputs.size() - 1, n = run_->outputs.n, m = run_->outputs.m;
  t_ = run_->outputs.t[last];
  // (data() + offset: a model without constraints has no multipliers, and
  // &lam[0] of an empty vector is out of range)
  q_ = Eigen::Map<const VecX>(run_->outputs.q.data() + size_t(last) * n, n);
  v_ = Eigen::Map<const VecX>(run_->outputs.v.data() + size_t(last) * n, n);
  a_ = Eigen::Map<const VecX>(run_->outputs.a.data() + size_t(last) * n, n);
  lam_ = Eigen::Map<const VecX>(run_->outputs.lam.data() + size_t(last) * m, m);
  solved_ = true;
  if (!failure_.empty()) {
    fresh_ = true;
    std::ostringstream s;
    s << failure_ << " Outputs up to t = " << t_ << " are kept in the simulator's result.";
    throw SimulationError(s.str(), t_, result_now());
  }
}

SimulatorState Simulator::state() {
  Call call(*this, "state");
  SimulatorState s;
  s.t = t_;
  s.q = q_;
  s.v = v_;
  s.inputs = inputs_;
  s.run_state = run_->data.run->state;
  s.closed_rows = run_->data.closed_rows();
  s.events = run_->events ? long(run_->events->records.size()) : 0;
  s.model_id = model().id();
  fresh_ = true;  // the run goes on from here as a restored copy would
  return s;
}

void Simulator::set_state(const SimulatorState& s) {
  Call call(*this, "set_state");
  const int n = model().n_coordinates();
  if (s.model_id != model().id() || s.q.size() != n || s.v.size() != n || s.inputs.size() != inputs_.size() ||
      s.run_state.size() != run_->data.run->state.size())
    throw ModelError("Simulator.set_state: the state was saved from a simulator of another model");
  if (!std::isfinite(s.t) || !s.q.allFinite() || !s.v.allFinite() || !s.inputs.allFinite())
    throw ModelError("Simulator.set_state: the state is not finite");
  t_ = s.t;
  q_ = s.q;
  v_ = s.v;
  inputs_ = s.inputs;
  run_->data.run->state = s.run_state;
  run_->data.close_rows(model(), s.closed_rows);  // (every Data of the run shares the set)
  if (run_->events && long(run_->events->records.size()) > s.events) run_->events->records.resize(size_t(s.events));
  // the outputs of this branch: those up to t, then t itself
  int keep = 0;
  while (keep < run_->outputs.size() && run_->outputs.t[keep] <= t_) ++keep;
  run_->outputs.truncate(keep);
  solved_ = false;
  failure_.clear();
  fresh_ = true;
  if (run_->outputs.t.empty() || run_->outputs.t.back() != t_) {
    run_->data.run->inputs = inputs_;
    try {
      run_->record(t_, q_.data(), v_.data(), true);
    } catch (const IntegratorFailure& e) {
      failure_ = e.what();
      throw SimulationError("Simulator.set_state: " + failure_, t_, result_now());
    }
  }
}

Trajectory Simulator::result() const {
  Call call(*this, "result");
  return result_now();
}

Trajectory Simulator::result_now() const {
  Trajectory tr = run_->outputs;
  tr.stats = stats_now();
  if (run_->events) tr.events = run_->events->records;
  return tr;
}

Stats Simulator::stats() const {
  Call call(*this, "stats");
  return stats_now();
}

Stats Simulator::stats_now() const {
  Stats s = run_->stats();
  s.wall_time = wall_;
  return s;
}

}  // namespace lagmb
