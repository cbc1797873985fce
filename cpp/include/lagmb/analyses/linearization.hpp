// The linear motion about a state: the matrices that mb.modes and
// mb.linearize reduce to the motions the joints allow.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "lagmb/model/model.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// M dq'' + C dq' + K dq + Phi_q^T dlam = 0, Phi_q dq = 0 about a state at
/// rest (v = 0, qdd = 0: a static equilibrium), in the model's coordinates
/// (n x n; Phi_q m x n):
///   M = M(q);
///   K = (Phi_q^T lam)_q - Q_q, the tangent stiffness (the constraint forces'
///       and the applied forces' change with q; (M qdd)_q is 0 at rest);
///   C = -Q_v, the damping (and, in space, gyroscopic) terms.
/// Dense: for models of up to a few hundred coordinates.
struct RestTangent {
  Eigen::MatrixXd M, K, C, Phi_q;
};

/// The matrices above at (q, lam, t); the rows of Phi left out as
/// redundant (ascending) have zero rows in Phi_q. ModelError for sizes that
/// do not match the model.
RestTangent tangent_at_rest(const Model& model, const VecX& q, const VecX& lam, double t,
                            const std::vector<int>& dropped_rows);

/// The linear motion about any consistent state (q, v, t) with the model's
/// inputs at u: differentiating M a + Phi_q^T lam = Q(q, v, t, u) and
/// Phi_q a = gamma(q, v, t) gives
///   M da + Phi_q^T dlam = -K dq - C dv + Q_u du,
///   Phi_q da            = G_q dq + G_v dv,
/// with
///   K   = (M a)_q + (Phi_q^T lam)_q - Q_q   (the tangent stiffness),
///   C   = -Q_v,
///   G_q = gamma_q - (Phi_q a)_q,  G_v = gamma_v = -2 Vq(v)
/// (Vq = d(Phi_q v + Phi_t)/dq: gamma = -(Phi_q v)_q v - 2 Phi_qt v - Phi_tt
/// is quadratic in v). Every term is an element's exact derivative except
/// gamma_q, which needs Phi's third derivatives: it is taken by central
/// differences of gamma (and is exactly 0 at v = 0 for constraints that
/// do not depend on time). a and lam are solved here from the augmented
/// system at (q, v, t). Sparse, in the model's coordinates; the rows of Phi
/// left out as redundant are zero in Phi_q, G_q, G_v and Phi_u.
struct StateTangent {
  std::vector<int> dropped_rows;  // the rows of Phi left out (ascending): redundant, and the stops' (open)
  VecX a, lam;          // (n), (m): the accelerations and multipliers at the state
  VecX Q, gamma, Phi, velocity_residual;  // at the state: Q, gamma, Phi, Phi_q v + Phi_t
  SpMat M, Phi_q;       // (n x n), (m x n)
  SpMat K, C;           // (n x n)
  SpMat G_q, G_v;       // (m x n)
  Eigen::MatrixXd Q_u;  // (n x p): dQ/du, one column per Model::inputs()
  Eigen::MatrixXd Phi_u;  // (m x p): dPhi/du, nonzero where an input drives a constraint
};

/// The terms above at (q, v, t) with the inputs at u (Model::inputs()
/// order). Q_u and Phi_u are central differences with a unit step
/// (max(1, |u|)): exact where Q and Phi are affine in u (forces, torques
/// and motions that take an input's value), which is checked; otherwise a
/// small step (1e-6 max(1, |u|)). ModelError for sizes that do not match the
/// model, dropped rows out of range, or an augmented system that is
/// singular at the state. Without dropped_rows, the rows redundant at
/// (q, t) are found as a run finds them (redundancy.hpp). The stops `held`
/// (by name) hold their joints on the limit they are at (within 1e-8 (1 +
/// |q|)) as the joint rows they are while captured (docs/methods.md, "The active set, step by step");
/// the other stops' rows are open. ModelError for a name that is no stop or
/// a stop at neither limit.
StateTangent tangent_at(const Model& model, const VecX& q, const VecX& v, double t, const VecX& u,
                        const std::optional<std::vector<int>>& dropped_rows,
                        const std::vector<std::string>& held = {});

}  // namespace lagmb
