// What simulate and a Simulator share to start and check a dynamic run.
#pragma once

#include <memory>
#include <string>

#include "events.hpp"
#include "integrators.hpp"
#include "lagmb/redundancy.hpp"

namespace lagmb {

/// The options every dynamic run takes (tolerances, method, bounds, start);
/// ModelError beginning with "who: " for one that is wrong.
void validate_run_options(const Model& model, const SimulationOptions& o, const std::string& who);

/// The consistent state a dynamic run starts from at o.t0: the model's
/// initial positions and velocities or, with o.start == "equilibrium", the
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
/// changes); SimulationError if that fails.
std::unique_ptr<EventRunner> start_events(const Model& model, const Data& run, double t, ConsistentState& start);

/// a and lam at the recorded outputs of `tr` from `first` on, from the
/// augmented system, appended output by output (tr.a holds size_t(k) * n
/// values once k are solved). Returns "" or why an output could not be
/// solved (a user function failing there, joint friction whose load does not
/// converge, a non-finite result); the outputs from that one on are then
/// unsolved.
std::string solve_outputs(const Model& model, Data& d, AugmentedSystem& kkt, Trajectory& tr, int first = 0);

/// Appends the output (t, q, v) and the input values to `tr`, and with
/// `solve` its a and lam;
/// first checks the rows left out as redundant (`watch`). Throws
/// IntegratorFailure (diagnose = false) with why, keeping only the outputs
/// solved before.
void record_output(const Model& model, Data& d, AugmentedSystem& kkt, RedundancyWatch& watch, Trajectory& tr,
                   double t, const double* q, const double* v, const VecX& inputs, bool solve);

/// Outputs of `tr` whose a and lam were solved.
int solved_outputs(const Trajectory& tr);

}  // namespace lagmb
