// The time integrators lagmb drives, behind one call each.
#pragma once

#include <functional>
#include <stdexcept>
#include <vector>

#include "dae.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

/// What every integrator is asked to do.
struct IntegrationPlan {
  double t0, t_end, rtol, atol, max_step;
  int max_order;
  long max_steps;
  std::vector<double> t_out;
  std::vector<double> breakpoints;  // inside (t0, t_end): stop and restart there
  std::function<void(double)> progress;
  double progress_interval;
};

/// The integrator gave up at time t; what() carries its diagnosis.
struct IntegratorFailure : std::runtime_error {
  IntegratorFailure(const std::string& what, double t_reached)
      : std::runtime_error(what), t(t_reached) {}
  double t;
};

/// Integrates `dae` with IDA from `start`; calls record(q, v) at each output
/// time, interpolated by IDA (the steps are not stopped at outputs).
void integrate_ida(DaeFormulation& dae, const ConsistentState& start, const IntegrationPlan& plan,
                   const std::function<void(const double* q, const double* v)>& record,
                   Stats& stats);

}  // namespace lagmb
