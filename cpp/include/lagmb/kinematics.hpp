// Kinematic analysis and inverse dynamics of a model whose motion is fully
// prescribed by its drivers (zero degrees of freedom).
//
// With rank Phi_q = n (every coordinate fixed by joints and drivers), the
// motion follows from the constraints alone; no differential equation is
// integrated. At each solve time t (the output times, plus the breakpoints
// of the time functions and any inserted sub-steps):
//
//   1. positions: Newton on Phi(q, t) = 0,
//        Phi_q(q_k) dq = -Phi(q_k, t),  q_{k+1} = q_k + dq,
//      from the prediction q0 = q + v dt + a dt^2/2 of the previous solution,
//      until |dq|_inf <= 1e-12 (1 + |q|_inf). The step dt is halved when
//      Newton needs more than 10 iterations or its first correction is larger
//      than half the predicted motion (guards against jumping to another
//      assembly branch), down to 1e-12 (1 + |t|);
//   2. velocities:    Phi_q v = -Phi_t;
//   3. accelerations: Phi_q a = gamma = -(Phi_q v)_q v - 2 Phi_qt v - Phi_tt;
//   4. inverse dynamics (at output times): the multipliers (joint reactions,
//      driver efforts) from M a + Phi_q^T lam = Q(q, v, t).
//
// Steps 2-4 are solves with the augmented matrix [M Phi_q^T; Phi_q 0]
// (AugmentedSystem) factorized for the last Newton iterate (it differs from
// the converged q by at most the 1e-12 tolerance): for a square, invertible
// Phi_q its second block row gives v and a alone, and the first then gives
// lam = Phi_q^-T (Q - M a), so 3 and 4 are one solve, as in
// solve_accelerations. Redundant rows (dropped at finalize) read 0 = 0 and
// get lam = 0. Masses may be 0 for a kinematic-only analysis.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "lagmb/model.hpp"
#include "lagmb/simulate.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

/// Degrees of freedom of the model at time t: coordinates minus the rank of
/// Phi_q at the assembled initial positions (at the given initial positions
/// if they cannot be assembled). Costs nothing beyond a count when there are
/// fewer independent equations than coordinates.
int degrees_of_freedom(const Model& model, double t = 0.0);

/// Bodies with a zero mass or (rigid bodies) a zero inertia, by index.
std::vector<int> massless_bodies(const Model& model);

/// The analysis options.analysis asks for, resolved: "dynamic", "kinematic"
/// or "inverse_dynamics". "auto" picks inverse_dynamics at 0 DOF
/// (kinematic if some body is massless) and dynamic otherwise. Throws
/// ModelError for an unknown name, a kinematic analysis of a model with
/// DOF > 0 (naming the count), or a dynamic analysis of a model with a
/// massless body (naming it).
std::string resolve_analysis(const Model& model, const SimulationOptions& options);

/// Kinematic analysis (steps 1-3 above) at the times t_out from t0; with
/// inverse_dynamics also step 4, else lam is NaN (not computed). The model
/// must have 0 DOF (see resolve_analysis). Stats: analysis, newton_iterations,
/// residual_evals (Phi), jacobian_evals (Phi_q), augmented_factorizations,
/// kinematic_solves; steps stays 0. Throws SimulationError naming the time and
/// the joints (diagnose_failure) with the outputs reached so far if Newton
/// fails (e.g. a driver pushes the mechanism through a toggle position).
Trajectory kinematic_analysis(const Model& model, double t0, const std::vector<double>& t_out,
                              bool inverse_dynamics,
                              const std::function<void(double)>& progress = {},
                              double progress_interval = 0.2);

}  // namespace lagmb
