// What the two drivers of the "projection" formulation (CVODE in
// cvode_integrator.cpp, ARKODE ERKStep in erk_integrator.cpp) share: the user
// data their callbacks reach, the right-hand side and event callbacks, and
// how an error crosses back from SUNDIALS' C frames.
#pragma once

#include <nvector/nvector_serial.h>

#include <exception>
#include <string>

#include "lagmb/events/event_runner.hpp"
#include "formulations/projection.hpp"
#include "integrators/integrators.hpp"
#include "solvers/nvector_ops.hpp"
#include "lagmb/errors.hpp"
#include "solvers/sun_compat.hpp"

namespace lagmb {

/// The callbacks' user data: the formulation, the model's event functions,
/// and the exception a callback caught, which the stepper rethrows (an
/// exception must not cross SUNDIALS' C frames).
struct OdeUserData {
  explicit OdeUserData(ProjectionFormulation& formulation) : ode(formulation), correction(2 * formulation.n()) {}
  ProjectionFormulation& ode;
  EventRunner* events = nullptr;
  std::exception_ptr error;
  bool rhs_failed = false;  // a right-hand side failed in a recoverable manner (ode_rhs returned 1)
  VecX correction;  // scratch: the change a projection of our own makes to (q, v)
};

/// Runs a callback's body; an exception is kept for the stepper and SUNDIALS
/// gets -1 (unrecoverable).
template <class Body>
int guarded(void* data, Body&& body) {
  auto* p = static_cast<OdeUserData*>(data);
  try {
    return body(*p);
  } catch (...) {
    p->error = std::current_exception();
    return -1;
  }
}

/// f = (v, qdd) at (t, y); 1 (recoverable: the step is cut) where the
/// augmented system is singular.
inline int ode_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
  return guarded(data, [&](OdeUserData& p) {
    if (p.ode.right_hand_side(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot))) return 0;
    p.rhs_failed = true;
    return 1;
  });
}

/// The model's event functions at (t, q, v); the closed stops' forces from
/// the formulation's multipliers (at a step's end, the next step's first
/// stage then finds them solved).
inline int ode_roots(sunrealtype t, N_Vector y, sunrealtype* g, void* data) {
  return guarded(data, [&](OdeUserData& p) {
    const double* yy = N_VGetArrayPointer(y);
    const double *q = yy, *v = yy + p.ode.n();
    const bool solved = p.events->reads_multipliers() && !p.ode.baumgarte() && p.ode.accelerations(t, q, v);
    p.events->values(t, q, v, g, solved ? p.ode.lam().data() : nullptr);
    return 0;
  });
}

/// A SUNDIALS set-up call that failed is an internal error, with its message.
inline void check(int flag, const char* call, sun::Context& ctx) {
  if (flag < 0)
    throw std::runtime_error(std::string("lagmb: ") + call + " failed (" + std::to_string(flag) +
                             "): " + ctx.sink().message);
}

/// Rethrows what a callback kept: a failing user function as an
/// IntegratorFailure at t (which keeps the partial result), anything else
/// as it was.
inline void rethrow_callback_error(const OdeUserData& p, double t) {
  if (!p.error) return;
  try {
    std::rethrow_exception(p.error);
  } catch (const UserFunctionError& e) {
    throw IntegratorFailure(e.what(), t);
  }
}

/// A SUNDIALS context with the vectors of y = (q, v): the state, its
/// absolute tolerances (atol_i for q_i and v_i) and an output. A driver's
/// session derives from it and frees its solver first.
struct OdeSession {
  OdeSession(const ConsistentState& start, const VecX& atol) {
    const int n = int(start.q.size());
    for (N_Vector* v : {&y, &abstol, &out}) {
      if (!(*v = N_VNew_Serial(2 * n, ctx))) throw std::bad_alloc();
      sun::use_compiled_vector_ops(*v);
    }
    Eigen::Map<VecX>(N_VGetArrayPointer(y), n) = start.q;
    Eigen::Map<VecX>(N_VGetArrayPointer(y) + n, n) = start.v;
    Eigen::Map<VecX>(N_VGetArrayPointer(abstol), n) = atol;
    Eigen::Map<VecX>(N_VGetArrayPointer(abstol) + n, n) = atol;
  }
  ~OdeSession() {
    for (N_Vector* v : {&y, &abstol, &out})
      if (*v) N_VDestroy(*v);
  }
  OdeSession(const OdeSession&) = delete;
  OdeSession& operator=(const OdeSession&) = delete;
  sun::Context ctx;
  N_Vector y = nullptr, abstol = nullptr, out = nullptr;
};

/// (q, v) of a consistent state into a SUNDIALS vector y = (q, v).
inline void load_state(N_Vector y, const ConsistentState& state, int n) {
  Eigen::Map<VecX>(N_VGetArrayPointer(y), n) = state.q;
  Eigen::Map<VecX>(N_VGetArrayPointer(y) + n, n) = state.v;
}

/// What the CVODE and ERKStep steppers share: y = (q, v) in one SUNDIALS
/// vector, the callbacks' data, and the roots the solver reports.
class OdeStepper : public Stepper {
 public:
  OdeStepper(N_Vector y, OdeUserData& data) : y_(y), p(data), n(data.ode.n()) {}
  bool root_found(std::vector<int>& fired) override {
    if (!at_root) return false;
    fired.assign(p.events->size(), 0);
    root_info(fired.data());
    return true;
  }
  const double* positions() const override { return N_VGetArrayPointer(y_); }
  const double* velocities() const override { return N_VGetArrayPointer(y_) + n; }
  void reset(double t, const ConsistentState& state) override {
    load_state(y_, state, n);
    restart(t);
  }
  bool motion_at(double t, const double* q, const double* v, const double*& qdd, const double*& lam) override {
    if (p.ode.baumgarte() || !p.ode.accelerations(t, q, v)) return false;
    qdd = p.ode.qdd().data(), lam = p.ode.lam().data();
    return true;
  }

 protected:
  /// fired[i] != 0 for the event functions the solver found a root of.
  virtual void root_info(int* fired) = 0;
  N_Vector y_;
  OdeUserData& p;
  const int n;
  bool at_root = false;  // the last step stopped at a root
};

/// What a failed step reports: the solver, where, its step size and flag.
inline IntegratorFailure solver_failure(const char* solver, double t, double h, int flag, const char* flag_name,
                                        const std::string& message) {
  IntegratorFailure f(std::string(solver) + " failed at t = " + to_text(t) + " (step size " + to_text(h) +
                          "), flag " + std::to_string(flag) + " (" + flag_name + "): " + message,
                      t);
  f.integrator_gave_up = true;
  return f;
}

}  // namespace lagmb
