// An inverted pendulum on a cart, held upright from C++: a PD controller
// sets the cart force every 10 ms through lagmb::Simulator (the loop of
// examples/cart_pole.py). Prints the largest tilt, before and after 1 s.
#include <cmath>
#include <cstdio>

#include "lagmb/lagmb.hpp"

int main() {
  using namespace lagmb;
  const double theta0 = 0.1;  // rad, the pole's tilt at the start (toward -x)
  ModelSpec spec;
  spec.set_gravity(Vec2(0.0, -9.81));
  spec.add("body", "cart", {{"mass", 1.0}, {"inertia", 0.01}, {"position", Vec2(0.0, 0.0)}});
  // a uniform rod of 1 m and 0.1 kg, its axis along body x (upright: angle pi/2)
  spec.add("body", "pole",
           {{"mass", 0.1},
            {"inertia", 0.1 / 12.0},
            {"position", Vec2(-0.5 * std::sin(theta0), 0.5 * std::cos(theta0))},
            {"angle", M_PI / 2 + theta0}});
  spec.add("translational", "rail",
           {{"body_i", "ground"}, {"body_j", "cart"}, {"at", Vec2(0.0, 0.0)}, {"axis", Vec2(1.0, 0.0)}});
  spec.add("revolute", "hinge", {{"body_i", "cart"}, {"body_j", "pole"}, {"at", Vec2(0.0, 0.0)}});
  // the force on the cart is an input, set by the controller below
  spec.add("force", "push", {{"body", "cart"}, {"force", input(0.0), constant(0.0)}});
  const std::shared_ptr<const Model> model = spec.compile();
  const int x = model->body(model->find("cart").group).first_coord;
  const int phi = model->body(model->find("pole").group).first_coord + 2;

  SimulationOptions options;
  options.rtol = 1e-6;
  Simulator sim(*model, options);
  const double k_p = 40.0, k_d = 8.0, k_x = 1.0, k_v = 2.0, period = 0.01;
  double largest = 0.0, largest_after_1s = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const double theta = sim.q()[phi] - M_PI / 2, rate = sim.v()[phi];
    sim.set_input("push", -(k_p * theta + k_d * rate) + k_x * sim.q()[x] + k_v * sim.v()[x]);
    sim.advance((k + 1) * period);
    const double tilt = std::abs(sim.q()[phi] - M_PI / 2);
    largest = std::max(largest, tilt);
    if (sim.t() >= 1.0) largest_after_1s = std::max(largest_after_1s, tilt);
  }
  const Stats stats = sim.stats();
  std::printf("t = %.2f s: largest tilt = %.6f rad, after 1 s = %.6f rad, cart at x = %+.6f m\n", sim.t(),
              largest, largest_after_1s, sim.q()[x]);
  std::printf("%ld input changes, %ld restarts, %ld steps\n", stats.input_changes, stats.restarts, stats.steps);
  return 0;
}
