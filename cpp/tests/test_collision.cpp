// The collision table (lagmb/collision/pairs.hpp): every pair's geometry
// gives the same contact points over doubles and Dual numbers (over both
// bodies' coordinates, and over the first's alone), its gaps' derivatives
// (the Dual part) are the central differences of its double gaps, and each
// gap's rate g' is that derivative along the velocities (d g / dt = g_c .
// cd), for bodies turning and moving in general ways.
#include <cmath>
#include <limits>
#include <vector>

#include "check.hpp"
#include "lagmb/collision/pairs.hpp"
#include "lagmb/collision/shape.hpp"
#include "lagmb/spatial.hpp"

using namespace lagmb_test;
using lagmb::CollisionShape;
using lagmb::Mat3;
using lagmb::Vec3;
using lagmb::Vec4;
using lagmb::collision::ContactDual;
using lagmb::collision::ContactPoint;
using lagmb::collision::Motion;

namespace {

using Loc = Eigen::Matrix<double, 14, 1>;
constexpr double kAll = std::numeric_limits<double>::infinity();  // (reach: every point exact)

CollisionShape shape(CollisionShape::Kind kind, Vec3 size, Vec3 position, const Mat3& axes) {
  CollisionShape s;
  s.kind = kind;
  s.size = size;
  s.position = position;
  s.axes = axes;
  return s;
}

Mat3 turn(double angle, Vec3 axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

/// (c, cd) of two bodies: unit Euler parameters, their rates across them (p . p' = 0).
void state(const Vec3& ra, const Mat3& Ra, const Vec3& rb, const Mat3& Rb, Loc& c, Loc& cd) {
  c << ra, lagmb::euler::from_matrix(Ra), rb, lagmb::euler::from_matrix(Rb);
  cd << 0.3, -0.2, -0.5, 0.0, 0.0, 0.0, 0.0, 0.1, 0.05, -0.1, 0.0, 0.0, 0.0, 0.0;
  const Vec3 wa(0.7, -0.4, 0.9), wb(-0.3, 0.5, 0.2);  // angular velocities, global
  cd.segment<4>(3) = 0.5 * lagmb::euler::E(c.segment<4>(3)).transpose() * wa;
  cd.segment<4>(10) = 0.5 * lagmb::euler::E(c.segment<4>(10)).transpose() * wb;
}

template <class T>
void motions(const T* c, const T* cd, Motion<T>& A, Motion<T>& B) {
  A.r = {c[0], c[1], c[2]};
  A.rd = {cd[0], cd[1], cd[2]};
  B.r = {c[7], c[8], c[9]};
  B.rd = {cd[7], cd[8], cd[9]};
  for (int k = 0; k < 4; ++k) {
    A.p[k] = c[3 + k], A.pd[k] = cd[3 + k], B.p[k] = c[10 + k], B.pd[k] = cd[10 + k];
  }
}

std::vector<ContactPoint<double>> points_at(const lagmb::collision::Pair& pair, const CollisionShape& a,
                                            const CollisionShape& b, const Loc& c, const Loc& cd) {
  Motion<double> A, B;
  motions(c.data(), cd.data(), A, B);
  std::vector<ContactPoint<double>> out(pair.points(a, b));
  pair.at(a, b, A, B, out.data(), kAll);
  return out;
}

/// The pair (a, b) at (c, cd): values over both number types, gap
/// derivatives against differences, rates against derivatives (`rated`:
/// how many of the points have exact rates: a cylinder's deepest rim point,
/// not the three beside it).
void check_pair(const CollisionShape& a, const CollisionShape& b, const Loc& c, const Loc& cd, int rated = -1) {
  const lagmb::collision::Pair* pair = lagmb::collision::find_pair(a.kind, b.kind);
  CHECK(pair != nullptr);
  if (!pair) return;
  const auto values = points_at(*pair, a, b, c, cd);
  ContactDual x[14], xd[14];
  for (int k = 0; k < 14; ++k) {
    x[k] = ContactDual(c[k]);
    x[k].d[k] = 1.0;
    xd[k] = ContactDual(cd[k]);
    xd[k].d[14 + k] = 1.0;
  }
  Motion<ContactDual> A, B;
  motions(x, xd, A, B);
  std::vector<int> all(values.size());
  for (size_t k = 0; k < values.size(); ++k) all[k] = int(k);
  std::vector<ContactPoint<ContactDual>> duals(values.size());
  pair->derivative(a, b, A, B, all.data(), int(all.size()), duals.data());
  // over body a's coordinates alone (the ground under it: OneBodyDual), the same first derivatives
  lagmb::collision::OneBodyDual y[14], yd[14];
  for (int k = 0; k < 14; ++k) {
    y[k] = lagmb::collision::OneBodyDual(c[k]);
    yd[k] = lagmb::collision::OneBodyDual(cd[k]);
    if (k < 7) y[k].d[k] = 1.0, yd[k].d[7 + k] = 1.0;
  }
  Motion<lagmb::collision::OneBodyDual> A1, B1;
  motions(y, yd, A1, B1);
  std::vector<ContactPoint<lagmb::collision::OneBodyDual>> ones(values.size());
  pair->one_body(a, b, A1, B1, all.data(), int(all.size()), ones.data());
  for (size_t k = 0; k < values.size(); ++k) {
    CHECK((ones[k].gap.d.head<7>() - duals[k].gap.d.head<7>()).norm() <= 1e-13);
    CHECK((ones[k].gap_rate.d.tail<7>() - duals[k].gap_rate.d.segment<7>(14)).norm() <= 1e-13);
  }
  const double h = 1e-6;
  for (size_t k = 0; k < values.size(); ++k) {
    CHECK_NEAR(duals[k].gap.v, values[k].gap, 1e-14);
    CHECK_NEAR(duals[k].gap_rate.v, values[k].gap_rate, 1e-13);
    CHECK((duals[k].point.value() - values[k].point.value()).norm() <= 1e-14);
    CHECK((duals[k].normal.value() - values[k].normal.value()).norm() <= 1e-14);
    double scale = 1.0, worst = 0.0, along = 0.0;
    for (int j = 0; j < 14; ++j) {
      Loc up = c, down = c;
      up[j] += h, down[j] -= h;
      const double fd = (points_at(*pair, a, b, up, cd)[k].gap - points_at(*pair, a, b, down, cd)[k].gap) / (2 * h);
      worst = std::max(worst, std::abs(duals[k].gap.d[j] - fd));
      scale = std::max(scale, std::abs(fd));
      along += duals[k].gap.d[j] * cd[j];
    }
    CHECK(worst <= 1e-7 * scale);
    if (rated < 0 || int(k) % 4 < rated) CHECK_NEAR(values[k].gap_rate, along, 1e-12);
  }
}

}  // namespace

TEST_CASE(vertex_and_ball_pairs_against_a_moving_plane) {
  const Mat3 Ra = turn(0.4, Vec3(1, 2, 3)), Rb = turn(0.2, Vec3(-1, 0.5, 1));
  Loc c, cd;
  state(Vec3(0.1, -0.05, 0.12), Ra, Vec3(0.0, 0.02, -0.03), Rb, c, cd);
  const CollisionShape plane = shape(CollisionShape::kPlane, Vec3::Zero(), Vec3(0.01, 0.0, 0.02), turn(0.1, Vec3(0, 1, 0)));
  const Mat3 own = turn(0.3, Vec3(0, 0, 1));
  check_pair(shape(CollisionShape::kSphere, Vec3(0.1, 0, 0), Vec3(0.02, 0.01, 0.0), own), plane, c, cd);
  check_pair(shape(CollisionShape::kCapsule, Vec3(0.05, 0.2, 0), Vec3(0.02, 0.01, 0.0), own), plane, c, cd);
  check_pair(shape(CollisionShape::kBox, Vec3(0.2, 0.1, 0.15), Vec3(0.02, 0.01, 0.0), own), plane, c, cd);
  CollisionShape hull = shape(CollisionShape::kConvex, Vec3::Zero(), Vec3(0.0, 0.01, 0.0), own);
  hull.vertices = {Vec3(0.1, 0, 0), Vec3(-0.1, 0.05, 0), Vec3(0, -0.1, 0.05), Vec3(0, 0, -0.12)};
  check_pair(hull, plane, c, cd);
  check_pair(shape(CollisionShape::kCylinder, Vec3(0.07, 0.15, 0), Vec3(0.02, 0.01, 0.0), own), plane, c, cd, 1);
}

TEST_CASE(a_hull_evaluates_in_full_only_the_vertices_asked_for) {
  // a hull whose vertices are from below the plane to 10 cm above it:
  // within reach 0 (touching) its points are those of reach infinity,
  // beyond it their gaps alone (to rounding; rate and point NaN); over Dual
  // numbers the touching ones asked for by number are those of all asked for
  const Mat3 Ra = turn(0.4, Vec3(1, 2, 3));
  Loc c, cd;
  state(Vec3(0.0, 0.0, 0.05), Ra, Vec3::Zero(), Mat3::Identity(), c, cd);
  const CollisionShape plane = shape(CollisionShape::kPlane, Vec3::Zero(), Vec3::Zero(), Mat3::Identity());
  CollisionShape hull = shape(CollisionShape::kConvex, Vec3::Zero(), Vec3(0.01, 0.0, 0.0), turn(0.3, Vec3(0, 0, 1)));
  hull.vertices = {Vec3(0.1, 0, 0), Vec3(-0.1, 0.05, 0), Vec3(0, -0.1, 0.05), Vec3(0, 0, -0.12), Vec3(0.03, 0.02, -0.09)};
  const lagmb::collision::Pair* pair = lagmb::collision::find_pair(hull.kind, plane.kind);
  const auto values = points_at(*pair, hull, plane, c, cd);
  Motion<double> A0, B0;
  motions(c.data(), cd.data(), A0, B0);
  std::vector<ContactPoint<double>> near(values.size());
  pair->at(hull, plane, A0, B0, near.data(), 0.0);
  std::vector<int> all, touching;
  for (size_t k = 0; k < values.size(); ++k) {
    all.push_back(int(k));
    CHECK_NEAR(near[k].gap, values[k].gap, 1e-16);
    if (values[k].gap <= 0.0) {
      touching.push_back(int(k));
      CHECK(near[k].gap == values[k].gap && near[k].gap_rate == values[k].gap_rate);
      CHECK((near[k].point.value() - values[k].point.value()).norm() == 0.0);
    } else {
      CHECK(std::isnan(near[k].gap_rate) && std::isnan(near[k].point.value().x()));
    }
  }
  CHECK(!touching.empty() && touching.size() < values.size());
  ContactDual x[14], xd[14];
  for (int k = 0; k < 14; ++k) {
    x[k] = ContactDual(c[k]), xd[k] = ContactDual(cd[k]);
    x[k].d[k] = 1.0, xd[k].d[14 + k] = 1.0;
  }
  Motion<ContactDual> A, B;
  motions(x, xd, A, B);
  std::vector<ContactPoint<ContactDual>> every(all.size()), some(touching.size());
  pair->derivative(hull, plane, A, B, all.data(), int(all.size()), every.data());
  pair->derivative(hull, plane, A, B, touching.data(), int(touching.size()), some.data());
  for (size_t j = 0; j < touching.size(); ++j) {
    const auto& p = some[j];
    const auto& q = every[touching[j]];
    CHECK(p.gap.v == q.gap.v && (p.gap.d - q.gap.d).norm() == 0.0 && (p.gap_rate.d - q.gap_rate.d).norm() == 0.0);
  }
}

TEST_CASE(ball_pairs_between_two_moving_bodies) {
  const Mat3 Ra = turn(0.7, Vec3(0, 1, 1)), Rb = turn(-0.5, Vec3(1, 0, 0.3));
  Loc c, cd;
  state(Vec3(0.12, 0.03, 0.1), Ra, Vec3(0.0, 0.0, 0.0), Rb, c, cd);
  const CollisionShape ball = shape(CollisionShape::kSphere, Vec3(0.1, 0, 0), Vec3(0.01, 0.0, 0.0), Mat3::Identity());
  const Mat3 own = turn(0.6, Vec3(1, 1, 0));
  check_pair(ball, shape(CollisionShape::kSphere, Vec3(0.08, 0, 0), Vec3(0.0, 0.01, 0.0), own), c, cd);
  check_pair(ball, shape(CollisionShape::kCapsule, Vec3(0.05, 0.3, 0), Vec3(0.0, 0.01, 0.0), own), c, cd);
  check_pair(ball, shape(CollisionShape::kBox, Vec3(0.2, 0.25, 0.18), Vec3(0.0, 0.01, 0.0), own), c, cd);
  check_pair(shape(CollisionShape::kCapsule, Vec3(0.05, 0.3, 0), Vec3(0.01, 0.0, 0.0), turn(1.2, Vec3(0, 1, 0))),
             shape(CollisionShape::kCapsule, Vec3(0.04, 0.25, 0), Vec3(0.0, 0.01, 0.0), own), c, cd);
}

TEST_CASE(the_table_names_its_pairs_one_way_round) {
  CHECK(lagmb::collision::find_pair(CollisionShape::kSphere, CollisionShape::kPlane) != nullptr);
  CHECK(lagmb::collision::find_pair(CollisionShape::kPlane, CollisionShape::kSphere) == nullptr);
  CHECK(lagmb::collision::find_pair(CollisionShape::kBox, CollisionShape::kBox) == nullptr);
  CHECK(lagmb::collision::find_pair(CollisionShape::kBox, CollisionShape::kPlane)->anchored);
  CHECK(!lagmb::collision::find_pair(CollisionShape::kSphere, CollisionShape::kPlane)->anchored);
  CHECK(lagmb::collision::known_pairs().find("capsule-capsule") != std::string::npos);
}

LAGMB_TEST_MAIN()
