// CVODE (BDF or Adams-Moulton) on the ODE in accelerations with coordinate
// projection: the "projection" formulation.
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <exception>
#include <sstream>

#include "events.hpp"
#include "integrators.hpp"
#include "lagmb/assembly.hpp"
#include "lagmb/time_function.hpp"
#include "sparse_lu_solver.hpp"
#include "sun_compat.hpp"

namespace lagmb {

namespace {

/// y = (q, v); f(t, y) = (v, qdd) with qdd, lam from the augmented system.
///
/// Newton matrix I - gamma J. J = [[0, I], [A_q, A_v]] with A the derivative
/// of qdd; we take the part that comes from the forces and the multipliers'
/// curvature, A_q ~ P M^-1 (Q_q - (Phi_q^T lam)_q), A_v ~ P M^-1 Q_v (P the
/// M-orthogonal projector on Phi_q a = 0), and leave out the derivatives of
/// gamma. Solving (I - gamma J) x = b then reduces to one sparse saddle-point
/// system of the size of the augmented matrix:
///   [ M - gamma Q_v - gamma^2 K   Phi_q^T ] [ x_v ]   [ M b_v + gamma K b_q ]
///   [ Phi_q                       0       ] [ mu  ] = [ Phi_q b_v           ]
///   x_q = b_q + gamma x_v,    K = Q_q - (Phi_q^T lam)_q.
struct OdeProblem {
  OdeProblem(const Model& m)
      : model(m), d(m), kkt(m), n(m.n_coordinates()), nc(m.n_constraints()) {
    qdd.resize(n);
    lam.resize(nc);
    lam_lin = VecX::Zero(nc);
    q_lin.resize(n);
    v_lin.resize(n);
    kappa.resize(nc);
    dq.resize(n);
    zero_n = VecX::Zero(n);
    // the Newton saddle-point pattern
    SparsityPattern p(n + nc, n + nc);
    auto add = [&](const SpMat& A, int r0, int c0, bool tr) {
      for (int c = 0; c < A.outerSize(); ++c)
        for (SpMat::InnerIterator it(A, c); it; ++it)
          tr ? p.add(r0 + c, c0 + int(it.row())) : p.add(r0 + int(it.row()), c0 + c);
    };
    for (int i = 0; i < n + nc; ++i) p.add(i, i);
    add(m.hessian_pattern(), 0, 0, false);
    add(m.force_q_pattern(), 0, 0, false);
    add(m.force_v_pattern(), 0, 0, false);
    add(m.jacobian_pattern(), n, 0, false);
    add(m.jacobian_pattern(), 0, n, true);
    N = p.build();
    for (int i = 0; i < n; ++i) diag.push_back(slot(N, i, i));
    hess = embed_slots(m.hessian_pattern(), N, 0, 0);
    Kq = embed_slots(m.force_q_pattern(), N, 0, 0);
    Cv = embed_slots(m.force_v_pattern(), N, 0, 0);
    G = embed_slots(m.jacobian_pattern(), N, n, 0);
    GT = embed_slots(m.jacobian_pattern(), N, 0, n, true);
    lu.analyzePattern(N);
    rhs.resize(n + nc);
    sol.resize(n + nc);
    Kb.resize(n);
    q0.resize(n);
    v0.resize(n);
    vnew.resize(n);
    Mv.resize(n);
    w.resize(nc);
  }

  /// qdd and lam at (t, q, v); false if the augmented matrix is singular.
  /// With Baumgarte terms: Phi_q qdd = gamma - 2 alpha (Phi_q v + Phi_t) - beta^2 Phi.
  bool accelerations(double t, const double* q, const double* v) {
    assemble_jacobian(model, d, q, t);
    if (!kkt.factorize(d)) return false;
    assemble_forces(model, d, q, v, t);
    assemble_gamma(model, d, q, v, t);
    if (alpha != 0.0) {
      assemble_phi_t(model, d, q, t);
      w = d.phi_t;
      add_jacobian_times(d, v, w.data());
      d.gamma -= 2.0 * alpha * w;
    }
    if (beta != 0.0) {
      assemble_constraints(model, d, q, t);
      d.gamma -= beta * beta * d.Phi;
    }
    kkt.solve(d.Q, d.gamma, qdd, lam);
    if (!model.friction_groups().empty()) solve_friction(model, d, kkt, q, v, t, qdd, lam);
    return qdd.allFinite();
  }

