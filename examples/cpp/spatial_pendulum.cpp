// A spatial model from C++: a uniform rod on a spherical joint at one end,
// released from horizontal (along x, gravity along -z). Prints the joint's
// reaction on the rod (force and torque about its centre, global axes) at
// release and at the end, and the rod's Euler parameters.
#include <cstdio>

#include "lagmb/lagmb.hpp"

int main() {
  using namespace lagmb;
  ModelSpec spec(3);  // dimension 3: spatial kinds ("spatial_body", "spherical", ...)
  spec.set_gravity(Vec3(0.0, 0.0, -9.81));
  // a rod along its body x axis: small moment about it, 1/12 m L^2 across
  spec.add("spatial_body", "rod",
           {{"mass", 1.0}, {"inertia", Vec3(1e-4, 1.0 / 12.0, 1.0 / 12.0)}, {"position", Vec3(0.5, 0.0, 0.0)}});
  spec.add("spherical", "pin", {{"body_i", "ground"}, {"body_j", "rod"}, {"at", Vec3(0.0, 0.0, 0.0)}});
  const std::shared_ptr<const Model> model = spec.compile();

  SimulationOptions options;
  options.t_end = 1.0;
  options.rtol = 1e-8;
  options.atol = 1e-10;
  options.n_out = 3;
  const Trajectory tr = simulate(*model, options);

  const ElementRef& pin = model->find("pin");
  const ConstraintGroupBase& joints = *model->constraint_groups()[pin.group];
  for (int k = 0; k < tr.size(); ++k) {
    const double* q = &tr.q[size_t(k) * tr.n];
    const VecX w = joints.reaction(pin.index, q, tr.t[k], &tr.lam[size_t(k) * tr.m], false);
    std::printf("t = %.2f s  p = (%+.6f, %+.6f, %+.6f, %+.6f)  force on rod = (%+.6f, %+.6f, %+.6f) N  "
                "torque = (%+.6f, %+.6f, %+.6f) N m\n",
                tr.t[k], q[3], q[4], q[5], q[6], w[0], w[1], w[2], w[3], w[4], w[5]);
  }
  std::printf("%ld steps\n", tr.stats.steps);
  return 0;
}
