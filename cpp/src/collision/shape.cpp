// Collision shapes (collision/shape.hpp): names, sizes and checks.
#include "lagmb/collision/shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lagmb {

namespace {
constexpr const char* kNames[] = {"plane", "sphere", "capsule", "box", "cylinder", "convex"};
constexpr int kSizes[] = {0, 1, 2, 3, 2, 0};
}  // namespace

const char* shape_kind_name(CollisionShape::Kind kind) { return kNames[kind]; }

CollisionShape::Kind shape_kind(const std::string& name) {
  std::string known;
  for (int k = 0; k < CollisionShape::kKinds; ++k) {
    if (name == kNames[k]) return CollisionShape::Kind(k);
    known += (k ? ", " : "") + std::string(kNames[k]);
  }
  throw ModelError("no collision shape kind '" + name + "'; the kinds are " + known);
}

int shape_size_count(CollisionShape::Kind kind) { return kSizes[kind]; }

double CollisionShape::bounding_radius() const {
  switch (kind) {
    case kPlane: return std::numeric_limits<double>::infinity();
    case kSphere: return size[0];
    case kCapsule: return size[0] + 0.5 * size[1];
    case kBox: return 0.5 * size.norm();
    case kCylinder: return std::hypot(size[0], 0.5 * size[1]);
    case kConvex: {
      double r = 0.0;
      for (const Vec3& v : vertices) r = std::max(r, v.norm());
      return r;
    }
    case kKinds: break;
  }
  return std::numeric_limits<double>::infinity();
}

void CollisionShape::check(const std::string& context) const {
  const std::string what = context + ": a " + shape_kind_name(kind);
  if (!position.allFinite()) throw ModelError(what + "'s position must be finite, got " + to_text(position));
  if (!axes.allFinite() || !(axes.transpose() * axes - Mat3::Identity()).isZero(1e-6) || !(axes.determinant() > 0.0))
    throw ModelError(what + "'s axes must be a rotation matrix");
  for (int k = 0; k < 3; ++k) {
    const bool used = k < shape_size_count(kind);
    if (used && !(std::isfinite(size[k]) && size[k] > 0.0) && !(kind == kCapsule && k == 1 && size[k] == 0.0))
      throw ModelError(what + "'s size must be positive and finite, got " + to_text(size));
    if (!used && size[k] != 0.0) throw ModelError(what + " has " + std::to_string(shape_size_count(kind)) +
                                                  " size numbers, got " + to_text(size));
  }
  if (kind == kConvex) {
    if (vertices.size() < 4) throw ModelError(what + " needs 4 vertices or more, got " + std::to_string(vertices.size()));
    Vec3 mean = Vec3::Zero();
    for (const Vec3& v : vertices) {
      if (!v.allFinite()) throw ModelError(what + " has a vertex that is not finite: " + to_text(v));
      mean += v / double(vertices.size());
    }
    Mat3 spread = Mat3::Zero();
    for (const Vec3& v : vertices) spread += (v - mean) * (v - mean).transpose();
    const double scale = spread.trace();
    if (!(scale > 0.0) || !(spread.determinant() > 1e-12 * scale * scale * scale))
      throw ModelError(what + "'s vertices span no volume (they lie in a plane)");
  } else if (!vertices.empty()) {
    throw ModelError(what + " has no vertices (only a convex shape has)");
  }
}

}  // namespace lagmb
