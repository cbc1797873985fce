// How fast the applied forces make a model move: the rate that bounds an
// explicit integrator's step, from which formulation "auto" chooses the
// method (run.cpp, choose_method).
#pragma once

#include "lagmb/model/model.hpp"

namespace lagmb {

/// The fastest rates of the applied forces at (q, v, t): with K = -Q_q and
/// C = -Q_v (springs, bushings, contact in progress, joint friction's
/// smoothed sign), omega = sqrt(|lambda_max(P K)|) (rad/s) and
/// sigma = |lambda_max(P C)| (1/s), by power iteration with the inverse
/// mass the joints leave, P b = the y of [M Phi_q^T; Phi_q 0] [y; mu] = [b;
/// 0] (a servo's torque on a joint moves every body that joint carries: a
/// light hub with a heavy arm welded to it is rated by both); M^-1 where
/// the model has no constraints or its augmented matrix does not factorize.
/// An explicit Runge-Kutta step h needs h max(omega, sigma) below a few
/// units to stay stable.
struct ForceRates {
  double omega = 0.0;  // rad/s, the fastest stiffness mode
  double sigma = 0.0;  // 1/s, the fastest damping rate
  double fastest() const { return omega > sigma ? omega : sigma; }
};
ForceRates force_rates(const Model& model, const double* q, const double* v, double t);

}  // namespace lagmb
