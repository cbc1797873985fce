// What a dynamic run starts from: its consistent state (given or at the
// static equilibrium), its integration plan and its event runner.
#include "run/start.hpp"

#include <algorithm>

#include "lagmb/analyses/equilibrium.hpp"
#include "lagmb/errors.hpp"

namespace lagmb {

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

std::unique_ptr<EventRunner> start_events(const Model& model, const Data& run, const SimulationOptions& options, double t,
                                          ConsistentState& start) {
  if (!model.has_events()) return nullptr;
  // (how accurate the positions are: the integrator's tolerances at the start's scale)
  const double position_tol = options.rtol * (1.0 + start.q.lpNorm<Eigen::Infinity>()) +
                              (options.atol_coordinates.empty() ? options.atol
                                                                : *std::max_element(options.atol_coordinates.begin(),
                                                                                    options.atol_coordinates.end()));
  auto events = std::make_unique<EventRunner>(model, run, position_tol);
  // a joint that starts at a limit gets its impact (moving into it) or its capture (pressing on it) at t
  try {
    if (events->start(t, start.q, start.v)) start = events->consistent(t, start.q, start.v);
  } catch (const IntegratorFailure& e) {
    throw SimulationError(e.what(), e.t);
  }
  return events;
}

}  // namespace lagmb
