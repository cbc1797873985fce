// Solver trouble: carries where it happened and what was computed until then.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lagmb/trajectory.hpp"

namespace lagmb {

/// The integrator or a solve failed. t is the time reached; partial holds
/// the outputs computed before the failure (possibly none).
struct SimulationError : std::runtime_error {
  SimulationError(const std::string& what, double t_reached, Trajectory partial_result = {})
      : std::runtime_error(what), t(t_reached), partial(std::move(partial_result)) {}
  double t;
  Trajectory partial;
};

/// Positions could not be made to satisfy Phi(q, t) = 0.
struct AssemblyError : SimulationError {
  AssemblyError(const std::string& what, double t_reached,
                std::vector<std::pair<std::string, double>> violated_elements)
      : SimulationError(what, t_reached), violated(std::move(violated_elements)) {}
  /// (element name, max |Phi| over its rows), largest first.
  std::vector<std::pair<std::string, double>> violated;
};

}  // namespace lagmb
