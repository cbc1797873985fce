// The small mechanisms the C++ unit tests check, built through the C++ API
// as a user does (examples/cpp): each test file takes them from here.
#pragma once

#include <memory>
#include <random>

#include "lagmb/model/model.hpp"
#include "lagmb/spec/spec.hpp"

namespace lagmb_test {

using namespace lagmb;

constexpr double kG = 9.81;

/// The seed pendulum: a uniform rod of 1 kg and 1 m pinned ("pin") at the
/// origin at one end, horizontal, at rest; its centre at (0.5, 0).
inline std::shared_ptr<const Model> pendulum() {
  ModelSpec spec;
  spec.set_gravity(Vec2(0.0, -kG));
  spec.add("body", "rod", {{"mass", 1.0}, {"inertia", 1.0 / 12.0}, {"position", Vec2(0.5, 0.0)}});
  spec.add("revolute", "pin", {{"body_i", "ground"}, {"body_j", "rod"}, {"at", Vec2(0.0, 0.0)}});
  return spec.compile();
}

/// The pendulum with a stop ("stop") on its pin: lower -pi/4, upper pi/4.
inline std::shared_ptr<const Model> pendulum_with_stop() {
  ModelSpec spec;
  spec.set_gravity(Vec2(0.0, -kG));
  spec.add("body", "rod", {{"mass", 1.0}, {"inertia", 1.0 / 12.0}, {"position", Vec2(0.5, 0.0)}});
  spec.add("revolute", "pin", {{"body_i", "ground"}, {"body_j", "rod"}, {"at", Vec2(0.0, 0.0)}});
  spec.add("stop", "stop", {{"joint", "pin"}, {"lower", -0.7853981633974483}, {"upper", 0.7853981633974483}});
  return spec.compile();
}

/// The same rod in space on a spherical joint ("pin"), gravity along -z.
inline std::shared_ptr<const Model> spatial_pendulum() {
  ModelSpec spec(3);
  spec.set_gravity(Vec3(0.0, 0.0, -kG));
  spec.add("spatial_body", "rod",
           {{"mass", 1.0}, {"inertia", Vec3(1e-4, 1.0 / 12.0, 1.0 / 12.0)}, {"position", Vec3(0.5, 0.0, 0.0)}});
  spec.add("spherical", "pin", {{"body_i", "ground"}, {"body_j", "rod"}, {"at", Vec3(0.0, 0.0, 0.0)}});
  return spec.compile();
}

/// Two such rods in a chain ("shoulder" at the origin, "elbow" at (1, 0)).
inline std::shared_ptr<const Model> double_pendulum() {
  ModelSpec spec;
  spec.set_gravity(Vec2(0.0, -kG));
  spec.add("body", "upper", {{"mass", 1.0}, {"inertia", 1.0 / 12.0}, {"position", Vec2(0.5, 0.0)}});
  spec.add("body", "lower", {{"mass", 1.0}, {"inertia", 1.0 / 12.0}, {"position", Vec2(1.5, 0.0)}});
  spec.add("revolute", "shoulder", {{"body_i", "ground"}, {"body_j", "upper"}, {"at", Vec2(0.0, 0.0)}});
  spec.add("revolute", "elbow", {{"body_i", "upper"}, {"body_j", "lower"}, {"at", Vec2(1.0, 0.0)}});
  return spec.compile();
}

/// examples/slider_crank.toml without its motor: crank (0.1 m) at 90 deg,
/// connecting rod (0.3 m), slider on a guide along x through the origin.
inline std::shared_ptr<const Model> slider_crank() {
  const double cx = 0.282842712474619;  // sqrt(0.3^2 - 0.1^2)
  ModelSpec spec;
  spec.set_gravity(Vec2(0.0, -kG));
  spec.add("body", "crank", {{"mass", 1.0}, {"inertia", 0.1 * 0.1 / 12.0}, {"position", Vec2(0.0, 0.05)},
                             {"angle", 1.5707963267948966}});
  spec.add("body", "rod", {{"mass", 2.0}, {"inertia", 2.0 * 0.09 / 12.0}, {"position", Vec2(cx / 2, 0.05)},
                           {"angle", -0.339836909454122}});
  spec.add("body", "slider", {{"mass", 0.5}, {"inertia", 1e-4}, {"position", Vec2(cx, 0.0)}});
  spec.add("revolute", "O", {{"body_i", "ground"}, {"body_j", "crank"}, {"at", Vec2(0.0, 0.0)}});
  spec.add("revolute", "B", {{"body_i", "crank"}, {"body_j", "rod"}, {"at", Vec2(0.0, 0.1)}});
  spec.add("revolute", "C", {{"body_i", "rod"}, {"body_j", "slider"}, {"at", Vec2(cx, 0.0)}});
  spec.add("translational", "guide",
           {{"body_i", "ground"}, {"body_j", "slider"}, {"at", Vec2(cx, 0.0)}, {"axis", Vec2(1.0, 0.0)}});
  return spec.compile();
}

/// A state drawn from `random`: every coordinate in [-1, 1] (Euler
/// parameters included: the constraints' derivatives hold off the unit
/// sphere too).
inline VecX random_vector(int n, std::mt19937& random) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VecX x(n);
  for (int k = 0; k < n; ++k) x[k] = u(random);
  return x;
}

}  // namespace lagmb_test
