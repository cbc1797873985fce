// The model: bodies and elements grouped by kind, frozen by finalize().
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <typeindex>
#include <vector>

#include "lagmb/model/constraint_group.hpp"
#include "lagmb/model/body.hpp"
#include "lagmb/model/gravity.hpp"
#include "lagmb/model/event_group.hpp"
#include "lagmb/model/force_group.hpp"
#include "lagmb/model/friction_group.hpp"
#include "lagmb/model/joint_turns.hpp"
#include "lagmb/model/registry.hpp"
#include "lagmb/time_function.hpp"
#include "lagmb/sparsity.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// The ground: body index -1, at rest at the origin with angle 0.
constexpr int kGround = -1;

/// An input of a model (time_function.hpp, Input): its name and what it feeds.
struct InputInfo {
  std::string name;       // what Simulator::set_input takes
  std::string element;    // the element it feeds
  std::string parameter;  // the element's parameter: "force", "torque", "f"; ".x", ".y", ".z" for a component
  std::string unit;       // SI unit of the value
  double initial = 0.0;
  const Input* function = nullptr;
};

/// An element as it was given: its name and values (the kind's Args).
struct GivenElement {
  std::string name;
  Args args;
};

/// What a name refers to.
struct ElementRef {
  enum Type { kBody, kConstraint, kForce, kFriction, kEvent } type;
  int group;  // constraint, force, friction or event group; body index for kBody
  int index;  // element within its group
};

/// A mechanism, compiled from a ModelSpec (spec.hpp): the bodies and the
/// elements grouped by kind. The builders of element kinds add to it; then
/// finalize() fixes coordinates, constraint rows, sparsity patterns and
/// element slots, and the model no longer changes. Kernels take
/// (const Model&, Data&); several runs may read one Model at once.
class Model {
 public:
  Model() = default;
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  /// The model's space: 2 (planar, the default) or 3 (spatial). Every body
  /// and element kind must be of it (add_element checks); set before any is added.
  void set_dimension(int dimension);
  int dimension() const { return dimension_; }

  /// Uniform gravity acceleration g (m/s^2) on every body (a planar model
  /// takes (x, y), a spatial one (x, y, z)).
  void set_gravity(Vec2 g);
  void set_gravity(Vec3 g);

  // --- for the builders of element kinds (registry.hpp) -----------------
  // Users add elements through a ModelSpec (spec.hpp); each kind's builder
  // (cpp/src/elements/<kind>.cpp) checks its values and adds the element
  // here, which numbers it and records its name.

  /// Adds a body or particle (its values already checked); returns its index.
  int add_body(Body body);
  /// Adds a constraint element of any kind (see constraint_group.hpp).
  /// `named` = false: a body's own element (a spatial body's normalization),
  /// whose name is for messages only and is not looked up.
  template <class Kind>
  void add_constraint(Kind element, bool named = true);
  /// Adds a force element of any kind (see force_group.hpp); `named` as for
  /// constraints.
  template <class Kind>
  void add_force_element(Kind element, bool named = true);
  /// Adds an event element of any kind (see event_group.hpp); an element
  /// that is also a force is added as a force first and not named again.
  template <class Kind>
  void add_event_element(Kind element, bool named = true);
  /// Adds a joint-friction element of any kind (see friction_group.hpp).
  template <class Kind>
  void add_friction(Kind element);
  /// Gives an element of a kind with per-run state its offset in
  /// Data::run->state (once: a contact is both a force and an event element).
  template <class Kind>
  void reserve_run_state(Kind& element) {
    if constexpr (run_state_size_v<Kind> > 0)
      if (element.run_state < 0) {
        element.run_state = run_state_size_;
        run_state_size_ += run_state_count(element);
      }
  }
  /// Counts the turns of a spatial joint's angle in a run (joint_turns.hpp;
  /// the joint's builder adds it): reserves its run state.
  void add_turn_counter(TurnCounter counter);
  /// The counter of `joint` (null: none, the joint does not turn in space);
  /// the mutable one marks it read by the element being built.
  const TurnCounter* turn_counter(const std::string& joint) const;
  TurnCounter* turn_counter(const std::string& joint);
  const std::vector<TurnCounter>& turn_counters() const { return turn_counters_; }
  /// Records an element as given (add_element does): what the model is
  /// built from again with other parameter values (parameters.hpp).
  void record_given(const std::string& name, const Args& args) { given_.push_back({name, args}); }
  /// The elements as given, in the order added.
  const std::vector<GivenElement>& given_elements() const { return given_; }
  /// The kind body or element `name` was added as (its role, its
  /// coordinate: registry.hpp); null for one the model made itself.
  /// ModelError if the model has no such name.
  const KindInfo* given_kind(const std::string& name) const;
  /// Gravity as set (absent if never set).
  const std::optional<Vec3>& given_gravity() const { return given_gravity_; }
  /// Notes a time function of a driver or force (for breakpoints()).
  void use_time_function(const TimeFunctionPtr& f);
  /// Records an input (time_function.hpp) of an element; the same Input
  /// given to several parameters is one input. ModelError if another input
  /// has the name already.
  void add_input(InputInfo info);
  /// ModelError naming `element` unless both bodies exist and differ.
  void check_pair(const std::string& element, int body_i, int body_j) const;
  /// The constraint element of kind Kind called `name`, or null.
  template <class Kind>
  const Kind* find_constraint(const std::string& name) const;
  /// What `name` is, for messages: "a body", "a weld", ...
  std::string describe(const std::string& name) const;

