// A spatial model from C++: a uniform rod on a spherical joint at one end,
// released from horizontal (along x, gravity along -z). Prints the joint's
// reaction on the rod (force and torque about its centre, global axes; from
// lagmb/run/outputs.hpp) at release and at the end, and the rod's Euler
// parameters; then the pin force at release of the same model run with a
// rod of 2 kg (a run-time parameter, lagmb/spec/parameters.hpp; its moment of
// inertia unchanged, so the force is m g I / (I + m r^2), not m g / 4).
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

  const OutputRows pin = reactions(*model, "pin", OutputView::of(tr));
  for (int k = 0; k < tr.size(); ++k) {
    const double* q = &tr.q[size_t(k) * tr.n];
    std::printf("t = %.2f s  p = (%+.6f, %+.6f, %+.6f, %+.6f)  force on rod = (%+.6f, %+.6f, %+.6f) N  "
                "torque = (%+.6f, %+.6f, %+.6f) N m\n",
                tr.t[k], q[3], q[4], q[5], q[6], pin(k, 0), pin(k, 1), pin(k, 2), pin(k, 3), pin(k, 4), pin(k, 5));
  }
  std::printf("%ld steps\n", tr.stats.steps);

  // the same compiled model, run with a heavier rod: the run keeps the model
  // built with that mass (run_model), whose reactions these outputs are
  const Trajectory heavy = simulate(*model, options, {{"rod.mass", 2.0}});
  const OutputRows heavy_pin = reactions(*heavy.run_model, "pin", OutputView::of(heavy));
  std::printf("rod.mass = 2 kg: force on rod at release = (%+.6f, %+.6f, %+.6f) N\n", heavy_pin(0, 0),
              heavy_pin(0, 1), heavy_pin(0, 2));
  return 0;
}
