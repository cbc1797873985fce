// lagmb: planar and spatial multibody dynamics in Cartesian coordinates with Lagrange
// multipliers. Include this header to use the library from C++.
#pragma once

#include "lagmb/analysis.hpp"
#include "lagmb/assembly.hpp"
#include "lagmb/augmented.hpp"
#include "lagmb/cosimulation.hpp"
#include "lagmb/data.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/model.hpp"
#include "lagmb/outputs.hpp"
#include "lagmb/parameters.hpp"
#include "lagmb/simulate.hpp"
#include "lagmb/simulator.hpp"
#include "lagmb/trajectory.hpp"
#include "lagmb/types.hpp"
#include "lagmb/kinematics.hpp"
#include "lagmb/equilibrium.hpp"
#include "lagmb/methods.hpp"
#include "lagmb/registry.hpp"
#include "lagmb/spec.hpp"
