// The Run: one dynamic run's state, stepped by its stepper (switching to
// GGL where formulation "auto" gives up on the explicit method), and its
// counts.
#include "run/run.hpp"

#include <algorithm>
#include <sstream>
#include <string_view>
#include <type_traits>

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/integrators/methods.hpp"

namespace lagmb {

namespace {

/// Adds the counts of a stepper (or of the run's own evaluations) to a
/// run's: every count (a long) of Stats summed, the factor's nonzeros (a
/// size) their maximum; the rest (order, step, names) is not a count.
void add_counts(Stats& total, const Stats& part) {
  Stats::for_each_member([&](const char* name, auto member) {
    if constexpr (std::is_same_v<std::decay_t<decltype(total.*member)>, long>) {
      if (std::string_view(name) == "factor_nonzeros" || std::string_view(name) == "lu_nonzeros")
        total.*member = std::max(total.*member, part.*member);
      else
        total.*member += part.*member;
    }
  });
}

/// The names of the method a run steps with, in its counts.
void name_method(Stats& s, const Method& method) {
  s.formulation = name_of(method.formulation);
  s.integrator = name_of(method.integrator);
  s.method = method.name;
}

}  // namespace

Run::Run(const Model& given, std::shared_ptr<const Model> with_parameters_, const SimulationOptions& options_,
         const Method& method_, bool stop_at_end)
    : with_parameters(std::move(with_parameters_)),
      model(with_parameters ? *with_parameters : given),
      options(options_),
      method(method_),
      data(model),
      kkt(model),
      current_(&method_),
      stop_at_end_(stop_at_end) {
  Redundancy redundancy;
  start = dynamic_start(model, options, data, kkt, redundancy);
  events = start_events(model, data, options, options.t0, start);
  plan = run_plan(model, options, method, data);
  plan.events = events.get();
  // the rows left out as redundant are checked at every output
  watch = std::make_unique<RedundancyWatch>(model, data, std::move(redundancy));
  outputs.n = model.n_coordinates();
  outputs.m = model.n_constraints();
  outputs.p = int(model.inputs().size());
  outputs.state_size = model.run_state_size();
  outputs.dropped_rows = start.dropped_rows;
  outputs.run_model = with_parameters;
  name_method(outputs.stats, method);
  outputs.stats.analysis = name_of(Analysis::kDynamic);
  if (options.formulation == Formulation::kAuto) {
    method_choice = choose_method(model, options).why;
    if (method.formulation == Formulation::kProjection) plan.stiff_steps = kAutoStiffSteps;
  }
  outputs.stats.method_choice = method_choice;
}

void Run::record(double t, const double* q, const double* v, bool solve) {
  if (current_->drifts) check_held(t, q);
  // (at a step's end the stepper's formulation has them solved)
  const double *qdd = nullptr, *lam = nullptr;
  if (!(solve && stepper_ && stepper_->motion_at(t, q, v, qdd, lam))) qdd = lam = nullptr;
  record_output(model, data, kkt, *watch, outputs, t, q, v, *data.run, solve, qdd, lam);
  if (!sensitivities) return;
  std::vector<VecX> s, sp;
  stepper_->sensitivities(t, s, sp);
  const int n = model.n_coordinates(), m = model.n_constraints();
  for (size_t i = 0; i < s.size(); ++i) {
    outputs.sensitivities.insert(outputs.sensitivities.end(), s[i].data(), s[i].data() + 2 * n + m);
    outputs.sensitivity_a.insert(outputs.sensitivity_a.end(), sp[i].data() + n, sp[i].data() + 2 * n);
  }
}

void Run::check_held(double t, const double* q) {
  const int n = model.n_coordinates();
  if (model.n_constraints() == 0) return;
  assemble_constraints(model, data, q, t);
  Eigen::Index row = 0;
  const double off = data.Phi.cwiseAbs().maxCoeff(&row);
  const double limit = 1e-2 * (1.0 + Eigen::Map<const VecX>(q, n).lpNorm<Eigen::Infinity>());
  if (off <= limit) return;
  IntegratorFailure f("the constraints had come apart by the output at t = " + to_text(t) + ": |Phi| = " +
                          to_text(off) + " at '" + model.constraint_name_of_row(int(row)) +
                          "' (more than 1e-2 (1 + |q|) = " + to_text(limit) + "): " + current_->name +
                          " holds them only through their second derivatives and its steps lost the motion. Use "
                          "a method that keeps them (ggl, projection-bdf, projection-erk), a smaller rtol, or "
                          "baumgarte=(alpha, beta)",
                      t);
  f.diagnose = false;
  throw f;
}

void Run::start_stepper(double t, const ConsistentState& from) {
  count_turns(model, from.q.data(), from.v.data(), 0.0, data.run->state.data());  // (the rates where the run starts)
  if (stepper_) {  // its counts are kept; the new one starts at order 1
    Stats s;
    stepper_->fill_stats(s);
    add_counts(finished_, s);
    finished_.restarts += loop_->restarts();
    ++restarts_;
  }
  loop_.reset();
  stepper_.reset();
  plan.t0 = t;
  stepper_ = make_stepper(*current_, model, from, plan);
  loop_ = std::make_unique<StepLoop>(*stepper_, model, plan, t, stop_at_end_);
}

void Run::restart_stepper(double t, const ConsistentState& from) {
  plan.t0 = t;  // the first step's scale: the stretch in progress
  stepper_->resume(t, from);
  loop_->restarted(t);
  ++restarts_;
}

bool Run::resume_in_place(double t, const VecX& q, const VecX& v, ConsistentState& now) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  if (!stepper_ || loop_->t() != t || !std::equal(q.data(), q.data() + n, stepper_->positions()) ||
      !std::equal(v.data(), v.data() + n, stepper_->velocities()))
    return false;
  if (m > 0) {
    assemble_constraints(model, data, q.data(), t);
    if (!(data.Phi.lpNorm<Eigen::Infinity>() <= 1e-12 * (1.0 + q.lpNorm<Eigen::Infinity>()))) return false;
  }
  const double *qdd = nullptr, *lam = nullptr;
  if (!stepper_->motion_at(t, q.data(), v.data(), qdd, lam)) return false;
  now.q = q, now.v = v;
  now.qdd = Eigen::Map<const VecX>(qdd, n);
  now.lam = Eigen::Map<const VecX>(lam, m);
  now.dropped_rows = data.redundant_rows();
  if (events && events->settle(t, now.q, now.v, false, now.lam.data(), now.qdd.data()))
    now = events->consistent(t, now.q, now.v);
  restart_stepper(t, now);
  return true;
}

