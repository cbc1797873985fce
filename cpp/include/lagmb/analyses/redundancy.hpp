// Redundant constraint equations: which rows a run leaves out, and the
// check that what was left out stays satisfied.
#pragma once

#include <string>
#include <vector>

#include "lagmb/assembly/augmented.hpp"
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

/// The rows of Phi a run drops, and the elements each depends on.
struct Redundancy {
  std::vector<int> rows;  // sorted
  /// For each dropped row, the names of the elements in its dependent set
  /// (its own element first).
  std::vector<std::vector<std::string>> partners;
  /// The rank of Phi_q at the start is lower than nearby: a singular
  /// position (a flat parallelogram, a toggle), not a redundancy.
  bool singular_start = false;
};

/// Rows of Phi that depend on the others for the motion near the assembled
/// configuration (q, t), i.e. consistently redundant equations (a
/// parallelogram's third crank, a joint given twice).
///
/// The rank of Phi_q also drops at singular positions, momentarily; there
/// the "dependent" rows are independent a little further on, and dropping
/// them would let the mechanism come apart. So where Phi_q(q, t) is rank
/// deficient (rank-revealing sparse QR of Phi_q^T), the rank is also taken at
/// a few nearby configurations on the constraint manifold: q plus a random
/// M-orthogonal move in the null space of Phi_q (and, for driven models, the
/// driven motion over a short time), re-assembled onto Phi = 0. The rows
/// dependent where the rank is highest are the redundant ones. `d` and `kkt`
/// are scratch (every row evaluated).
Redundancy find_redundancy(const Model& model, Data& d, class AugmentedSystem& kkt, const VecX& q, double t);

/// Names the partners of each dropped row: its coefficients as a
/// combination of the kept rows, from the augmented system factorized with
/// the kept rows (kkt) at q, and the full Jacobian in `full`.
void name_partners(const Model& model, const Data& full, AugmentedSystem& kkt, Redundancy& r);

/// Along a run, the dropped rows must stay as satisfied as the kept rows
/// make them: |Phi_r(q, t)| <= 1e-6 (1 + |q|) + 100 max |Phi_kept|. A
/// consistently redundant row is a combination of kept rows, so it stays
/// within that; a row that was dependent only at the start (conflicting
/// drivers, a loop closed at a toggle) grows. Returns "" or the violation,
/// naming the elements.
class RedundancyWatch {
 public:
  /// The rows are evaluated with the inputs and element state of `run`.
  RedundancyWatch(const Model& model, const Data& run, Redundancy redundancy);
  bool active() const { return !r_.rows.empty(); }
  std::string violation(const double* q, double t);
  long element_evaluations() const { return full_.element_evaluations; }

 private:
  const Model& model_;
  Redundancy r_;
  Data full_;  // every row evaluated
};

/// "'A', 'B' and 'C'".
std::string quoted_names(const std::vector<std::string>& names);

}  // namespace lagmb