  /// Factorizes the Newton saddle-point matrix at the linearization point.
  bool setup(double gamma) {
    const double* q = q_lin.data();
    const double* v = v_lin.data();
    const VecX& M = model.mass_diagonal();
    double* x = N.valuePtr();
    N.coeffs().setZero();
    for (int i = 0; i < n; ++i) x[diag[i]] = M[i];
    assemble_jacobian(model, d, q, t_lin);
    for (size_t k = 0; k < G.size(); ++k) x[G[k]] = x[GT[k]] = d.Phi_q.valuePtr()[k];
    // K = Q_q - (Phi_q^T lam)_q, kept for the right side
    assemble_constraint_hessian(model, d, q, t_lin, lam_lin.data());
    for (size_t k = 0; k < hess.size(); ++k) x[hess[k]] += gamma * gamma * d.H.valuePtr()[k];
    if (!model.state_dependent_forces().empty()) {
      assemble_force_derivatives(model, d, q, v, t_lin);
      for (size_t k = 0; k < Kq.size(); ++k) x[Kq[k]] -= gamma * gamma * d.Q_q.valuePtr()[k];
      for (size_t k = 0; k < Cv.size(); ++k) x[Cv[k]] -= gamma * d.Q_v.valuePtr()[k];
    }
    if (!model.friction_groups().empty()) {
      // joint friction at the linearization multipliers; its dependence on
      // lam (through the reactions) is left out of this Newton matrix
      assemble_friction_derivatives(model, d, q, v, lam_lin.data());
      for (size_t k = 0; k < Kq.size(); ++k) x[Kq[k]] -= gamma * gamma * d.friction_Q_q.valuePtr()[k];
      for (size_t k = 0; k < Cv.size(); ++k) x[Cv[k]] -= gamma * d.friction_Q_v.valuePtr()[k];
    }
    ++factorizations;
    gamma_setup = gamma;
    return factorize_finite(lu, N);
  }

  /// x = (I - gamma J)^-1 b with the gamma of the last setup.
  void solve(const double* b, double* x) {
    const double g = gamma_setup;
    const VecX& M = model.mass_diagonal();
    Eigen::Map<const VecX> bq(b, n), bv(b + n, n);
    Eigen::Map<VecX> xq(x, n), xv(x + n, n);
    // K b_q = (Q_q - H) b_q, from the values still in d (same linearization)
    Kb.noalias() = -(d.H * bq);
    if (!model.state_dependent_forces().empty()) Kb.noalias() += d.Q_q * bq;
    if (!model.friction_groups().empty()) Kb.noalias() += d.friction_Q_q * bq;
    rhs.head(n) = M.cwiseProduct(bv) + g * Kb;
    rhs.tail(nc).setZero();
    add_jacobian_times(d, bv.data(), rhs.data() + n);
    sol = lu.solve(rhs);
    xv = sol.head(n);
    xq = bq + g * xv;
  }