void Run::step_to(double target, const std::vector<double>& t_out, size_t& k, const Record& record) {
  for (;;) {
    try {
      // outputs inside the step taken last, before it steps on
      for (; k < t_out.size() && t_out[k] <= loop_->valid_until(); ++k) {
        const double *q = nullptr, *v = nullptr;
        stepper_->interpolate(t_out[k], q, v);
        record(q, v);
      }
      loop_->run(target, t_out, k, record);
      return;
    } catch (IntegratorFailure& e) {
      if (!e.q.size()) e.q = Eigen::Map<const VecX>(stepper_->positions(), model.n_coordinates());
      if (!switch_to_ggl(e)) throw;
    }
  }
}

bool Run::switch_to_ggl(const IntegratorFailure& why) {
  if (options.formulation != Formulation::kAuto || current_->formulation != Formulation::kProjection ||
      !why.integrator_gave_up)
    return false;
  const int n = model.n_coordinates();
  const double t = loop_->t();
  const VecX q = Eigen::Map<const VecX>(stepper_->positions(), n), v = Eigen::Map<const VecX>(stepper_->velocities(), n);
  ConsistentState from;
  try {
    from = make_consistent(model, data, kkt, q, v, t);
  } catch (const std::exception&) {
    return false;  // (the explicit method's failure says more)
  }
  std::ostringstream s;
  s << "; at t = " << t << " GGL took over: " << why.what();
  method_choice += s.str();
  current_ = &find_method(Formulation::kGgl, Integrator::kDefault);
  plan.stiff_steps = 0;
  plan.max_order = std::min(options.max_order ? options.max_order : current_->max_order, current_->max_order);
  start_stepper(t, from);
  return true;
}

Stats Run::stats() const {
  Stats s = finished_;
  if (stepper_) {
    Stats now;
    stepper_->fill_stats(now);
    add_counts(s, now);
    s.last_order = now.last_order;
    s.last_step = now.last_step;
    s.restarts += loop_->restarts();
  }
  s.restarts += restarts_;
  s.input_changes = input_changes;
  s.augmented_factorizations += kkt.factorizations() + (events ? events->factorizations() : 0);
  // the start, the outputs' solves and the checks of the dropped rows
  s.element_evaluations += data.element_evaluations + watch->element_evaluations();
  name_method(s, *current_);
  s.method_choice = method_choice;
  s.analysis = name_of(Analysis::kDynamic);
  if (events) {
    s.events = events->events;
    s.impacts = events->impacts;
    s.captures = events->captures;
    s.releases = events->releases;
    s.root_evals = events->root_evals;
  }
  return s;
}

}  // namespace lagmb
