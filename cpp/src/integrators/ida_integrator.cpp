// IDA (variable-order, variable-step BDF) on a DaeFormulation.
#include <idas/idas.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <sstream>

#include "formulations/dae.hpp"
#include "lagmb/events/event_runner.hpp"
#include "integrators/integrators.hpp"
#include "lagmb/solvers/sundials.hpp"
#include "lagmb/time_function.hpp"
#include "solvers/nvector_ops.hpp"
#include "solvers/sparse_lu_solver.hpp"
#include "solvers/sun_compat.hpp"

namespace lagmb {

namespace {

struct Callbacks {
  DaeFormulation* dae = nullptr;
  std::exception_ptr error;  // a C++ exception must not cross SUNDIALS' C frames
  void* mem = nullptr;
  double rtol = 0.0, h_default = 0.0;
  const double* abstol = nullptr;
  const double* id = nullptr;
  std::vector<int> level;  // index of each component (DaeFormulation::index_levels)
  bool scale_relative = false;
  EventRunner* events = nullptr;
  bool fresh = false;  // restarted from a new state: weights for h_default until a step is taken
  SensitivityPlan* sens = nullptr;
  std::vector<const double*> s, sp;  // scratch of sensitivity_residual_fn
  std::vector<double*> out;
  // the state of the last sensitivity residual and its F_p (one per
  // parameter): the corrector iterates on s at one converged state
  double sens_t = 0.0;
  VecX sens_y, sens_yp;
  std::vector<VecX> F_p;
};

/// Error weights. An index-k component (k = 2, 3: multipliers and, in the
/// index-3 form, velocities) is fixed by the constraints only to (roundoff
/// in Phi) x cj^(k-1), cj ~ 1/h, so its absolute tolerance is divided by
/// h^(k-1), as RADAU5 does (Hairer & Wanner, Solving ODEs II, VII.8); that
/// governs both the Newton convergence test and, for components in the error
/// test, the error test; forms that keep such components in the error test
/// scale the relative part as well (RADAU5 scales the whole error). Index-1
/// components get 1 / (rtol |y| + atol). The multipliers of rows the run
/// leaves out (an open stop, a redundant row) stay 0 and add nothing to a
/// norm but its count N: the weights are scaled by sqrt(N / (N - those)),
/// so that the WRMS norms are those of the rows that count.
int weights_fn(N_Vector yv, N_Vector ewtv, void* data) {
  auto* cb = static_cast<Callbacks*>(data);
  sun::real h = 0.0;
  IDAGetCurrentStep(cb->mem, &h);
  const double inv_h = 1.0 / (h > 0.0 && !cb->fresh ? h : cb->h_default);
  const double* y = N_VGetArrayPointer(yv);
  double* ewt = N_VGetArrayPointer(ewtv);
  const sun::index N = N_VGetLength(yv);
  const double counted = std::sqrt(double(N) / double(N - cb->dae->left_out_components()));
  for (sun::index i = 0; i < N; ++i) {
    double a = cb->abstol[i], r = cb->rtol * std::abs(y[i]);
    for (int k = 1; k < cb->level[i]; ++k) {
      a *= inv_h;
      if (cb->scale_relative) r *= inv_h;
    }
    const double tol = r + a;
    if (!(tol > 0.0)) return -1;
    ewt[i] = counted / tol;
  }
  return 0;
}

int residual_fn(sun::real t, N_Vector y, N_Vector yp, N_Vector F, void* data) {
  auto* cb = static_cast<Callbacks*>(data);
  try {
    return cb->dae->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), N_VGetArrayPointer(F));
  } catch (...) {
    cb->error = std::current_exception();
    return -1;
  }
}

int jacobian_fn(sun::real t, sun::real cj, N_Vector y, N_Vector yp, N_Vector, SUNMatrix, void* data,
                N_Vector, N_Vector, N_Vector) {
  auto* cb = static_cast<Callbacks*>(data);
  try {
    cb->dae->newton_matrix(t, cj, N_VGetArrayPointer(y), N_VGetArrayPointer(yp));
    return 0;
  } catch (...) {
    cb->error = std::current_exception();
    return -1;
  }
}

