// A model as a co-simulation slave: its variables numbered by value
// reference, values set and got by number, stepped by communication steps
// (what an FMI 3.0 co-simulation FMU exposes; `lagmb fmu`, cpp/fmu/).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "lagmb/run/simulator.hpp"
#include "lagmb/spec/spec.hpp"

namespace lagmb {

/// What a co-simulation runs: the model (ModelSpec::to_text), the run's
/// options, and the reactions and driver efforts to output, by element name.
struct CoSimulationSetup {
  std::string model;
  SimulationOptions options;
  std::vector<std::string> reactions, efforts;

  /// As text that from_text reads back (the resource an FMU carries).
  std::string to_text() const;
  static CoSimulationSetup from_text(const std::string& text);
};

/// One variable; its value reference is its index in variables().
struct CoVariable {
  std::string name;         // "time", "push", "cart.mass", "pole.angle", "der(pole.angle)", "hinge.reaction.x"
  std::string causality;    // "independent", "input", "parameter" or "output"
  std::string variability;  // "continuous" or "fixed"
  std::string unit;         // "" if none or not one unit
  std::string description;
  double start = 0.0;       // inputs and parameters
};

/// A co-simulation's state to come back to (an FMU state): the simulator's
/// and the input values set.
struct CoSimulationState {
  SimulatorState simulator;
  std::vector<double> inputs;
};

/// The slave's life, as FMI has it: instantiated (parameters and inputs may
/// be set), initialization (the same, and outputs may be read), stepping.
/// Errors are ModelError (a wrong value reference, a parameter set after
/// initialization, a value not finite, a step from another time) or
/// SimulationError (the integrator failed); after one of the latter the
/// slave stays failed until reset().
class CoSimulation {
 public:
  explicit CoSimulation(CoSimulationSetup setup);
  ~CoSimulation();

  const std::vector<CoVariable>& variables() const { return variables_; }
  void set(size_t value_reference, double value);
  double get(size_t value_reference);

  /// Starts initialization at t0; a relative tolerance, if given (> 0),
  /// replaces the setup's rtol.
  void enter_initialization(double t0, double tolerance = 0.0);
  void exit_initialization();
  /// Integrates from t (the time reached) to t + h.
  void do_step(double t, double h);
  /// Back to instantiated, with the setup's parameter and input values.
  void reset();
  /// The state after initialization (Simulator::state: the next step
  /// restarts there, so a restored copy steps on bit for bit), and back to it.
  CoSimulationState state();
  void set_state(const CoSimulationState& state);
  double time() const;

 private:
  struct Slot {
    enum Kind { kTime, kInput, kParameter, kCoordinate, kVelocity, kReaction, kEffort } kind;
    int index = 0;      // input, parameter, coordinate; constraint row (effort)
    int component = 0;  // reaction component
    std::string element = {}, key = {};
  };
  void add(CoVariable variable, Slot slot);
  void start_run();  // compiles the spec with the parameters set, starts the simulator
  Simulator& running();

  CoSimulationSetup setup_;
  ModelSpec spec_;
  std::vector<CoVariable> variables_;
  std::vector<Slot> slots_;
  std::vector<double> parameters_, inputs_;  // values set
  enum class Mode { kInstantiated, kInitialization, kStepping } mode_ = Mode::kInstantiated;
  double t0_ = 0.0, tolerance_ = 0.0;
  std::shared_ptr<const Model> model_;
  std::unique_ptr<Simulator> sim_;
};

}  // namespace lagmb
