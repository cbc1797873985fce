// The seed pendulum from C++: a uniform rod pinned at one end, released from
// horizontal. Prints the pin force on the rod at release and at the end.
#include <cstdio>

#include "lagmb/lagmb.hpp"

int main() {
  using namespace lagmb;
  Model model;
  model.set_gravity(Vec2(0.0, -9.81));
  const int rod = model.add_body("rod", 1.0, 1.0 / 12.0, Vec2(0.5, 0.0));
  model.add_revolute("pin", kGround, rod, Vec2(0.0, 0.0));
  model.finalize();

  SimulationOptions options;
  options.t_end = 1.0;
  options.rtol = 1e-8;
  options.atol = 1e-10;
  options.n_out = 3;
  const Trajectory tr = simulate(model, options);

  // the multipliers are the force the pin puts on the ground side (body i);
  // the rod gets the opposite: -lam
  for (int k = 0; k < tr.size(); ++k)
    std::printf("t = %.2f s  phi = %+.6f rad  pin force on rod = (%+.6f, %+.6f) N\n", tr.t[k],
                tr.q[3 * k + 2], -tr.lam[2 * k], -tr.lam[2 * k + 1]);
  std::printf("%ld steps, %ld LU factorizations\n", tr.stats.steps, tr.stats.lu_factorizations);
  return 0;
}
