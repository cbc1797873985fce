// Prescribed motion of a coordinate x, y or z of a body's centre of mass.
#pragma once

#include "lagmb/elements/spatial_driver_base.hpp"

namespace lagmb {

/// A coordinate x, y or z (k = 0, 1, 2) of body j's centre of mass (body i
/// is the ground): g = r_j,k. Effort: the force along that axis on body j.
struct SpatialPositionDriver : SpatialCoordinateDriverBase<SpatialPositionDriver> {
  static constexpr const char* kind = "spatial_position_driver";
  int axis = 0;
  spatial::ScalarTerm coordinate(const spatial::Loc& c, const spatial::Want&) const {
    spatial::ScalarTerm g;
    g.value = c[7 + axis];
    g.gradient[7 + axis] = 1.0;
    g.hessian.setZero();
    return g;
  }
};

}  // namespace lagmb
