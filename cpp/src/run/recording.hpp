// A run's outputs as they are recorded: the states at the output times,
// and their accelerations and multipliers solved from the augmented system.
#pragma once

#include <string>

#include "lagmb/analyses/redundancy.hpp"
#include "lagmb/assembly/augmented.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

/// a and lam at the recorded outputs of `tr` from `first` on, from the
/// augmented system, appended output by output (tr.a holds size_t(k) * n
/// values once k are solved). Returns "" or why an output could not be
/// solved (a user function failing there, joint friction whose load does not
/// converge, a non-finite result); the outputs from that one on are then
/// unsolved.
std::string solve_outputs(const Model& model, Data& d, AugmentedSystem& kkt, Trajectory& tr, int first = 0);

/// Appends the output (t, q, v) and the run's values there (its inputs and
/// element state) to `tr`, and with `solve` its a and lam (`qdd`, `lam`
/// where the caller has them solved at (t, q, v) on the run's rows, else
/// solved here); first checks the rows left out as redundant (`watch`).
/// Throws IntegratorFailure (diagnose = false) with why, keeping only the
/// outputs solved before.
void record_output(const Model& model, Data& d, AugmentedSystem& kkt, RedundancyWatch& watch, Trajectory& tr,
                   double t, const double* q, const double* v, const Data::RunValues& values, bool solve,
                   const double* qdd = nullptr, const double* lam = nullptr);

/// Outputs of `tr` whose a and lam were solved.
int solved_outputs(const Trajectory& tr);

}  // namespace lagmb