  /// Records that `element` attaches at `local` (body axes; global for the
  /// ground) on `body` (add_element does it for every point parameter); a
  /// planar point has z = 0.
  void attach(const std::string& element, int body, Vec3 local);
  void attach(const std::string& element, int body, Vec2 local) { attach(element, body, Vec3(local.x(), local.y(), 0.0)); }
  /// Local points where elements attach to a body, in the order added,
  /// each once: what a drawing of the body joins.
  const std::vector<Vec3>& outline(int body) const;
  /// (body, local point) where an element attaches, in the order recorded.
  const std::vector<std::pair<int, Vec3>>& attachments(const std::string& element) const;
  /// A global point of the initial configuration in the body's axes.
  Vec2 local_point(int body, Vec2 global_point) const;
  Vec3 local_point(int body, Vec3 global_point) const;
  /// A global direction of the initial configuration in a spatial body's axes.
  Vec3 local_direction(int body, Vec3 global_direction) const;
  /// A direction in a spatial body's axes in global axes (initial configuration).
  Vec3 body_direction(int body, Vec3 local_direction) const;
  /// Initial position of a spatial body's centre of mass (the origin for the ground).
  Vec3 body_position(int body) const;
  /// Initial position of a body's centre of mass (the origin for the ground).
  Vec2 initial_position(int body) const;
  double initial_angle(int body) const;

  /// Freezes the model: numbers coordinates and rows, builds patterns and
  /// slots. Linear in the model's size, and no solver runs here: which
  /// equations are redundant depends on where a run starts, so each run
  /// decides it (redundancy.hpp) and keeps it in its Data.
  void finalize();
  bool finalized() const { return finalized_; }
  /// A number no other model of this process has had: what a saved run
  /// state names as its model (an address may be reused once freed).
  std::uint64_t id() const { return id_; }
  /// A structure a layer above derives from the frozen model alone (the
  /// augmented system's Schur pattern and ordering): T(model) is made on
  /// first use and shared by every run after it, from any thread. T must
  /// read only what finalize() fixed (patterns, sizes), never parameters.
  template <class T>
  const T& derived() const;

