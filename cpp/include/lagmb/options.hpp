// How a run is made: the choices (typed once, named at the boundaries) and
// the one options struct whose defaults every caller reads.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "lagmb/types.hpp"

namespace lagmb {

/// What a run computes (simulate; docs/methods.md, 'Choosing the analysis').
enum class Analysis {
  kAuto,             // inverse dynamics at 0 degrees of freedom (kinematic if a body is massless), else dynamic
  kDynamic,          // the DAE integrated
  kKinematic,        // q, v, a from the constraints alone (lam not computed)
  kInverseDynamics,  // kinematic, and lam from M a + Phi_q^T lam = Q
};

/// Where a dynamic run starts.
enum class Start {
  kGiven,        // the model's initial positions and velocities (made consistent)
  kEquilibrium,  // at rest in the static equilibrium at t0 (equilibrium.hpp)
};

/// The equations a dynamic run integrates (methods.hpp pairs each with its
/// integrators); kAuto: the method chosen from the model (choose_method,
/// run.hpp).
enum class Formulation { kGgl, kIndex3, kIndex1, kProjection, kAli3p, kAuto };

/// The integrator of a formulation; kDefault: the formulation's first.
enum class Integrator { kDefault, kBdf, kAdams, kErk, kTrapezoidal };

/// The names users give and read for each choice (Python, scenes, the FMU),
/// in the order messages list them.
template <class Choice>
struct ChoiceNames;
template <>
struct ChoiceNames<Analysis> {
  static constexpr const char* what = "analysis";
  static constexpr std::array<std::pair<Analysis, const char*>, 4> names{
      {{Analysis::kAuto, "auto"},
       {Analysis::kDynamic, "dynamic"},
       {Analysis::kKinematic, "kinematic"},
       {Analysis::kInverseDynamics, "inverse_dynamics"}}};
};
template <>
struct ChoiceNames<Start> {
  static constexpr const char* what = "start";
  static constexpr std::array<std::pair<Start, const char*>, 2> names{
      {{Start::kGiven, "given"}, {Start::kEquilibrium, "equilibrium"}}};
};
template <>
struct ChoiceNames<Formulation> {
  static constexpr const char* what = "formulation";
  static constexpr std::array<std::pair<Formulation, const char*>, 6> names{
      {{Formulation::kAuto, "auto"},
       {Formulation::kGgl, "ggl"},
       {Formulation::kIndex3, "index3"},
       {Formulation::kIndex1, "index1"},
       {Formulation::kProjection, "projection"},
       {Formulation::kAli3p, "ali3p"}}};
};
template <>
struct ChoiceNames<Integrator> {
  static constexpr const char* what = "integrator";
  static constexpr std::array<std::pair<Integrator, const char*>, 5> names{
      {{Integrator::kDefault, ""},
       {Integrator::kBdf, "bdf"},
       {Integrator::kAdams, "adams"},
       {Integrator::kErk, "erk"},
       {Integrator::kTrapezoidal, "trapezoidal"}}};
};

/// The name of a choice ("inverse_dynamics"; "" for Integrator::kDefault).
template <class Choice>
const char* name_of(Choice c) {
  for (const auto& [value, name] : ChoiceNames<Choice>::names)
    if (value == c) return name;
  return "?";
}

/// The choice called `text`; ModelError "unknown <what> 'text' (the choices
/// are a, b, c)" for any other text: the one place a name becomes a choice.
template <class Choice>
Choice choice_from(const std::string& text) {
  std::string known;
  for (const auto& [value, name] : ChoiceNames<Choice>::names) {
    if (text == name) return value;
    if (*name) known += std::string(known.empty() ? "" : ", ") + name;
  }
  throw ModelError(std::string("unknown ") + ChoiceNames<Choice>::what + " '" + text + "' (the choices are " +
                   known + ")");
}

template <class T>
inline constexpr bool is_choice_v = std::is_same_v<T, Analysis> || std::is_same_v<T, Start> ||
                                    std::is_same_v<T, Formulation> || std::is_same_v<T, Integrator>;

/// Everything a run is asked to do; the defaults here are lagmb's (Python's
/// signatures, scenes and the FMU read them from here).
struct SimulationOptions {
  double t0 = 0.0;
  double t_end = 1.0;
  /// Output times, increasing, inside [t0, t_end]; empty: n_out equally
  /// spaced times from t0 to t_end.
  std::vector<double> t_out;
  int n_out = 101;
  /// Error tolerances of the integrators with error control (not ali3p).
  double rtol = 1e-6;
  double atol = 1e-8;
  /// Per-coordinate absolute tolerances (n entries, for q_i and v_i); empty:
  /// atol for every coordinate.
  std::vector<double> atol_coordinates;
  double max_step = 0.0;  // 0: no limit; ali3p: its fixed step
  /// 0: no limit; else SimulationError when reached, and a max_step that
  /// needs more steps than this over [t0, t_end] is refused up front.
  long max_steps = 500000;
  int max_order = 0;  // 0: the method's highest (BDF 5, Adams 12; methods.hpp)
  /// The method (methods.hpp, which lists them): a formulation and one of
  /// its integrators (kDefault: its first, e.g. BDF; Adams for projection),
  /// or kAuto (the default): the method chosen from the model
  /// (choose_method, run.hpp). ali3p takes a fixed step, given as max_step.
  Formulation formulation = Formulation::kAuto;
  Integrator integrator = Integrator::kDefault;
  double baumgarte_alpha = 0.0, baumgarte_beta = 0.0;  // index1, and projection with adams
  /// ali3p's Newton iteration: corrections of q below newton_rtol |q| + newton_atol.
  double newton_rtol = 1e-10, newton_atol = 1e-12;
  /// Called between steps with the time reached, at most every
  /// progress_interval seconds of wall time; may throw to stop the run.
  std::function<void(double t)> progress;
  double progress_interval = 0.2;
  /// What the run computes; kinematic and inverse dynamics need 0 degrees
  /// of freedom (kinematics.hpp).
  Analysis analysis = Analysis::kAuto;
  /// A dynamic analysis only.
  Start start = Start::kGiven;

  /// f(name, field) for every field but progress: the one list bindings
  /// read options by (Python passes them by these names; the choices as
  /// their names, choice_from).
  template <class F>
  void for_each_field(F&& f) {
    f("t0", t0), f("t_end", t_end), f("t_out", t_out), f("n_out", n_out), f("rtol", rtol), f("atol", atol);
    f("atol_coordinates", atol_coordinates), f("max_step", max_step), f("max_steps", max_steps);
    f("max_order", max_order), f("formulation", formulation), f("integrator", integrator);
    f("baumgarte_alpha", baumgarte_alpha), f("baumgarte_beta", baumgarte_beta);
    f("newton_rtol", newton_rtol), f("newton_atol", newton_atol);
    f("progress_interval", progress_interval), f("analysis", analysis), f("start", start);
  }
};

}  // namespace lagmb
