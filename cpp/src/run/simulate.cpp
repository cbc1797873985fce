#include "lagmb/run/simulate.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

#include "integrators/events.hpp"
#include "integrators/integrators.hpp"
#include "run/run.hpp"
#include "lagmb/assembly/analysis.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/analyses/equilibrium.hpp"
#include "lagmb/analyses/kinematics.hpp"
#include "lagmb/integrators/methods.hpp"
#include "lagmb/interrupt.hpp"
#include "lagmb/analyses/redundancy.hpp"

namespace lagmb {

namespace {

/// The options of simulate's outputs; the rest as validate_run_options (its method).
const Method& validate(const Model& model, const SimulationOptions& o) {
  const Method& method = validate_run_options(model, o, "simulate");
  if (!(std::isfinite(o.t_end) && o.t_end > o.t0))
    throw ModelError("simulate: t_end must be finite and greater than t0 = " + to_text(o.t0) + ", got " +
                     to_text(o.t_end));
  check_time(o.t_end, "simulate", "t_end");
  if (o.t_end - o.t0 < shortest_span(o.t0, o.t_end))
    throw ModelError("simulate: t_end = " + to_text(o.t_end) + " is within " + to_text(shortest_span(o.t0, o.t_end)) +
                     " s of t0 = " + to_text(o.t0) + ", below the time resolution there (" + to_text(kTimeResolution) +
                     " max(|t|, 1 s))");
  // a step bound that needs more steps between two outputs than allowed
  // would run for hours: refuse it now
  if (o.max_step > 0 && o.max_steps > 0) {
    double gap = 0.0, from = o.t0, to = o.t0;
    if (o.t_out.empty()) {
      gap = (o.t_end - o.t0) / std::max(o.n_out - 1, 1);
      to = o.t0 + gap;
    } else {
      double last = o.t0;
      for (double tk : o.t_out) {
        if (tk - last > gap) gap = tk - last, from = last, to = tk;
        last = tk;
      }
      if (o.t_end - last > gap) gap = o.t_end - last, from = last, to = o.t_end;
    }
    if (gap / o.max_step > double(o.max_steps)) {
      std::ostringstream s;
      s << "simulate: " << (o.formulation == Formulation::kAli3p ? "step" : "max_step") << " = " << o.max_step
        << " s needs at least " << gap / o.max_step << " steps between the outputs at t = " << from << " and "
        << to << ", more than max_steps = " << o.max_steps
        << " (the bound on the steps between outputs): take a longer step, ask for outputs more often or raise "
           "max_steps";
      throw ModelError(s.str());
    }
  }
  if (o.t_out.empty() && o.n_out < 2)
    throw ModelError("simulate: n_out must be at least 2, got " + std::to_string(o.n_out));
  // outputs are kept in memory: refuse what cannot fit rather than fail half way
  const double outputs = o.t_out.empty() ? double(o.n_out) : double(o.t_out.size());
  const double values = outputs * (3.0 * model.n_coordinates() + model.n_constraints());
  if (values > 2e9)
    throw ModelError("simulate: " + std::to_string(long(outputs)) + " outputs of this model would hold " +
                     std::to_string(long(values)) + " numbers (" + std::to_string(long(values * 8e-9)) +
                     " GB): ask for fewer outputs (n_out or t_out)");
  for (size_t k = 0; k < o.t_out.size(); ++k) {
    const double tk = o.t_out[k];
    if (!std::isfinite(tk) || tk < o.t0 || tk > o.t_end)
      throw ModelError("simulate: t_out[" + std::to_string(k) + "] = " + std::to_string(tk) +
                       " is outside [t0, t_end]");
    if (k && !(tk > o.t_out[k - 1]))
      throw ModelError("simulate: t_out must be strictly increasing (t_out[" + std::to_string(k) +
                       "] = " + std::to_string(tk) + ")");
  }
  return method;
}

}  // namespace

const Method& validate_run_options(const Model& model, const SimulationOptions& o, const std::string& who) {
  const std::string at = who + ": ";
  if (!model.finalized()) throw ModelError(at + "the model is not finalized");
  if (model.n_coordinates() == 0) throw ModelError(at + "the model has no bodies");
  auto positive = [&](double x, const char* name) {
    if (!(std::isfinite(x) && x > 0))
      throw ModelError(at + name + " must be positive and finite, got " + std::to_string(x));
  };
  if (!std::isfinite(o.t0)) throw ModelError(at + "t0 is not finite");
  check_time(o.t0, who, "t0");
  positive(o.rtol, "rtol");
  if (o.rtol >= 1.0)
    throw ModelError(at + "rtol = " + to_text(o.rtol) +
                     " must be below 1: a relative error of 100 % or more bounds nothing (typical: 1e-3 to 1e-10)");
  if (o.rtol < 1e-14)
    throw ModelError(at + "rtol = " + std::to_string(o.rtol) +
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
  const Method& method = find_method(o.formulation, o.integrator);
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

namespace {

std::vector<double> output_times(const SimulationOptions& o) {
  if (!o.t_out.empty()) return o.t_out;
  std::vector<double> t(o.n_out);
  for (int k = 0; k < o.n_out; ++k) t[k] = o.t0 + (o.t_end - o.t0) * k / (o.n_out - 1);
  t.back() = o.t_end;
  return t;
}

}  // namespace

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

Run::Run(const Model& model_, const SimulationOptions& options_, const Method& method_)
    : model(model_), options(options_), method(method_), data(model_), kkt(model_) {
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
  outputs.stats.formulation = name_of(method.formulation);
  outputs.stats.integrator = name_of(method.integrator);
  outputs.stats.analysis = name_of(Analysis::kDynamic);
}

void Run::record(double t, const double* q, const double* v, bool solve) {
  record_output(model, data, kkt, *watch, outputs, t, q, v, data.run->inputs, solve);
}

void Run::report_events(Trajectory& tr) const {
  if (!events) return;
  tr.events = events->records;
  tr.stats.events = events->events;
  tr.stats.impacts = events->impacts;
  tr.stats.root_evals = events->root_evals;
}


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

ConsistentState assemble(const Model& model, double t) {
  if (!model.finalized()) throw ModelError("assemble: the model is not finalized");
  if (model.n_coordinates() == 0) throw ModelError("assemble: the model has no bodies");
  if (!std::isfinite(t)) throw ModelError("assemble: t is not finite");
  Data d(model);
  AugmentedSystem kkt(model);
  return start_state(model, d, kkt, model.initial_q(), model.initial_v(), t);
}

void solve_accelerations(const Model& model, const VecX& q, const VecX& v, double t, VecX& qdd,
                         VecX& lam) {
  if (!model.finalized()) throw ModelError("solve_accelerations: the model is not finalized");
  const int n = model.n_coordinates();
  if (n == 0) throw ModelError("solve_accelerations: the model has no bodies");
  if (q.size() != n || v.size() != n)
    throw ModelError("solve_accelerations: q and v must have " + std::to_string(n) + " entries");
  if (!q.allFinite() || !v.allFinite() || !std::isfinite(t))
    throw ModelError("solve_accelerations: q, v and t must be finite");
  if (const auto massless = massless_bodies(model); !massless.empty())
    throw ModelError("solve_accelerations: body '" + model.body(massless.front()).name +
                     "' is massless, so its accelerations are not determined by forces");
  Data d(model);
  // one instant: the rows dependent here are left out (their multipliers 0)
  d.drop_rows(model, constraint_rank(model, q, t).dependent_rows);
  AugmentedSystem kkt(model);
  qdd.resize(n);
  lam.resize(model.n_constraints());
  solve_accelerations(model, d, kkt, q.data(), v.data(), t, qdd.data(), lam.data());
  if (!qdd.allFinite() || !lam.allFinite())
    throw SimulationError("solve_accelerations: " + non_finite_source(model, d, q.data(), v.data(), t), t);
}

Analysis resolve_analysis(const Model& model, const SimulationOptions& o) {
  const Analysis a = o.analysis;
  const std::vector<int> massless = massless_bodies(model);
  auto refuse_massless = [&] {
    const Body& b = model.body(massless.front());
    std::ostringstream s;
    s << "simulate: body '" << b.name << "' is massless (mass " << b.mass;
    if (b.spatial)
      s << ", principal moments of inertia " << to_text(principal_moments(b.inertia_tensor));
    else if (!b.particle)
      s << ", inertia " << b.inertia;
    s << "), so its accelerations are not determined by forces: a dynamic analysis needs every mass and "
      << "inertia > 0 (in space every principal moment). For a mechanism whose motion is fully prescribed by "
      << "drivers use analysis=\"kinematic\".";
    throw ModelError(s.str());
  };
  if (a == Analysis::kDynamic) {
    if (!massless.empty()) refuse_massless();
    return a;
  }
  // stops and contact switch on events, which only the integrators find
  const bool events = !model.event_groups().empty();
  if (events && a != Analysis::kAuto)
    throw ModelError(std::string("simulate: analysis \"") + name_of(a) + "\" solves the constraints at the output times only and " +
                     "would miss the events of '" + model.event_groups().front()->name(0) +
                     "' (stops, contact): use analysis=\"dynamic\"");
  const int dof = degrees_of_freedom(model, o.t0);
  if (a == Analysis::kAuto) {
    if (dof > 0 || events) {
      if (!massless.empty()) refuse_massless();
      return Analysis::kDynamic;
    }
    return massless.empty() ? Analysis::kInverseDynamics : Analysis::kKinematic;
  }
  if (dof > 0)
    throw ModelError(std::string("simulate: analysis \"") + name_of(a) + "\" needs a mechanism whose motion is fully prescribed " +
                     "(0 degrees of freedom), but this model has " + std::to_string(dof) +
                     " degree(s) of freedom: drive them, or use analysis=\"dynamic\"");
  return a;  // massless bodies are fine for inverse dynamics too: they carry no inertia force
}

Trajectory simulate(const Model& model, const SimulationOptions& options, const ParameterValues& parameters) {
  const std::shared_ptr<const Model> run_model = with_parameters(model, parameters);
  if (!run_model) return simulate(model, options);
  try {
    Trajectory tr = simulate(*run_model, options);
    tr.run_model = run_model;
    return tr;
  } catch (SimulationError& e) {
    e.partial.run_model = run_model;
    throw;
  }
}

Trajectory simulate(const Model& model, const SimulationOptions& o) {
  const Method& method = validate(model, o);
  const auto wall0 = std::chrono::steady_clock::now();
  // what the scene needs: a fully driven model is solved from its constraints alone
  const Analysis analysis = resolve_analysis(model, o);
  if (analysis != Analysis::kDynamic) {
    if (o.start != Start::kGiven)
      throw ModelError(std::string("simulate: start '") + name_of(o.start) + "' applies to a dynamic analysis; the " +
                       "positions of this fully driven model (0 degrees of freedom) follow from its drivers (" +
                       name_of(analysis) + ")");
    const bool with_lam = analysis == Analysis::kInverseDynamics;
    Trajectory tr = kinematic_analysis(model, o.t0, output_times(o), with_lam, o.progress, o.progress_interval,
                                       o.max_steps);
    // a result holds finite numbers (a kinematic-only run has no multipliers: NaN, never read)
    for (int i = 0; i < tr.size(); ++i) {
      const size_t n = size_t(tr.n), m = size_t(tr.m);
      const bool finite = Eigen::Map<const VecX>(&tr.q[i * n], tr.n).allFinite() &&
                          Eigen::Map<const VecX>(&tr.v[i * n], tr.n).allFinite() &&
                          Eigen::Map<const VecX>(&tr.a[i * n], tr.n).allFinite() &&
                          (!with_lam || Eigen::Map<const VecX>(tr.lam.data() + i * m, tr.m).allFinite());
      if (finite) continue;
      const std::string why = non_finite_source(model, Data(model), &tr.q[i * n], &tr.v[i * n], tr.t[i]);
      const double t = tr.t[i];
      tr.truncate(i);
      std::ostringstream s;
      s << "kinematic analysis: at the output t = " << t << " the solution is not finite: " << why
        << ". Outputs up to t = " << (tr.t.empty() ? o.t0 : tr.t.back()) << " are kept in the partial result.";
      throw SimulationError(s.str(), t, std::move(tr));
    }
    return tr;
  }
  const int n = model.n_coordinates();
  // the run (its Data with the inputs at their initial values, start,
  // events, redundancy watch), stepped to t_end
  Run run(model, o, method);
  IntegrationPlan& plan = run.plan;
  plan.t_out = output_times(o);
  for (double b : model.breakpoints())
    if (b > o.t0 && b < o.t_end) plan.breakpoints.push_back(b);
  Trajectory& tr = run.outputs;
  tr.t.reserve(plan.t_out.size());
  tr.q.reserve(plan.t_out.size() * n);
  tr.v.reserve(plan.t_out.size() * n);
  // a contact's damping depends on the impact speed of the contact in
  // progress (event state): with event elements, a and lam are solved when
  // an output is recorded, not from the final state after the run
  const bool solve_when_recorded = !model.event_groups().empty();
  auto record = [&](const double* q, const double* v) {
    run.record(plan.t_out[tr.t.size()], q, v, solve_when_recorded);
  };
  // solves the outputs not yet solved; returns why one failed ("" if none)
  // and keeps only the solved ones
  auto finish = [&]() -> std::string {
    std::string why;
    if (!solve_when_recorded) {
      try {
        why = solve_outputs(model, run.data, run.kkt, tr);
      } catch (Interrupted&) {  // interrupted again: keep what was solved
      }
    }
    tr.truncate(solved_outputs(tr));
    // start, outputs, checks
    tr.stats.element_evaluations += run.data.element_evaluations + run.watch->element_evaluations();
    run.report_events(tr);
    tr.stats.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    return why;
  };
  auto kept = [&] {
    std::ostringstream s;
    s << " Outputs up to t = " << (tr.t.empty() ? o.t0 : tr.t.back()) << " are kept in the partial result.";
    return s.str();
  };

  try {
    integrate(method, model, run.start, plan, record, tr.stats);
  } catch (const IntegratorFailure& e) {
    const std::string output_failure = finish();
    std::ostringstream msg;
    msg << e.what();
    if (e.q.size() && e.diagnose) msg << diagnose_failure(model, e.q, e.t, run.start.dropped_rows);
    if (!output_failure.empty()) msg << " Also, " << output_failure << ".";
    msg << kept();
    throw SimulationError(msg.str(), e.t, std::move(tr));
  } catch (const UserFunctionError& e) {  // the progress report failed
    finish();
    const double t = tr.t.empty() ? o.t0 : tr.t.back();
    throw SimulationError(e.what() + kept(), t, std::move(tr));
  } catch (Interrupted& e) {
    finish();
    e.t = tr.t.empty() ? o.t0 : tr.t.back();
    e.partial = std::move(tr);
    throw;
  } catch (const SimulationError& e) {  // a solve inside a step or restart (friction load, augmented system)
    if (!e.partial.t.empty()) throw;
    finish();
    const double t = std::isfinite(e.t) ? e.t : (tr.t.empty() ? o.t0 : tr.t.back());
    throw SimulationError(e.what() + kept(), t, std::move(tr));
  }
  const std::string output_failure = finish();
  if (!output_failure.empty()) {
    const double t = tr.size() < int(plan.t_out.size()) ? plan.t_out[tr.size()] : o.t_end;
    throw SimulationError(output_failure + "." + kept(), t, std::move(tr));
  }
  return std::move(tr);  // (tr is the run's: moved out, not copied)
}

}  // namespace lagmb
