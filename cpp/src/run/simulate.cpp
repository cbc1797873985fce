#include "lagmb/run/simulate.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

#include "lagmb/events/event_runner.hpp"
#include "integrators/integrators.hpp"
#include "run/run.hpp"
#include "lagmb/analyses/diagnosis.hpp"
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

namespace {

std::vector<double> output_times(const SimulationOptions& o) {
  if (!o.t_out.empty()) return o.t_out;
  std::vector<double> t(o.n_out);
  for (int k = 0; k < o.n_out; ++k) t[k] = o.t0 + (o.t_end - o.t0) * k / (o.n_out - 1);
  t.back() = o.t_end;
  return t;
}

}  // namespace

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
  require_determined_motion(model, q, t, "solve_accelerations");
  Data d(model);
  AugmentedSystem kkt(model);
  qdd.resize(n);
  lam.resize(model.n_constraints());
  // one instant: the rows dependent here are left out (their multipliers 0); the
  // rank test only where S's pivots do not already show every row independent
  bool independent = false;
  try {
    solve_accelerations(model, d, kkt, q.data(), v.data(), t, qdd.data(), lam.data());
    independent = model.n_constraints() == 0 || kkt.independent_rows();
  } catch (const SimulationError&) {  // (singular with every row: the rank test decides)
  }
  if (!independent) {
    if (model.n_constraints() > 0) d.drop_rows(model, constraint_rank(model, q, t).dependent_rows);
    solve_accelerations(model, d, kkt, q.data(), v.data(), t, qdd.data(), lam.data());
  }
  if (!qdd.allFinite() || !lam.allFinite())
    throw SimulationError("solve_accelerations: " + non_finite_source(model, d, q.data(), v.data(), t), t);
}

Analysis resolve_analysis(const Model& model, const SimulationOptions& o) {
  const Analysis a = o.analysis;
  const std::vector<int> massless = massless_bodies(model);
  // massless bodies run where the augmented matrix is regular (its LU: no M^-1 is needed)
  auto require_determined = [&] {
    try {
      require_determined_motion(model, model.initial_q(), o.t0, "simulate");
    } catch (const ModelError& e) {
      throw ModelError(std::string(e.what()) + " For a mechanism whose motion is fully prescribed by drivers use "
                       "analysis=\"kinematic\".");
    }
  };
  if (a == Analysis::kDynamic) {
    require_determined();
    return a;
  }
  // stops and contact switch on events, which only the integrators find
  const bool events = model.has_events();
  if (events && a != Analysis::kAuto)
    throw ModelError(std::string("simulate: analysis \"") + name_of(a) + "\" solves the constraints at the output times only and " +
                     "would miss the events of '" + model.event_element_name() +
                     "' (stops, contact): use analysis=\"dynamic\"");
  // fewer equations than coordinates: free to move whatever the rank (no QR needed)
  const int equations = model.n_constraints() - int(model.switched_rows().size());
  const bool free = model.n_coordinates() > equations || degrees_of_freedom(model, o.t0) > 0;
  if (a == Analysis::kAuto) {
    if (free || events) {
      require_determined();
      return Analysis::kDynamic;
    }
    return massless.empty() ? Analysis::kInverseDynamics : Analysis::kKinematic;
  }
  if (free)
    throw ModelError(std::string("simulate: analysis \"") + name_of(a) + "\" needs a mechanism whose motion is fully prescribed " +
                     "(0 degrees of freedom), but this model has " + std::to_string(degrees_of_freedom(model, o.t0)) +
                     " degree(s) of freedom: drive them, or use analysis=\"dynamic\"");
  return a;  // massless bodies are fine for inverse dynamics too: they carry no inertia force
}

