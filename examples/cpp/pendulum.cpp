// The seed pendulum from C++: a uniform rod pinned at one end, released from
// horizontal. Prints the pin force on the rod at release and at the end.
#include <cstdio>

#include "lagmb/lagmb.hpp"

int main() {
  using namespace lagmb;
  // the description, checked as it grows; then the immutable model runs read
  ModelSpec spec;
  spec.set_gravity(Vec2(0.0, -9.81));
  spec.add("body", "rod", {{"mass", 1.0}, {"inertia", 1.0 / 12.0}, {"position", Vec2(0.5, 0.0)}});
  spec.add("revolute", "pin", {{"body_i", "ground"}, {"body_j", "rod"}, {"at", Vec2(0.0, 0.0)}});
  const std::shared_ptr<const Model> model = spec.compile();

  SimulationOptions options;
  options.t_end = 1.0;
  options.rtol = 1e-8;
  options.atol = 1e-10;
  options.n_out = 3;
  const Trajectory tr = simulate(*model, options);

  // the multipliers are the force the pin puts on the ground side (body i);
  // the rod gets the opposite: -lam
  for (int k = 0; k < tr.size(); ++k)
    std::printf("t = %.2f s  phi = %+.6f rad  pin force on rod = (%+.6f, %+.6f) N\n", tr.t[k],
                tr.q[3 * k + 2], -tr.lam[2 * k], -tr.lam[2 * k + 1]);
  std::printf("%ld steps, %ld LU factorizations\n", tr.stats.steps, tr.stats.lu_factorizations);
  return 0;
}
