// Structural questions about a model at one configuration.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "lagmb/model/data.hpp"

namespace lagmb {

/// Rank of Phi_q(q, t) and the rows found dependent on the others.
struct ConstraintRank {
  int rank = 0;
  int equations = 0;
  int coordinates = 0;
  std::vector<int> dependent_rows;
  /// Degrees of freedom: coordinates - rank.
  int degrees_of_freedom() const { return coordinates - rank; }
};

/// Rank-revealing sparse QR (COLAMD ordering, column pivoting by norm) of
/// Phi_q^T; a column (equation) whose remaining norm falls below
/// tol * (largest column norm) counts as dependent.
ConstraintRank constraint_rank(const Model& model, const VecX& q, double t, double tol = 1e-9);

/// The coordinates of q that turn, with the angle per unit of each: a
/// planar body's angle (1) and a spatial body's Euler parameters (2: a turn
/// by theta moves p by about theta / 2). What the step limits of assembly,
/// equilibrium and kinematic analysis bound.
std::vector<std::pair<int, double>> turning_coordinates(const Model& model);

/// "body 'rod' angle": the body and the role of coordinate `coord` of q.
std::string coordinate_label(const Model& model, int coord);

/// Why a run may have stopped at (q, t), in terms of the model: if Phi_q is
/// (nearly) singular there (the ratio of its smallest to largest singular
/// value tenfold below that ratio at the start, or below 1e-6; the rows the run dropped as redundant left out), the elements
/// whose equations take part in the dependency (the left singular vector)
/// are named: a dead point, toggle or lock-up, and formulation "ali3p" is
/// suggested for a mechanism that should pass through it. Otherwise a hint
/// about stiffness or time resolution. Dense SVD: models up to 1000 equations.
std::string diagnose_failure(const Model& model, const VecX& q, double t, const std::vector<int>& dropped_rows);

/// What makes (q, v, t) give non-finite accelerations: a non-finite state,
/// applied force (naming the body and coordinate and the force kinds) or
/// constraint term gamma (naming the element), with the inputs and element
/// state of `run`.
std::string non_finite_source(const Model& model, const Data& run, const double* q, const double* v, double t);

}  // namespace lagmb