  /// Projects (q, v) onto Phi = 0 and Phi_q v + Phi_t = 0 (least change in
  /// the M-metric), and the error estimate onto the tangent space.
  int project(double t, double* q, double* v, double* corr, double* err) {
    Eigen::Map<VecX> Q(q, n), V(v, n);
    q0 = Q;
    v0 = V;
    for (int it = 0; it < 3; ++it) {
      assemble_constraints(model, d, q, t);
      const double e = nc ? d.Phi.lpNorm<Eigen::Infinity>() : 0.0;
      if (e <= 1e-14 * (1.0 + Q.lpNorm<Eigen::Infinity>())) break;
      assemble_jacobian(model, d, q, t);
      if (!kkt.factorize(d)) return 1;
      d.Phi = -d.Phi;  // in place: no temporary
      kkt.solve(zero_n, d.Phi, dq, kappa);
      Q += dq;
    }
    assemble_jacobian(model, d, q, t);
    if (!kkt.factorize(d)) return 1;
    assemble_phi_t(model, d, q, t);
    Mv = model.mass_diagonal().cwiseProduct(V);
    d.phi_t = -d.phi_t;
    kkt.solve(Mv, d.phi_t, vnew, kappa);
    V = vnew;
    Eigen::Map<VecX>(corr, n) = Q - q0;
    Eigen::Map<VecX>(corr + n, n) = V - v0;
    if (err) {
      for (int part = 0; part < 2; ++part) {
        Eigen::Map<VecX> e(err + part * n, n);
        w.setZero();
        add_jacobian_times(d, e.data(), w.data());
        w = -w;
        kkt.solve(zero_n, w, dq, kappa);
        e += dq;
      }
    }
    ++projections;
    return 0;
  }

  const Model& model;
  Data d;
  AugmentedSystem kkt;
  int n, nc;
  VecX qdd, lam, lam_lin, q_lin, v_lin, kappa, dq, zero_n, rhs, sol;
  VecX Kb, q0, v0, vnew, Mv, w;  // scratch, sized once: no allocation per solve or projection
  double t_lin = 0.0, gamma_setup = 0.0;
  double alpha = 0.0, beta = 0.0;  // Baumgarte (Adams: CVODE projects only for BDF)
  SpMat N;
  std::vector<int> diag, hess, Kq, Cv, G, GT;
  Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>> lu;
  long factorizations = 0, projections = 0;
  std::exception_ptr error;
  EventRunner* events = nullptr;
};

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

SUNLinearSolver make_saddle_solver(SUNContext ctx, OdeProblem* p) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  S->content = p;
  S->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  S->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  S->ops->setup = [](SUNLinearSolver S, SUNMatrix A) -> int {
    auto* p = static_cast<OdeProblem*>(S->content);
    try {
      return p->setup(-imat(A).c) ? 0 : SUNLS_LUFACT_FAIL;
    } catch (...) {
      p->error = std::current_exception();
      return -1;
    }
  };
  S->ops->solve = [](SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) -> int {
    auto* p = static_cast<OdeProblem*>(S->content);
    p->solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
    return 0;
  };
  S->ops->free = [](SUNLinearSolver S) -> int {
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return 0;
  };
  return S;
}

int rhs_fn(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
  auto* p = static_cast<OdeProblem*>(data);
  try {
    const double* yy = N_VGetArrayPointer(y);
    double* f = N_VGetArrayPointer(ydot);
    if (!p->accelerations(t, yy, yy + p->n)) return 1;  // recoverable
    std::copy(yy + p->n, yy + 2 * p->n, f);
    std::copy(p->qdd.data(), p->qdd.data() + p->n, f + p->n);
    return 0;
  } catch (...) {
    p->error = std::current_exception();
    return -1;
  }
}

int jac_fn(sunrealtype t, N_Vector y, N_Vector, SUNMatrix, void* data, N_Vector, N_Vector, N_Vector) {
  auto* p = static_cast<OdeProblem*>(data);
  try {
    // the linearization point: state and multipliers at (t, y)
    const double* yy = N_VGetArrayPointer(y);
    if (!p->accelerations(t, yy, yy + p->n)) return 1;
    p->t_lin = t;
    p->q_lin = Eigen::Map<const VecX>(yy, p->n);
    p->v_lin = Eigen::Map<const VecX>(yy + p->n, p->n);
    p->lam_lin = p->lam;
    return 0;
  } catch (...) {
    p->error = std::current_exception();
    return -1;
  }
}

int proj_fn(sunrealtype t, N_Vector y, N_Vector corr, sunrealtype, N_Vector err, void* data) {
  auto* p = static_cast<OdeProblem*>(data);
  try {
    double* yy = N_VGetArrayPointer(y);
    return p->project(t, yy, yy + p->n, N_VGetArrayPointer(corr), err ? N_VGetArrayPointer(err) : nullptr);
  } catch (...) {
    p->error = std::current_exception();
    return -1;
  }
}

int root_fn(sunrealtype t, N_Vector y, sunrealtype* g, void* data) {
  auto* p = static_cast<OdeProblem*>(data);
  try {
    const double* yy = N_VGetArrayPointer(y);
    p->events->values(t, yy, yy + p->n, g);
    return 0;
  } catch (...) {
    p->error = std::current_exception();
    return -1;
  }
}

struct CvodeSession {
  sun::Context ctx;
  void* mem = nullptr;
  N_Vector y = nullptr, abstol = nullptr, out = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  ~CvodeSession() {
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    for (N_Vector* v : {&y, &abstol, &out})
      if (*v) N_VDestroy(*v);
  }
};

void check(int flag, const char* call, sun::Context& ctx) {
  if (flag < 0)
    throw std::runtime_error(std::string("lagmb: ") + call + " failed (" + std::to_string(flag) +
                             "): " + ctx.sink().message);
}

}  // namespace

