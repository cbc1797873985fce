// What simulate and a Simulator share to start and check a dynamic run.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "integrators/events.hpp"
#include "integrators/integrators.hpp"
#include "lagmb/analyses/redundancy.hpp"

namespace lagmb {

/// Times closer than kTimeResolution max(|t|, 1 s) are one time to a run
/// (about 45 units in the last place of t): an end time, an advance or an
/// output interval shorter than that is refused.
constexpr double kTimeResolution = 1e-14;
inline double shortest_span(double t0, double t1) {
  return kTimeResolution * std::max({std::abs(t0), std::abs(t1), 1.0});
}

/// The latest time a run reaches, |t| <= 1e9 s (about 32 years): near t the
/// integrators' smallest step is about 100 eps |t| (2e-5 s here; IDA's
/// bound), so much later a mechanism's motion cannot be resolved.
constexpr double kLatestTime = 1e9;
/// ModelError "who: what = t ..." unless |t| <= kLatestTime.
inline void check_time(double t, const std::string& who, const char* what) {
  if (!(std::abs(t) <= kLatestTime))
    throw ModelError(who + ": " + what + " = " + to_text(t) + " is beyond the times a run can resolve, |t| <= " +
                     to_text(kLatestTime) + " s (the integrators' smallest step there is 100 eps |t|)");
}

/// The options every dynamic run takes (tolerances, method, bounds, start);
/// ModelError beginning with "who: " for one that is wrong. Returns the method.
const Method& validate_run_options(const Model& model, const SimulationOptions& o, const std::string& who);

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

/// Everything one dynamic run changes, in one place (docs/design.md 2.8):
/// its Data (the dropped rows, the input values, the elements' run state:
/// Data::RunValues, which every Data of the run shares), the augmented
/// system, the event runner, the watch over the rows left out as redundant,
/// the integration plan and the outputs recorded so far. simulate builds one
/// and steps it to t_end; a Simulator keeps one and advances it in chunks.
/// The stepper and its loop are the caller's (simulate's stops at t_end, a
/// Simulator's steps past the time asked for). Constructing it validates
/// nothing: the options are the caller's, checked (validate_run_options).
class Run {
 public:
  /// Starts the run at options.t0 (dynamic_start, start_events): the
  /// consistent state is `start`; outputs holds none yet.
  Run(const Model& model, const SimulationOptions& options, const Method& method);
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  const Model& model;
  const SimulationOptions& options;
  const Method& method;
  Data data;  // the run's: plan.run and every formulation's Data join it
  AugmentedSystem kkt;
  ConsistentState start;
  std::unique_ptr<EventRunner> events;  // null without event elements
  IntegrationPlan plan;                 // outputs and breakpoints: the caller's
  std::unique_ptr<RedundancyWatch> watch;
  Trajectory outputs;  // n, m, p, dropped rows and the method's names set

  /// Appends the output (t, q, v) with the run's input values (and, with
  /// `solve`, its a and lam): record_output.
  void record(double t, const double* q, const double* v, bool solve);
  /// Copies the event runner's records and counts into `tr`.
  void report_events(Trajectory& tr) const;
};

}  // namespace lagmb
