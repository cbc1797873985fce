// ARKODE's ERKStep (explicit Runge-Kutta with embedded error estimates)
// driving the "projection" formulation (formulations/projection.hpp): the
// ODE in accelerations, with q and v projected onto Phi = 0 and
// Phi_q v + Phi_t = 0 after every accepted step. For non-stiff mechanisms
// (long chains, free swinging): a few high-order steps where BDF takes many
// low-order ones.
#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <cmath>

#include "integrators/ode_callbacks.hpp"

namespace lagmb {

namespace {

/// After each accepted step: the mass-orthogonal projection of q onto
/// Phi(q, t) = 0, then of v onto Phi_q v + Phi_t = 0 (ProjectionFormulation::project).
int erk_project(sunrealtype t, N_Vector y, void* data) {
  return guarded(data, [&](OdeUserData& p) {
    double* yy = N_VGetArrayPointer(y);
    return p.ode.project(t, yy, yy + p.ode.n(), p.correction.data(), nullptr) == 0 ? 0 : -1;
  });
}

/// The Prince-Dormand RK8(7)13M pair (P. J. Prince and J. R. Dormand, High
/// order embedded Runge-Kutta formulae, J. Comput. Appl. Math. 7 (1981)
/// 67-75; the rational coefficients as tabulated in Hairer, Norsett and
/// Wanner, Solving ODEs I, sec. II.5): 13 stages, the 8th-order solution
/// carried on, the 7th-order one embedded for the error estimate. It
/// replaces ARKODE's order-8 default, Fehlberg 7(8), whose estimate is
/// h 41/840 (k1 + k11 - k12 - k13): stages 1 and 12 both at the step's start and
/// 11 and 13 both at its end, so it vanishes where f depends on t alone (a
/// quadrature) and nearly so where f hardly depends on y. A rod spinning
/// about a pin without gravity is such a problem (its accelerations depend on
/// the angle only, which every stage integrates exactly): Fehlberg's steps
/// grew to 18 s and the energy drifted 2.8 % at any rtol. Here the two
/// solutions' weights differ on c^7 ((b - d) . c^7 = 1.06e-4): a quadrature's
/// error is seen. (The coefficients, as
/// typed here, hold the row sums and b . c^k = 1/(k + 1) to k = 8, d . c^k
/// to k = 6, to 1e-17.)
ARKodeButcherTable prince_dormand_8_7() {
  constexpr int s = 13;
  double c[s] = {0.0, 1.0 / 18, 1.0 / 12, 1.0 / 8, 5.0 / 16, 3.0 / 8, 59.0 / 400, 93.0 / 200,
                 5490023248.0 / 9719169821, 13.0 / 20, 1201146811.0 / 1299019798, 1.0, 1.0};
  double A[s][s] = {};
  A[1][0] = 1.0 / 18;
  A[2][0] = 1.0 / 48, A[2][1] = 1.0 / 16;
  A[3][0] = 1.0 / 32, A[3][2] = 3.0 / 32;
  A[4][0] = 5.0 / 16, A[4][2] = -75.0 / 64, A[4][3] = 75.0 / 64;
  A[5][0] = 3.0 / 80, A[5][3] = 3.0 / 16, A[5][4] = 3.0 / 20;
  A[6][0] = 29443841.0 / 614563906, A[6][3] = 77736538.0 / 692538347, A[6][4] = -28693883.0 / 1125000000,
  A[6][5] = 23124283.0 / 1800000000;
  A[7][0] = 16016141.0 / 946692911, A[7][3] = 61564180.0 / 158732637, A[7][4] = 22789713.0 / 633445777,
  A[7][5] = 545815736.0 / 2771057229, A[7][6] = -180193667.0 / 1043307555;
  A[8][0] = 39632708.0 / 573591083, A[8][3] = -433636366.0 / 683701615, A[8][4] = -421739975.0 / 2616292301,
  A[8][5] = 100302831.0 / 723423059, A[8][6] = 790204164.0 / 839813087, A[8][7] = 800635310.0 / 3783071287;
  A[9][0] = 246121993.0 / 1340847787, A[9][3] = -37695042795.0 / 15268766246, A[9][4] = -309121744.0 / 1061227803,
  A[9][5] = -12992083.0 / 490766935, A[9][6] = 6005943493.0 / 2108947869, A[9][7] = 393006217.0 / 1396673457,
  A[9][8] = 123872331.0 / 1001029789;
  A[10][0] = -1028468189.0 / 846180014, A[10][3] = 8478235783.0 / 508512852, A[10][4] = 1311729495.0 / 1432422823,
  A[10][5] = -10304129995.0 / 1701304382, A[10][6] = -48777925059.0 / 3047939560,
  A[10][7] = 15336726248.0 / 1032824649, A[10][8] = -45442868181.0 / 3398467696, A[10][9] = 3065993473.0 / 597172653;
  A[11][0] = 185892177.0 / 718116043, A[11][3] = -3185094517.0 / 667107341, A[11][4] = -477755414.0 / 1098053517,
  A[11][5] = -703635378.0 / 230739211, A[11][6] = 5731566787.0 / 1027545527, A[11][7] = 5232866602.0 / 850066563,
  A[11][8] = -4093664535.0 / 808688257, A[11][9] = 3962137247.0 / 1805957418, A[11][10] = 65686358.0 / 487910083;
  A[12][0] = 403863854.0 / 491063109, A[12][3] = -5068492393.0 / 434740067, A[12][4] = -411421997.0 / 543043805,
  A[12][5] = 652783627.0 / 914296604, A[12][6] = 11173962825.0 / 925320556, A[12][7] = -13158990841.0 / 6184727034,
  A[12][8] = 3936647629.0 / 1978049680, A[12][9] = -160528059.0 / 685178525, A[12][10] = 248638103.0 / 1413531060;
  double b[s] = {14005451.0 / 335480064, 0, 0, 0, 0, -59238493.0 / 1068277825, 181606767.0 / 758867731,
                 561292985.0 / 797845732, -1041891430.0 / 1371343529, 760417239.0 / 1151165299,
                 118820643.0 / 751138087, -528747749.0 / 2220607170, 1.0 / 4};
  double d[s] = {13451932.0 / 455176623, 0, 0, 0, 0, -808719846.0 / 976000145, 1757004468.0 / 5645159321,
                 656045339.0 / 265891186, -3867574721.0 / 1518517206, 465885868.0 / 322736535,
                 53011238.0 / 667516719, 2.0 / 45, 0};
  return ARKodeButcherTable_Create(s, 8, 7, c, &A[0][0], b, d);
}

struct ErkSession : OdeSession {
  using OdeSession::OdeSession;
  void* mem = nullptr;
  ~ErkSession() {
    if (mem) ERKStepFree(&mem);
  }
};

/// The quintic Hermite interpolant of q on a step [t0, t0 + h] from q, v = q'
/// and a = q'' at both ends, and its derivative for v (errors O(h^6) and
/// O(h^5)); outputs are then projected onto the constraints. ARKODE's own
/// dense output for ERKStep is a cubic Hermite polynomial: with the long steps of a high-order method its error is
/// orders of magnitude above the steps' (4.6e-6 against 5e-10 on the double
/// pendulum at rtol 1e-9).
///   q(s) = H0 q0 + H5 q1 + h (H1 v0 + H4 v1) + h^2 (H2 a0 + H3 a1),  s = (t - t0) / h
/// with H0 = 1 - 10s^3 + 15s^4 - 6s^5, H5 = 1 - H0, H1 = s - 6s^3 + 8s^4 - 3s^5,
/// H4 = -4s^3 + 7s^4 - 3s^5, H2 = s^2/2 - 3s^3/2 + 3s^4/2 - s^5/2,
/// H3 = s^3/2 - s^4 + s^5/2.
void quintic_hermite(double s, double h, int n, const double* q0, const double* v0, const double* a0,
                     const double* q1, const double* v1, const double* a1, double* q, double* v) {
  const double s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
  const double H0 = 1 - 10 * s3 + 15 * s4 - 6 * s5, H1 = s - 6 * s3 + 8 * s4 - 3 * s5,
               H2 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5), H3 = 0.5 * (s3 - 2 * s4 + s5),
               H4 = -4 * s3 + 7 * s4 - 3 * s5;
  // d/ds of each, for v = dq/dt = (dq/ds) / h
  const double D0 = -30 * s2 + 60 * s3 - 30 * s4, D1 = 1 - 18 * s2 + 32 * s3 - 15 * s4,
               D2 = s - 4.5 * s2 + 6 * s3 - 2.5 * s4, D3 = 1.5 * s2 - 4 * s3 + 2.5 * s4,
               D4 = -12 * s2 + 28 * s3 - 15 * s4;
  for (int i = 0; i < n; ++i) {
    q[i] = H0 * q0[i] + (1 - H0) * q1[i] + h * (H1 * v0[i] + H4 * v1[i]) + h * h * (H2 * a0[i] + H3 * a1[i]);
    v[i] = D0 * (q0[i] - q1[i]) / h + D1 * v0[i] + D4 * v1[i] + h * (D2 * a0[i] + D3 * a1[i]);
  }
}

/// What an ERKStep stepper owns, built before its OdeStepper base (which
/// refers to the state vector and the callbacks' data).
struct ErkParts {
  ErkParts(const Model& model, const ConsistentState& start, const IntegrationPlan& plan)
      : ode_(model, 0.0, 0.0, plan.run), user_(ode_), s(start, plan.atol) {}
  ProjectionFormulation ode_;
  OdeUserData user_;
  ErkSession s;
};

/// ERKStep behind the shared stepping loop.
struct ErkStepper final : ErkParts, OdeStepper {
  const IntegrationPlan& plan;
  Stats before;  // counts of the segments before the last ERKStepReInit (which zeroes them)
  // the last step's ends, (q, v) and their accelerations (computed when an
  // output falls inside the step), for the interpolant
  struct End {
    double t = 0.0;
    VecX y, f;  // y = (q, v), f = (v, a)
    bool has_f = false;
  } start_, end_;
  VecX out_;
  long extra_rhs_ = 0;  // accelerations at step ends for outputs
  double first_h_ = 0.0;  // the first step (0: ARKODE's estimate), kept for every segment as ReInit kept it
  double resume_h_ = 0.0;  // resume(): the first step of a segment after an input's jump
  int order_ = 0;            // of the segment's pair (0: plan.max_order; resume() may lower it)
  bool resuming_ = false;
  double stop_ = NAN;  // the stop time last set (set_stop), for a step tried again
  double segment_start_ = 0.0;  // the last restart's time
  N_Vector error_ = nullptr, weight_ = nullptr;  // resume()'s scratch: the last step's error and weights

