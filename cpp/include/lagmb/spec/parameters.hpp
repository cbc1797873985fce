// Run-time parameters: the numbers given to a model's elements, which a run
// may change without the user compiling the model again.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lagmb/model/model.hpp"
#include "lagmb/spec/spec.hpp"

namespace lagmb {

/// One parameter of a compiled model: a number given to an element (a
/// parameter of type real), or one component of a point or vector it was
/// given, named as the FMU and `lagmb info` name it:
///   "rod.mass", "spring.stiffness", "pin.at.x", "pole.angle.start"
/// (".start" where the name would be a body coordinate's: the initial value).
struct ParameterInfo {
  std::string name;
  std::string element;  // "rod"
  std::string key;      // its parameter in the registry: "mass", "at"
  int component = -1;   // -1: a number; 0, 1, 2: x, y, z of a point or vector
  std::string unit;     // SI
  std::string doc;
  double value = 0.0;   // the compiled model's (a run's default)
};

/// Parameter values by name.
using ParameterValues = std::map<std::string, double>;

/// The parameters of `model`, element by element in the order added: every
/// real, point and vector parameter with a value (given or the kind's
/// default). Inertia tensors, orientations, flags and functions of time are
/// not parameters.
std::vector<ParameterInfo> parameters(const Model& model);

/// `model` with other parameter values: its elements built again from their
/// given values with `values` in place (through the same builders, so the
/// result equals a model compiled with those values, bit for bit, and each
/// value is checked as ModelSpec::add checks it), finalized. The structure
/// (coordinates, rows, patterns, inputs) is that of `model`. ModelError for
/// an unknown name (listing the parameters), a value that is not finite or
/// that the element refuses. `copy`: as ModelSpec::build applies it to the
/// time functions. Empty `values`: null (run `model` itself).
std::shared_ptr<Model> with_parameters(const Model& model, const ParameterValues& values,
                                       const ModelSpec::FunctionCopy& copy = nullptr);

}  // namespace lagmb