/// The sensitivity residuals F_y s_i + F_y' s_i' + F_p_i (SensitivityPlan).
int sensitivity_residual_fn(int Ns, sun::real t, N_Vector y, N_Vector yp, N_Vector, N_Vector* yS, N_Vector* ypS,
                            N_Vector* resS, void* data, N_Vector tmp1, N_Vector tmp2, N_Vector) {
  auto* cb = static_cast<Callbacks*>(data);
  try {
    const double *yy = N_VGetArrayPointer(y), *yyp = N_VGetArrayPointer(yp);
    cb->s.resize(Ns), cb->sp.resize(Ns), cb->out.resize(Ns);
    for (int i = 0; i < Ns; ++i) {
      cb->s[i] = N_VGetArrayPointer(yS[i]);
      cb->sp[i] = N_VGetArrayPointer(ypS[i]);
      cb->out[i] = N_VGetArrayPointer(resS[i]);
    }
    const int N = int(N_VGetLength(y));
    const Eigen::Map<const VecX> y_now(yy, N), yp_now(yyp, N);
    const bool same = int(cb->F_p.size()) == Ns && cb->sens_t == t && cb->sens_y == y_now && cb->sens_yp == yp_now;
    if (!cb->dae->sensitivity_products(t, yy, yyp, same, Ns, cb->s.data(), cb->sp.data(), cb->out.data()))
      return -1;
    if (!same) {  // F_p = (F(p + delta) - F(p - delta)) / (2 delta) at this state
      cb->F_p.resize(Ns);
      double *plus = N_VGetArrayPointer(tmp1), *minus = N_VGetArrayPointer(tmp2);
      for (int i = 0; i < Ns; ++i) {
        if (int flag = cb->sens->plus[i]->residual(t, yy, yyp, plus)) return cb->F_p.clear(), flag;
        if (int flag = cb->sens->minus[i]->residual(t, yy, yyp, minus)) return cb->F_p.clear(), flag;
        cb->F_p[i] = (Eigen::Map<const VecX>(plus, N) - Eigen::Map<const VecX>(minus, N)) * (0.5 / cb->sens->delta[i]);
      }
      cb->sens_t = t, cb->sens_y = y_now, cb->sens_yp = yp_now;
    }
    for (int i = 0; i < Ns; ++i) {
      Eigen::Map<VecX> o(cb->out[i], N);
      o += cb->F_p[i];
      if (!o.allFinite()) return 1;
    }
    return 0;
  } catch (...) {
    cb->error = std::current_exception();
    return -1;
  }
}

int root_fn(sun::real t, N_Vector y, N_Vector, sun::real* g, void* data) {
  auto* cb = static_cast<Callbacks*>(data);
  try {
    const double* yy = N_VGetArrayPointer(y);
    cb->events->values(t, cb->dae->q(yy), cb->dae->v(yy), g);
    return 0;
  } catch (...) {
    cb->error = std::current_exception();
    return -1;
  }
}

/// Frees what IDA was given, in the right order, whatever happens.
struct IdaSession {
  sun::Context ctx;
  void* mem = nullptr;
  N_Vector y = nullptr, yp = nullptr, id = nullptr, abstol = nullptr, out = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  sun::SparseLU lu;
  int Ns = 0;  // forward sensitivities
  N_Vector *yS = nullptr, *ypS = nullptr;
  ~IdaSession() {
    if (mem) IDAFree(&mem);
    if (yS) N_VDestroyVectorArray(yS, Ns);
    if (ypS) N_VDestroyVectorArray(ypS, Ns);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    for (N_Vector* v : {&y, &yp, &id, &abstol, &out})
      if (*v) N_VDestroy(*v);
  }
};

void check(int flag, const char* call, sun::Context& ctx) {
  if (flag < 0)
    throw std::runtime_error(std::string("lagmb: ") + call + " failed (" + std::to_string(flag) +
                             "): " + ctx.sink().message);
}

/// IDA's own first-step rule, h0 = min(1e-3 (t_end - t0), 0.5 / |y'|_WRMS),
/// over the index-1 differential components only; chosen here so that the weights
/// of the algebraic components (scaled by 1/h) are set for the step that is
/// actually tried first.
double initial_step(const IntegrationPlan& plan, const double* y, const double* yp, const Callbacks& cb,
                    int N) {
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < N; ++i) {
    if (!(cb.id[i] > 0.0) || cb.level[i] > 1) continue;
    const double w = yp[i] / (plan.options->rtol * std::abs(y[i]) + cb.abstol[i]);
    sum += w * w;
    ++count;
  }
  double h = 1e-3 * (plan.t_end - plan.t0);
  const double ypnorm = count ? std::sqrt(sum / count) : 0.0;
  if (ypnorm > 0.5 / h) h = 0.5 / ypnorm;
  if (plan.options->max_step > 0.0) h = std::min(h, plan.options->max_step);
  return h;
}