namespace {

/// simulate of `given`, or of `with_parameters` (the model built from it
/// with the run's parameters) when not null.
Trajectory simulate_run(const Model& given, const std::shared_ptr<const Model>& with_parameters,
                        const SimulationOptions& options, const std::vector<std::string>& sensitivities) {
  const Model& model = with_parameters ? *with_parameters : given;
  // sensitivities are IDAS' on the GGL form: what formulation "auto" runs then
  SimulationOptions o = options;
  const bool sensitivities_choose = !sensitivities.empty() && o.formulation == Formulation::kAuto;
  if (sensitivities_choose) o.formulation = Formulation::kGgl, o.integrator = Integrator::kDefault;
  // a fully driven model's reactions have sensitivities too: through a dynamic run
  if (!sensitivities.empty() && o.analysis == Analysis::kAuto) o.analysis = Analysis::kDynamic;
  const Method& method = validate(model, o);
  const auto wall0 = std::chrono::steady_clock::now();
  // what the scene needs: a fully driven model is solved from its constraints alone
  const Analysis analysis = resolve_analysis(model, o);
  if (analysis != Analysis::kDynamic) {
    if (!sensitivities.empty())
      throw ModelError(std::string("simulate: sensitivities are integrated beside a dynamic run; analysis \"") +
                       name_of(analysis) + "\" integrates nothing (use analysis=\"dynamic\" or the default)");
    if (o.start != Start::kGiven)
      throw ModelError(std::string("simulate: start '") + name_of(o.start) + "' applies to a dynamic analysis; the " +
                       "positions of this fully driven model (0 degrees of freedom) follow from its drivers (" +
                       name_of(analysis) + ")");
    const bool with_lam = analysis == Analysis::kInverseDynamics;
    Trajectory tr = kinematic_analysis(model, o.t0, output_times(o), with_lam, o.progress, o.progress_interval,
                                       o.max_steps);
    tr.run_model = with_parameters;
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
  Run run(given, with_parameters, o, method, /*stop_at_end=*/true);
  if (!sensitivities.empty()) {
    run.start_sensitivities(sensitivities);
    if (sensitivities_choose)
      run.method_choice = run.outputs.stats.method_choice =
          "auto: ggl, the run has sensitivities (IDAS integrates them beside the GGL form)";
  }
  IntegrationPlan& plan = run.plan;
  plan.t_out = output_times(o);
  for (double b : model.breakpoints())
    if (b > o.t0 && b < o.t_end) plan.breakpoints.push_back(b);
  Trajectory& tr = run.outputs;
  tr.t.reserve(plan.t_out.size());
  tr.q.reserve(plan.t_out.size() * n);
  tr.v.reserve(plan.t_out.size() * n);
  // a contact's damping depends on the impact speed of the contact in
  // progress (event state), the multipliers on the stops closed then: with
  // events, a and lam are solved when an output is recorded, not from the
  // final state after the run
  const bool solve_when_recorded = model.has_events();
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
    tr.stats = run.stats();
    tr.stats.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (run.events) tr.events = run.events->records;
    return why;
  };
  auto kept = [&] {
    std::ostringstream s;
    s << " Outputs up to t = " << (tr.t.empty() ? o.t0 : tr.t.back()) << " are kept in the partial result.";
    return s.str();
  };

  try {
    run.start_stepper(o.t0, run.start);
    size_t k = 0;
    for (; k < plan.t_out.size() && plan.t_out[k] <= o.t0; ++k) record(run.start.q.data(), run.start.v.data());
    run.step_to(o.t_end, plan.t_out, k, record);
  } catch (const IntegratorFailure& e) {
    const std::string output_failure = finish();
    std::ostringstream msg;
    msg << e.what();
    if (e.q.size() && e.diagnose) msg << diagnose_failure(model, e.q, e.t, run.start.dropped_rows);
    if (run.sensitivities && e.diagnose)  // (not at an event, which says why itself)
      msg << " The run integrates sensitivities: their F_p is a difference of the residual over 1e-4 of each "
             "parameter, good to about 1e-12 of the residual's scale, so an atol much below that in them "
             "cannot be met (try atol >= 1e-12).";
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

}  // namespace

Trajectory simulate(const Model& model, const SimulationOptions& options, const ParameterValues& parameters,
                    const std::vector<std::string>& sensitivities) {
  const std::shared_ptr<const Model> with = with_parameters(model, parameters);
  try {
    return simulate_run(model, with, options, sensitivities);
  } catch (SimulationError& e) {  // a failure before the run started has no outputs to point at the model
    if (with) e.partial.run_model = with;
    throw;
  }
}

Trajectory simulate(const Model& model, const SimulationOptions& options) { return simulate(model, options, {}); }

}  // namespace lagmb
