// Static equilibrium of a model, and whether it is stable.
//
// At rest (v = 0) and time t, equilibrium is a configuration q with
// multipliers lam such that
//
//   F(q, lam) = [ Q(q, 0, t) - Phi_q^T lam ] = 0     (n: the forces balance)
//               [ Phi(q, t)                ]         (m: the joints close)
//
// solved by Newton with the exact Jacobian of -F's first block and of the
// second,
//
//   [ K(q, lam)  Phi_q^T ] [ dq   ]   [ Q - Phi_q^T lam ]
//   [ Phi_q      0       ] [ dlam ] = [ -Phi            ],
//
//   K = H(lam) - Q_q,   H(lam) = (Phi_q^T lam)_q = sum_r lam_r d2Phi_r/dq2,
//
// the tangent stiffness (for conservative forces Q = -V_q it is the Hessian
// of V + lam^T Phi). Redundant rows (found where the
// assembly lands, redundancy.hpp, and dropped in its Data) get lam = 0.
// Start: the assembled initial configuration (least change, as for a
// dynamic run) and the least-squares multipliers of Phi_q^T lam = Q there.
// Each step is limited to 0.5 rad in any angle and half a model length in
// any position, then halved until the merit |F1|^2 / f^2 + |Phi|^2 / l^2
// decreases (f: the force scale |Q|, l: the length scale).
//
// Stability: K reduced to the motions the joints allow, K_r = Z^T K_s Z with
// Z an orthonormal basis of the null space of Phi_q and K_s the symmetric
// part of K (non-conservative forces make K unsymmetric; for them this is a
// static check only). K_r positive definite: stable (a strict minimum of
// the potential on the constraint manifold); a negative eigenvalue:
// unstable, its eigenvector the mode in which it falls. Z and K_r are dense
// (a QR of Phi_q^T and a symmetric eigensolve, O(n^3)): a check meant for
// models up to a few hundred bodies.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "lagmb/model/model.hpp"

namespace lagmb {

struct EquilibriumOptions {
  double t = 0.0;              // time at which Q and the drivers are evaluated
  double tol = 1e-12;          // relative: |Q - Phi_q^T lam| <= tol |Q|, |Phi| <= tol (1 + |q|)
  int max_iterations = 100;
  bool allow_unstable = false;  // else an unstable equilibrium is an EquilibriumError
  // check stability (dense: O(n^3) in the coordinates, 15 s at 1,000 links);
  // without it `stable` is not known and allow_unstable has no effect
  bool stability = true;
};

struct Equilibrium {
  VecX q, lam;
  int iterations = 0;
  /// max |Q - Phi_q^T lam| (N or N m) and max |Phi| at q.
  double force_residual = 0.0, constraint_residual = 0.0;
  bool stability_checked = false, stable = false;
  /// Eigenvalues of the reduced tangent stiffness K_r, ascending (empty at
  /// 0 degrees of freedom or unchecked), and the mode (in q, unit norm) of the smallest.
  VecX stiffness_eigenvalues, softest_mode;
  /// Rows of Phi left out as redundant at q (ascending; lam is 0 there).
  std::vector<int> dropped_rows;
};

/// No equilibrium found, or an unstable one not allowed. A ModelError (the
/// model has no usable rest state), so a ValueError in Python.
struct EquilibriumError : ModelError {
  EquilibriumError(const std::string& what, std::vector<std::pair<std::string, double>> unbalanced_forces = {})
      : ModelError(what), unbalanced(std::move(unbalanced_forces)) {}
  /// (coordinate, e.g. "body 'rod' y", unbalanced generalized force), largest first.
  std::vector<std::pair<std::string, double>> unbalanced;
};

/// Finds the static equilibrium nearest (in the Newton sense) to the
/// assembled initial configuration. Throws EquilibriumError if Newton does
/// not converge (naming the coordinates with the largest unbalanced force)
/// or the equilibrium is unstable and not allowed; AssemblyError if the
/// initial configuration cannot be assembled.
Equilibrium find_equilibrium(const Model& model, const EquilibriumOptions& options = {});

}  // namespace lagmb