  ARKodeButcherTable pair_8_7_ = nullptr;  // (ERKStepSetTable copies it)

  ~ErkStepper() override {
    if (error_) N_VDestroy(error_), N_VDestroy(weight_);
    if (pair_8_7_) ARKodeButcherTable_Free(pair_8_7_);
  }
  ErkStepper(const Model& model, const ConsistentState& start, const IntegrationPlan& plan_)
      : ErkParts(model, start, plan_), OdeStepper(s.y, user_), plan(plan_), out_(2 * n) {
    first_h_ = first_step();
    segment_start_ = plan.t0;
    create(plan.t0);
    mark(plan.t0);
  }
  /// A new ERKStep memory from s.y at t with the run's settings. A restart
  /// of a model with event functions builds a new one rather than calling
  /// ERKStepReInit (one without them reinitializes): ARKODE (6.4 to
  /// 7.5, unlike CVODE and IDA) keeps its "a root was returned" flag across
  /// ReInit, so after the first step of the new segment it evaluates the
  /// root functions again at the segment's start on that step's
  /// interpolant, and a stop that rebounded there (its gap 0 to rounding)
  /// can read just beyond its limit: a crossing back within that step is
  /// then not a sign change and is missed.
  void create(double t) {
    const bool roots = plan.events && plan.events->size() > 0;
    if (s.mem && !roots) {  // (no root functions, no flag to fear: ReInit keeps the settings and memory)
      check(ERKStepReInit(s.mem, ode_rhs, t, s.y), "ERKStepReInit", s.ctx);
      set_pair();
      check(ERKStepSetInitStep(s.mem, resume_h_ > 0.0 ? resume_h_ : first_h_), "ERKStepSetInitStep", s.ctx);
      return;
    }
    if (s.mem) ERKStepFree(&s.mem);
    s.mem = ERKStepCreate(ode_rhs, t, s.y, s.ctx);
    if (!s.mem) throw std::runtime_error("lagmb: ERKStepCreate failed");
    s.ctx.attach_erkstep(s.mem);
    check(ERKStepSVtolerances(s.mem, plan.options->rtol, s.abstol), "ERKStepSVtolerances", s.ctx);
    check(ERKStepSetUserData(s.mem, &user_), "ERKStepSetUserData", s.ctx);
    set_pair();
    if (plan.options->max_step > 0) check(ERKStepSetMaxStep(s.mem, plan.options->max_step), "ERKStepSetMaxStep", s.ctx);
    check(ERKStepSetMinStep(s.mem, minimum_step(plan)), "ERKStepSetMinStep", s.ctx);
    const double h0 = resume_h_ > 0.0 ? resume_h_ : first_h_;
    if (h0 > 0.0) check(ERKStepSetInitStep(s.mem, h0), "ERKStepSetInitStep", s.ctx);
    if (ode_.n_constraints() > 0)
      check(ERKStepSetPostprocessStepFn(s.mem, erk_project), "ERKStepSetPostprocessStepFn", s.ctx);
    if (plan.events && plan.events->size() > 0) {  // only models with event elements
      user_.events = plan.events;
      check(ERKStepRootInit(s.mem, plan.events->size(), ode_roots), "ERKStepRootInit", s.ctx);
      check(ERKStepSetRootDirection(s.mem, plan.events->directions()), "ERKStepSetRootDirection", s.ctx);
    }
  }
  /// The segment's pair: ARKODE's default table of its order, but at order 8
  /// Prince-Dormand 8(7) for Fehlberg 7(8), whose error estimate is blind to
  /// quadratures (prince_dormand_8_7).
  void set_pair() {
    const int order = order_ > 0 ? order_ : plan.max_order;
    if (order != 8) {
      check(ERKStepSetOrder(s.mem, order), "ERKStepSetOrder", s.ctx);
      return;
    }
    if (!pair_8_7_) pair_8_7_ = prince_dormand_8_7();
    if (!pair_8_7_) throw std::runtime_error("lagmb: ARKodeButcherTable_Create failed");
    check(ERKStepSetTable(s.mem, pair_8_7_), "ERKStepSetTable", s.ctx);
  }
  /// The first step, as Hairer, Norsett and Wanner choose it for explicit
  /// Runge-Kutta methods of order p (Solving ODEs I, sec. II.4): with the
  /// weighted RMS norms of y0, f0 = f(y0) and of the change of f over an
  /// explicit Euler step of h0 = 0.01 |y0| / |f0|, d2 = |f1 - f0| / h0,
  ///   h = min(100 h0, (0.01 / max(|f0|, d2))^(1 / (p + 1))),
  /// within the run's span and max_step. ARKODE's own estimate starts a
  /// mechanism released at rest (f's position part 0) near 1e-10 s, and the
  /// ramp from there took a third of the steps of a 1 s chain run. 0 (let
  /// ARKODE choose) where f cannot be evaluated.
  double first_step() {
    const int size = 2 * n;
    const double rtol = plan.options->rtol;
    const Eigen::Map<const VecX> y0(N_VGetArrayPointer(s.y), size), atol(N_VGetArrayPointer(s.abstol), size);
    VecX f0(size), y1(size), f1(size);
    if (!p.ode.right_hand_side(plan.t0, y0.data(), f0.data())) return 0.0;
    auto norm = [&](const VecX& x, const VecX& at) {
      return std::sqrt(((x.array() / (atol.array() + rtol * at.array().abs())).square()).mean());
    };
    const VecX y_now = y0;
    const double d0 = norm(y_now, y_now), d1 = norm(f0, y_now);
    const double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    y1 = y_now + h0 * f0;
    if (!p.ode.right_hand_side(plan.t0 + h0, y1.data(), f1.data())) return 0.0;
    const double d2 = norm(f1 - f0, y_now) / h0, largest = std::max(d1, d2);
    const double h1 = largest <= 1e-15 ? std::max(1e-6, 1e-3 * h0)
                                       : std::pow(0.01 / largest, 1.0 / (plan.max_order + 1));
    double h = std::min(100.0 * h0, h1);
    if (plan.t_end > plan.t0) h = std::min(h, plan.t_end - plan.t0);
    if (plan.options->max_step > 0) h = std::min(h, plan.options->max_step);
    extra_rhs_ += 2;
    return std::isfinite(h) && h > minimum_step(plan) ? h : 0.0;
  }

