// lagmb: planar and spatial multibody dynamics in Cartesian coordinates with Lagrange
// multipliers. Include this header to use the library from C++. The headers
// sit in folders by layer, each including only from the layers before it
// (docs/design.md, section 2): the basic types here, then model/, the
// element kinds (elements/), spec/, solvers/, assembly/, analyses/,
// events/, integrators/, run/ and fmu/.
#pragma once

#include "lagmb/errors.hpp"
#include "lagmb/options.hpp"
#include "lagmb/trajectory.hpp"
#include "lagmb/types.hpp"

#include "lagmb/collision/pairs.hpp"
#include "lagmb/collision/shape.hpp"

#include "lagmb/model/contact_reading.hpp"
#include "lagmb/model/coordinates.hpp"
#include "lagmb/model/data.hpp"
#include "lagmb/model/model.hpp"
#include "lagmb/model/registry.hpp"

#include "lagmb/spec/parameters.hpp"
#include "lagmb/spec/spec.hpp"

#include "lagmb/solvers/block_cholesky.hpp"
#include "lagmb/solvers/sparse_qr.hpp"
#include "lagmb/solvers/sparse_lu.hpp"
#include "lagmb/solvers/sundials.hpp"

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/assembly/augmented.hpp"

#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/analyses/diagnosis.hpp"
#include "lagmb/analyses/equilibrium.hpp"
#include "lagmb/analyses/joint_space.hpp"
#include "lagmb/analyses/kinematics.hpp"
#include "lagmb/analyses/linearization.hpp"
#include "lagmb/analyses/redundancy.hpp"
#include "lagmb/analyses/stiffness.hpp"

#include "lagmb/events/event_runner.hpp"

#include "lagmb/integrators/methods.hpp"

#include "lagmb/run/outputs.hpp"
#include "lagmb/run/simulate.hpp"
#include "lagmb/run/simulator.hpp"

#include "lagmb/fmu/cosimulation.hpp"
