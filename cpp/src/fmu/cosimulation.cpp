// CoSimulation (cosimulation.hpp): a model behind value references, stepped
// by a Simulator.
#include "lagmb/fmu/cosimulation.hpp"

#include "lagmb/run/outputs.hpp"
#include "lagmb/spec/parameters.hpp"

#include <map>

#include <cmath>
#include <iomanip>
#include <sstream>

#include "lagmb/integrators/methods.hpp"
#include "lagmb/model/coordinates.hpp"
#include "lagmb/model/model.hpp"

namespace lagmb {

namespace {

constexpr const char* kHeader = "lagmb-cosimulation 1";

const ModelSpec::Element* element_of(const ModelSpec& spec, const std::string& name) {
  for (const auto& e : spec.elements())
    if (e.name == name) return &e;
  return nullptr;
}

/// The unit of what a driver drives (rad for an angle, m for a slide), for
/// its input and its effort (N m or N): the kinds say "rad or m".
std::string driven_unit(const ModelSpec& spec, const ModelSpec::Element& driver) {
  const auto& values = driver.args.values();
  auto text = [&](const char* key) -> std::string {
    auto it = values.find(key);
    const std::string* s = it == values.end() ? nullptr : std::get_if<std::string>(&it->second);
    return s ? *s : "";
  };
  if (const std::string c = text("coordinate"); !c.empty()) return c == "angle" ? "rad" : "m";
  if (const std::string joint = text("joint"); !joint.empty())
    if (const auto* e = element_of(spec, joint))
      return e->args.kind().coordinate == CoordinateKind::kAngle ? "rad" : "m";
  return "";
}


}  // namespace

std::string CoSimulationSetup::to_text() const {
  std::ostringstream out;
  out << std::setprecision(17) << kHeader << '\n';
  SimulationOptions o = options;
  o.for_each_field([&](const char* name, const auto& value) {
    using T = std::decay_t<decltype(value)>;
    out << "option " << name << ' ';
    if constexpr (std::is_same_v<T, std::string>)
      out << std::quoted(value);
    else if constexpr (is_choice_v<T>)
      out << std::quoted(std::string(name_of(value)));
    else if constexpr (std::is_same_v<T, std::vector<double>>) {
      out << value.size();
      for (double x : value) out << ' ' << x;
    } else
      out << value;
    out << '\n';
  });
  for (const std::string& r : reactions) out << "reaction " << std::quoted(r) << '\n';
  for (const std::string& e : efforts) out << "effort " << std::quoted(e) << '\n';
  out << "model\n" << model;
  return out.str();
}

CoSimulationSetup CoSimulationSetup::from_text(const std::string& text) {
  CoSimulationSetup setup;
  std::istringstream lines(text);
  std::string line;
  if (!std::getline(lines, line) || line != kHeader)
    throw ModelError("co-simulation setup: not lagmb's (no '" + std::string(kHeader) + "' first)");
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    std::string word;
    in >> word;
    if (word == "model") {
      std::ostringstream rest;
      rest << lines.rdbuf();
      setup.model = rest.str();
      return setup;
    }
    std::string name;
    if (word == "reaction" || word == "effort") {
      in >> std::quoted(name);
      (word == "reaction" ? setup.reactions : setup.efforts).push_back(name);
      continue;
    }
    if (word != "option") throw ModelError("co-simulation setup: unexpected line '" + line + "'");
    in >> name;
    bool known = false;
    setup.options.for_each_field([&](const char* field, auto& value) {
      if (name != field) return;
      known = true;
      using T = std::decay_t<decltype(value)>;
      if constexpr (std::is_same_v<T, std::string>)
        in >> std::quoted(value);
      else if constexpr (is_choice_v<T>) {
        std::string text;
        in >> std::quoted(text);
        value = choice_from<T>(text);
      } else if constexpr (std::is_same_v<T, std::vector<double>>) {
        size_t n = 0;
        in >> n;
        value.assign(n, 0.0);
        for (double& x : value) in >> x;
      } else
        in >> value;
    });
    if (!known || in.fail()) throw ModelError("co-simulation setup: bad option line '" + line + "'");
  }
  throw ModelError("co-simulation setup: no 'model' section");
}

