#include "lagmb/time_function.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <istream>
#include <sstream>

#include "lagmb/types.hpp"

namespace lagmb {

namespace {

void require_finite(double x, const char* what) {
  if (!std::isfinite(x)) throw ModelError(std::string("time function: ") + what + " is not finite");
}

/// Numbers as text that reads back to the same doubles.
std::string numbers(std::initializer_list<double> xs, const std::vector<double>& more = {}) {
  std::ostringstream s;
  s << std::setprecision(17);
  for (double x : xs) s << ' ' << x;
  for (double x : more) s << ' ' << x;
  return s.str();
}

struct Constant final : TimeFunction {
  double c;
  explicit Constant(double c_) : c(c_) {}
  TimeValue eval(double) const override { return {c, 0.0, 0.0}; }
  std::string text() const override { return "constant" + numbers({c}); }
  bool varies() const override { return false; }
};

/// start + rate t (its own kind, so that its text reads back as what was given)
struct Linear final : TimeFunction {
  double rate, start;
  Linear(double r, double s) : rate(r), start(s) {}
  TimeValue eval(double t) const override { return {rate * t + start, rate, 0.0}; }
  std::string text() const override { return "linear" + numbers({rate, start}); }
};

struct Polynomial final : TimeFunction {
  std::vector<double> c;
  explicit Polynomial(std::vector<double> c_) : c(std::move(c_)) {}
  TimeValue eval(double t) const override {
    // Horner for f, f', f''
    TimeValue v;
    for (size_t k = c.size(); k-- > 0;) {
      v.ddf = v.ddf * t + 2.0 * v.df;
      v.df = v.df * t + v.f;
      v.f = v.f * t + c[k];
    }
    return v;
  }
  std::string text() const override { return "polynomial" + numbers({double(c.size())}, c); }
};

struct Harmonic final : TimeFunction {
  double a, w, p, o;
  Harmonic(double a_, double w_, double p_, double o_) : a(a_), w(w_), p(p_), o(o_) {}
  TimeValue eval(double t) const override {
    const double s = std::sin(w * t + p), c = std::cos(w * t + p);
    return {o + a * s, a * w * c, -a * w * w * s};
  }
  std::string text() const override { return "harmonic" + numbers({a, w, p, o}); }
};

struct SmoothStep final : TimeFunction {
  double t0, t1, y0, y1;
  SmoothStep(double a, double b, double c, double d) : t0(a), t1(b), y0(c), y1(d) {}
  std::vector<double> breakpoints() const override { return {t0, t1}; }
  std::string text() const override { return "smooth_step" + numbers({t0, t1, y0, y1}); }
  TimeValue eval(double t) const override {
    if (t <= t0) return {y0, 0.0, 0.0};
    if (t >= t1) return {y1, 0.0, 0.0};
    const double T = t1 - t0, s = (t - t0) / T, dy = y1 - y0;
    const double s2 = s * s, s3 = s2 * s;
    return {y0 + dy * s3 * (10.0 - 15.0 * s + 6.0 * s2), dy * 30.0 * s2 * (1.0 - 2.0 * s + s2) / T,
            dy * 60.0 * s * (1.0 - 3.0 * s + 2.0 * s2) / (T * T)};
  }
};

/// Natural cubic spline: second derivatives M_k from the tridiagonal system.
struct Spline final : TimeFunction {
  std::vector<double> x, y, M;
  Spline(std::vector<double> xs, std::vector<double> ys) : x(std::move(xs)), y(std::move(ys)) {
    const size_t n = x.size();
    M.assign(n, 0.0);
    if (n < 3) return;
    std::vector<double> c(n, 0.0), d(n, 0.0);  // Thomas algorithm
    for (size_t i = 1; i + 1 < n; ++i) {
      const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
      const double a = h0 / 6.0, b = (h0 + h1) / 3.0, cc = h1 / 6.0;
      const double r = (y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0;
      const double m = b - a * c[i - 1];
      c[i] = cc / m;
      d[i] = (r - a * d[i - 1]) / m;
    }
    for (size_t i = n - 2; i >= 1; --i) M[i] = d[i] - c[i] * M[i + 1];
  }
  std::vector<double> breakpoints() const override { return x; }
  std::string text() const override {
    std::vector<double> xy = x;
    xy.insert(xy.end(), y.begin(), y.end());
    return "spline" + numbers({double(x.size())}, xy);
  }
  TimeValue eval(double t) const override {
    const size_t n = x.size();
    if (n == 1) return {y[0], 0.0, 0.0};
    // linear extrapolation with the end slopes (and a t that is not a
    // number, which no interval holds, gives NaN here)
    if (!(t > x[0] && t < x[n - 1])) {
      const bool left = !(t >= x[n - 1]);
      const size_t k = left ? 0 : n - 2;
      const double h = x[k + 1] - x[k];
      const double slope = (y[k + 1] - y[k]) / h +
                           (left ? -h * (2.0 * M[k] + M[k + 1]) / 6.0 : h * (M[k] + 2.0 * M[k + 1]) / 6.0);
      const double xe = left ? x[0] : x[n - 1], ye = left ? y[0] : y[n - 1];
      return {ye + slope * (t - xe), slope, 0.0};
    }
    const size_t k = std::upper_bound(x.begin(), x.end(), t) - x.begin() - 1;
    const double h = x[k + 1] - x[k], a = (x[k + 1] - t) / h, b = (t - x[k]) / h;
    const double f = a * y[k] + b * y[k + 1] + ((a * a * a - a) * M[k] + (b * b * b - b) * M[k + 1]) * h * h / 6.0;
    const double df = (y[k + 1] - y[k]) / h + (-(3.0 * a * a - 1.0) * M[k] + (3.0 * b * b - 1.0) * M[k + 1]) * h / 6.0;
    const double ddf = a * M[k] + b * M[k + 1];
    return {f, df, ddf};
  }
};

}  // namespace

TimeFunctionPtr constant(double c) {
  require_finite(c, "the constant");
  return std::make_shared<Constant>(c);
}

TimeFunctionPtr linear(double rate, double start) {
  require_finite(rate, "rate");
  require_finite(start, "start");
  return std::make_shared<Linear>(rate, start);
}

TimeFunctionPtr polynomial(std::vector<double> coeffs) {
  if (coeffs.empty()) throw ModelError("time function: a polynomial needs at least one coefficient");
  for (double c : coeffs) require_finite(c, "a polynomial coefficient");
  return std::make_shared<Polynomial>(std::move(coeffs));
}

TimeFunctionPtr harmonic(double amplitude, double omega, double phase, double offset) {
  for (double v : {amplitude, omega, phase, offset}) require_finite(v, "a harmonic parameter");
  return std::make_shared<Harmonic>(amplitude, omega, phase, offset);
}

TimeFunctionPtr smooth_step(double t0, double t1, double y0, double y1) {
  for (double v : {t0, t1, y0, y1}) require_finite(v, "a smooth-step parameter");
  if (!(t1 > t0)) throw ModelError("time function: a smooth step needs t1 > t0");
  return std::make_shared<SmoothStep>(t0, t1, y0, y1);
}

TimeFunctionPtr spline(std::vector<double> times, std::vector<double> values) {
  if (times.size() != values.size() || times.size() < 2)
    throw ModelError("time function: a spline needs as many values as times, at least 2");
  for (size_t k = 0; k < times.size(); ++k) {
    require_finite(times[k], "a spline time");
    require_finite(values[k], "a spline value");
    if (k && !(times[k] > times[k - 1])) throw ModelError("time function: spline times must increase");
  }
  return std::make_shared<Spline>(std::move(times), std::move(values));
}

std::string Input::text() const {
  std::ostringstream s;
  s << "input" << numbers({initial_}) << ' ' << std::quoted(name_);
  return s.str();
}

TimeFunctionPtr time_function_from_text(std::istream& in) {
  std::string type;
  in >> type;
  auto read = [&](const char* what) {
    double x = 0.0;
    if (!(in >> x)) throw ModelError("time function '" + type + "': " + what + " is missing or not a number");
    return x;
  };
  auto list = [&](const char* what) {
    const double count = read("the count");
    if (!(count >= 1 && count <= 1e7 && count == std::floor(count)))
      throw ModelError("time function '" + type + "': a count of " + to_text(count));
    std::vector<double> xs(static_cast<size_t>(count));
    for (double& x : xs) x = read(what);
    return xs;
  };
  if (type == "constant") return constant(read("c"));
  if (type == "linear") {
    const double rate = read("rate");
    return linear(rate, read("start"));
  }
  if (type == "polynomial") return polynomial(list("a coefficient"));
  if (type == "harmonic") {
    const double a = read("amplitude"), w = read("omega"), p = read("phase");
    return harmonic(a, w, p, read("offset"));
  }
  if (type == "smooth_step") {
    const double t0 = read("t0"), t1 = read("t1"), y0 = read("y0");
    return smooth_step(t0, t1, y0, read("y1"));
  }
  if (type == "spline") {
    std::vector<double> xy = list("a time");
    const size_t n = xy.size();
    for (size_t k = 0; k < n; ++k) xy.push_back(read("a value"));
    return spline(std::vector<double>(xy.begin(), xy.begin() + n), std::vector<double>(xy.begin() + n, xy.end()));
  }
  if (type == "input") {
    const double initial = read("initial");
    std::string name;
    if (!(in >> std::quoted(name))) throw ModelError("time function 'input': the name is missing");
    return input(initial, name);
  }
  throw ModelError("unknown time function '" + type +
                   "' (known: constant, linear, polynomial, harmonic, smooth_step, spline, input)");
}

std::shared_ptr<Input> input(double initial, std::string name) {
  require_finite(initial, "an input's initial value");
  if (!(std::abs(initial) <= kLargestGiven))
    throw ModelError("an input's initial value " + to_text(initial) + " is beyond " + to_text(kLargestGiven) +
                     ", the largest lagmb takes for a gain or an input: " + largest_given_reason());
  return std::make_shared<Input>(initial, std::move(name));
}

}  // namespace lagmb
