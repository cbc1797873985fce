// Uniform gravity acting on every body of the model.
#pragma once

#include <string>
#include <vector>

#include "lagmb/force_group.hpp"

namespace lagmb {

/// Q_i += m_i g on the centre-of-mass coordinates of every body and particle;
/// potential V = -sum_i m_i g . r_i. Q does not depend on the state, so it
/// adds nothing to the Newton matrix.
class Gravity final : public ForceGroupBase {
 public:
  explicit Gravity(Vec2 g) : g_(g) {}
  const Vec2& g() const { return g_; }

  int size() const override { return 1; }
  const std::string& name(int) const override { return name_; }
  const char* kind() const override { return "gravity"; }
  bool has_derivatives() const override { return false; }

  void place(const Model& model) override;
  void declare(SparsityPattern&, SparsityPattern&) const override {}
  void bind(const SpMat&, const SpMat&) override {}

  void add_forces(const double*, const double*, double, const double*, double* Q) const override {
    for (const auto& b : bodies_) {
      Q[b.ix] += b.mass * g_.x();
      Q[b.ix + 1] += b.mass * g_.y();
    }
  }
  void add_derivatives(const double*, const double*, double, const double*, double*, double*) const override {}
  double potential(const double* q, double) const override {
    double V = 0.0;
    for (const auto& b : bodies_) V -= b.mass * (g_.x() * q[b.ix] + g_.y() * q[b.ix + 1]);
    return V;
  }

 private:
  struct Placed {
    int ix;
    double mass;
  };
  Vec2 g_;
  std::string name_ = "gravity";
  std::vector<Placed> bodies_;
};

}  // namespace lagmb
