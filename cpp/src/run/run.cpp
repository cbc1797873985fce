#include "run/run.hpp"

#include <algorithm>
#include <iterator>
#include <map>
#include <sstream>
#include <string_view>
#include <type_traits>

#include "lagmb/analyses/equilibrium.hpp"
#include "lagmb/analyses/stiffness.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/analyses/diagnosis.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/integrators/methods.hpp"
#include "lagmb/spec/parameters.hpp"

namespace lagmb {

namespace {

/// Adds the counts of a stepper (or of the run's own evaluations) to a
/// run's: every count (a long) of Stats summed, the factor's nonzeros (a
/// size) their maximum; the rest (order, step, names) is not a count.
void add_counts(Stats& total, const Stats& part) {
  Stats::for_each_member([&](const char* name, auto member) {
    if constexpr (std::is_same_v<std::decay_t<decltype(total.*member)>, long>) {
      if (std::string_view(name) == "factor_nonzeros")
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

MethodChoice choose_method(const Model& model, const SimulationOptions& o) {
  MethodChoice c;
  auto choose = [&](Formulation f, Integrator i, std::string why) {
    c.method = &find_method(f, i);
    c.why = "auto: " + c.method->name + ", " + why;
    return c;
  };
  for (const auto& g : model.event_groups())
    if (!g->bounds_motion() && g->size() > 0)
      return choose(Formulation::kGgl, Integrator::kDefault,
                    std::string("the model has a ") + g->kind() + " ('" + g->name(0) +
                        "'), whose onset an explicit step could pass over");
  if (!model.friction_groups().empty())
    return choose(Formulation::kGgl, Integrator::kDefault,
                  "the model has joint friction from the joints' loads ('" + model.friction_groups().front()->name(0) +
                      "')");
  const VecX q = model.initial_q(), v = model.initial_v();
  const ForceRates rates = force_rates(model, q.data(), v.data(), o.t0);
  const double span = o.t_end > o.t0 ? o.t_end - o.t0 : 1.0;
  std::ostringstream why;
  why.precision(3);
  why << "the forces' fastest rate " << rates.fastest() << " 1/s times the span " << span << " s is "
      << rates.fastest() * span;
  if (!(rates.fastest() * span <= kStiffSpan)) {
    why << " > " << kStiffSpan << " (stiff)";
    return choose(Formulation::kGgl, Integrator::kDefault, why.str());
  }
  why << " <= " << kStiffSpan << " (not stiff)";
  return choose(Formulation::kProjection, Integrator::kErk, why.str());
}

const Method& validate_run_options(const Model& model, const SimulationOptions& o, const std::string& who) {
  const std::string at = who + ": ";
  if (!model.finalized()) throw ModelError(at + "the model is not finalized");
  if (model.n_coordinates() == 0) throw ModelError(at + "the model has no bodies");
  auto positive = [&](double x, const char* name) {
    if (!(std::isfinite(x) && x > 0))
      throw ModelError(at + name + " must be positive and finite, got " + to_text(x));
  };
  if (!std::isfinite(o.t0)) throw ModelError(at + "t0 is not finite");
  check_time(o.t0, who, "t0");
  positive(o.rtol, "rtol");
  if (o.rtol >= 1.0)
    throw ModelError(at + "rtol = " + to_text(o.rtol) +
                     " must be below 1: a relative error of 100 % or more bounds nothing (typical: 1e-3 to 1e-10)");
  if (o.rtol < 1e-14)
    throw ModelError(at + "rtol = " + to_text(o.rtol) +
                     " is below 1e-14, which double precision cannot deliver");
  positive(o.atol, "atol");
  if (!o.atol_coordinates.empty()) {
    if (int(o.atol_coordinates.size()) != model.n_coordinates())
      throw ModelError(at + "atol needs one entry per coordinate (" + std::to_string(model.n_coordinates()) +
                       "), got " + std::to_string(o.atol_coordinates.size()));
    for (double a : o.atol_coordinates) positive(a, "every atol entry");
  }
  if (o.max_step != 0.0) positive(o.max_step, "max_step");
  if (o.max_steps < 0) throw ModelError(at + "max_steps must be >= 0 (0: no limit)");
  if (o.formulation == Formulation::kAuto && o.integrator != Integrator::kDefault)
    throw ModelError(at + "integrator '" + name_of(o.integrator) +
                     "' needs its formulation: formulation 'auto' chooses both");
  if (o.formulation == Formulation::kAuto && (o.baumgarte_alpha != 0.0 || o.baumgarte_beta != 0.0))
    throw ModelError(at + "Baumgarte terms need the formulation they apply to (index1, or projection with adams); "
                     "formulation 'auto' does not choose those");
  const Method& method =
      o.formulation == Formulation::kAuto ? *choose_method(model, o).method : find_method(o.formulation, o.integrator);
  // what a method does not model is refused, not ignored
  auto those = [](bool Method::*has) {
    std::string s;
    for (const Method& m : methods())
      if (m.*has) s += (s.empty() ? "" : ", ") + m.name;
    return s;
  };
  if (method.fixed_step && o.max_step == 0.0)
    throw ModelError(at + "formulation '" + name_of(method.formulation) +
                     "' takes fixed steps: give the step as max_step (step= in Python)");
  if (!method.friction && !model.friction_groups().empty())
    throw ModelError(at + "formulation '" + name_of(method.formulation) + "' does not include joint friction ('" +
                     model.friction_groups().front()->name(0) + "'); the methods that do: " +
                     those(&Method::friction));
  if (!method.events && !model.event_groups().empty())
    throw ModelError(at + "formulation '" + name_of(method.formulation) +
                     "' has no root finding for stops or contact events ('" + model.event_groups().front()->name(0) +
                     "'); the methods that have: " + those(&Method::events));
  if (!method.contact)
    for (const auto& g : model.event_groups())
      if (!g->bounds_motion() && g->size() > 0)
        throw ModelError(at + method.name + " cannot place the onset of " + g->kind() + " '" + g->name(0) +
                         "' (an explicit step can pass a whole contact); the methods that can: " +
                         those(&Method::contact) + " (formulation 'auto' chooses ggl here)");
  if (o.max_order < 0 || o.max_order > method.max_order)
    throw ModelError(at + "max_order must be in 1.." + std::to_string(method.max_order) + " for " +
                     method.name + " (integrator " + name_of(method.integrator) + "; 0: its highest order), got " +
                     std::to_string(o.max_order));
  if ((o.baumgarte_alpha != 0.0 || o.baumgarte_beta != 0.0) && !method.baumgarte)
    throw ModelError(at + "Baumgarte terms apply to the methods " + those(&Method::baumgarte) + ", not to formulation '" +
                     name_of(method.formulation) + "' with integrator '" + name_of(method.integrator) + "'");
  if (!std::isfinite(o.baumgarte_alpha) || !std::isfinite(o.baumgarte_beta) || o.baumgarte_alpha < 0 ||
      o.baumgarte_beta < 0)
    throw ModelError(at + "Baumgarte alpha and beta must be finite and >= 0");
  if (method.fixed_step) {
    positive(o.newton_rtol, "newton_rtol");
    positive(o.newton_atol, "newton_atol");
  }
  return method;
}

std::string solve_outputs(const Model& model, Data& d, AugmentedSystem& kkt, Trajectory& tr, int first) {
  const int n = tr.n, m = tr.m, k = tr.size();
  for (int i = first; i < k; ++i) {
    tr.a.resize(size_t(i + 1) * n);
    tr.lam.resize(size_t(i + 1) * m);
    double *a = tr.a.data() + size_t(i) * n, *lam = tr.lam.data() + size_t(i) * m;
    const double *q = tr.q.data() + size_t(i) * n, *v = tr.v.data() + size_t(i) * n;
    std::string why;
    try {
      solve_accelerations(model, d, kkt, q, v, tr.t[i], a, lam);
      if (!Eigen::Map<const VecX>(a, n).allFinite() || !Eigen::Map<const VecX>(lam, m).allFinite())
        why = non_finite_source(model, d, q, v, tr.t[i]);
    } catch (const UserFunctionError& e) {
      why = e.what();
    } catch (const SimulationError& e) {
      why = e.what();
    }
    if (!why.empty()) {
      tr.a.resize(size_t(i) * n);
      tr.lam.resize(size_t(i) * m);
      std::ostringstream s;
      s << "at the output t = " << tr.t[i] << " the accelerations and multipliers cannot be solved: " << why;
      return s.str();
    }
  }
  return "";
}

void record_output(const Model& model, Data& d, AugmentedSystem& kkt, RedundancyWatch& watch, Trajectory& tr,
                   double t, const double* q, const double* v, const VecX& inputs, bool solve) {
  auto stop = [&](const std::string& why) {
    IntegratorFailure f(why, t);
    f.diagnose = false;  // the message is complete
    throw f;
  };
  if (watch.active())
    if (const std::string why = watch.violation(q, t); !why.empty()) stop(why);
  const int n = tr.n;
  tr.t.push_back(t);
  tr.q.insert(tr.q.end(), q, q + n);
  tr.v.insert(tr.v.end(), v, v + n);
  tr.inputs.insert(tr.inputs.end(), inputs.data(), inputs.data() + inputs.size());
  if (solve)
    if (const std::string why = solve_outputs(model, d, kkt, tr, tr.size() - 1); !why.empty()) {
      tr.truncate(solved_outputs(tr));
      stop(why);
    }
}

int solved_outputs(const Trajectory& tr) { return tr.n > 0 ? int(tr.a.size() / size_t(tr.n)) : tr.size(); }

ConsistentState dynamic_start(const Model& model, const SimulationOptions& o, Data& d, AugmentedSystem& kkt,
                              Redundancy& redundancy) {
  VecX q_start = model.initial_q(), v_start = model.initial_v();
  try {
    if (o.start == Start::kEquilibrium) {  // at rest in the static equilibrium at t0
      EquilibriumOptions eo;
      eo.t = o.t0;
      q_start = find_equilibrium(model, eo).q;
      v_start.setZero();
    }
    return start_state(model, d, kkt, q_start, v_start, o.t0, &redundancy);
  } catch (const UserFunctionError& e) {
    throw SimulationError(e.what(), o.t0);
  }
}

IntegrationPlan run_plan(const Model& model, const SimulationOptions& o, const Method& method, const Data& run) {
  const int n = model.n_coordinates();
  IntegrationPlan plan;
  plan.options = &o;
  plan.t0 = o.t0;
  plan.t_end = o.t_end;
  plan.atol = VecX::Constant(n, o.atol);
  if (!o.atol_coordinates.empty()) plan.atol = Eigen::Map<const VecX>(o.atol_coordinates.data(), n);
  plan.max_order = o.max_order ? o.max_order : method.max_order;
  plan.run = &run;
  return plan;
}

std::unique_ptr<EventRunner> start_events(const Model& model, const Data& run, double t, ConsistentState& start) {
  if (model.event_groups().empty()) return nullptr;
  auto events = std::make_unique<EventRunner>(model, run);
  // a joint that starts at a limit, moving into it, gets its impact at t
  try {
    if (events->start(t, start.q, start.v)) start = events->consistent(t, start.q, start.v);
  } catch (const IntegratorFailure& e) {
    throw SimulationError(e.what(), e.t);
  }
  return events;
}

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
  events = start_events(model, data, options.t0, start);
  plan = run_plan(model, options, method, data);
  plan.events = events.get();
  // the rows left out as redundant are checked at every output
  watch = std::make_unique<RedundancyWatch>(model, data, std::move(redundancy));
  outputs.n = model.n_coordinates();
  outputs.m = model.n_constraints();
  outputs.p = int(model.inputs().size());
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
  record_output(model, data, kkt, *watch, outputs, t, q, v, data.run->inputs, solve);
  if (!sensitivities) return;
  std::vector<VecX> s, sp;
  stepper_->sensitivities(t, s, sp);
  const int n = model.n_coordinates(), m = model.n_constraints();
  for (size_t i = 0; i < s.size(); ++i) {
    outputs.sensitivities.insert(outputs.sensitivities.end(), s[i].data(), s[i].data() + 2 * n + m);
    outputs.sensitivity_a.insert(outputs.sensitivity_a.end(), sp[i].data() + n, sp[i].data() + 2 * n);
  }
}

void Run::consistent_sensitivities(SensitivityPlan& sens) {
  // the differences of the perturbed starts hold the constraints' linearization,
  //   Phi_q s_q + Phi_p = 0,   Phi_q s_v + Vq s_q + (Phi_q v + Phi_t)_p = 0,
  // only to their assembly's tolerance over delta (1e-12 / 1e-4 relative),
  // which an error test at rtol 1e-10 cannot start from: each is made
  // exact by the least change in the M-metric, and s_q' = s_v (F1, mu = 0)
  const int n = model.n_coordinates(), m = model.n_constraints(), N = 2 * n + 2 * m;
  GglFormulation base(model);
  base.join_run(data);
  VecX y(N), yp(N), plus(N), minus(N);
  base.initial(start, y.data(), yp.data());
  Data d(model);
  d.join_run(model, data);
  AugmentedSystem k(model);
  assemble_jacobian(model, d, start.q.data(), options.t0);
  if (!k.factorize(d)) throw SimulationError("simulate: sensitivities: the augmented matrix is singular at the start", options.t0);
  assemble_velocity_jacobian(model, d, start.q.data(), start.v.data(), options.t0);
  const VecX zero_n = VecX::Zero(n);
  VecX dq(n), kappa(m);
  for (int i = 0; i < sens.count(); ++i) {
    VecX& s = sens.s0[i];
    VecX& sp = sens.sp0[i];
    sens.plus[i]->residual(options.t0, y.data(), yp.data(), plus.data());
    sens.minus[i]->residual(options.t0, y.data(), yp.data(), minus.data());
    const VecX F_p = (plus - minus) / (2.0 * sens.delta[i]);
    VecX r3 = d.Phi_q * s.head(n) + F_p.segment(2 * n, m);
    k.solve(zero_n, -r3, dq, kappa);
    s.head(n) += dq;
    VecX r4 = d.Vq * s.head(n) + d.Phi_q * s.segment(n, n) + F_p.segment(2 * n + m, m);
    k.solve(zero_n, -r4, dq, kappa);
    s.segment(n, n) += dq;
    s.tail(m).setZero();  // mu = 0 on every nearby solution
    sp.head(n) = s.segment(n, n);
  }
}

void Run::start_sensitivities(const std::vector<std::string>& names) {
  const std::string who = "simulate: sensitivities: ";
  if (current_->formulation != Formulation::kGgl)
    throw ModelError(who + "they are integrated by IDAS with the GGL form (method 'ggl'), not with " +
                     current_->name);
  if (!model.event_groups().empty())
    throw ModelError(who + "the model has '" + model.event_groups().front()->name(0) +
                     "' (a stop or contact): at its events the motion jumps, and so would the sensitivities; "
                     "remove it to differentiate the run");
  if (!model.friction_groups().empty())
    throw ModelError(who + "the model has joint friction ('" + model.friction_groups().front()->name(0) +
                     "'), whose derivatives through the joint loads sensitivities do not take yet");
  std::map<std::string, double> values;
  std::string known;
  for (const ParameterInfo& p : parameters(model)) {
    values[p.name] = p.value;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  auto sens = std::make_unique<SensitivityPlan>();
  for (const std::string& name : names) {
    const auto it = values.find(name);
    if (it == values.end())
      throw ModelError(who + "no parameter '" + name + "'; the model's parameters are " + known);
    if (std::find(sens->names.begin(), sens->names.end(), name) != sens->names.end())
      throw ModelError(who + "'" + name + "' is asked for twice");
    // F_p's difference step: its rounding (eps / 1e-4 of F's scale) stays
    // below the error tests of rtol 1e-10 and its truncation (about 1e-9
    // relative for a parameter of the geometry) below what a sensitivity
    // is asked for; 1e-6 made the rounding 1e-10 and the error test fail
    const double p = it->second, scale = p != 0.0 ? std::abs(p) : 1.0, delta = 1e-4 * scale;
    // the models at p + delta and p - delta; at a bound of p's range (a
    // damping of 0) the model at p stands for the side beyond it, and the
    // differences are one-sided: half their span is what delta[i] holds
    std::shared_ptr<const Model> models[2];
    std::string refused[2];
    double values[2] = {p + delta, p - delta};
    for (int side = 0; side < 2; ++side) try {
        models[side] = lagmb::with_parameters(model, {{name, values[side]}});
      } catch (const ModelError& e) {
        refused[side] = e.what();
      }
    const std::string parameter = "'" + name + "' = " + to_text(p);
    if (!models[0] && !models[1])
      throw ModelError(who + parameter + " has no sensitivity: the model takes no other value of it nearby (at " +
                       to_text(values[0]) + ": " + refused[0] + "; at " + to_text(values[1]) + ": " + refused[1] +
                       ")");
    const double span = (models[0] ? delta : 0.0) + (models[1] ? delta : 0.0);
    for (int side = 0; side < 2; ++side)
      if (!models[side]) models[side] = lagmb::with_parameters(model, {{name, values[side] = p}});
    sens->names.push_back(name);
    sens->delta.push_back(0.5 * span);
    sens->scale.push_back(scale);
    VecX y[2], yp[2];
    for (int side = 0; side < 2; ++side) {
      std::shared_ptr<const Model> at = models[side];
      auto form = std::make_unique<GglFormulation>(*at);
      Data d(*at);
      AugmentedSystem k(*at);
      Redundancy redundancy;
      ConsistentState st;
      try {
        st = dynamic_start(*at, options, d, k, redundancy);
      } catch (const SimulationError& e) {  // (an AssemblyError among them)
        throw ModelError(who + parameter + " has no sensitivity: the model with it at " + to_text(values[side]) +
                         " cannot start: " + e.what());
      }
      if (st.dropped_rows != start.dropped_rows) {
        std::vector<int> changed;
        std::set_symmetric_difference(st.dropped_rows.begin(), st.dropped_rows.end(), start.dropped_rows.begin(),
                                      start.dropped_rows.end(), std::back_inserter(changed));
        std::vector<std::string> names;
        for (int r : changed)
          if (std::find(names.begin(), names.end(), model.constraint_name_of_row(r)) == names.end())
            names.push_back(model.constraint_name_of_row(r));
        throw ModelError(who + parameter + " has no sensitivity: which equations of " + quoted_names(names) +
                         " are redundant at the start differs between its value and " + to_text(values[side]) +
                         " (a redundant set, such as two joints holding one motion, that the change breaks or "
                         "makes): the run is not differentiable in it there");
      }
      form->join_run(data);
      y[side].resize(form->size()), yp[side].resize(form->size());
      form->initial(st, y[side].data(), yp[side].data());
      (side == 0 ? sens->plus : sens->minus).push_back(std::move(form));
      sens->models.push_back(std::move(at));
    }
    sens->s0.push_back((y[0] - y[1]) / span);
    sens->sp0.push_back((yp[0] - yp[1]) / span);
  }
  consistent_sensitivities(*sens);
  outputs.sensitivity_names = sens->names;
  sensitivities = std::move(sens);
  plan.sensitivities = sensitivities.get();
}

void Run::start_stepper(double t, const ConsistentState& from) {
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
  loop_ = std::make_unique<StepLoop>(*stepper_, plan, t, stop_at_end_);
}

void Run::restart_stepper(double t, const ConsistentState& from) {
  plan.t0 = t;  // the first step's scale: the stretch in progress
  stepper_->reset(t, from);
  loop_->restarted(t);
  ++restarts_;
}

void Run::step_to(double target, const std::vector<double>& t_out, size_t& k, const Record& record) {
  for (;;) {
    try {
      // outputs inside the step taken last, before it steps on
      for (; k < t_out.size() && t_out[k] <= loop_->t(); ++k) {
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
  // the start, the outputs' solves and the checks of the dropped rows
  s.element_evaluations += data.element_evaluations + watch->element_evaluations();
  name_method(s, *current_);
  s.method_choice = method_choice;
  s.analysis = name_of(Analysis::kDynamic);
  if (events) {
    s.events = events->events;
    s.impacts = events->impacts;
    s.root_evals = events->root_evals;
  }
  return s;
}

}  // namespace lagmb
