#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "lagmb/events/event_runner.hpp"
#include "integrators/integrators.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/interrupt.hpp"
#include "lagmb/model/joint_turns.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

StepLoop::StepLoop(Stepper& stepper, const Model& model, const IntegrationPlan& plan, double t, bool stop_at_end)
    : stepper_(stepper), model_(model), plan_(plan), t_(t), stop_at_end_(stop_at_end) {
  restarted(t);
}

void StepLoop::restarted(double t) {
  t_ = t;
  pending_ = false;
  graze_pending_ = INFINITY;
  const auto& b = plan_.breakpoints;
  next_break_ = size_t(std::upper_bound(b.begin(), b.end(), t) - b.begin());
  stepper_.set_stop(stop_time());
}

double StepLoop::stop_time() const {
  if (next_break_ < plan_.breakpoints.size()) return plan_.breakpoints[next_break_];
  // no stop: the largest time (SUNDIALS 6 cannot clear a stop time)
  return stop_at_end_ ? plan_.t_end : std::numeric_limits<double>::max();
}

bool StepLoop::at_breakpoint(double t, bool at_stop) const {
  return at_stop && next_break_ < plan_.breakpoints.size() && t >= plan_.breakpoints[next_break_];
}

bool StepLoop::act(double t, bool at_stop) {
  if (plan_.events) {
    // a root of the event functions (or a crossing the integrator
    // stepped over): the elements act, and the run restarts from the
    // state they leave, at order 1
    const bool root = stepper_.root_found(fired_);
    const double *q = stepper_.positions(), *v = stepper_.velocities();
    if (root || plan_.events->missed(t, q, v, fired_, multipliers(t, q, v))) {
      if (act_on_crossings(t, stepper_.positions(), stepper_.velocities())) {
        if (at_breakpoint(t, at_stop)) ++next_break_;  // the event fell on a breakpoint: pass it
        stepper_.set_stop(stop_time());
        return true;
      }
    }
  }
  if (at_breakpoint(t, at_stop)) {
    // a derivative of a time function jumps here: restart at order 1
    // from the (continuous, consistent) state instead of stepping across
    ++next_break_;
    ++restarts_;
    bool settled = false;
    if (plan_.events) {  // a force's jump may release a stop or press a joint on its limit
      const int n = int(plan_.atol.size());
      q_event_ = Eigen::Map<const VecX>(stepper_.positions(), n);
      v_event_ = Eigen::Map<const VecX>(stepper_.velocities(), n);
      try {
        const double *qdd = nullptr, *lam = nullptr;
        if (!stepper_.motion_at(t, q_event_.data(), v_event_.data(), qdd, lam)) qdd = lam = nullptr;
        settled = plan_.events->settle(t, q_event_, v_event_, false, lam, qdd);
        if (settled) stepper_.reset(t, plan_.events->consistent(t, q_event_, v_event_));
      } catch (const SimulationError& e) {
        throw IntegratorFailure(std::string("at a breakpoint: ") + e.what(), t);
      }
    }
    if (!settled) stepper_.restart(t);
    stepper_.set_stop(stop_time());
    return true;
  }
  return false;
}

double StepLoop::grazed(double t0, double t1) {
  // (a step that stopped at a root is looked at up to it: a long step can
  // graze one limit before it reaches another)
  if (!plan_.events || !(t1 > t0)) return INFINITY;
  const double t = plan_.events->grazed(
      t0, t1, [&](double at, const double*& q, const double*& v) { stepper_.interpolate(at, q, v); }, fired_,
      [&](double at, const double* q, const double* v) { return multipliers(at, q, v); });
  return std::isnan(t) ? INFINITY : t;
}

const double* StepLoop::multipliers(double t, const double* q, const double* v) {
  if (!plan_.events->reads_multipliers()) return nullptr;  // (none to give: it reads none)
  const double *qdd = nullptr, *lam = nullptr;
  return stepper_.motion_at(t, q, v, qdd, lam) ? lam : nullptr;
}

bool StepLoop::act_on_crossings(double t, const double* q, const double* v) {
  const int n = int(plan_.atol.size());
  q_event_ = Eigen::Map<const VecX>(q, n);
  v_event_ = Eigen::Map<const VecX>(v, n);
  try {
    if (!plan_.events->handle(t, q_event_, v_event_, fired_)) return false;
    stepper_.reset(t, plan_.events->consistent(t, q_event_, v_event_));
  } catch (const IntegratorFailure& e) {  // keep the outputs so far (and what the failure says of itself)
    IntegratorFailure f(std::string("at an event: ") + e.what(), t);
    f.diagnose = e.diagnose;
    throw f;
  } catch (const SimulationError& e) {
    throw IntegratorFailure(std::string("at an event: ") + e.what(), t);
  } catch (const UserFunctionError& e) {
    throw IntegratorFailure(e.what(), t);
  }
  ++restarts_;
  return true;
}

bool StepLoop::act_at_graze(double t, double h) {
  count_joint_turns(t, h);
  const double *q = nullptr, *v = nullptr;
  stepper_.interpolate(t, q, v);
  if (!act_on_crossings(t, q, v)) return false;
  t_ = t;
  pending_ = false;
  stepper_.set_stop(stop_time());
  return true;
}