CoSimulation::CoSimulation(CoSimulationSetup setup)
    : setup_(std::move(setup)), spec_(ModelSpec::from_text(setup_.model)) {
  const std::shared_ptr<const Model> model = spec_.compile();
  add({"time", "independent", "continuous", "s", "simulation time"}, {Slot::kTime});
  for (size_t k = 0; k < model->inputs().size(); ++k) {
    const InputInfo& in = model->inputs()[k];
    std::string unit = in.unit;
    if (unit.find(" or ") != std::string::npos)
      if (const auto* e = element_of(spec_, in.element)) unit = driven_unit(spec_, *e);
    add({in.name, "input", "continuous", unit, "input to " + in.element + " (" + in.parameter + ")", in.initial},
        {Slot::kInput, int(k)});
    inputs_.push_back(in.initial);
  }
  for (const ParameterInfo& p : parameters(*model)) {
    add({p.name, "parameter", "fixed", p.unit, p.doc, p.value}, {Slot::kParameter, int(parameters_.size())});
    parameters_.push_back(p.value);
  }
  for (const Body& b : model->bodies()) {
    for (int c = 0; c < b.n_coordinates(); ++c) {
      const std::string coordinate = body_coordinate_name(b, c), unit = body_coordinate_unit(b, c);
      const std::string rate = (unit.empty() ? "1" : unit) + "/s";
      add({b.name + "." + coordinate, "output", "continuous", unit, "coordinate of body " + b.name},
          {Slot::kCoordinate, b.first_coord + c});
      add({"der(" + b.name + "." + coordinate + ")", "output", "continuous", rate, "its rate"},
          {Slot::kVelocity, b.first_coord + c});
    }
  }
  for (const std::string& name : setup_.reactions) {
    if (!model->has(name) || model->find(name).type != ElementRef::kConstraint)
      throw ModelError("co-simulation: reaction of '" + name + "': not a joint or driver of the model");
    const std::vector<std::string>& components = reaction_components(model->dimension());
    for (int c = 0; c < int(components.size()); ++c) {
      const std::string& component = components[size_t(c)];
      add({name + ".reaction." + component, "output", "continuous", component.rfind("torque", 0) == 0 ? "N m" : "N",
           "force and torque of " + name + " on its second body, global axes"},
          {Slot::kReaction, 0, c, name});
    }
  }
  for (const std::string& name : setup_.efforts) {
    const ModelSpec::Element* e = element_of(spec_, name);
    if (!e || e->args.kind().role != Role::kDriver)
      throw ModelError("co-simulation: effort of '" + name + "': not a driver of the model");
    const ElementRef& r = model->find(name);
    const int row = model->constraint_groups()[r.group]->placement(r.index).row0;
    const std::string unit = driven_unit(spec_, *e) == "rad" ? "N m" : "N";
    add({name + ".effort", "output", "continuous", unit, "what " + name + " applies along what it drives"},
        {Slot::kEffort, row, 0, name});
  }
  // an FMU names each variable once: names made from element and input
  // names can collide (an input "a.x" and body a's coordinate x)
  std::map<std::string, size_t> seen;
  for (size_t vr = 0; vr < variables_.size(); ++vr) {
    const auto [at, fresh] = seen.emplace(variables_[vr].name, vr);
    if (fresh) continue;
    const CoVariable &first = variables_[at->second], &second = variables_[vr];
    throw ModelError("co-simulation: two variables would be called '" + second.name + "': the " + first.causality +
                     " (" + first.description + ") and the " + second.causality + " (" + second.description +
                     "); rename the element or input one of them comes from");
  }
}

CoSimulation::~CoSimulation() = default;

void CoSimulation::add(CoVariable variable, Slot slot) {
  variables_.push_back(std::move(variable));
  slots_.push_back(std::move(slot));
}

double CoSimulation::time() const { return sim_ ? sim_->t() : t0_; }

void CoSimulation::set(size_t vr, double value) {
  if (vr >= slots_.size()) throw ModelError("no variable with value reference " + std::to_string(vr));
  const Slot& s = slots_[vr];
  const std::string& name = variables_[vr].name;
  if (!std::isfinite(value)) throw ModelError("'" + name + "' must be finite, got " + to_text(value));
  switch (s.kind) {
    case Slot::kInput:
      inputs_[s.index] = value;
      if (sim_) sim_->set_input(name, value);
      return;
    case Slot::kParameter:
      if (mode_ == Mode::kStepping)
        throw ModelError("parameter '" + name + "' is fixed once initialization has ended");
      parameters_[s.index] = value;
      sim_.reset();  // the model is compiled anew with it
      return;
    default:
      throw ModelError("'" + name + "' is " + (s.kind == Slot::kTime ? "the time" : "an output") +
                       ": it cannot be set");
  }
}

