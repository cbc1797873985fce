// CVODE (BDF or Adams-Moulton) driving the "projection" formulation
// (formulations/projection.hpp): SUNDIALS plumbing, a linear solver that hands
// CVODE's Newton systems to the formulation, and the stepper.
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>

#include <exception>
#include "integrators/ode_callbacks.hpp"

namespace lagmb {

namespace {

/// The Newton "matrix" I + c J, held implicitly: CVODE only scales it
/// (SUNMatScaleAddI with c = -gamma), copies and zeroes it; the linear solver
/// assembles the saddle-point form with that gamma.
struct ImplicitMatrix {
  double c = 0.0;
};

ImplicitMatrix& imat(SUNMatrix A) { return *static_cast<ImplicitMatrix*>(A->content); }

SUNMatrix make_implicit_matrix(SUNContext ctx);

SUNMatrix clone_implicit(SUNMatrix A) {
  SUNMatrix B = make_implicit_matrix(A->sunctx);
  imat(B) = imat(A);
  return B;
}

SUNMatrix make_implicit_matrix(SUNContext ctx) {
  SUNMatrix M = SUNMatNewEmpty(ctx);
  if (!M) return nullptr;
  M->content = new ImplicitMatrix;
  M->ops->getid = [](SUNMatrix) { return SUNMATRIX_CUSTOM; };
  M->ops->clone = clone_implicit;
  M->ops->zero = [](SUNMatrix A) -> int {
    imat(A).c = 0.0;
    return 0;
  };
  M->ops->copy = [](SUNMatrix A, SUNMatrix B) -> int {
    imat(B) = imat(A);
    return 0;
  };
  M->ops->scaleaddi = [](sunrealtype c, SUNMatrix A) -> int {
    imat(A).c = c;
    return 0;
  };
  M->ops->destroy = [](SUNMatrix A) {
    delete static_cast<ImplicitMatrix*>(A->content);
    A->content = nullptr;
    SUNMatFreeEmpty(A);
  };
  return M;
}

SUNLinearSolver make_saddle_solver(SUNContext ctx, OdeUserData* p) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  S->content = p;
  S->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  S->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  S->ops->setup = [](SUNLinearSolver S, SUNMatrix A) -> int {
    return guarded(S->content, [&](OdeUserData& p) { return p.ode.setup(-imat(A).c) ? 0 : SUNLS_LUFACT_FAIL; });
  };
  S->ops->solve = [](SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) -> int {
    auto* p = static_cast<OdeUserData*>(S->content);
    p->ode.solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
    return 0;
  };
  S->ops->free = [](SUNLinearSolver S) -> int {
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return 0;
  };
  return S;
}

int jac_fn(sunrealtype t, N_Vector y, N_Vector, SUNMatrix, void* data, N_Vector, N_Vector, N_Vector) {
  return guarded(data, [&](OdeUserData& p) { return p.ode.linearize(t, N_VGetArrayPointer(y)) ? 0 : 1; });
}

int proj_fn(sunrealtype t, N_Vector y, N_Vector corr, sunrealtype, N_Vector err, void* data) {
  return guarded(data, [&](OdeUserData& p) {
    double* yy = N_VGetArrayPointer(y);
    return p.ode.project(t, yy, yy + p.ode.n(), N_VGetArrayPointer(corr), err ? N_VGetArrayPointer(err) : nullptr);
  });
}

struct CvodeSession : OdeSession {
  using OdeSession::OdeSession;
  void* mem = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  ~CvodeSession() {
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
  }
};

/// What a CVODE stepper owns, built before its OdeStepper base (which
/// refers to the state vector and the callbacks' data).
struct CvodeParts {
  CvodeParts(const Model& model, double alpha, double beta, const ConsistentState& start, const IntegrationPlan& plan)
      : ode_(model, alpha, beta, plan.run), user_(ode_), s(start, plan.atol) {}
  ProjectionFormulation ode_;
  OdeUserData user_;
  CvodeSession s;
};

/// CVODE behind the shared stepping loop.
class CvodeStepper final : CvodeParts, public OdeStepper {
 public:
  CvodeStepper(const Model& model, bool adams, double alpha, double beta, const ConsistentState& start,
               const IntegrationPlan& plan)
      : CvodeParts(model, alpha, beta, start, plan), OdeStepper(s.y, user_), plan_(plan) {
    s.mem = CVodeCreate(adams ? CV_ADAMS : CV_BDF, s.ctx);
    if (!s.mem) throw std::runtime_error("lagmb: CVodeCreate failed");
    s.ctx.attach_cvode(s.mem);
    check(CVodeInit(s.mem, ode_rhs, plan.t0, s.y), "CVodeInit", s.ctx);
    check(CVodeSVtolerances(s.mem, plan.options->rtol, s.abstol), "CVodeSVtolerances", s.ctx);
    check(CVodeSetUserData(s.mem, &user_), "CVodeSetUserData", s.ctx);
    check(CVodeSetMaxOrd(s.mem, plan.max_order), "CVodeSetMaxOrd", s.ctx);
    if (plan.options->max_step > 0) check(CVodeSetMaxStep(s.mem, plan.options->max_step), "CVodeSetMaxStep", s.ctx);
    check(CVodeSetMinStep(s.mem, minimum_step(plan)), "CVodeSetMinStep", s.ctx);
    s.A = make_implicit_matrix(s.ctx);
    s.LS = make_saddle_solver(s.ctx, &user_);
    if (!s.A || !s.LS) throw std::runtime_error("lagmb: cannot create the CVODE linear solver");
    check(CVodeSetLinearSolver(s.mem, s.LS, s.A), "CVodeSetLinearSolver", s.ctx);
    check(CVodeSetJacFn(s.mem, jac_fn), "CVodeSetJacFn", s.ctx);
    if (ode_.n_constraints() > 0 && !adams) {  // CVODE's projection works with BDF only
      check(CVodeSetProjFn(s.mem, proj_fn), "CVodeSetProjFn", s.ctx);
      // keep the error estimate as it is: projected onto the manifold it
      // vanishes for a fully driven mechanism and the steps run away
      check(CVodeSetProjErrEst(s.mem, SUNFALSE), "CVodeSetProjErrEst", s.ctx);
    }
    if (plan.events && plan.events->size() > 0) {  // only models with event elements
      user_.events = plan.events;
      check(CVodeRootInit(s.mem, plan.events->size(), ode_roots), "CVodeRootInit", s.ctx);
      check(CVodeSetRootDirection(s.mem, plan.events->directions()), "CVodeSetRootDirection", s.ctx);
    }
  }
  const char* name() const override { return "CVODE"; }
  void set_stop(double stop) override { check(CVodeSetStopTime(s.mem, stop), "CVodeSetStopTime", s.ctx); }
  double step(bool& at_stop) override {
    sunrealtype t = 0.0;
    const int flag = CVode(s.mem, plan_.t_end, s.y, &t, CV_ONE_STEP);
    rethrow_callback_error(p, t);
    if (flag < 0) {
      sunrealtype h = 0;
      CVodeGetCurrentStep(s.mem, &h);
      throw solver_failure("CVODE", t, h, flag, CVodeGetReturnFlagName(flag), s.ctx.sink().message);
    }
    at_stop = flag == CV_TSTOP_RETURN;
    at_root = flag == CV_ROOT_RETURN;
    return t;
  }
  void root_info(int* fired) override { check(CVodeGetRootInfo(s.mem, fired), "CVodeGetRootInfo", s.ctx); }
  void interpolate(double t, const double*& q, const double*& v) override {
    check(CVodeGetDky(s.mem, t, 0, s.out), "CVodeGetDky", s.ctx);
    q = N_VGetArrayPointer(s.out);
    v = q + n;
  }
  void restart(double t) override {
    fill_stats(before_);
    check(CVodeReInit(s.mem, t, s.y), "CVodeReInit", s.ctx);
  }
  void fill_stats(Stats& stats) override {
    const Stats b = before_;
    long v = 0;
    CVodeGetNumSteps(s.mem, &v), stats.steps = b.steps + v;
    CVodeGetNumRhsEvals(s.mem, &v), stats.residual_evals = b.residual_evals + v;
    CVodeGetNumJacEvals(s.mem, &v), stats.jacobian_evals = b.jacobian_evals + v;
    CVodeGetNumNonlinSolvIters(s.mem, &v), stats.newton_iterations = b.newton_iterations + v;
    CVodeGetNumErrTestFails(s.mem, &v), stats.error_test_failures = b.error_test_failures + v;
    CVodeGetNumNonlinSolvConvFails(s.mem, &v), stats.convergence_failures = b.convergence_failures + v;
    int order = 0;
    CVodeGetLastOrder(s.mem, &order), stats.last_order = order;
    sunrealtype h = 0;
    CVodeGetLastStep(s.mem, &h), stats.last_step = h;
    p.ode.count(stats);
  }

 private:
  const IntegrationPlan& plan_;
  Stats before_;  // counts of the segments before the last CVodeReInit (which zeroes them)
};

}  // namespace

std::unique_ptr<Stepper> make_cvode_stepper(const Model& model, bool adams, double alpha, double beta,
                                            const ConsistentState& start, const IntegrationPlan& plan) {
  return std::make_unique<CvodeStepper>(model, adams, alpha, beta, start, plan);
}

}  // namespace lagmb
