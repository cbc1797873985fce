// Collision shapes: the geometry a spatial contact pairs (elements/
// spatial_contact.hpp), fixed in a body (or the ground) at a pose in its axes.
#pragma once

#include <string>
#include <vector>

#include "lagmb/types.hpp"

namespace lagmb {

/// One collision shape, in the axes of its body from the body's centre of
/// mass (the ground's: global): its centre `position` and its own axes
/// (`axes`: their columns in body axes). By kind, `size` holds
///   plane     ()                   the half-space z <= 0 of its own axes
///                                  (boundary through `position`, outward normal +z)
///   sphere    (R)
///   capsule   (R, L)               a segment of length L along its z, swept by a sphere of radius R
///   box       (lx, ly, lz)         edge lengths
///   cylinder  (R, L)               along its z
///   convex    ()                   the convex hull of `vertices` (its own axes, m)
/// and the unused entries of `size` are 0.
struct CollisionShape {
  enum Kind { kPlane, kSphere, kCapsule, kBox, kCylinder, kConvex, kKinds };
  int body = -1;  // the body's index, -1: the ground
  Kind kind = kSphere;
  Vec3 size = Vec3::Zero();
  Vec3 position = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
  std::vector<Vec3> vertices;  // kConvex

  /// The radius of a sphere about `position` that holds the shape (a
  /// plane's: infinite), the broad phase of a contact.
  double bounding_radius() const;
  /// ModelError naming `context` unless the size (and vertices) fit the
  /// kind: finite, positive where a length, a convex shape with vertices
  /// spanning a volume, axes a rotation.
  void check(const std::string& context) const;
};

/// The name of a shape kind ("plane", "sphere", ...) and its kind from a name
/// (ModelError listing the kinds).
const char* shape_kind_name(CollisionShape::Kind kind);
CollisionShape::Kind shape_kind(const std::string& name);
/// How many numbers a kind's size has (plane 0, sphere 1, capsule and cylinder 2, box 3, convex 0).
int shape_size_count(CollisionShape::Kind kind);

}  // namespace lagmb