/// IDA behind the shared stepping loop; owns the formulation and the session.
class IdaStepper final : public Stepper {
 public:
  IdaStepper(std::unique_ptr<DaeFormulation> formulation, const ConsistentState& start, const IntegrationPlan& plan)
      : dae_(std::move(formulation)), plan(plan) {
    DaeFormulation& dae = *dae_;  // (made of the plan's run Data: methods.cpp)
    const int N = dae.size();
    s.y = N_VNew_Serial(N, s.ctx);
    s.yp = N_VNew_Serial(N, s.ctx);
    s.id = N_VNew_Serial(N, s.ctx);
    s.abstol = N_VNew_Serial(N, s.ctx);
    s.out = N_VNew_Serial(N, s.ctx);
    for (N_Vector v : {s.y, s.yp, s.id, s.abstol, s.out}) {
      if (!v) throw std::bad_alloc();
      sun::use_compiled_vector_ops(v);
    }
    dae.initial(start, N_VGetArrayPointer(s.y), N_VGetArrayPointer(s.yp));
    dae.ids(N_VGetArrayPointer(s.id));
    dae.tolerances(plan.atol, N_VGetArrayPointer(s.abstol));

    cb.dae = &dae;
    s.mem = IDACreate(s.ctx);
    if (!s.mem) throw std::runtime_error("lagmb: IDACreate failed");
    cb.mem = s.mem;
    cb.rtol = plan.options->rtol;
    cb.abstol = N_VGetArrayPointer(s.abstol);
    cb.id = N_VGetArrayPointer(s.id);
    cb.level.resize(N);
    dae.index_levels(cb.level.data());
    cb.scale_relative = dae.scale_relative_tolerance();
    cb.h_default = initial_step(plan, N_VGetArrayPointer(s.y), N_VGetArrayPointer(s.yp), cb, N);
    s.ctx.attach_ida(s.mem);
    check(IDAInit(s.mem, residual_fn, plan.t0, s.y, s.yp), "IDAInit", s.ctx);
    check(IDAWFtolerances(s.mem, weights_fn), "IDAWFtolerances", s.ctx);
    check(IDASetUserData(s.mem, &cb), "IDASetUserData", s.ctx);
    check(IDASetId(s.mem, s.id), "IDASetId", s.ctx);
    check(IDASetSuppressAlg(s.mem, SUNTRUE), "IDASetSuppressAlg", s.ctx);
    check(IDASetMaxOrd(s.mem, plan.max_order), "IDASetMaxOrd", s.ctx);
    if (plan.options->max_step > 0) check(IDASetMaxStep(s.mem, plan.options->max_step), "IDASetMaxStep", s.ctx);
    check(IDASetInitStep(s.mem, cb.h_default), "IDASetInitStep", s.ctx);
    // a step shorter than a few ulps of t cannot make progress: fail there
    // (a lock-up or a singular passage) instead of shrinking h for ever
    check(IDASetMinStep(s.mem, minimum_step(plan)), "IDASetMinStep", s.ctx);

    s.lu.row_scale = &dae.row_scale();
    s.lu.col_scale = &dae.col_scale();
    s.A = sun::make_matrix_view(s.ctx, &dae.matrix());
    s.LS = sun::make_sparse_lu_solver(s.ctx, &s.lu);
    if (!s.A || !s.LS) throw std::runtime_error("lagmb: cannot create the linear solver");
    check(IDASetLinearSolver(s.mem, s.LS, s.A), "IDASetLinearSolver", s.ctx);
    check(IDASetJacFn(s.mem, jacobian_fn), "IDASetJacFn", s.ctx);
    if (plan.events && plan.events->size() > 0) {  // only models with event elements
      cb.events = plan.events;
      check(IDARootInit(s.mem, plan.events->size(), root_fn), "IDARootInit", s.ctx);
      check(IDASetRootDirection(s.mem, plan.events->directions()), "IDASetRootDirection", s.ctx);
    }
    if (plan.sensitivities) start_sensitivities(*plan.sensitivities);
  }

