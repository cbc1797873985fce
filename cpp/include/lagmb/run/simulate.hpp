// Time integration of a model: options in, Trajectory out.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/model/model.hpp"
#include "lagmb/options.hpp"
#include "lagmb/spec/parameters.hpp"
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
/// `sensitivities`: parameter names whose forward sensitivities the run
/// integrates beside the state (Trajectory::sensitivities; IDAS on the GGL
/// form, which formulation "auto" then runs); ModelError where a run cannot
/// be differentiated (events, joint friction, another method, a fully
/// driven model).
Trajectory simulate(const Model& model, const SimulationOptions& options, const ParameterValues& parameters,
                    const std::vector<std::string>& sensitivities = {});

/// The analysis options.analysis asks for, resolved: dynamic, kinematic or
/// inverse dynamics. kAuto picks inverse dynamics at 0 DOF (kinematic if
/// some body is massless) and dynamic otherwise. Throws ModelError for a
/// kinematic analysis of a model with DOF > 0 (naming the count), or a
/// dynamic analysis of a model with a massless body (naming it).
Analysis resolve_analysis(const Model& model, const SimulationOptions& options);

/// qdd and lam at one instant (the augmented system of docs/design.md section 1.2).
void solve_accelerations(const Model& model, const VecX& q, const VecX& v, double t, VecX& qdd,
                         VecX& lam);

/// Consistent (q, v, qdd, lam) at time t from the model's initial values.
ConsistentState assemble(const Model& model, double t = 0.0);

}  // namespace lagmb