void integrate_cvode(const Model& model, bool adams, double alpha, double beta, const ConsistentState& start,
                     const IntegrationPlan& plan,
                     const std::function<void(const double* q, const double* v)>& record, Stats& stats) {
  OdeProblem p(model);
  if (plan.run) p.d.join_run(model, *plan.run);
  p.alpha = alpha;
  p.beta = beta;
  CvodeSession s;
  const int n = p.n;
  s.y = N_VNew_Serial(2 * n, s.ctx);
  s.abstol = N_VNew_Serial(2 * n, s.ctx);
  s.out = N_VNew_Serial(2 * n, s.ctx);
  Eigen::Map<VecX>(N_VGetArrayPointer(s.y), n) = start.q;
  Eigen::Map<VecX>(N_VGetArrayPointer(s.y) + n, n) = start.v;
  Eigen::Map<VecX>(N_VGetArrayPointer(s.abstol), n) = plan.atol;
  Eigen::Map<VecX>(N_VGetArrayPointer(s.abstol) + n, n) = plan.atol;

  s.mem = CVodeCreate(adams ? CV_ADAMS : CV_BDF, s.ctx);
  if (!s.mem) throw std::runtime_error("lagmb: CVodeCreate failed");
  s.ctx.attach_cvode(s.mem);
  check(CVodeInit(s.mem, rhs_fn, plan.t0, s.y), "CVodeInit", s.ctx);
  check(CVodeSVtolerances(s.mem, plan.rtol, s.abstol), "CVodeSVtolerances", s.ctx);
  check(CVodeSetUserData(s.mem, &p), "CVodeSetUserData", s.ctx);
  check(CVodeSetMaxOrd(s.mem, plan.max_order), "CVodeSetMaxOrd", s.ctx);
  if (plan.max_step > 0) check(CVodeSetMaxStep(s.mem, plan.max_step), "CVodeSetMaxStep", s.ctx);
  check(CVodeSetMinStep(s.mem, minimum_step(plan)), "CVodeSetMinStep", s.ctx);
  s.A = make_implicit_matrix(s.ctx);
  s.LS = make_saddle_solver(s.ctx, &p);
  if (!s.A || !s.LS) throw std::runtime_error("lagmb: cannot create the CVODE linear solver");
  check(CVodeSetLinearSolver(s.mem, s.LS, s.A), "CVodeSetLinearSolver", s.ctx);
  check(CVodeSetJacFn(s.mem, jac_fn), "CVodeSetJacFn", s.ctx);
  if (p.nc > 0 && !adams) {  // CVODE's projection works with BDF only
    check(CVodeSetProjFn(s.mem, proj_fn), "CVodeSetProjFn", s.ctx);
    // keep the error estimate as it is: projected onto the manifold it
    // vanishes for a fully driven mechanism and the steps run away
    check(CVodeSetProjErrEst(s.mem, SUNFALSE), "CVodeSetProjErrEst", s.ctx);
  }
  if (plan.events && plan.events->size() > 0) {  // only models with event elements
    p.events = plan.events;
    check(CVodeRootInit(s.mem, plan.events->size(), root_fn), "CVodeRootInit", s.ctx);
    check(CVodeSetRootDirection(s.mem, plan.events->directions()), "CVodeSetRootDirection", s.ctx);
  }

  /// CVODE behind the shared stepping loop.
  struct CvodeStepper final : Stepper {
    CvodeSession& s;
    OdeProblem& p;
    double t_end;
    Stats before;  // counts of the segments before the last CVodeReInit (which zeroes them)
    CvodeStepper(CvodeSession& s_, OdeProblem& p_, double t_end_) : s(s_), p(p_), t_end(t_end_) {}
    const char* name() const override { return "CVODE"; }
    void set_stop(double stop) override { check(CVodeSetStopTime(s.mem, stop), "CVodeSetStopTime", s.ctx); }
    double step(bool& at_stop) override {
      sunrealtype t = 0.0;
      const int flag = CVode(s.mem, t_end, s.y, &t, CV_ONE_STEP);
      if (p.error) {
        try {
          std::rethrow_exception(p.error);
        } catch (const UserFunctionError& e) {
          throw IntegratorFailure(e.what(), t);  // keeps the partial result
        }
      }
      if (flag < 0) {
        sunrealtype h = 0;
        CVodeGetCurrentStep(s.mem, &h);
        std::ostringstream msg;
        msg << "CVODE failed at t = " << t << " (step size " << h << "), flag " << flag << " ("
            << CVodeGetReturnFlagName(flag) << "): " << s.ctx.sink().message;
        throw IntegratorFailure(msg.str(), t);
      }
      at_stop = flag == CV_TSTOP_RETURN;
      at_root = flag == CV_ROOT_RETURN;
      return t;
    }
    bool at_root = false;
    bool root_found(std::vector<int>& fired) override {
      if (!at_root) return false;
      fired.assign(p.events->size(), 0);
      check(CVodeGetRootInfo(s.mem, fired.data()), "CVodeGetRootInfo", s.ctx);
      return true;
    }
    const double* velocities() const override { return N_VGetArrayPointer(s.y) + p.n; }
    void reset(double t, const ConsistentState& state) override {
      Eigen::Map<VecX>(N_VGetArrayPointer(s.y), p.n) = state.q;
      Eigen::Map<VecX>(N_VGetArrayPointer(s.y) + p.n, p.n) = state.v;
      restart(t);
    }
    void interpolate(double t, const double*& q, const double*& v) override {
      check(CVodeGetDky(s.mem, t, 0, s.out), "CVodeGetDky", s.ctx);
      q = N_VGetArrayPointer(s.out);
      v = q + p.n;
    }
    const double* positions() const override { return N_VGetArrayPointer(s.y); }
    void restart(double t) override {
      fill_stats(before);
      check(CVodeReInit(s.mem, t, s.y), "CVodeReInit", s.ctx);
    }
    void fill_stats(Stats& stats) override {
      const Stats b = before;
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
      stats.lu_factorizations = p.factorizations;
      stats.augmented_factorizations = p.kkt.factorizations();
      stats.projections = p.projections;
      stats.element_evaluations = p.d.element_evaluations;
    }
  } stepper(s, p, plan.t_end);
  run_steps(stepper, plan, start, record, stats);
}

}  // namespace lagmb
