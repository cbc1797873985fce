// The fixed-step driver of the "ali3p" formulation (formulations/ali3p.hpp):
// steps of the fixed length `step`, the last one landing on the stop time,
// retries of a step near a singular position, cubic Hermite outputs.
//
// Singular positions: where Phi_q loses rank the exact multipliers may have a
// pole (lam ~ 1 / sigma, sigma the smallest singular value; Phi_q^T lam stays
// finite). A step landing within roundoff of such a position meets a nearly
// unsolvable system: Newton diverges, or converges with multipliers more
// than 10 times those of the step before (and above the size of M a and Q),
// where the local error of the step is large; the step is then retried
// with lengths 0.5, 1.5, 0.25, 1.75 h (counted in Stats::convergence_failures)
// so that it lands beside the singular position; the next steps take h again.
//
// Events (stops): after each step the event functions are evaluated at its
// end; a downward sign change is located on the step's cubic Hermite
// interpolant (regula falsi, Illinois variant), and the step is taken again
// to end there, so that the runner acts on a state of the method's own
// solution; the steps after the event take h again.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "formulations/ali3p.hpp"
#include "lagmb/events/event_runner.hpp"
#include "integrators/integrators.hpp"

namespace lagmb {

namespace {

class Ali3pStepper final : public Stepper {
 public:
  Ali3pStepper(const Model& model, const ConsistentState& start, const IntegrationPlan& plan)
      : form_(model, start, plan.options->newton_rtol,
              VecX::Constant(model.n_coordinates(), plan.options->newton_atol), plan.run),
        m_(model.n_constraints()),
        h_(plan.options->max_step),
        t_(plan.t0),
        stop_(plan.t_end),
        t_prev_(plan.t0),
        events_(plan.events && plan.events->size() > 0 ? plan.events : nullptr) {}

  const char* name() const override { return "ALI3-P"; }
  void set_stop(double stop) override { stop_ = stop; }

  double step(bool& at_stop) override {
    double h = h_;
    at_stop = false;
    // the last step lands on the stop time, stretched by up to 1 % rather
    // than followed by a sliver (t accumulates rounding over many steps)
    if (stop_ - t_ <= 1.01 * h) {
      h = stop_ - t_;
      at_stop = true;
    }
    form_.begin_step();
    t_prev_ = t_;
    // A step that lands very close to a singular position (Phi_q loses rank)
    // meets a nearly unsolvable system: the multipliers there grow like
    // 1 / sigma. Newton then stalls or diverges; the step is retried shorter
    // or longer so that it lands elsewhere; the next steps take h again.
    double err = INFINITY;
    int it = 0;
    const double lam_before = m_ ? form_.lam_prev.lpNorm<Eigen::Infinity>() : 0.0;
    for (int attempt = 0;; ++attempt) {
      // converged, and the multipliers did not jump by a factor > 10 (a
      // landing next to the pole; the last attempt is taken as it is)
      if (form_.newton(t_prev_ + h, h, it, err) &&
          (attempt == max_retries ||
           !(m_ && form_.lam.lpNorm<Eigen::Infinity>() > lam_jump * lam_before + form_.force_scale())))
        break;
      form_.undo_step();
      if (attempt == max_retries) fail(t_prev_ + h, "the Newton iteration did not converge", it, err);
      ++retries_;
      h = h_ * retry_factors[attempt];
      at_stop = false;
      if (t_prev_ + h >= stop_) {  // a longer retry must not pass a breakpoint or t_end
        h = stop_ - t_prev_;
        at_stop = true;
      }
    }
    double t1 = at_stop ? stop_ : t_prev_ + h;
    form_.finish_step(t1, h);
    if (events_ && crossing(t1, h)) {  // the step again, to the earliest crossing
      const double t_root = root_time_;
      form_.undo_step();
      form_.v = form_.v_prev, form_.a = form_.a_prev;
      h = t_root - t_prev_;
      if (!form_.newton(t_root, h, it, err)) fail(t_root, "the Newton iteration did not converge at an event", it, err);
      t1 = t_root;
      at_stop = false;
      form_.finish_step(t1, h);
    }
    t_ = t1;
    ++steps_;
    return t_;
  }

  bool root_found(std::vector<int>& fired) override {
    if (!at_root_) return false;
    fired = fired_;
    at_root_ = false;
    return true;
  }
  const double* velocities() const override { return form_.v.data(); }

  void interpolate(double t, const double*& q, const double*& v) override {
    // cubic Hermite through (q, v) at both ends of the last step
    const double h = t_ - t_prev_;
    if (!(h > 0.0)) {
      q_out_ = form_.q;
      v_out_ = form_.v;
    } else {
      const double s = std::clamp((t - t_prev_) / h, 0.0, 1.0), s2 = s * s, s3 = s2 * s;
      const double h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
      const double d10 = 3 * s2 - 4 * s + 1, d01 = (-6 * s2 + 6 * s) / h, d11 = 3 * s2 - 2 * s;
      // h00 = 1 - h01 and d00 = -d01: in differences, which neither cancel
      // nor overflow where q is large (an angle of 1e308 rad)
      const VecX dq = form_.q - form_.q_prev;
      q_out_ = form_.q_prev + h01 * dq + h * (h10 * form_.v_prev + h11 * form_.v);
      v_out_ = d01 * dq + d10 * form_.v_prev + d11 * form_.v;
    }
    q = q_out_.data();
    v = v_out_.data();
  }

