// Uniform gravity acting on every body of the model.
#pragma once

#include <string>
#include <vector>

#include "lagmb/model/force_group.hpp"

namespace lagmb {

/// Q_i += m_i g on the centre-of-mass coordinates of every body and particle
/// (x, y in the plane, x, y, z in space); potential V = -sum_i m_i g . r_i.
/// Q does not depend on the state, so it adds nothing to the Newton matrix.
class Gravity final : public ForceGroupBase {
 public:
  explicit Gravity(Vec3 g) : g_(g) {}
  const Vec3& g() const { return g_; }

  int size() const override { return 1; }
  const std::string& name(int) const override { return name_; }
  const char* kind() const override { return "gravity"; }
  bool has_derivatives() const override { return false; }

  void place(const Model& model) override;
  void declare(SparsityPattern&, SparsityPattern&) const override {}
  void bind(const SpMat&, const SpMat&) override {}

  void add_forces(const double*, const double*, const Instant&, const double*, double* Q) const override {
    for (const auto& b : bodies_)
      for (int a = 0; a < b.dimension; ++a) Q[b.ix + a] += b.mass * g_[a];
  }
  void add_derivatives(const double*, const double*, const Instant&, const double*, double*, double*) const override {}
  double potential(const double* q, const Instant&) const override {
    double V = 0.0;
    for (const auto& b : bodies_)
      for (int a = 0; a < b.dimension; ++a) V -= b.mass * g_[a] * q[b.ix + a];
    return V;
  }

 private:
  struct Placed {
    int ix;
    double mass;
    int dimension;  // centre-of-mass coordinates: 2 or 3
  };
  Vec3 g_;
  std::string name_ = "gravity";
  std::vector<Placed> bodies_;
};

}  // namespace lagmb
