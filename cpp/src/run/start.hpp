// What a dynamic run starts from: its consistent state, its integration
// plan and its event runner.
#pragma once

#include <memory>

#include "lagmb/events/event_runner.hpp"
#include "integrators/integrators.hpp"
#include "lagmb/analyses/redundancy.hpp"

namespace lagmb {

/// The consistent state a dynamic run starts from at o.t0: the model's
/// initial positions and velocities or, with o.start == Start::kEquilibrium, the
/// static equilibrium at rest; assembled with the rows found redundant there
/// left out (start_state; `redundancy` gets them). A failing user function
/// is a SimulationError at t0.
ConsistentState dynamic_start(const Model& model, const SimulationOptions& o, Data& d, AugmentedSystem& kkt,
                              Redundancy& redundancy);

/// The plan of a dynamic run from the options (no outputs or breakpoints
/// yet); `run` is the run's Data.
IntegrationPlan run_plan(const Model& model, const SimulationOptions& o, const Method& method, const Data& run);

/// The event runner of a model with event elements (null without): a joint
/// that starts at a limit, moving into it, gets its impact at t (`start`
/// changes); SimulationError if that fails. The options' tolerances say how
/// accurate the run's positions are.
std::unique_ptr<EventRunner> start_events(const Model& model, const Data& run, const SimulationOptions& options, double t,
                                          ConsistentState& start);

}  // namespace lagmb
