// One container per force kind and the loop that runs over it.
#pragma once

#include <string>

#include "lagmb/sparsity.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

class Model;

/// A kind of applied force. Each contributes to Q(q, v, t) and, where Q
/// depends on the state, to its exact derivatives Q_q and Q_v, which the
/// Newton matrix needs (stiff springs). Kinds whose Q is constant say so in
/// has_derivatives() and are skipped when the Newton matrix is assembled.
class ForceGroupBase {
 public:
  virtual ~ForceGroupBase() = default;
  virtual int size() const = 0;
  virtual const std::string& name(int k) const = 0;
  virtual const char* kind() const = 0;
  virtual bool has_derivatives() const = 0;

  // finalize: find coordinates, declare and bind derivative slots
  virtual void place(const Model& model) = 0;
  virtual void declare(SparsityPattern& Q_q, SparsityPattern& Q_v) const = 0;
  virtual void bind(const SpMat& Q_q, const SpMat& Q_v) = 0;

  virtual void add_forces(const double* q, const double* v, double t, double* Q) const = 0;
  virtual void add_derivatives(const double* q, const double* v, double t, double* Q_q_values,
                               double* Q_v_values) const = 0;
  /// Potential energy of the conservative part; 0 for dissipative kinds.
  virtual double potential(const double* q, double t) const = 0;
};

}  // namespace lagmb
