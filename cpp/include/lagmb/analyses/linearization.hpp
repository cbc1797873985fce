// The linear motion about a state at rest: the matrices that mb.modes (and
// mb.linearize, at rest) reduce to the motions the joints allow.
#pragma once

#include <Eigen/Core>
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

}  // namespace lagmb
