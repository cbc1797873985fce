// The small mechanisms the C++ unit tests check, built through the C++ API
// as a user does (examples/cpp): each test file takes them from here.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <random>

#include "lagmb/model/model.hpp"
#include "lagmb/model/registry.hpp"
#include "lagmb/spec/spec.hpp"
#include "lagmb/time_function.hpp"

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

/// A block of 1 kg ("block") on a vertical guide ("guide": a translational
/// joint along y through the origin, its slide s = y) with a stop ("stop")
/// at `lower` and, unless NaN, `upper`, of restitution e; under gravity,
/// and pushed up by F = push_rate t (N) where push_rate > 0 ("push").
/// Its rows: the guide's two, then the gaps g_lower = s - lower and
/// g_upper = upper - s; its event functions, one per gap in that order.
inline std::shared_ptr<const Model> block_on_a_guide(double lower, double upper, double e, double push_rate = 0.0) {
  ModelSpec spec;
  spec.set_gravity(Vec2(0.0, -kG));
  spec.add("body", "block", {{"mass", 1.0}, {"inertia", 1.0 / 12.0}, {"position", Vec2(0.0, 0.0)}});
  spec.add("translational", "guide",
           {{"body_i", "ground"}, {"body_j", "block"}, {"at", Vec2(0.0, 0.0)}, {"axis", Vec2(0.0, 1.0)}});
  Args stop(find_kind("stop"));
  stop.set("joint", std::string("guide"));
  stop.set("lower", lower);
  if (!std::isnan(upper)) stop.set("upper", upper);
  stop.set("restitution", e);
  spec.add("stop", std::move(stop));
  if (push_rate > 0.0) spec.add("force", "push", {{"body", "block"}, {"force", constant(0.0), linear(push_rate)}});
  return spec.compile();
}

/// A ball ("ball", radius R, 1 kg) at (-1, 0, 0) and a sphere of radius r
/// fixed at the origin ("post", on the ground), their contact "touch"
/// (stiffness 1e6, e = 0.5, no friction); no gravity.
inline std::shared_ptr<const Model> ball_and_post(double R, double r) {
  ModelSpec spec(3);
  spec.add("spatial_body", "ball",
           {{"mass", 1.0}, {"inertia", Vec3(Vec3::Constant(0.4 * R * R))}, {"position", Vec3(-1.0, 0.0, 0.0)}});
  CollisionShape ball, post;
  ball.body = spec.draft().find("ball").group;
  ball.kind = post.kind = CollisionShape::kSphere;
  ball.size = Vec3(R, 0.0, 0.0);
  post.size = Vec3(r, 0.0, 0.0);  // (body -1: the ground; at the origin)
  Args touch(find_kind("spatial_contact"));
  touch.set("shape_a", ball), touch.set("shape_b", post);
  touch.set("stiffness", 1e6), touch.set("restitution", 0.5);
  spec.add("touch", std::move(touch));
  return spec.compile();
}

/// A cube of 1 kg and edge a on a floor ("floor": a plane at z = 0;
/// stiffness k, friction mu, static friction mu_s), sunk to where its four
/// corners carry its weight (d0 = (g / 4k)^(2/3) each), pushed along x by
/// F = push_rate t (N) at (0, 0, -d0), the level of its pressing corners
/// ("push"). Gravity along -z.
inline std::shared_ptr<const Model> block_on_a_floor(double a, double k, double mu, double mu_s, double push_rate) {
  const double d0 = std::pow(kG / (4.0 * k), 2.0 / 3.0);
  ModelSpec spec(3);
  spec.set_gravity(Vec3(0.0, 0.0, -kG));
  spec.add("spatial_body", "block",
           {{"mass", 1.0}, {"inertia", Vec3(Vec3::Constant(a * a / 6.0))}, {"position", Vec3(0.0, 0.0, a / 2 - d0)}});
  CollisionShape box, plane;
  box.body = spec.draft().find("block").group;
  box.kind = CollisionShape::kBox;
  box.size = Vec3(a, a, a);
  plane.kind = CollisionShape::kPlane;
  Args contact(find_kind("spatial_contact"));
  contact.set("shape_a", box), contact.set("shape_b", plane);
  contact.set("stiffness", k), contact.set("restitution", 0.5), contact.set("friction", mu);
  contact.set("static_friction", mu_s);
  spec.add("floor", std::move(contact));
  Args push(find_kind("spatial_force"));
  push.set("body", std::string("block"));
  push.set("force", std::array<TimeFunctionPtr, 3>{linear(push_rate), constant(0.0), constant(0.0)});
  push.set("point", Vec3(0.0, 0.0, -d0));
  spec.add("push", std::move(push));
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
