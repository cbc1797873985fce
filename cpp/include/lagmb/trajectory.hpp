// What a simulation returns: states at the output times, and solver counts.
#pragma once

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lagmb {

class Model;

/// Solver statistics of one run.
struct Stats {
  long steps = 0;
  long residual_evals = 0;
  long jacobian_evals = 0;
  long lu_factorizations = 0;         // of the Newton matrix
  // of the augmented matrix: the projection formulation's, the run's (its
  // start, restarts and solved outputs) and the event runner's (closed
  // stops' forces, impacts, active sets)
  long augmented_factorizations = 0;
  long projections = 0;               // coordinate projections (projection formulation)
  long newton_iterations = 0;
  long error_test_failures = 0;
  long convergence_failures = 0;
  /// Elements evaluated by the assembly kernels (added per kind group and
  /// call: the cost of the scene's effects, 0 for kinds it does not have).
  long element_evaluations = 0;
  int last_order = 0;
  double last_step = 0.0;
  double wall_time = 0.0;  // s
  std::string formulation;
  std::string integrator;
  /// The method's listed name (methods(), docs/methods.md) of formulation
  /// with integrator; a kinematic analysis's "kinematic".
  std::string method;
  /// "given", or what formulation "auto" chose and why (choose_method).
  std::string method_choice = "given";
  /// "dynamic" (the DAE integrated), "kinematic" or "inverse_dynamics" (a
  /// fully driven model solved from its constraints alone: steps = 0).
  std::string analysis = "dynamic";
  long kinematic_solves = 0;  // position solves of a kinematic analysis (outputs + sub-steps)
  long events = 0;    // event-function crossings handled (stops, contact switches)
  long impacts = 0;   // of which velocity jumps
  long captures = 0;  // unilateral rows closed (a stop comes to rest on its limit)
  long releases = 0;  // unilateral rows opened (a stop would have to pull)
  long root_evals = 0;  // evaluations of the event functions
  /// Restarts of the integrator at order 1: at breakpoints of the time
  /// functions, after events' actions, and (a Simulator) at input changes
  /// and fresh starts from a saved state.
  long restarts = 0;
  long input_changes = 0;  // a Simulator's: values set that differ from the ones before
  /// The augmented system's Schur complement S = Phi_q M^-1 Phi_q^T in the
  /// right-hand sides of the projection formulation: how often its pattern
  /// was analyzed (once per run) and the nonzeros of its Cholesky factor
  /// (linear in a chain's length); 0 where the LU path ran.
  long symbolic_analyses = 0;
  long factor_nonzeros = 0;
  /// Nonzeros of the Newton matrix's LU factors (KLU: L and U with their
  /// diagonals) at its last factorization, in the implicit methods (GGL,
  /// index 3 and 1, projection-bdf/adams); 0 in the others. Linear in a
  /// chain's length where the ordering holds the fill down.
  long lu_nonzeros = 0;

  /// f(name, field) for every field, in this order: the one list bindings
  /// and reports read (Python's r.stats is this dict) and add_counts sums.
  template <class F>
  void for_each_field(F&& f) const {
    for_each_member([&](const char* name, auto member) { f(name, this->*member); });
  }
  /// f(name, &Stats::field) for every field, in for_each_field's order:
  /// the fields of two Stats side by side (a run's counts summed).
  template <class F>
  static void for_each_member(F&& f) {
    f("steps", &Stats::steps), f("residual_evals", &Stats::residual_evals);
    f("jacobian_evals", &Stats::jacobian_evals), f("lu_factorizations", &Stats::lu_factorizations);
    f("augmented_factorizations", &Stats::augmented_factorizations), f("projections", &Stats::projections);
    f("newton_iterations", &Stats::newton_iterations), f("error_test_failures", &Stats::error_test_failures);
    f("convergence_failures", &Stats::convergence_failures);
    f("element_evaluations", &Stats::element_evaluations), f("last_order", &Stats::last_order);
    f("last_step", &Stats::last_step), f("wall_time", &Stats::wall_time);
    f("formulation", &Stats::formulation), f("integrator", &Stats::integrator);
    f("method_choice", &Stats::method_choice);
    f("analysis", &Stats::analysis), f("kinematic_solves", &Stats::kinematic_solves), f("events", &Stats::events);
    f("impacts", &Stats::impacts), f("captures", &Stats::captures);
    f("releases", &Stats::releases), f("root_evals", &Stats::root_evals), f("restarts", &Stats::restarts);
    f("input_changes", &Stats::input_changes);
    f("symbolic_analyses", &Stats::symbolic_analyses);
    f("factor_nonzeros", &Stats::factor_nonzeros);
    f("lu_nonzeros", &Stats::lu_nonzeros);
    f("method", &Stats::method);  // last: where r.stats had it when Python added it
  }
};

/// One handled event: an impact at a stop, or a switch of a contact force.
struct EventRecord {
  double t = 0.0;
  std::string element;
  std::string kind;   // "impact", "capture", "release" (a stop), "restart" (a force switches)
  std::string label;  // "lower", "upper", "onset", "release", ...
  double speed_before = 0.0;  // g' before (negative: approaching), rad/s or m/s
  double speed_after = 0.0;   // g' after the jump
};

/// States at the output times, row-major: q[k * n + i] is coordinate i at
/// output k. a and lam are solved from the augmented system at each output
/// state (q, v), so they satisfy the equations of motion for exactly the
/// reported positions and velocities.
struct Trajectory {
  int n = 0, m = 0;
  std::vector<double> t, q, v, a, lam;
  /// The values of the model's inputs (Model::inputs) at each output, row-major
  /// (p per output): what a Simulator was given; their initial values in simulate.
  int p = 0;
  std::vector<double> inputs;
  /// The run's element state (Data::RunValues::state, Model::run_state_size
  /// per output, row-major) at each output: what the elements read there
  /// beside q and v (the turns of the spatial joints, a contact's impact speed).
  int state_size = 0;
  std::vector<double> run_state;
  Stats stats;
  std::vector<EventRecord> events;
  /// Rows of Phi left out as redundant (found where the run started); they
  /// were checked at every output.
  std::vector<int> dropped_rows;
  /// The model the run evaluated where it is not the one simulate was given:
  /// that model with the run's parameter values (parameters.hpp). Reactions,
  /// energy and residuals of these outputs (outputs.hpp) are of this model.
  std::shared_ptr<const Model> run_model;
  /// Forward sensitivities (simulate with sensitivities): for output k and
  /// parameter i (of sensitivity_names), d(q, v, lam)/dp_i at
  /// sensitivities[(k * count + i) * (2n + m) ...] and da/dp_i at
  /// sensitivity_a[(k * count + i) * n ...]. Empty without.
  std::vector<std::string> sensitivity_names;
  std::vector<double> sensitivities, sensitivity_a;
  int size() const { return static_cast<int>(t.size()); }
  /// Keeps the first k outputs (a, lam only as far as they were solved).
  void truncate(int k) {
    const size_t kk = size_t(std::max(0, std::min(k, size())));
    t.resize(kk);
    q.resize(std::min(q.size(), kk * size_t(n)));
    v.resize(std::min(v.size(), kk * size_t(n)));
    a.resize(std::min(a.size(), kk * size_t(n)));
    lam.resize(std::min(lam.size(), kk * size_t(m)));
    inputs.resize(std::min(inputs.size(), kk * size_t(p)));
    run_state.resize(std::min(run_state.size(), kk * size_t(state_size)));
    const size_t count = sensitivity_names.size();
    sensitivities.resize(std::min(sensitivities.size(), kk * count * size_t(2 * n + m)));
    sensitivity_a.resize(std::min(sensitivity_a.size(), kk * count * size_t(n)));
  }
};

}  // namespace lagmb
