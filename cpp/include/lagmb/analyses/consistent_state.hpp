// The consistent states of the equations of motion at one instant, solved
// with the augmented system (lagmb/assembly/augmented.hpp): positions on
// Phi = 0, velocities on Phi_q v + Phi_t = 0, accelerations and multipliers
// (with joint friction's load, a fixed point), and the state a run starts
// from (with the rows found redundant there left out).
#pragma once

#include <functional>
#include <vector>

#include "lagmb/assembly/augmented.hpp"
#include "lagmb/model/data.hpp"

namespace lagmb {

struct Redundancy;  // redundancy.hpp

/// q, v, qdd and lam that satisfy Phi = 0, Phi_q v + Phi_t = 0 and the
/// augmented system at time t.
struct ConsistentState {
  VecX q, v, qdd, lam;
  std::vector<int> dropped_rows;  // the rows left out (Data::dropped_rows)
};

/// Makes (q, v) consistent at time t:
///  1. positions by Newton least-change in the M-metric:
///       [M Phi_q^T; Phi_q 0] [dq; kappa] = [0; -Phi],  q += dq, until |Phi| small;
///  2. velocities by M-orthogonal projection:
///       [M Phi_q^T; Phi_q 0] [v; kappa] = [M v0; -Phi_t];
///  3. accelerations and multipliers: [M Phi_q^T; Phi_q 0] [qdd; lam] = [Q; gamma].
/// The rows d drops stay dropped (see start_state). Throws AssemblyError
/// naming the constraint elements still violated.
ConsistentState make_consistent(const Model& model, Data& d, AugmentedSystem& kkt, VecX q,
                                VecX v, double t);

/// Step 1 alone: positions satisfying Phi(q, t) = 0, by least change from q
/// (Newton in the M-metric; see consistent_state.cpp for its safeguards).
VecX solve_positions(const Model& model, Data& d, AugmentedSystem& kkt, VecX q, double t);

/// Step 3 alone: qdd and lam at the state (q, v, t).
void solve_accelerations(const Model& model, Data& d, AugmentedSystem& kkt, const double* q,
                         const double* v, double t, double* qdd, double* lam);

/// Joint friction Q_f(q, v, lam) takes its load from the multipliers, so the
/// equations that give lam become nonlinear in it. From d.Q (forces without
/// friction) and the frictionless lam, iterates: d.Q = Q + Q_f(lam_k), then
/// solve(lam) gives lam_{k+1} from that d.Q, until |lam_{k+1} - lam_k|_inf
/// <= 1e-12 (|lam|_inf + mass scale), at most 2000 times (the convergence is
/// linear); throws SimulationError if it does not converge (friction so large
/// that the load-friction loop locks). Leaves d.Q with friction.
void iterate_friction_load(const Model& model, Data& d, const double* q, const double* v, double t, VecX& lam,
                           const std::function<void(VecX& lam)>& solve);

/// iterate_friction_load on the augmented system: kkt factorized at q,
/// d.gamma, and the frictionless (qdd, lam) in; both updated.
void solve_friction(const Model& model, Data& d, AugmentedSystem& kkt, const double* q, const double* v,
                    double t, VecX& qdd, VecX& lam);

/// The consistent state a run starts from: positions solved with every
/// row of Phi, then the rows found redundant there (find_redundancy) dropped
/// in d, then make_consistent. The dropped rows must hold at velocity and
/// acceleration level too (a consistent redundancy does: its equations are
/// combinations of the kept ones); otherwise the equations conflict, e.g.
/// two drivers prescribing one angle at different rates, and AssemblyError
/// names them. `redundancy`, if given, receives what was decided.
ConsistentState start_state(const Model& model, Data& d, AugmentedSystem& kkt, VecX q, VecX v, double t,
                            Redundancy* redundancy = nullptr);

}  // namespace lagmb
