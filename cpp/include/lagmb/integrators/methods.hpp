// The integration methods: each formulation with the integrators that can
// run it, declared once (cpp/src/integrators/methods.cpp). simulate validates its options
// against this table and runs the entry; lagmb.methods(), `lagmb info
// --methods`, the scene reader and the work-precision presets list it.
#pragma once

#include <string>
#include <vector>

#include "lagmb/options.hpp"

namespace lagmb {

struct Method {
  std::string name;         // unique: "ggl", "projection-adams", ...
  Formulation formulation = Formulation::kGgl;  // SimulationOptions::formulation
  Integrator integrator = Integrator::kBdf;      // SimulationOptions::integrator (never kDefault here)
  std::string solver;       // what integrates it: "IDA", "CVODE", "fixed-step trapezoidal rule"
  std::string description;  // one line for users
  int max_order = 0;        // highest order (the default); 2 for the fixed-step trapezoidal rule
  bool fixed_step = false;  // needs step (SimulationOptions::max_step), no error control
  bool events = true;       // finds roots: stops, contact onset and release
  /// places a contact's onset: an explicit step can pass a whole contact
  /// (its force felt only at stages), whose onset its interpolant then
  /// places wrongly (a bouncing ball 1 km off), so the explicit method does not
  bool contact = true;
  bool friction = true;     // joint friction (loads from the multipliers)
  bool baumgarte = false;   // takes baumgarte=(alpha, beta)
  bool drifts = false;      // positions are not held on Phi = 0 (only Phi'' = 0)

  /// f(name, field) for every field (lagmb.methods() lists them by these
  /// names; the formulation and integrator by their names).
  template <class F>
  void for_each_field(F&& f) const {
    f("name", name), f("formulation", std::string(name_of(formulation)));
    f("integrator", std::string(name_of(integrator))), f("solver", solver);
    f("description", description), f("max_order", max_order), f("fixed_step", fixed_step);
    f("events", events), f("contact", contact), f("friction", friction), f("baumgarte", baumgarte);
    f("drifts", drifts);
  }
};

/// Every method, in the order users see them (GGL first; formulation
/// "auto", the default, chooses one: choose_method, run.hpp).
const std::vector<Method>& methods();

/// The method of a formulation and integrator (kDefault: the formulation's
/// first); ModelError naming the ones there are if there is none.
const Method& find_method(Formulation formulation, Integrator integrator);

}  // namespace lagmb
