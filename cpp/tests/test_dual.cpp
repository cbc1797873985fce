// Forward-mode dual numbers (lagmb/dual.hpp): the derivatives a Dual<N>
// carries through +, -, *, /, sqrt, pow, sin and cos are the closed-form
// ones, and value_of reads the value of a double and a Dual alike.
#include <cmath>

#include "check.hpp"
#include "lagmb/dual.hpp"

using namespace lagmb_test;
using lagmb::Dual;

namespace {

/// x seeded as input k of N: value x, derivative 1 in slot k.
template <int N>
Dual<N> input(double x, int k) {
  Dual<N> d(x);
  d.d[k] = 1.0;
  return d;
}

/// f(x, y) = sin(x) y^1.5 / (1 + x^2) + sqrt(x y) - cos(y) * 3 - (-x), written once.
template <class T>
T f(const T& x, const T& y) {
  using std::cos;
  using std::pow;
  using std::sin;
  using std::sqrt;
  return sin(x) * pow(y, 1.5) / (T(1.0) + x * x) + sqrt(x * y) - cos(y) * T(3.0) - (-x);
}

}  // namespace

TEST_CASE(derivatives_are_the_closed_forms) {
  const double x = 0.7, y = 1.3;
  const Dual<2> r = f(input<2>(x, 0), input<2>(y, 1));
  CHECK_NEAR(r.v, f(x, y), 1e-15);
  const double den = 1.0 + x * x;
  const double fx = (std::cos(x) * den - std::sin(x) * 2.0 * x) / (den * den) * std::pow(y, 1.5) +
                    0.5 * std::sqrt(y / x) + 1.0;
  const double fy = std::sin(x) * 1.5 * std::sqrt(y) / den + 0.5 * std::sqrt(x / y) + 3.0 * std::sin(y);
  CHECK_NEAR(r.d[0], fx, 1e-14);
  CHECK_NEAR(r.d[1], fy, 1e-14);
}

TEST_CASE(constants_carry_no_derivative) {
  const Dual<3> c(2.5);
  CHECK(c.d.isZero());
  CHECK_NEAR(lagmb::value_of(c), 2.5, 0.0);
  CHECK_NEAR(lagmb::value_of(2.5), 2.5, 0.0);
  const Dual<3> p = c * input<3>(4.0, 2);
  CHECK_NEAR(p.v, 10.0, 0.0);
  CHECK_NEAR(p.d[0], 0.0, 0.0);
  CHECK_NEAR(p.d[2], 2.5, 0.0);
}

LAGMB_TEST_MAIN()