  const char* name() const override { return "IDA"; }
  void set_stop(double stop) override { check(IDASetStopTime(s.mem, stop), "IDASetStopTime", s.ctx); }
  double step(bool& at_stop) override {
    sun::real t = 0.0;
    // in one-step mode tout only gives the direction (and, at the start, a scale)
    const int flag = IDASolve(s.mem, plan.t_end, &t, s.y, s.yp, IDA_ONE_STEP);
    if (cb.error) {
      try {
        std::rethrow_exception(cb.error);
      } catch (const UserFunctionError& e) {
        throw IntegratorFailure(e.what(), t);  // keeps the partial result
      }
    }
    if (flag < 0) {
      sun::real h = 0;
      IDAGetCurrentStep(s.mem, &h);
      std::ostringstream msg;
      msg << "IDA failed at t = " << t << " (step size " << h << "), flag " << flag << " ("
          << IDAGetReturnFlagName(flag) << "): " << s.ctx.sink().message;
      throw IntegratorFailure(msg.str(), t);
    }
    at_stop = flag == IDA_TSTOP_RETURN;
    at_root_ = flag == IDA_ROOT_RETURN;
    cb.fresh = false;
    return t;
  }
  bool root_found(std::vector<int>& fired) override {
    if (!at_root_) return false;
    fired.assign(cb.events->size(), 0);
    check(IDAGetRootInfo(s.mem, fired.data()), "IDAGetRootInfo", s.ctx);
    return true;
  }
  const double* velocities() const override { return dae_->v(N_VGetArrayPointer(s.y)); }
  void reset(double t, const ConsistentState& state) override {
    // a jump of the state (an event, a new input) would make the
    // sensitivities jump too: a run with sensitivities ends there (its
    // outputs so far kept); the runs with sensitivities take no new inputs
    if (s.Ns) {
      IntegratorFailure f("the forward sensitivities cannot follow the motion through an event at t = " +
                              to_text(t) + " (an impact, or a stop holding or letting go of its joint: the "
                              "equations or the state jump there, and their derivatives with them); the outputs "
                              "before it are kept in the partial result",
                          t);
      f.diagnose = false;
      throw f;
    }
    dae_->initial(state, N_VGetArrayPointer(s.y), N_VGetArrayPointer(s.yp));
    restart(t);
  }
  void interpolate(double t, const double*& q, const double*& v) override {
    check(IDAGetDky(s.mem, t, 0, s.out), "IDAGetDky", s.ctx);
    const double* yo = N_VGetArrayPointer(s.out);
    q = dae_->q(yo);
    v = dae_->v(yo);
  }
  const double* positions() const override { return dae_->q(N_VGetArrayPointer(s.y)); }
  void restart(double t) override {
    fill_stats(before_);
    // a new first step, and weights for it (as at the start): the index-2
    // and index-3 weights scale with 1/h, and the last step before the
    // restart says nothing about the first step after it (IDA takes the
    // one set here; the weights of the last step's h would make index 3's
    // Newton test 1e4 times too strict or too loose). The rule's 1e-3 of
    // the whole run, not of the time left: events on every step would
    // otherwise creep toward t_end in ever smaller steps
    cb.h_default = initial_step(plan, N_VGetArrayPointer(s.y), N_VGetArrayPointer(s.yp), cb, dae_->size());
    cb.fresh = true;
    check(IDASetInitStep(s.mem, cb.h_default), "IDASetInitStep", s.ctx);
    if (s.Ns) {  // the sensitivities go on from where they are (the state is continuous here)
      for (int i = 0; i < s.Ns; ++i) {
        check(IDAGetSensDky1(s.mem, t, 0, i, s.yS[i]), "IDAGetSensDky1", s.ctx);
        check(IDAGetSensDky1(s.mem, t, 1, i, s.ypS[i]), "IDAGetSensDky1", s.ctx);
      }
    }
    check(IDAReInit(s.mem, t, s.y, s.yp), "IDAReInit", s.ctx);
    if (s.Ns) check(IDASensReInit(s.mem, IDA_STAGGERED, s.yS, s.ypS), "IDASensReInit", s.ctx);
  }
  void sensitivities(double t, std::vector<VecX>& out, std::vector<VecX>& out_p) override {
    if (!s.Ns) throw std::logic_error("lagmb: this run has no sensitivities");
    const int N = dae_->size();
    out.resize(s.Ns), out_p.resize(s.Ns);
    long steps = 0;
    IDAGetNumSteps(s.mem, &steps);
    for (int i = 0; i < s.Ns; ++i) {
      out[i].resize(N), out_p[i].resize(N);
      if (steps == 0 && before_.steps == 0) {  // at the start: no step to interpolate in yet
        out[i] = plan.sensitivities->s0[i];
        out_p[i] = plan.sensitivities->sp0[i];
        continue;
      }
      check(IDAGetSensDky1(s.mem, t, 0, i, s.out), "IDAGetSensDky1", s.ctx);
      out[i] = Eigen::Map<const VecX>(N_VGetArrayPointer(s.out), N);
      check(IDAGetSensDky1(s.mem, t, 1, i, s.out), "IDAGetSensDky1", s.ctx);
      out_p[i] = Eigen::Map<const VecX>(N_VGetArrayPointer(s.out), N);
    }
  }
  void fill_stats(Stats& stats) override {
    const Stats b = before_;
    long v = 0;
    IDAGetNumSteps(s.mem, &v), stats.steps = b.steps + v;
    IDAGetNumResEvals(s.mem, &v), stats.residual_evals = b.residual_evals + v;
    IDAGetNumJacEvals(s.mem, &v), stats.jacobian_evals = b.jacobian_evals + v;
    IDAGetNumNonlinSolvIters(s.mem, &v), stats.newton_iterations = b.newton_iterations + v;
    IDAGetNumErrTestFails(s.mem, &v), stats.error_test_failures = b.error_test_failures + v;
    IDAGetNumNonlinSolvConvFails(s.mem, &v), stats.convergence_failures = b.convergence_failures + v;
    int order = 0;
    IDAGetLastOrder(s.mem, &order), stats.last_order = order;
    sun::real h = 0;
    IDAGetLastStep(s.mem, &h), stats.last_step = h;
    stats.lu_factorizations = s.lu.factorizations;
    stats.lu_nonzeros = s.lu.lu.factor_nonzeros();
    stats.element_evaluations = dae_->element_evaluations();
  }

