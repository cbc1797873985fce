// Time integration of a model: options in, Trajectory out.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "lagmb/augmented.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/model.hpp"
#include "lagmb/options.hpp"
#include "lagmb/parameters.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {


/// Makes the initial state consistent, integrates, and returns the states at
/// the output times. Throws ModelError for bad options, AssemblyError if the
/// initial positions cannot be made consistent, SimulationError (with the
/// outputs reached so far) if the integrator fails.
Trajectory simulate(const Model& model, const SimulationOptions& options);
/// The same run of `model` with other parameter values (parameters.hpp):
/// the model built with them runs, and the trajectory keeps it
/// (Trajectory::run_model). Empty `parameters`: simulate(model, options).
Trajectory simulate(const Model& model, const SimulationOptions& options, const ParameterValues& parameters);

/// Version of the SUNDIALS library lagmb was built with, e.g. "6.4.1".
std::string sundials_version();

/// lagmb's own operations on SUNDIALS serial vectors (they replace the
/// library's, which Debian builds without optimization) against SUNDIALS'
/// serial ones, on random vectors of length n, with the aliasings SUNDIALS
/// uses (z = x or y in a linear sum; z = X_0 or X_1 in a linear
/// combination; Z = Y in a scale-add): the largest difference per
/// operation, relative to the largest entry.
std::map<std::string, double> compare_vector_operations(int n, unsigned seed);

/// qdd and lam at one instant (the augmented system of docs/design.md section 1.2).
void solve_accelerations(const Model& model, const VecX& q, const VecX& v, double t, VecX& qdd,
                         VecX& lam);

/// Consistent (q, v, qdd, lam) at time t from the model's initial values.
ConsistentState assemble(const Model& model, double t = 0.0);

}  // namespace lagmb