Simulator& CoSimulation::running() {
  if (mode_ == Mode::kInstantiated)
    throw ModelError("the outputs are computed from initialization on (enter initialization mode first)");
  if (!sim_) start_run();
  return *sim_;
}

double CoSimulation::get(size_t vr) {
  if (vr >= slots_.size()) throw ModelError("no variable with value reference " + std::to_string(vr));
  const Slot& s = slots_[vr];
  switch (s.kind) {
    case Slot::kTime: return time();
    case Slot::kInput: return inputs_[s.index];
    case Slot::kParameter: return parameters_[s.index];
    case Slot::kCoordinate: return running().q()[s.index];
    case Slot::kVelocity: return running().v()[s.index];
    case Slot::kEffort: return -running().lam()[s.index];
    case Slot::kReaction: {
      Simulator& sim = running();
      const double t = sim.t();
      const VecX q = sim.q(), lam = sim.lam(), inputs = sim.inputs();
      OutputView now;
      now.k = 1;
      now.t = &t;
      now.q = q.data();
      now.lam = lam.data();
      now.inputs = inputs.data();
      return reactions(*model_, s.element, now)(0, s.component);
    }
  }
  return NAN;
}

void CoSimulation::start_run() {
  // the parameters set: the model built with those values (checked as when first added)
  ParameterValues changed;
  for (size_t vr = 0; vr < slots_.size(); ++vr)
    if (slots_[vr].kind == Slot::kParameter && parameters_[slots_[vr].index] != variables_[vr].start)
      changed[variables_[vr].name] = parameters_[slots_[vr].index];
  model_ = spec_.compile();
  if (!changed.empty()) model_ = with_parameters(*model_, changed);
  SimulationOptions o = setup_.options;
  o.t0 = t0_;
  // the importer's tolerance is for the method's error control (FMI: a suggestion); a fixed-step
  // method has none, and the run refuses tolerances given to it
  bool fixed_step = false;
  for (const Method& m : methods()) fixed_step = fixed_step || (m.formulation == o.formulation && m.fixed_step);
  if (tolerance_ > 0.0 && !fixed_step) o.rtol = tolerance_;
  sim_ = std::make_unique<Simulator>(*model_, o);
  for (size_t k = 0; k < inputs_.size(); ++k) sim_->set_input(model_->inputs()[k].name, inputs_[k]);
}

void CoSimulation::enter_initialization(double t0, double tolerance) {
  if (mode_ != Mode::kInstantiated) throw ModelError("initialization was entered already");
  if (!std::isfinite(t0)) throw ModelError("the start time is not finite");
  if (!(std::isfinite(tolerance) && tolerance >= 0.0)) throw ModelError("the tolerance must be finite and >= 0");
  t0_ = t0;
  tolerance_ = tolerance;
  mode_ = Mode::kInitialization;
}

void CoSimulation::exit_initialization() {
  if (mode_ != Mode::kInitialization) throw ModelError("not in initialization mode");
  running();
  mode_ = Mode::kStepping;
}

void CoSimulation::do_step(double t, double h) {
  if (mode_ != Mode::kStepping) throw ModelError("a step needs initialization to have ended");
  const double now = sim_->t();
  if (!(std::abs(t - now) <= 1e-9 * std::max(1.0, std::abs(now))))  // NaN too
    throw ModelError("a step from t = " + to_text(t) + ", but the model is at t = " + to_text(now));
  if (!(std::isfinite(h) && h > 0.0)) throw ModelError("the step size must be positive and finite, got " + to_text(h));
  sim_->advance(now + h);
}

CoSimulationState CoSimulation::state() {
  if (mode_ != Mode::kStepping) throw ModelError("a state is taken once initialization has ended");
  return {sim_->state(), inputs_};
}

void CoSimulation::set_state(const CoSimulationState& state) {
  if (mode_ != Mode::kStepping) throw ModelError("a state is restored once initialization has ended");
  if (state.inputs.size() != inputs_.size()) throw ModelError("the state is of another model");
  sim_->set_state(state.simulator);
  inputs_ = state.inputs;
}

void CoSimulation::reset() {
  sim_.reset();
  model_.reset();
  mode_ = Mode::kInstantiated;
  for (size_t vr = 0; vr < slots_.size(); ++vr) {
    if (slots_[vr].kind == Slot::kParameter) parameters_[slots_[vr].index] = variables_[vr].start;
    if (slots_[vr].kind == Slot::kInput) inputs_[slots_[vr].index] = variables_[vr].start;
  }
}

}  // namespace lagmb
