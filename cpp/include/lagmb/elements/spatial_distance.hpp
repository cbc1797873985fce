// The spatial kind "spatial_distance" (registry.hpp; its builder in cpp/src/elements/spatial_distance.cpp).
#pragma once

#include "lagmb/elements/spatial_joint.hpp"

namespace lagmb {

/// Distance: a massless rigid link between the points s_i and s_j,
///   Phi = (d . d - L^2) / (2 L),
/// scaled so that lam is the link's tension (the force on body j is -lam d / L).
/// Joint axes: (f, g, d / |d|), f and g across the link.
struct SpatialDistanceJoint : SpatialJointBase, spatial::TermJoint<SpatialDistanceJoint, 1> {
  static constexpr const char* kind = "spatial_distance";
  double length = 1.0;
  spatial::Terms<1> terms(const spatial::Loc& c, const spatial::Want& want) const {
    const spatial::VectorTerm d = offset(c, want);
    spatial::ScalarTerm f = spatial::dot(d, d, want);
    f.value = (f.value - length * length) / (2.0 * length);
    f.gradient /= 2.0 * length;
    f.gradient_rate /= 2.0 * length;
    f.velocity /= 2.0 * length;
    f.convective /= 2.0 * length;
    if (want.hessian) f.hessian /= 2.0 * length;
    return {f};
  }
  Mat3 axes(const spatial::Loc& c, double) const {
    Vec3 e = offset(c, {}).value;
    e = e.norm() > 0.0 ? Vec3(e.normalized()) : Vec3::UnitZ();
    Vec3 f, g;
    euler::complete_basis(e, f, g);
    Mat3 E;
    E << f, g, e;
    return E;
  }
};

}  // namespace lagmb
