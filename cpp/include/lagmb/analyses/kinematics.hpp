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
// At 0 DOF the independent rows of Phi_q (the rows not dropped as redundant
// where the run starts, redundancy.hpp) form a square, invertible n x n matrix: every solve above is
// one with its sparse LU (Newton reuses the factorization while it contracts
// well), and step 4 one with its transpose, lam = Phi_q^-T (Q - M a),
// refined against the exact Phi_q at the converged q. That is half the size
// of the augmented matrix [M Phi_q^T; Phi_q 0] a dynamic run factorizes, and
// needs no regularization (AugmentedSystem remains the fallback when
// dependent rows appear that the start did not show). Joint friction, whose
// load is lam itself, is solved by fixed point in step 4. Redundant rows read 0 = 0 and
// get lam = 0. Masses may be 0 for a kinematic-only analysis.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "lagmb/model/model.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

/// Degrees of freedom of the model at time t: coordinates minus the rank of
/// Phi_q at the assembled initial positions (at the given initial positions
/// if they cannot be assembled). Costs nothing beyond a count when there are
/// fewer independent equations than coordinates.
int degrees_of_freedom(const Model& model, double t = 0.0);

/// Bodies with a zero mass or (rigid bodies) a zero inertia, by index.
std::vector<int> massless_bodies(const Model& model);
/// ModelError (from `who`) unless the motion of a model with massless
/// bodies follows from its forces at q: the augmented matrix
/// [M Phi_q^T; Phi_q 0] (its independent rows) is regular. A massless link
/// between two joints that hold it (two revolutes with intersecting axes)
/// passes; one its joints leave free to move (at the end of a chain) does
/// not, and the message names the massless bodies. Nothing to check (and
/// no cost) when every body has mass and inertia.
void require_determined_motion(const Model& model, const VecX& q, double t, const std::string& who);
/// The principal moments of an inertia tensor, ascending.
Vec3 principal_moments(const Mat3& J);

/// Kinematic analysis (steps 1-3 above) at the times t_out from t0; with
/// inverse_dynamics also step 4, else lam is NaN (not computed). The model
/// must have 0 DOF (see resolve_analysis, simulate.hpp). Stats: analysis, newton_iterations,
/// residual_evals (Phi), jacobian_evals (Phi_q), lu_factorizations (of the
/// square Jacobian), augmented_factorizations (assembly at t0, fallback),
/// kinematic_solves; steps stays 0. Throws SimulationError naming the time and
/// the joints (diagnose_failure) with the outputs reached so far if Newton
/// fails (e.g. a driver pushes the mechanism through a toggle position), or
/// if following the drivers takes more than max_steps sub-steps (0: no bound;
/// a sub-step turns no body by more than 0.25 rad, so a driver turning at
/// 1e18 rad/s is refused rather than followed for ever).
Trajectory kinematic_analysis(const Model& model, double t0, const std::vector<double>& t_out,
                              bool inverse_dynamics,
                              const std::function<void(double)>& progress = {},
                              double progress_interval = 0.2, long max_steps = 0);

}  // namespace lagmb
