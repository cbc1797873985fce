// Structural questions about a model at one configuration.
#pragma once

#include <string>
#include <vector>

#include "lagmb/model.hpp"

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

}  // namespace lagmb
