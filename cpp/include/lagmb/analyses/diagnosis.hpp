// What a failed run or solve says about the model: where the constraint
// Jacobian became singular, and what made a state's accelerations non-finite.
#pragma once

#include <string>
#include <vector>

#include "lagmb/model/data.hpp"

namespace lagmb {

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
