// Forward sensitivities of a run to its parameters: the models at p +- delta,
// their formulations made of the run's Data and the consistent initial
// sensitivities (Run::start_sensitivities).
#include "run/run.hpp"

#include <algorithm>
#include <iterator>
#include <map>

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/spec/parameters.hpp"

namespace lagmb {

void Run::consistent_sensitivities(SensitivityPlan& sens) {
  // the differences of the perturbed starts hold the constraints' linearization,
  //   Phi_q s_q + Phi_p = 0,   Phi_q s_v + Vq s_q + (Phi_q v + Phi_t)_p = 0,
  // only to their assembly's tolerance over delta (1e-12 / 1e-4 relative),
  // which an error test at rtol 1e-10 cannot start from: each is made
  // exact by the least change in the M-metric, and s_q' = s_v (F1, mu = 0)
  const int n = model.n_coordinates(), m = model.n_constraints(), N = 2 * n + 2 * m;
  const std::unique_ptr<DaeFormulation> base = make_sensitivity_formulation(model, data);
  VecX y(N), yp(N), plus(N), minus(N);
  base->initial(start, y.data(), yp.data());
  Data d(model, &data);
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
  // a stop is a pair of rows left out while open: the equations are those
  // without it until an event (an impact, a capture, a release), where the
  // run stops (IdaStepper::reset); a contact's force switches at its onset
  if (!model.event_groups().empty())
    throw ModelError(who + "the model has '" + model.event_groups().front()->name(0) +
                     "' (a contact): at its events the motion jumps, and so would the sensitivities; "
                     "remove it to differentiate the run");
  if (!data.closed_rows().empty())
    throw ModelError(who + "stop '" + model.constraint_name_of_row(data.closed_rows().front()) +
                     "' holds its joint on a limit at the start: the sensitivities of a run that starts on a "
                     "stop are not taken yet (start the joint off the limit)");
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
      std::unique_ptr<DaeFormulation> form = make_sensitivity_formulation(*at, data);
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

}  // namespace lagmb