  /// The current state of s.y at t becomes the end of the last step.
  void mark(double t) {
    end_.t = t;
    end_.y = Eigen::Map<const VecX>(N_VGetArrayPointer(s.y), 2 * n);
    end_.f.resize(2 * n);
    end_.has_f = false;
  }
  void accelerations(End& e) {
    if (e.has_f) return;
    ++extra_rhs_;
    if (!p.ode.right_hand_side(e.t, e.y.data(), e.f.data()))
      throw IntegratorFailure("the augmented system is singular at t = " + to_text(e.t), e.t);
    e.has_f = true;
  }
  const char* name() const override { return "ARKODE ERKStep"; }
  bool steps_to_outputs() const override { return true; }
  void set_stop(double stop) override {
    stop_ = stop;
    check(ERKStepSetStopTime(s.mem, stop), "ERKStepSetStopTime", s.ctx);
  }
  double step(bool& at_stop) override {
    sunrealtype t = 0.0;
    p.rhs_failed = false;
    int flag = ERKStepEvolve(s.mem, plan.t_end, s.y, &t, ARK_ONE_STEP);
    rethrow_callback_error(p, end_.t);  // (the time reached: a stage's time may lie beyond it)
    // ERKStep takes a right-hand side that failed in a recoverable manner
    // (a stage of a long trial step far off the motion, where the augmented
    // matrix is singular: the Panda's servos at rest, whose first step the
    // rule makes 0.98 s) for a failure: the step is tried again from its
    // start, 4 times shorter, as CVODE and IDA would (10 times at most)
    for (int tries = 0; flag == ARK_UNREC_RHSFUNC_ERR && p.rhs_failed && tries < 10; ++tries) {
      sunrealtype h = 0.0;
      ERKStepGetCurrentStep(s.mem, &h);
      if (!(h > 4.0 * minimum_step(plan))) break;
      Eigen::Map<VecX>(N_VGetArrayPointer(s.y), 2 * n) = end_.y;
      resume_h_ = 0.25 * double(h);
      resuming_ = true;  // (the segment's pair kept)
      restart(end_.t);
      resuming_ = false;
      resume_h_ = 0.0;
      if (std::isfinite(stop_)) set_stop(stop_);
      p.rhs_failed = false;
      flag = ERKStepEvolve(s.mem, plan.t_end, s.y, &t, ARK_ONE_STEP);
      rethrow_callback_error(p, end_.t);
    }
    if (flag < 0) {
      sunrealtype h = 0;
      ERKStepGetCurrentStep(s.mem, &h);
      throw solver_failure("ERKStep", t, h, flag, ERKStepGetReturnFlagName(flag), s.ctx.sink().message);
    }
    std::swap(start_, end_);
    mark(t);
    at_stop = flag == ARK_TSTOP_RETURN;
    at_root = flag == ARK_ROOT_RETURN;
    return t;
  }
  void root_info(int* fired) override { check(ERKStepGetRootInfo(s.mem, fired), "ERKStepGetRootInfo", s.ctx); }
  void interpolate(double t, const double*& q, const double*& v) override {
    // (the step's ends are states of the motion, on the constraints)
    if (t == end_.t || end_.t == start_.t) {
      q = end_.y.data(), v = q + n;
      return;
    }
    if (t == start_.t) {
      q = start_.y.data(), v = q + n;
      return;
    }
    accelerations(start_);
    accelerations(end_);
    const double h = end_.t - start_.t;
    const double *y0 = start_.y.data(), *y1 = end_.y.data(), *f0 = start_.f.data(), *f1 = end_.f.data();
    quintic_hermite((t - start_.t) / h, h, n, y0, y0 + n, f0 + n, y1, y1 + n, f1 + n, out_.data(), out_.data() + n);
    // onto the constraints, as the steps' ends are (the interpolant is off by O(h^6))
    if (p.ode.n_constraints() > 0 && p.ode.project(t, out_.data(), out_.data() + n, p.correction.data(), nullptr) != 0)
      throw IntegratorFailure("the augmented system is singular at t = " + to_text(t), t);
    q = out_.data(), v = q + n;
  }
  /// An input's jump: the state goes on, and a one-step method needs no
  /// history: the segment's first step is 3.5 times the last one where the
  /// stop, not the error, cut it (its error allowed 4 times longer), else
  /// estimated at the state reached (first_step(), two right-hand sides), not the run's
  /// first step, which a mechanism started at rest makes small (the Panda
  /// at 1 kHz took two steps per tick, its first 0.46 ms); the error test
  /// cuts a step the jump makes too long.
  void resume(double t, const ConsistentState& state) override {
    sunrealtype h = 0.0, last = 0.0;
    double growth = 0.0;  // how much longer the error test would have let the last step be
    if (s.mem) {
      ERKStepGetCurrentStep(s.mem, &h);
      ERKStepGetLastStep(s.mem, &last);
      if (!error_) error_ = N_VClone(s.y), weight_ = N_VClone(s.y);  // (once: a control loop resumes every tick)
      N_Vector error = error_, weight = weight_;
      if (ERKStepGetEstLocalErrors(s.mem, error) == ARK_SUCCESS && ERKStepGetErrWeights(s.mem, weight) == ARK_SUCCESS) {
        N_VProd(error, weight, error);  // (ARKODE's weighted RMS norm of the last step's error: 1 at the tolerance)
        const double dsm = std::sqrt(N_VDotProd(error, error) / double(N_VGetLength(error)));
        growth = dsm > 0.0 ? std::pow(dsm, -1.0 / ((order_ > 0 ? order_ : plan.max_order) + 1)) : INFINITY;
      }
    }
    load_state(s.y, state, n);
    // inputs changing at every stop, each segment's step allowed 4 times
    // longer than the stop let it be (a control loop: the ticks, not the
    // error, bound the steps): ARKODE's order-4 pair reaches the tolerance
    // there in fewer stages (the Panda at 1 kHz: 6.5 right-hand sides per
    // tick, not 31; the error test still holds every step), and the last
    // step is the first one's estimate (first_step() would cost two more)
    const bool ticks_bound = t - segment_start_ > 0.0 && growth >= 4.0 && std::isfinite(last) && last > 0.0;
    order_ = ticks_bound ? std::min(4, plan.max_order) : 0;
    resume_h_ = ticks_bound ? 3.5 * double(last) : std::max(first_step(), std::isfinite(h) ? double(h) : 0.0);
    resuming_ = true;
    restart(t);
    resuming_ = false;
    resume_h_ = 0.0;
  }
  void restart(double t) override {
    if (!resuming_) order_ = 0;  // (an event's restart: the run's own pair)
    segment_start_ = t;
    Stats counts = before;
    arkode_counts(counts);
    before = counts;
    create(t);
    mark(t);
    start_ = end_;
  }
  /// ERKStep's counts, over the segments since the start.
  void arkode_counts(Stats& stats) const {
    const Stats b = before;
    long v = 0;
    ERKStepGetNumSteps(s.mem, &v), stats.steps = b.steps + v;
    ERKStepGetNumRhsEvals(s.mem, &v), stats.residual_evals = b.residual_evals + v;
    ERKStepGetNumErrTestFails(s.mem, &v), stats.error_test_failures = b.error_test_failures + v;
  }
  void fill_stats(Stats& stats) override {
    arkode_counts(stats);
    stats.residual_evals += extra_rhs_;
    sunrealtype h = 0;
    ERKStepGetLastStep(s.mem, &h), stats.last_step = h;
    p.ode.count(stats);
  }
};

}  // namespace

std::unique_ptr<Stepper> make_erk_stepper(const Model& model, const ConsistentState& start,
                                          const IntegrationPlan& plan) {
  // ERKStep's tables (SUNDIALS 6 and 7): orders 2 to 6 and 8
  if (plan.max_order < 2 || plan.max_order == 7 || plan.max_order > 8)
    throw ModelError("simulate: the explicit Runge-Kutta methods have orders 2, 3, 4, 5, 6 and 8, not " +
                     std::to_string(plan.max_order) + " (max_order)");
  return std::make_unique<ErkStepper>(model, start, plan);
}

}  // namespace lagmb
