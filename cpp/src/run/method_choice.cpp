// Formulation "auto": the method a run takes, and why (choose_method).
#include "run/method_choice.hpp"

#include <sstream>

#include "lagmb/analyses/stiffness.hpp"
#include "lagmb/integrators/methods.hpp"

namespace lagmb {

MethodChoice choose_method(const Model& model, const SimulationOptions& o) {
  MethodChoice c;
  auto choose = [&](Formulation f, Integrator i, std::string why) {
    c.method = &find_method(f, i);
    c.why = "auto: " + c.method->name + ", " + why;
    return c;
  };
  for (const auto& g : model.event_groups())
    if (!g->bounds_motion() && g->size() > 0)
      return choose(Formulation::kGgl, Integrator::kDefault,
                    std::string("the model has a ") + g->kind() + " ('" + g->name(0) +
                        "'), whose onset an explicit step could pass over");
  if (!model.positive_mass())  // (the stiffness estimate below needs M^-1)
    return choose(Formulation::kGgl, Integrator::kDefault,
                  "the model has a body without mass or inertia, whose accelerations only the augmented system "
                  "gives");
  if (!model.friction_groups().empty())
    return choose(Formulation::kGgl, Integrator::kDefault,
                  "the model has joint friction from the joints' loads ('" + model.friction_groups().front()->name(0) +
                      "')");
  const VecX q = model.initial_q(), v = model.initial_v();
  const ForceRates rates = force_rates(model, q.data(), v.data(), o.t0);
  const double span = o.t_end > o.t0 ? o.t_end - o.t0 : 1.0;
  std::ostringstream why;
  why.precision(3);
  why << "the forces' fastest rate " << rates.fastest() << " 1/s times the span " << span << " s is "
      << rates.fastest() * span;
  if (!(rates.fastest() * span <= kStiffSpan)) {
    why << " > " << kStiffSpan << " (stiff)";
    return choose(Formulation::kGgl, Integrator::kDefault, why.str());
  }
  why << " <= " << kStiffSpan << " (not stiff)";
  return choose(Formulation::kProjection, Integrator::kErk, why.str());
}

}  // namespace lagmb