  // --- after finalize() -------------------------------------------------
  int n_coordinates() const { return n_; }
  int n_constraints() const { return m_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  const Body& body(int i) const { return bodies_.at(i); }
  /// Diagonal of the constant part of M: all of M for a planar model; 0 at
  /// the Euler parameters of spatial bodies, whose block depends on q
  /// (mass.cpp, elements/spatial_body.hpp).
  const VecX& mass_diagonal() const { return mass_diag_; }
  /// Whether M is constant (no spatial body): M = diag(mass_diagonal()).
  bool constant_mass() const { return spatial_masses_.empty(); }
  /// Whether M is definite: every mass positive (and every inertia tensor
  /// positive definite); a massless body is for kinematic analysis only.
  bool positive_mass() const { return positive_mass_; }
  /// Pattern of M (n x n): its diagonal, and a 4 x 4 block at the Euler
  /// parameters of each spatial body.
  const SpMat& mass_pattern() const { return mass_pattern_; }
  /// Where each diagonal entry of M sits in mass_pattern()'s values.
  const std::vector<int>& mass_diagonal_slots() const { return mass_diagonal_slots_; }
  /// The state-dependent blocks of M: one per spatial body.
  struct SpatialMass {
    int p = 0;                  // position of its Euler parameters in q
    std::array<int, 16> slots;  // its 4 x 4 block in mass_pattern() (column-major)
    Mat3 J, J_inverse;          // inertia tensor J' (body axes) and its inverse
    double jbar = 0.0;          // trace(J') / 3
  };
  const std::vector<SpatialMass>& spatial_masses() const { return spatial_masses_; }
  /// Initial coordinates and velocities as given (not yet consistent).
  VecX initial_q() const;
  VecX initial_v() const;

  const std::vector<std::unique_ptr<ConstraintGroupBase>>& constraint_groups() const {
    return constraints_;
  }
  /// Constraint groups whose equations depend on time explicitly.
  const std::vector<const ConstraintGroupBase*>& time_dependent_groups() const {
    return time_dependent_;
  }
  const std::vector<std::unique_ptr<ForceGroupBase>>& force_groups() const { return forces_; }
  /// Event groups (stops, contact switches). What they record during a run
  /// goes to the run's Data::run->state, never into the Model.
  const std::vector<std::unique_ptr<EventGroupBase>>& event_groups() const { return events_; }
  /// The rows of unilateral kinds (stops; constraint_group.hpp), ascending:
  /// open (left out) unless a run's active set closes them.
  const std::vector<int>& unilateral_rows() const { return unilateral_rows_; }
  /// The rows that hold stuck contacts (constraint_group.hpp, is_stick),
  /// ascending: open (left out) unless the run's event runner closes them.
  const std::vector<int>& stick_rows() const { return stick_rows_; }
  /// Both, ascending: the rows a run opens and closes, which are not
  /// equations of the motion while open.
  const std::vector<int>& switched_rows() const { return switched_rows_; }
  /// Whether a run has event functions: event elements or unilateral rows.
  bool has_events() const { return !events_.empty() || !unilateral_rows_.empty(); }
  /// An element with event functions, for messages ("" if none).
  std::string event_element_name() const;
  /// Force groups whose Q depends on q or v.
  const std::vector<const ForceGroupBase*>& state_dependent_forces() const {
    return state_dependent_;
  }

  /// Joint-friction groups (forces that depend on the multipliers); empty
  /// for a model without friction.
  const std::vector<std::unique_ptr<FrictionGroupBase>>& friction_groups() const { return frictions_; }

  /// Pattern of Phi_q (m x n).
  const SpMat& jacobian_pattern() const { return jacobian_pattern_; }
  /// Pattern of sum_r w_r d2Phi_r/dq2 (n x n).
  const SpMat& hessian_pattern() const { return hessian_pattern_; }
  /// Patterns of Q_q and Q_v (n x n).
  const SpMat& force_q_pattern() const { return force_q_pattern_; }
  const SpMat& force_v_pattern() const { return force_v_pattern_; }

  /// Looks an element or body up by name; throws ModelError if unknown.
  const ElementRef& find(const std::string& name) const;
  bool has(const std::string& name) const { return names_.count(name) > 0; }
  /// Name of the constraint element owning row `row` of Phi.
  std::string constraint_name_of_row(int row) const;
  /// Index of the constraint group (constraint_groups()) owning row `row` of Phi.
  int group_of_row(int row) const { return constraint_order_[row_owner_[row]].first; }
  /// The element (its place in insertion order) a constraint row belongs to; an element's rows are consecutive.
  int element_of_row(int row) const { return row_owner_[row]; }
  /// The element a constraint row belongs to, as its index within its group.
  int element_in_group_of_row(int row) const { return constraint_order_[row_owner_[row]].second; }
  /// Body owning coordinate `coord` of q.
  const Body& body_of_coordinate(int coord) const;
  /// Positions in q of the local coordinates of a pair of bodies:
  /// (x_i, y_i, phi_i, x_j, y_j, phi_j) in the plane, (r_i, p_i, r_j, p_j) in
  /// space (space.hpp); -1 for the ground, a missing angle and the rest.
  LocalCoords local_coordinates(int body_i, int body_j) const;
  /// The same for the bodies of an element that joins more than two.
  LocalCoords local_coordinates(const std::vector<int>& element_bodies) const;

  /// Sorted times where a time function of the model has a breakpoint.
  std::vector<double> breakpoints() const;
  /// The time functions of drivers and forces, each once.
  const std::vector<TimeFunctionPtr>& time_functions() const { return time_functions_; }

  /// The inputs of the model's elements, in the order added; a Simulator
  /// holds one value per entry.
  const std::vector<InputInfo>& inputs() const { return inputs_; }
  /// Their functions, in the same order (Drive::input indexes both).
  const std::vector<const Input*>& input_functions() const { return input_functions_; }
  /// The index of the input called `name` in inputs(), -1 if none.
  int input_index(const std::string& name) const;
  /// The index in inputs() of the input whose function is `f`, -1 if none.
  int input_slot(const TimeFunction* f) const;

  /// Mean body mass (kg): regularization and multiplier tolerances scale with it.
  double mass_scale() const { return mass_scale_; }
  /// Doubles of per-run element state (Data::run->state); 0 for most models.
  int run_state_size() const { return run_state_size_; }

 private:
  void require_open(const std::string& what) const;
  void build_mass();
  void check_new_name(const std::string& name) const;
  void register_name(const std::string& name, ElementRef ref);

  bool finalized_ = false;
  std::uint64_t id_ = next_model_id();
  mutable std::mutex derived_mutex_;
  mutable std::map<std::type_index, std::shared_ptr<const void>> derived_;
  static std::uint64_t next_model_id();
  int dimension_ = 2;
  std::vector<Body> bodies_;
  std::vector<GivenElement> given_;
  std::optional<Vec3> given_gravity_;
  std::vector<std::vector<Vec3>> outlines_;  // per body
  std::map<std::string, std::vector<std::pair<int, Vec3>>> attachments_;  // per element
  std::vector<std::unique_ptr<ConstraintGroupBase>> constraints_;
  std::map<std::type_index, int> constraint_group_of_kind_, force_group_of_kind_;
  std::vector<std::pair<int, int>> constraint_order_;  // (group, index) in insertion order
  std::vector<std::unique_ptr<ForceGroupBase>> forces_;
  std::vector<std::unique_ptr<EventGroupBase>> events_;
  std::map<std::type_index, int> event_group_of_kind_;
  std::vector<const ConstraintGroupBase*> time_dependent_;
  std::vector<const ForceGroupBase*> state_dependent_;
  std::vector<TimeFunctionPtr> time_functions_;  // of drivers and forces, for breakpoints
  std::set<const TimeFunction*> time_function_set_;  // the same, to add each once
  std::vector<InputInfo> inputs_;
  std::vector<const Input*> input_functions_;
  std::map<std::string, ElementRef> names_;
  std::vector<std::unique_ptr<FrictionGroupBase>> frictions_;
  std::map<std::type_index, int> friction_group_of_kind_;

  int n_ = 0, m_ = 0;
  VecX mass_diag_;
  SpMat mass_pattern_;
  std::vector<int> mass_diagonal_slots_;
  std::vector<SpatialMass> spatial_masses_;
  bool positive_mass_ = false;
  SpMat jacobian_pattern_, hessian_pattern_, force_q_pattern_, force_v_pattern_;
  std::vector<int> row_owner_;  // row -> index into constraint_order_
  std::vector<int> unilateral_rows_;
  std::vector<int> stick_rows_;
  std::vector<int> switched_rows_;
  std::vector<int> coord_owner_;
  double mass_scale_ = 1.0;
  int run_state_size_ = 0;
  std::vector<TurnCounter> turn_counters_;
};

template <class T>
const T& Model::derived() const {
  const std::type_index key(typeid(T));
  {
    std::lock_guard<std::mutex> lock(derived_mutex_);
    if (auto it = derived_.find(key); it != derived_.end()) return *static_cast<const T*>(it->second.get());
  }
  // made outside the lock (T may derive others); the first one stored wins
  auto made = std::make_shared<const T>(*this);
  std::lock_guard<std::mutex> lock(derived_mutex_);
  return *static_cast<const T*>(derived_.try_emplace(key, std::move(made)).first->second.get());
}

template <class Kind>
void Model::add_constraint(Kind element, bool named) {
  require_open("add " + std::string(Kind::kind) + " '" + element.name + "'");
  if (named) check_new_name(element.name);
  check_pair(element.name, element.body_i, element.body_j);
  auto [it, inserted] =
      constraint_group_of_kind_.try_emplace(std::type_index(typeid(Kind)), int(constraints_.size()));
  if (inserted) constraints_.push_back(std::make_unique<ConstraintGroup<Kind>>());
  auto& group = static_cast<ConstraintGroup<Kind>&>(*constraints_[it->second]);
  if (named) register_name(element.name, {ElementRef::kConstraint, it->second, group.size()});
  constraint_order_.emplace_back(it->second, group.size());
  group.add(std::move(element));
}

template <class Kind>
void Model::add_force_element(Kind element, bool named) {
  require_open("add " + std::string(Kind::kind) + " '" + element.name + "'");
  if (named) check_new_name(element.name);
  check_pair(element.name, element.body_i, element.body_j);  // single-body forces: body_j = ground
  auto [it, inserted] =
      force_group_of_kind_.try_emplace(std::type_index(typeid(Kind)), int(forces_.size()));
  if (inserted) forces_.push_back(std::make_unique<ForceGroup<Kind>>());
  auto& group = static_cast<ForceGroup<Kind>&>(*forces_[it->second]);
  reserve_run_state(element);
  if (named) register_name(element.name, {ElementRef::kForce, it->second, group.size()});
  group.add(std::move(element));
}

template <class Kind>
void Model::add_event_element(Kind element, bool named) {
  require_open("add " + std::string(Kind::kind) + " '" + element.name + "'");
  if (named) check_new_name(element.name);
  check_pair(element.name, element.body_i, element.body_j);
  auto [it, inserted] =
      event_group_of_kind_.try_emplace(std::type_index(typeid(Kind)), int(events_.size()));
  if (inserted) events_.push_back(std::make_unique<EventGroup<Kind>>());
  auto& group = static_cast<EventGroup<Kind>&>(*events_[it->second]);
  reserve_run_state(element);
  // (an element that is also a force keeps the name of its force entry)
  if (named) register_name(element.name, {ElementRef::kEvent, it->second, group.size()});
  group.add(std::move(element));
}

template <class Kind>
const Kind* Model::find_constraint(const std::string& name) const {
  auto named = names_.find(name);
  auto group = constraint_group_of_kind_.find(std::type_index(typeid(Kind)));
  if (named == names_.end() || group == constraint_group_of_kind_.end()) return nullptr;
  const ElementRef& r = named->second;
  if (r.type != ElementRef::kConstraint || r.group != group->second) return nullptr;
  return &static_cast<const ConstraintGroup<Kind>&>(*constraints_[r.group]).items[r.index];
}

template <class Kind>
void ForceGroup<Kind>::place(const Model& model) {
  coord_.clear();
  for (const auto& e : items) coord_.push_back(model.local_coordinates(e.body_i, e.body_j));
}

template <class Kind>
void Model::add_friction(Kind element) {
  auto [it, inserted] =
      friction_group_of_kind_.try_emplace(std::type_index(typeid(Kind)), int(frictions_.size()));
  if (inserted) frictions_.push_back(std::make_unique<FrictionGroup<Kind>>());
  auto& group = static_cast<FrictionGroup<Kind>&>(*frictions_[it->second]);
  register_name(element.name, {ElementRef::kFriction, it->second, group.size()});
  group.add(std::move(element));
}

template <class Kind>
void FrictionGroup<Kind>::place(const Model& model) {
  place_.clear();
  for (const auto& e : items)
    place_.push_back(model.constraint_groups()[e.joint_group]->placement(e.joint_index));
}

template <class Kind>
void EventGroup<Kind>::place(const Model& model) {
  coord_.clear();
  for (const auto& e : items) coord_.push_back(model.local_coordinates(e.body_i, e.body_j));
}

}  // namespace lagmb
