// Basic types of lagmb: planar vectors, rotations, the error classes.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lagmb {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using VecX = Eigen::VectorXd;

/// Local coordinates of the (at most) two bodies an element connects:
/// (x_i, y_i, phi_i, x_j, y_j, phi_j). The ground, and the missing angle of a
/// particle, read as zero there.
using Local6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

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

/// 2-D cross product a x b (the z component).
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Bad input when building a model: names the element and the value.
struct ModelError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

}  // namespace lagmb