 private:
  /// IDAS' forward sensitivities with the staggered corrector (the
  /// sensitivity systems solved after the state's Newton iteration
  /// converged, with its Newton matrix), tolerances estimated from the
  /// state's weights scaled by pbar, and the sensitivities in the error test.
  void start_sensitivities(SensitivityPlan& sens) {
    const int N = dae_->size();
    cb.sens = &sens;
    s.Ns = sens.count();
    s.yS = N_VCloneVectorArray(s.Ns, s.y);
    s.ypS = N_VCloneVectorArray(s.Ns, s.y);
    if (!s.yS || !s.ypS) throw std::bad_alloc();
    for (int i = 0; i < s.Ns; ++i) {
      std::copy(sens.s0[i].data(), sens.s0[i].data() + N, N_VGetArrayPointer(s.yS[i]));
      std::copy(sens.sp0[i].data(), sens.sp0[i].data() + N, N_VGetArrayPointer(s.ypS[i]));
    }
    check(IDASensInit(s.mem, s.Ns, IDA_STAGGERED, sensitivity_residual_fn, s.yS, s.ypS), "IDASensInit", s.ctx);
    check(IDASetSensParams(s.mem, nullptr, sens.scale.data(), nullptr), "IDASetSensParams", s.ctx);
    check(IDASensEEtolerances(s.mem), "IDASensEEtolerances", s.ctx);
    check(IDASetSensErrCon(s.mem, SUNTRUE), "IDASetSensErrCon", s.ctx);
  }

  std::unique_ptr<DaeFormulation> dae_;
  const IntegrationPlan& plan;
  IdaSession s;
  Callbacks cb;
  Stats before_;  // counts of the segments before the last IDAReInit (which zeroes them)
  bool at_root_ = false;
};

}  // namespace

std::string sundials_version() { return SUNDIALS_VERSION; }

std::unique_ptr<Stepper> make_ida_stepper(std::unique_ptr<DaeFormulation> dae, const ConsistentState& start,
                                          const IntegrationPlan& plan) {
  return std::make_unique<IdaStepper>(std::move(dae), start, plan);
}

}  // namespace lagmb
