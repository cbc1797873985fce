// Basic types of lagmb: vectors, planar rotations, the error classes.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lagmb {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec4 = Eigen::Vector4d;
using VecX = Eigen::VectorXd;

constexpr double kPi = 3.14159265358979323846;
/// The largest magnitude a gain or an input value may have: the integrator's
/// error norms square the forces they make, and beyond about 1e154 a square
/// overflows a double (1.8e308); 1e150 leaves room for sums (load_urdf's
/// LARGEST, for the numbers of a file, is the same).
constexpr double kLargestGiven = 1e150;
/// Why a value beyond kLargestGiven is refused, for messages.
inline const char* largest_given_reason() {
  return "the integrator's error norms square the forces it makes, and beyond that those squares overflow double "
         "precision (1.8e308)";
}

/// Local coordinates of the (at most) two bodies an element connects. A
/// planar element has (x_i, y_i, phi_i, x_j, y_j, phi_j); the ground, and the
/// missing angle of a particle, read as zero there. A spatial element has 14
/// (space.hpp).
using Local6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// The most local coordinates an element has (a coupling of two spatial
/// joints: 4 bodies x 7).
constexpr int kMaxLocal = 28;
/// Positions in q of an element's local coordinates; -1 where the ground, or
/// a particle's missing angle, stands.
using LocalCoords = std::array<int, kMaxLocal>;

/// max_i |x_i|, the infinity norm of x (0 for an empty vector).
inline double max_abs(const VecX& x) { return x.size() ? x.lpNorm<Eigen::Infinity>() : 0.0; }

/// Rotation matrix A(phi) of a body's local axes into global axes.
inline Mat2 rotation(double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  Mat2 A;
  A << c, -s, s, c;
  return A;
}

/// B(phi) = dA/dphi = A(phi) R90, with R90 the rotation by +90 degrees.
inline Mat2 rotation_derivative(double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  Mat2 B;
  B << -s, -c, c, -s;
  return B;
}

/// A number as messages show it (shortest form, e.g. 0.001, 1e+308, nan).
inline std::string to_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}
inline std::string to_text(const Vec2& v) { return "(" + to_text(v.x()) + ", " + to_text(v.y()) + ")"; }
inline std::string to_text(const Vec3& v) {
  return "(" + to_text(v.x()) + ", " + to_text(v.y()) + ", " + to_text(v.z()) + ")";
}

/// 2-D cross product a x b (the z component).
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Bad input when building a model: names the element and the value.
struct ModelError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

}  // namespace lagmb
