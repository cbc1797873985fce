// What the spatial drivers share: one row g(c) - f(t), time dependent
// through f. As in the plane, the effort is -lam, positive along the driven
// coordinate.
#pragma once

#include <cmath>
#include <string>

#include "lagmb/spatial_terms.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

/// One row, time dependent through f.
struct SpatialDriverBase {
  using Space = Spatial;
  static constexpr int rows = 1;
  static constexpr bool time_dependent = true;
  using Row = Eigen::Matrix<double, 1, 1>;
  using Grad = Eigen::Matrix<double, 1, 14>;
  std::string name;
  int body_i = -1, body_j = -1;
  Drive f;  // the prescribed value
  static constexpr bool reads_inputs = true;
  static constexpr bool ties_motion = true;  // (is_tie)
  Mat3 axes(const spatial::Loc&, const Instant&) const { return Mat3::Identity(); }
};

/// Shared by drivers whose row is g(c) - f(t) with g a scalar term:
/// Phi_t = -f', Phi_tc = 0, Phi_tt = -f''. A kind whose g is an angle
/// (periodic = true) takes the difference into (-pi, pi]: g and g + 2 pi are
/// one configuration, and the row then has the one root g = f (mod 2 pi),
/// whatever f's start and however far it jumps; the wrap is constant near
/// the root, so the derivatives are those of g - f.
template <class Kind>
struct SpatialCoordinateDriverBase : SpatialDriverBase {
  static constexpr bool periodic = false;
  Row phi(const spatial::Loc& c, const Instant& t) const {
    const double difference = self().coordinate(c, {}).value - f.at(t).f;
    return Row(Kind::periodic ? std::remainder(difference, 2.0 * kPi) : difference);
  }
  Grad jacobian(const spatial::Loc& c, const Instant&) const { return self().coordinate(c, {}).gradient; }
  void hessians(const spatial::Loc& c, const Instant&, spatial::Mat14* H) const { H[0] = self().coordinate(c, {true}).hessian; }
  Grad rates(const spatial::Loc& c, const spatial::Loc& cd, const Instant&) const {
    spatial::Want want;
    want.rate = &cd;
    return self().coordinate(c, want).gradient_rate;
  }
  Row phi_t(const spatial::Loc&, const Instant& t) const { return Row(-f.at(t).df); }
  Grad phi_tc(const spatial::Loc&, const Instant&) const { return Grad::Zero(); }
  Row phi_tt(const spatial::Loc&, const Instant& t) const { return Row(-f.at(t).ddf); }

 private:
  const Kind& self() const { return static_cast<const Kind&>(*this); }
};

}  // namespace lagmb
