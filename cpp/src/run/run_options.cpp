// The options of a dynamic run, checked against the model and the method
// (validate_run_options).
#include "run/run_options.hpp"

#include <cmath>
#include <string>

#include "lagmb/errors.hpp"
#include "lagmb/integrators/methods.hpp"
#include "run/method_choice.hpp"

namespace lagmb {

const Method& validate_run_options(const Model& model, const SimulationOptions& o, const std::string& who) {
  const std::string at = who + ": ";
  if (!model.finalized()) throw ModelError(at + "the model is not finalized");
  if (model.n_coordinates() == 0) throw ModelError(at + "the model has no bodies");
  auto positive = [&](double x, const char* name) {
    if (!(std::isfinite(x) && x > 0))
      throw ModelError(at + name + " must be positive and finite, got " + to_text(x));
  };
  if (!std::isfinite(o.t0)) throw ModelError(at + "t0 is not finite");
  check_time(o.t0, who, "t0");
  positive(o.rtol, "rtol");
  if (o.rtol >= 1.0)
    throw ModelError(at + "rtol = " + to_text(o.rtol) +
                     " must be below 1: a relative error of 100 % or more bounds nothing (typical: 1e-3 to 1e-10)");
  if (o.rtol < 1e-14)
    throw ModelError(at + "rtol = " + to_text(o.rtol) +
                     " is below 1e-14, which double precision cannot deliver");
  positive(o.atol, "atol");
  if (!o.atol_coordinates.empty()) {
    if (int(o.atol_coordinates.size()) != model.n_coordinates())
      throw ModelError(at + "atol needs one entry per coordinate (" + std::to_string(model.n_coordinates()) +
                       "), got " + std::to_string(o.atol_coordinates.size()));
    for (double a : o.atol_coordinates) positive(a, "every atol entry");
  }
  if (o.max_step != 0.0) positive(o.max_step, "max_step");
  if (o.max_steps < 0) throw ModelError(at + "max_steps must be >= 0 (0: no limit)");
  if (o.formulation == Formulation::kAuto && o.integrator != Integrator::kDefault)
    throw ModelError(at + "integrator '" + name_of(o.integrator) +
                     "' needs its formulation: formulation 'auto' chooses both");
  if (o.formulation == Formulation::kAuto && (o.baumgarte_alpha != 0.0 || o.baumgarte_beta != 0.0))
    throw ModelError(at + "Baumgarte terms need the formulation they apply to (index1, or projection with adams); "
                     "formulation 'auto' does not choose those");
  const Method& method =
      o.formulation == Formulation::kAuto ? *choose_method(model, o).method : find_method(o.formulation, o.integrator);
  // what a method does not model is refused, not ignored
  auto those = [](bool Method::*has) {
    std::string s;
    for (const Method& m : methods())
      if (m.*has) s += (s.empty() ? "" : ", ") + m.name;
    return s;
  };
  // a fixed-step method has no error control: tolerances given to it would be ignored
  const SimulationOptions defaults;
  if (method.fixed_step && (o.rtol != defaults.rtol || o.atol != defaults.atol || !o.atol_coordinates.empty()))
    throw ModelError(at + "formulation '" + name_of(method.formulation) +
                     "' takes fixed steps without error control: rtol and atol do not apply; its Newton corrections "
                     "are bounded by newton_rtol (default " + to_text(defaults.newton_rtol) +
                     ") and newton_atol (default " + to_text(defaults.newton_atol) + ")");
  if (method.fixed_step && o.max_step == 0.0)
    throw ModelError(at + "formulation '" + name_of(method.formulation) +
                     "' takes fixed steps: give the step as max_step (step= in Python)");
  if (!method.friction && !model.friction_groups().empty())
    throw ModelError(at + "formulation '" + name_of(method.formulation) + "' does not include joint friction ('" +
                     model.friction_groups().front()->name(0) + "'); the methods that do: " +
                     those(&Method::friction));
  if (!method.events && model.has_events())
    throw ModelError(at + "formulation '" + name_of(method.formulation) +
                     "' has no root finding for stops or contact events ('" + model.event_element_name() +
                     "'); the methods that have: " + those(&Method::events));
  if (!method.contact)
    for (const auto& g : model.event_groups())
      if (!g->bounds_motion() && g->size() > 0)
        throw ModelError(at + method.name + " cannot place the onset of " + g->kind() + " '" + g->name(0) +
                         "' (an explicit step can pass a whole contact); the methods that can: " +
                         those(&Method::contact) + " (formulation 'auto' chooses ggl here)");
  if (o.max_order < 0 || o.max_order > method.max_order)
    throw ModelError(at + "max_order must be in 1.." + std::to_string(method.max_order) + " for " +
                     method.name + " (integrator " + name_of(method.integrator) + "; 0: its highest order), got " +
                     std::to_string(o.max_order));
  if ((o.baumgarte_alpha != 0.0 || o.baumgarte_beta != 0.0) && !method.baumgarte)
    throw ModelError(at + "Baumgarte terms apply to the methods " + those(&Method::baumgarte) + ", not to formulation '" +
                     name_of(method.formulation) + "' with integrator '" + name_of(method.integrator) + "'");
  if (!std::isfinite(o.baumgarte_alpha) || !std::isfinite(o.baumgarte_beta) || o.baumgarte_alpha < 0 ||
      o.baumgarte_beta < 0)
    throw ModelError(at + "Baumgarte alpha and beta must be finite and >= 0");
  if (method.fixed_step) {
    positive(o.newton_rtol, "newton_rtol");
    positive(o.newton_atol, "newton_atol");
  }
  return method;
}

}  // namespace lagmb
