#include <chrono>
#include <sstream>

#include "events.hpp"
#include "integrators.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/interrupt.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

void run_steps(Stepper& stepper, const IntegrationPlan& plan, const ConsistentState& start,
               const std::function<void(const double* q, const double* v)>& record, Stats& stats) {
  size_t next_break = 0;
  auto stop_time = [&] {
    return next_break < plan.breakpoints.size() ? plan.breakpoints[next_break] : plan.t_end;
  };
  stepper.set_stop(stop_time());

  const auto& t_out = plan.t_out;
  size_t k = 0;
  for (; k < t_out.size() && t_out[k] <= plan.t0; ++k) record(start.q.data(), start.v.data());

  auto clock = std::chrono::steady_clock::now();
  long steps = 0;
  std::vector<int> fired;
  VecX q_event, v_event;
  try {
    while (k < t_out.size()) {
      poll_interrupt();
      bool at_stop = false;
      const double t = stepper.step(at_stop);
      for (; k < t_out.size() && t_out[k] <= t; ++k) {
        const double *q = nullptr, *v = nullptr;
        stepper.interpolate(t_out[k], q, v);
        record(q, v);
      }
      if (plan.max_steps > 0 && ++steps >= plan.max_steps && t < plan.t_end) {
        std::ostringstream msg;
        msg << stepper.name() << " reached max_steps = " << plan.max_steps << " at t = " << t
            << " before t_end = " << plan.t_end << ".";
        throw IntegratorFailure(msg.str(), t);
      }
      if (plan.events) {
        // a root of the event functions (or a crossing the integrator
        // stepped over): the elements act, and the run restarts from the
        // state they leave, at order 1
        const bool root = stepper.root_found(fired);
        if (root || plan.events->missed(t, stepper.positions(), stepper.velocities(), fired)) {
          q_event = Eigen::Map<const VecX>(stepper.positions(), start.q.size());
          v_event = Eigen::Map<const VecX>(stepper.velocities(), start.v.size());
          bool acted = false;
          try {
            acted = plan.events->handle(t, q_event, v_event, fired);
            if (acted) stepper.reset(t, plan.events->consistent(t, q_event, v_event));
          } catch (const SimulationError& e) {  // keep the outputs so far
            throw IntegratorFailure(std::string("at an event: ") + e.what(), t);
          } catch (const UserFunctionError& e) {
            throw IntegratorFailure(e.what(), t);
          }
          if (acted) {
            if (at_stop) {  // the event fell on a breakpoint or t_end: pass it
              if (next_break >= plan.breakpoints.size()) break;
              ++next_break;
            }
            stepper.set_stop(stop_time());
            continue;
          }
        }
      }
      if (at_stop) {
        if (next_break >= plan.breakpoints.size()) break;  // t_end
        // a derivative of a time function jumps here: restart at order 1
        // from the (continuous, consistent) state instead of stepping across
        ++next_break;
        stepper.restart(t);
        stepper.set_stop(stop_time());
        continue;
      }
      if (plan.progress) {
        auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - clock).count() >= plan.progress_interval) {
          clock = now;
          stepper.fill_stats(stats);
          plan.progress(t);
        }
      }
    }
  } catch (IntegratorFailure& e) {
    stepper.fill_stats(stats);
    e.q = Eigen::Map<const VecX>(stepper.positions(), start.q.size());
    throw;
  } catch (...) {
    stepper.fill_stats(stats);
    throw;
  }
  stepper.fill_stats(stats);
}

}  // namespace lagmb
