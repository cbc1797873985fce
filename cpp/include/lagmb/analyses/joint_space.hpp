// Joint space: a joint's scalar coordinate (angle or slide) read from
// lagmb's coordinates, and the joint efforts a given motion needs.
#pragma once

#include <string>
#include <vector>

#include "lagmb/model/model.hpp"

namespace lagmb {

/// A joint's scalar coordinate (JointCoordinate: a revolute's angle in rad,
/// phi_j - phi_i in the plane, in space read within half a turn of the
/// angle a run's state holds or, without one, of the joint's initial angle
/// (model/joint_turns.hpp); a translational's slide in m; in space the
/// joint's `angle` or `slide` in the initial configuration, 0 by default)
/// with its rate and acceleration.
struct JointMotion {
  double value = 0.0, rate = 0.0, acceleration = 0.0;
};

/// The coordinate of `joint` at (q, v, a) (one state, arrays over q): with g
/// the coordinate as a function of the local coordinates c of the joint's two
/// bodies (the function its drivers hold),
///   value = g(c),  rate = g_c c',  acceleration = g_c c'' + (g_c)' c'.
/// `slide` picks a cylindrical joint's slide (else its angle); a revolute has
/// only its angle, a translational only its slide. a may be null (then the
/// acceleration is 0). `state`: the run's element state at that instant
/// (Data::RunValues::state, a Trajectory's run_state row), whose turns the
/// angle counts; null: the angle within half a turn of its initial one.
/// ModelError naming the joint if it has no such coordinate.
JointMotion joint_motion(const Model& model, const std::string& joint, bool slide, const double* q, const double* v,
                         const double* a, const double* state = nullptr);

/// One joint coordinate whose effort inverse_dynamics solves for.
struct JointEffort {
  std::string joint;
  bool slide = false;  // its slide (else its angle)
};

/// The efforts tau (N m about an angle, N along a slide) of `joints` and
/// the multipliers lam that make the motion (q, v, a) at time t:
///   M(q) a + Phi_q^T lam = Q(q, v, t) + G^T tau,   G_k = d theta_k / dq,
/// a least-squares solve of [Phi_q^T, -G^T] [lam; tau] = Q - M a (sparse QR;
/// the rows of a redundant set share their load as its minimum-norm split).
/// For a tree driven at every joint the system is square and the efforts
/// are exact (recursive Newton-Euler's). SimulationError if the motion
/// needs forces that neither the joints nor the efforts given can apply
/// (residual above 1e-9 (1 + |Q - M a|)), naming the coordinate where the
/// largest is missing.
struct InverseDynamics {
  VecX efforts;  // one per JointEffort
  VecX lam;
};
InverseDynamics inverse_dynamics(const Model& model, const std::vector<JointEffort>& joints, const double* q,
                                 const double* v, const double* a, double t);

}  // namespace lagmb