void StepLoop::count_joint_turns(double t, double h) {
  if (model_.turn_counters().empty()) return;
  const double *q = nullptr, *v = nullptr;
  stepper_.interpolate(t, q, v);
  if (const TurnCounter* c = count_turns(model_, q, v, h, plan_.run->run->state.data())) {
    std::ostringstream msg;
    msg << "joint '" << c->joint << "' turned by half a turn or more in one step (from t = " << t - h << " to " << t
        << "): the elements that act on its angle read it within half a turn of the last step's; the run stops "
           "here. Give a smaller max_step.";
    IntegratorFailure f(msg.str(), t);
    f.diagnose = false;
    throw f;
  }
}

void StepLoop::run(double target, const std::vector<double>& t_out, size_t& k, const Record& record) {
  auto clock = std::chrono::steady_clock::now();
  long steps = 0;
  // a crossing found in the last step beyond the last run's target: the
  // outputs before it are recorded (Run::step_to), the impact is now
  if (graze_pending_ <= target) {
    const double t_grazed = graze_pending_;
    graze_pending_ = INFINITY;
    for (; k < t_out.size() && t_out[k] <= t_grazed; ++k) {
      const double *q = nullptr, *v = nullptr;
      stepper_.interpolate(t_out[k], q, v);
      record(q, v);
    }
    act_at_graze(t_grazed, t_grazed - graze_step_start_);
  }
  if (pending_ && t_ < target && graze_pending_ == INFINITY) {  // (while target is inside the last step, it holds the outputs)
    pending_ = false;
    act(t_, pending_at_stop_);
  }
  const bool to_outputs = stepper_.steps_to_outputs();
  while (t_ < target) {
    poll_interrupt();
    // (after the last output the stop is the breakpoint's or the end's again;
    // a closed stop's force changing fast bounds the step: step_bound())
    const double bound = plan_.events ? plan_.events->step_bound() : INFINITY;
    if (to_outputs || bound < INFINITY || bounded_) {
      const double stop = std::min(to_outputs && k < t_out.size() ? std::min(stop_time(), t_out[k]) : stop_time(), bound);
      stepper_.set_stop(stop);
      bounded_ = bound < INFINITY;
    }
    bool at_stop = false;
    const double t_before = t_;
    double t = t_ = stepper_.step(at_stop);
    // a stop's limit crossed and left within the step: the step ends there
    // (a Simulator's step past its target keeps its interpolant for the
    // times before: a crossing found beyond the target waits for the next
    // run, which acts on it once its target passes it)
    double t_grazed = grazed(t_before, t);
    if (!stop_at_end_ && t_grazed > target && t_grazed < t) {  // (held for the next run)
      graze_pending_ = t_grazed, graze_step_start_ = t_before;
      t_grazed = INFINITY;
    }
    if (t_grazed < t) {  // the outputs before it, then the impact there (if one happens)
      for (; k < t_out.size() && t_out[k] <= t_grazed; ++k) {
        const double *q = nullptr, *v = nullptr;
        stepper_.interpolate(t_out[k], q, v);
        record(q, v);
        steps = 0;
      }
      if (act_at_graze(t_grazed, t_grazed - t_before)) continue;
    }
    for (; k < t_out.size() && t_out[k] <= t; ++k) {
      const double *q = nullptr, *v = nullptr;
      stepper_.interpolate(t_out[k], q, v);
      record(q, v);
      steps = 0;
    }
    count_joint_turns(t, t - t_before);
    // max_steps bounds the steps between outputs (as SUNDIALS' mxstep):
    // a run that cannot end stops, an accurate long one does not
    if (plan_.options->max_steps > 0 && ++steps >= plan_.options->max_steps && t < target) {
      std::ostringstream msg;
      msg << stepper_.name() << " took max_steps = " << plan_.options->max_steps << " steps without reaching the next output "
          << "(at t = " << (k < t_out.size() ? t_out[k] : target) << "; now at t = " << t
          << "): max_steps bounds the steps between outputs; raise it, or ask for outputs more often.";
      IntegratorFailure f(msg.str(), t);
      f.integrator_gave_up = true;
      throw f;
    }
    if (plan_.stiff_steps > 0 && steps >= plan_.stiff_steps && t < target) {
      std::ostringstream msg;
      msg << stepper_.name() << " took " << plan_.stiff_steps << " steps between two outputs (now at t = " << t
          << "): the model is too stiff for it";
      IntegratorFailure f(msg.str(), t);
      f.integrator_gave_up = true;
      throw f;
    }
    if (!stop_at_end_ && t >= target) {  // the last step of this run: act at the start of the next
      pending_ = true;
      pending_at_stop_ = at_stop;
      break;
    }
    if (act(t, at_stop)) continue;
    if (plan_.options->progress) {
      auto now = std::chrono::steady_clock::now();
      if (std::chrono::duration<double>(now - clock).count() >= plan_.options->progress_interval) {
        clock = now;
        plan_.options->progress(t);
      }
    }
  }
}

}  // namespace lagmb