  void restart(double t) override {
    form_.restart(t);
    t_ = t_prev_ = t;
    g_valid_ = false;
  }

  void reset(double t, const ConsistentState& state) override {
    form_.q = form_.q_prev = state.q;
    form_.v = form_.v_prev = state.v;
    form_.a = form_.a_prev = state.qdd;
    form_.lam = form_.lam_prev = state.lam;
    t_ = t_prev_ = t;
    g_valid_ = false;
  }

  const double* positions() const override { return form_.q.data(); }

  void fill_stats(Stats& s) override {
    form_.count(s);
    s.steps = steps_;
    s.convergence_failures = retries_;
    s.last_order = 2;
    s.last_step = t_ - t_prev_;
  }

 private:
  static constexpr int max_retries = 4;
  static constexpr double lam_jump = 10.0;
  /// Lengths of the retries of a step, in units of h: shorter, then longer
  /// (stepping over the singular position), then more so.
  static constexpr double retry_factors[max_retries] = {0.5, 1.5, 0.25, 1.75};

  [[noreturn]] void fail(double t, const char* why, int iterations, double err) const {
    std::ostringstream msg;
    msg << "ALI3-P failed in the step from t = " << t_prev_ << " to " << t << ": " << why << " after "
        << iterations << " Newton iterations (weighted |dq| = " << err << ", 1 needed; step " << h_
        << " s). Try a smaller step.";
    throw IntegratorFailure(msg.str(), t_prev_);
  }

  /// The event functions at time t on the last step's interpolant (into g).
  void values_at(double t, std::vector<double>& g) {
    const double *q = nullptr, *v = nullptr;
    interpolate(t, q, v);
    events_->values(t, q, v, g.data());
  }

  /// Whether an event function of direction -1 crossed downward in the step
  /// just converged (t_prev_, t1]; then root_time_ is the earliest crossing
  /// and fired_ flags the functions crossing there (within the time
  /// tolerance). g at the step's start is kept from the step before (or
  /// evaluated after a restart).
  bool crossing(double t1, double h) {
    const int count = events_->size();
    const int* dir = events_->directions();
    t_ = t1;  // (interpolate() reads the step as [t_prev_, t_])
    if (!g_valid_) {
      g_start_.resize(count);
      events_->values(t_prev_, form_.q_prev.data(), form_.v_prev.data(), g_start_.data());
    }
    g_end_.resize(count);
    events_->values(t1, form_.q.data(), form_.v.data(), g_end_.data());
    const double t_tol = 1e-12 * (std::abs(t1) + h);
    double earliest = INFINITY;
    std::vector<double> root(count, INFINITY);
    std::vector<double> g(count);
    for (int i = 0; i < count; ++i) {
      if (dir[i] >= 0 || !(g_start_[i] > 0.0 && g_end_[i] < 0.0)) continue;
      // Illinois regula falsi on g_i along the interpolant
      double a = t_prev_, b = t1, ga = g_start_[i], gb = g_end_[i];
      int side = 0;
      for (int it = 0; it < 100 && b - a > t_tol; ++it) {
        const double c = std::clamp(b - gb * (b - a) / (gb - ga), a + 0.01 * (b - a), b - 0.01 * (b - a));
        values_at(c, g);
        if (g[i] > 0.0) {
          a = c, ga = g[i];
          if (side == 1) gb *= 0.5;
          side = 1;
        } else {
          b = c, gb = g[i];
          if (side == -1) ga *= 0.5;
          side = -1;
        }
      }
      root[i] = b;  // (the end past the crossing: the runner acts there)
      earliest = std::min(earliest, b);
    }
    g_start_ = g_end_;
    g_valid_ = true;
    if (!(earliest < INFINITY)) return false;
    fired_.assign(count, 0);
    for (int i = 0; i < count; ++i)
      if (root[i] <= earliest + 10.0 * t_tol) fired_[i] = -1;  // (falling, as SUNDIALS' root info)
    root_time_ = earliest;
    at_root_ = true;
    g_valid_ = false;  // (the state after the event is new)
    return true;
  }

  Ali3pFormulation form_;
  int m_;
  double h_;
  double t_, stop_, t_prev_;
  VecX q_out_, v_out_;
  long steps_ = 0, retries_ = 0;
  EventRunner* events_;  // null: no event functions
  std::vector<double> g_start_, g_end_;
  bool g_valid_ = false, at_root_ = false;
  std::vector<int> fired_;
  double root_time_ = 0.0;
};

}  // namespace

std::unique_ptr<Stepper> make_ali3p_stepper(const Model& model, const ConsistentState& start,
                                            const IntegrationPlan& plan) {
  return std::make_unique<Ali3pStepper>(model, start, plan);
}

}  // namespace lagmb
