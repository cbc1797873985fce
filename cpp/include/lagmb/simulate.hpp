// Time integration of a model: options in, Trajectory out.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "lagmb/augmented.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/model.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

struct SimulationOptions {
  double t0 = 0.0;
  double t_end = 1.0;
  /// Output times, increasing, inside [t0, t_end]; empty: n_out equally
  /// spaced times from t0 to t_end.
  std::vector<double> t_out;
  int n_out = 101;
  double rtol = 1e-6;
  double atol = 1e-8;
  /// Per-coordinate absolute tolerances (n entries, for q_i and v_i); empty:
  /// atol for every coordinate.
  std::vector<double> atol_coordinates;
  double max_step = 0.0;  // 0: no limit
  /// 0: no limit; else SimulationError when reached, and a max_step that
  /// needs more steps than this over [t0, t_end] is refused up front.
  long max_steps = 500000;
  int max_order = 0;  // 0: the method's highest (BDF 5, Adams 12; methods.hpp)
  /// The method (methods.hpp, which lists them): a formulation ("ggl", the
  /// default, "index3", "index1", "projection", "ali3p") and one of its
  /// integrators ("": the formulation's first, e.g. "bdf"; "adams" for
  /// projection). ali3p takes a fixed step, given as max_step.
  std::string formulation = "ggl";
  std::string integrator;
  double baumgarte_alpha = 0.0, baumgarte_beta = 0.0;  // index1, and projection with adams
  /// Called between steps with the time reached, at most every
  /// progress_interval seconds of wall time; may throw to stop the run.
  std::function<void(double t)> progress;
  double progress_interval = 0.2;
  /// "auto": kinematic analysis + inverse dynamics when the model has 0
  /// degrees of freedom (kinematic only if a body is massless), else
  /// dynamic; "dynamic": integrate the DAE even at 0 DOF; "kinematic":
  /// q, v, a only (lam NaN); "inverse_dynamics": also lam. The last two need
  /// 0 DOF (see kinematics.hpp).
  std::string analysis = "auto";
  /// "given": start from the model's initial positions and velocities;
  /// "equilibrium": from the static equilibrium at t0 (equilibrium.hpp),
  /// at rest. A dynamic analysis only.
  std::string start = "given";

  /// f(name, field) for every field but progress: the one list bindings
  /// read options by (Python passes them by these names).
  template <class F>
  void for_each_field(F&& f) {
    f("t0", t0), f("t_end", t_end), f("t_out", t_out), f("n_out", n_out), f("rtol", rtol), f("atol", atol);
    f("atol_coordinates", atol_coordinates), f("max_step", max_step), f("max_steps", max_steps);
    f("max_order", max_order), f("formulation", formulation), f("integrator", integrator);
    f("baumgarte_alpha", baumgarte_alpha), f("baumgarte_beta", baumgarte_beta);
    f("progress_interval", progress_interval), f("analysis", analysis), f("start", start);
  }
};

/// Makes the initial state consistent, integrates, and returns the states at
/// the output times. Throws ModelError for bad options, AssemblyError if the
/// initial positions cannot be made consistent, SimulationError (with the
/// outputs reached so far) if the integrator fails.
Trajectory simulate(const Model& model, const SimulationOptions& options);

/// Version of the SUNDIALS library lagmb was built with, e.g. "6.4.1".
std::string sundials_version();

/// lagmb's own operations on SUNDIALS serial vectors (they replace the
/// library's, which Debian builds without optimization) against SUNDIALS'
/// serial ones, on random vectors of length n, with the aliasings SUNDIALS
/// uses (z = x or y in a linear sum; z = X_0 or X_1 in a linear
/// combination; Z = Y in a scale-add): the largest difference per
/// operation, relative to the largest entry.
std::map<std::string, double> compare_vector_operations(int n, unsigned seed);

/// qdd and lam at one instant (the augmented system of docs/design.md section 1.2).
void solve_accelerations(const Model& model, const VecX& q, const VecX& v, double t, VecX& qdd,
                         VecX& lam);

/// Consistent (q, v, qdd, lam) at time t from the model's initial values.
ConsistentState assemble(const Model& model, double t = 0.0);

}  // namespace lagmb
