// The table of integration methods (lagmb/integrators/methods.hpp) and how each runs.
#include "lagmb/integrators/methods.hpp"

#include <functional>

#include "formulations/dae.hpp"
#include "integrators/integrators.hpp"
#include "lagmb/errors.hpp"

namespace lagmb {

namespace {

using Factory = std::unique_ptr<Stepper> (*)(const Model&, const ConsistentState&, const IntegrationPlan&);

struct Entry {
  Method method;
  Factory make;
};

template <bool adams>
std::unique_ptr<Stepper> cvode(const Model& model, const ConsistentState& start, const IntegrationPlan& plan) {
  return make_cvode_stepper(model, adams, plan.options->baumgarte_alpha, plan.options->baumgarte_beta, start, plan);
}

template <class Dae>
std::unique_ptr<Stepper> ida(const Model& model, const ConsistentState& start, const IntegrationPlan& plan) {
  return make_ida_stepper(std::make_unique<Dae>(model, plan.run), start, plan);
}

const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = [] {
    std::vector<Entry> t;
    auto add = [&](Method m, Factory make) { t.push_back({std::move(m), make}); };
    Method m;
    using F = Formulation;
    using I = Integrator;
    m = {"ggl", F::kGgl, I::kBdf, "IDA",
         "stabilized index 2 (Gear-Gupta-Leimkuhler): positions and velocities stay on the constraints; "
         "what \"auto\" runs for stiff forces, contact and friction",
         5};
    add(m, &ida<GglFormulation>);
    m = {"index3", F::kIndex3, I::kBdf, "IDA",
         "index 3: position constraints only, multipliers and velocities weighted as index-3 and index-2 variables",
         5};
    add(m, &ida<Index3Formulation>);
    m = {"index1", F::kIndex1, I::kBdf, "IDA",
         "index 1: acceleration constraints only, drifts unless baumgarte=(alpha, beta) feeds Phi and Phi' back", 5};
    m.baumgarte = true;
    m.drifts = true;
    add(m, [](const Model& model, const ConsistentState& start, const IntegrationPlan& plan) {
      const SimulationOptions& o = *plan.options;
      return make_ida_stepper(
          std::make_unique<Index1Formulation>(model, o.baumgarte_alpha, o.baumgarte_beta, plan.run), start, plan);
    });
    m = {"projection-bdf", F::kProjection, I::kBdf, "CVODE",
         "ODE in accelerations from the augmented system, BDF, positions and velocities projected after each step",
         5};
    add(m, &cvode<false>);
    m = {"projection-adams", F::kProjection, I::kAdams, "CVODE",
         "ODE in accelerations, Adams-Moulton (non-stiff); CVODE cannot project here, so baumgarte terms hold "
         "the constraints",
         12};
    m.baumgarte = true;
    m.drifts = true;
    add(m, &cvode<true>);
    m = {"projection-erk", F::kProjection, I::kErk, "ARKODE ERKStep",
         "ODE in accelerations, explicit Runge-Kutta (Prince-Dormand 8(7) by default), positions and velocities "
         "projected after each step; for non-stiff mechanisms such as long free chains",
         8};
    m.contact = false;
    add(m, [](const Model& model, const ConsistentState& start, const IntegrationPlan& plan) {
      return make_erk_stepper(model, start, plan);
    });
    m = {"ali3p", F::kAli3p, I::kTrapezoidal, "fixed-step trapezoidal rule",
         "index-3 augmented Lagrangian with mass-orthogonal projections (ALI3-P), fixed step; runs through "
         "singular positions",
         2};
    m.fixed_step = true;
    m.contact = false;
    m.friction = false;
    add(m, &make_ali3p_stepper);
    return t;
  }();
  return table;
}

std::string listing() {
  std::string s;
  for (const Entry& e : entries())
    s += std::string(s.empty() ? "" : ", ") + name_of(e.method.formulation) + " with " + name_of(e.method.integrator);
  return s;
}

}  // namespace

const std::vector<Method>& methods() {
  static const std::vector<Method> list = [] {
    std::vector<Method> v;
    for (const Entry& e : entries()) v.push_back(e.method);
    return v;
  }();
  return list;
}

const Method& find_method(Formulation formulation, Integrator integrator) {
  const Method* of_formulation = nullptr;
  for (const Method& m : methods()) {
    if (m.formulation != formulation) continue;
    if (integrator == Integrator::kDefault || m.integrator == integrator) return m;
    if (!of_formulation) of_formulation = &m;
  }
  if (!of_formulation)  // (every formulation has a method)
    throw std::logic_error(std::string("lagmb: no method of formulation ") + name_of(formulation));
  std::string theirs;
  for (const Method& m : methods())
    if (m.formulation == formulation) theirs += std::string(theirs.empty() ? "'" : ", '") + name_of(m.integrator) + "'";
  throw ModelError(std::string("simulate: integrator '") + name_of(integrator) + "': formulation '" +
                   name_of(formulation) + "' is integrated by " + theirs + ", not by '" + name_of(integrator) +
                   "' (the methods are: " + listing() + ")");
}

std::unique_ptr<Stepper> make_stepper(const Method& method, const Model& model, const ConsistentState& start,
                                      const IntegrationPlan& plan) {
  for (const Entry& e : entries())
    if (e.method.name == method.name) return e.make(model, start, plan);
  throw std::logic_error("lagmb: no stepper for method " + method.name);
}


}  // namespace lagmb
