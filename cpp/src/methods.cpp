// The table of integration methods (lagmb/methods.hpp) and how each runs.
#include "lagmb/methods.hpp"

#include <functional>

#include "dae.hpp"
#include "integrators.hpp"
#include "lagmb/errors.hpp"

namespace lagmb {

namespace {

using Factory = std::unique_ptr<Stepper> (*)(const Model&, const SimulationOptions&, const ConsistentState&,
                                              const IntegrationPlan&);

struct Entry {
  Method method;
  Factory make;
};

template <bool adams>
std::unique_ptr<Stepper> cvode(const Model& model, const SimulationOptions& o, const ConsistentState& start,
                               const IntegrationPlan& plan) {
  return make_cvode_stepper(model, adams, o.baumgarte_alpha, o.baumgarte_beta, start, plan);
}

template <class Formulation>
std::unique_ptr<Stepper> ida(const Model& model, const SimulationOptions&, const ConsistentState& start,
                             const IntegrationPlan& plan) {
  return make_ida_stepper(std::make_unique<Formulation>(model), start, plan);
}

const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = [] {
    std::vector<Entry> t;
    auto add = [&](Method m, Factory make) { t.push_back({std::move(m), make}); };
    Method m;
    m = {"ggl", "ggl", "bdf", "IDA",
         "stabilized index 2 (Gear-Gupta-Leimkuhler): positions and velocities stay on the constraints; the default",
         5};
    add(m, &ida<GglFormulation>);
    m = {"index3", "index3", "bdf", "IDA",
         "index 3: position constraints only, multipliers and velocities weighted as index-3 and index-2 variables",
         5};
    add(m, &ida<Index3Formulation>);
    m = {"index1", "index1", "bdf", "IDA",
         "index 1: acceleration constraints only, drifts unless baumgarte=(alpha, beta) feeds Phi and Phi' back", 5};
    m.baumgarte = true;
    m.drifts = true;
    add(m, [](const Model& model, const SimulationOptions& o, const ConsistentState& start,
              const IntegrationPlan& plan) {
      return make_ida_stepper(std::make_unique<Index1Formulation>(model, o.baumgarte_alpha, o.baumgarte_beta),
                              start, plan);
    });
    m = {"projection-bdf", "projection", "bdf", "CVODE",
         "ODE in accelerations from the augmented system, BDF, positions and velocities projected after each step",
         5};
    add(m, &cvode<false>);
    m = {"projection-adams", "projection", "adams", "CVODE",
         "ODE in accelerations, Adams-Moulton (non-stiff); CVODE cannot project here, so baumgarte terms hold "
         "the constraints",
         12};
    m.baumgarte = true;
    m.drifts = true;
    add(m, &cvode<true>);
    m = {"projection-erk", "projection", "erk", "ARKODE ERKStep",
         "ODE in accelerations, explicit Runge-Kutta (Fehlberg 7(8) by default), positions and velocities "
         "projected after each step; for non-stiff mechanisms such as long free chains",
         8};
    add(m, [](const Model& model, const SimulationOptions&, const ConsistentState& start,
              const IntegrationPlan& plan) { return make_erk_stepper(model, start, plan); });
    m = {"ali3p", "ali3p", "trapezoidal", "fixed-step trapezoidal rule",
         "index-3 augmented Lagrangian with mass-orthogonal projections (ALI3-P), fixed step; runs through "
         "singular positions",
         2};
    m.fixed_step = true;
    m.events = false;
    m.friction = false;
    add(m, [](const Model& model, const SimulationOptions& o, const ConsistentState& start,
              const IntegrationPlan& plan) { return make_ali3p_stepper(model, o.max_step, start, plan); });
    return t;
  }();
  return table;
}

std::string listing() {
  std::string s;
  for (const Entry& e : entries())
    s += (s.empty() ? "" : ", ") + e.method.formulation + " with " + e.method.integrator;
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

const Method& find_method(const std::string& formulation, const std::string& integrator) {
  const Method* of_formulation = nullptr;
  for (const Method& m : methods()) {
    if (m.formulation != formulation) continue;
    if (integrator.empty() || m.integrator == integrator) return m;
    if (!of_formulation) of_formulation = &m;
  }
  if (!of_formulation)
    throw ModelError("simulate: unknown formulation '" + formulation + "' (the methods are: " + listing() + ")");
  std::string theirs;
  for (const Method& m : methods())
    if (m.formulation == formulation) theirs += (theirs.empty() ? "'" : ", '") + m.integrator + "'";
  throw ModelError("simulate: integrator '" + integrator + "': formulation '" + formulation + "' is integrated by " +
                   theirs + ", not by '" + integrator + "' (the methods are: " + listing() + ")");
}

std::unique_ptr<Stepper> make_stepper(const Method& method, const Model& model, const SimulationOptions& options,
                                      const ConsistentState& start, const IntegrationPlan& plan) {
  for (const Entry& e : entries())
    if (e.method.name == method.name) return e.make(model, options, start, plan);
  throw std::logic_error("lagmb: no stepper for method " + method.name);
}

void integrate(const Method& method, const Model& model, const SimulationOptions& options,
               const ConsistentState& start, const IntegrationPlan& plan,
               const std::function<void(const double* q, const double* v)>& record, Stats& stats) {
  run_steps(*make_stepper(method, model, options, start, plan), plan, start, record, stats);
}

}  // namespace lagmb
