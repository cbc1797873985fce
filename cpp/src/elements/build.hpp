// What the builders of element kinds share (registry.hpp): the checks every
// kind makes of its bodies, and the conversion of the initial
// configuration's global points and directions to body axes. Each builder
// lives in cpp/src/elements/<kind>.cpp next to its kind's declaration.
#pragma once

#include <array>
#include <string>

#include "lagmb/elements/contact_law.hpp"
#include "lagmb/elements/stop.hpp"
#include "lagmb/model/joint_coordinate.hpp"
#include "lagmb/model/joint_reading.hpp"
#include "lagmb/projected_offset.hpp"
#include "lagmb/spatial.hpp"
#include "lagmb/model/model.hpp"
#include "lagmb/model/registry.hpp"

namespace lagmb::build {

/// How messages name an element: "<kind> '<name>'" ("rack pinion 'r1'").
std::string label(const Args& args, const std::string& name);

/// A new element of Kind called `name` acting between body_i and body_j
/// (kGround for a single-body element's other side); ModelError unless both
/// exist and differ.
template <class Kind>
Kind joining(const Model& m, const std::string& name, int body_i, int body_j) {
  m.check_pair(name, body_i, body_j);
  Kind e;
  e.name = name;
  e.body_i = body_i;
  e.body_j = body_j;
  return e;
}

/// What an element follows: `f`, or the run's value of the model's input
/// `f` is (added before the builder runs; Drive::input its slot).
Drive drive(const Model& m, TimeFunctionPtr f);
std::array<Drive, 3> drive_triple(const Model& m, const std::array<TimeFunctionPtr, 3>& f);

/// ModelError "'<element>': <what>" unless x is finite and positive.
void require_positive(double x, const std::string& element, const char* what);
/// ModelError naming `element` unless 4 x^2 is finite (a length squared in an equation).
void require_squarable(double x, const std::string& element, const char* what);
/// ModelError "'<element>': <what>" unless x is finite and >= 0.
void require_nonnegative(double x, const std::string& element, const char* what);
/// ModelError naming `element`, `what` and x unless x is finite and |x| <= kLargestGiven (a gain).
void require_within_largest(double x, const std::string& element, const char* what, const char* unit);

/// A body that takes this element needs an angle (particles have none).
void require_rigid(const Model& m, int body, const std::string& element, const char* why);
/// On a particle the element's point must be the particle itself.
void require_on_particle(const Model& m, int body, Vec2 point, const std::string& element);

/// A unit direction, given globally in the initial configuration, in the
/// body's axes; ModelError for a zero vector.
Vec2 local_direction(const Model& m, int body, Vec2 direction, const std::string& element);
/// The line through `at` along `axis` fixed in body i, as the offset from it
/// measured across the line: w = axis turned +90 deg (body i's axes),
/// s_i, s_j = `at` in each body's axes.
ProjectedOffset across_line(const Model& m, int body_i, int body_j, Vec2 at, Vec2 axis,
                            const std::string& element);

/// The scalar coordinate of the joint called `joint` (its kind's
/// coordinate(), joint_coordinate.hpp) and the element it is; ModelError
/// naming `element` if there is no such joint or its kind has none (listing
/// the kinds of the model's space that have one).
struct JointOf : JointCoordinate {
  ElementRef joint;
};
JointOf joint_coordinate(const Model& m, const std::string& joint, const std::string& element);
/// How a spatial element reads that coordinate (joint_reading.hpp), an
/// angle within pi of `center` (rad).
spatial::JointReading joint_reading(const JointCoordinate& c, double center);
/// The joint's coordinate (its angle within pi of `around`, or its slide)
/// in the model's initial configuration.
double initial_joint_value(const Model& m, const JointCoordinate& c, double around = 0.0);
/// Gives the spatial joint `joint`, just added, the counter of its turns in
/// a run if it turns (model/joint_turns.hpp); its builder calls this with
/// the angle it was given in the initial configuration (`angle`: a joint
/// built at 3.96 rad reads 3.96, not 3.96 - 2 pi).
void count_turns(Model& m, const std::string& joint, double angle = 0.0);
/// How an element that acts on joint `joint` (coordinate c) in the run's
/// equations reads it: a turning joint's angle continuous through its
/// turns (the counter's reading, which this marks read), a slide as it is.
spatial::JointReading continuous_reading(Model& m, const std::string& joint, const JointCoordinate& c);

/// The contact law a contact is given (stiffness, restitution, friction,
/// slip_velocity; contact_law.hpp), checked, and the parameters that give it.
ContactLaw contact_law(const Args& a, const std::string& label);
std::vector<Param> contact_law_params();

// --- spatial kinds -----------------------------------------------------------

/// A kind's registry entry (KindInfo), each field named where it is given:
///   return build::kind("bushing")
///       .method("add_bushing")
///       .table("forces")
///       .type("bushing")
///       .role(Role::kForce)
///       .in_space()
///       .doc("...")
///       .params({...})
///       .build(build_bushing)
///       .effort("...", {"x", "y", "z", ...});
class KindBuilder {
 public:
  explicit KindBuilder(std::string name) { k_.name = std::move(name); }
  /// The Python Model method that adds one ("add_revolute").
  KindBuilder& method(std::string method) { return set(&KindInfo::method, std::move(method)); }
  /// Its scene table ("joints").
  KindBuilder& table(std::string table) { return set(&KindInfo::table, std::move(table)); }
  /// Its `type` in that table (not given: the table has this one kind).
  KindBuilder& type(std::string type) { return set(&KindInfo::type, std::move(type)); }
  KindBuilder& role(Role role) { return set(&KindInfo::role, role); }
  /// A kind of a spatial model (KindInfo::dimension 3; not given: planar).
  KindBuilder& in_space() { return set(&KindInfo::dimension, 3); }
  /// A joint kind's scalar coordinate.
  KindBuilder& coordinate(CoordinateKind coordinate) { return set(&KindInfo::coordinate, coordinate); }
  KindBuilder& doc(std::string doc) { return set(&KindInfo::doc, std::move(doc)); }
  KindBuilder& params(std::vector<Param> params) { return set(&KindInfo::params, std::move(params)); }
  KindBuilder& build(decltype(KindInfo::build) build) { return set(&KindInfo::build, std::move(build)); }
  /// A kind whose elements have an effort: what Result.effort reads, with its
  /// unit; `components`: its columns' names where it has several.
  KindBuilder& effort(std::string effort, std::vector<std::string> components = {}) {
    k_.effort_components = std::move(components);
    return set(&KindInfo::effort, std::move(effort));
  }
  operator KindInfo() const { return k_; }

 private:
  template <class Field, class Value>
  KindBuilder& set(Field KindInfo::*field, Value&& value) {
    k_.*field = std::forward<Value>(value);
    return *this;
  }
  KindInfo k_;
};
inline KindBuilder kind(std::string name) { return KindBuilder(std::move(name)); }

/// What a joint stop (planar or spatial) is given: its limits, checked (one
/// at least, lower below upper), restitution in [0, 1] and rest_speed > 0;
/// and the parameters that give them (stop_params, after the joint).
/// A stop's limits and contact values (stop.hpp), checked.
StopLimits stop_limits(const Args& a, const std::string& label);
std::vector<Param> stop_params();

/// The unit global direction given as `key`; ModelError for a zero vector.
Vec3 unit_direction(const Args& a, const std::string& key, const std::string& label);

/// A new spatial joint of Kind at the point `at` with the triple (f, g, a)
/// around the global direction `axis`, all in the axes of the bodies'
/// initial configuration (SpatialJointBase).
template <class Kind>
Kind spatial_joint(Model& m, const std::string& name, const Args& a, const Vec3& axis) {
  Kind j = joining<Kind>(m, name, a.body("body_i"), a.body("body_j"));
  const Vec3 at = a.vec3("at");
  j.s_i = m.local_point(j.body_i, at);
  j.s_j = m.local_point(j.body_j, at);
  Vec3 f, g;
  euler::complete_basis(axis, f, g);
  j.f_i = m.local_direction(j.body_i, f);
  j.g_i = m.local_direction(j.body_i, g);
  j.a_i = m.local_direction(j.body_i, axis);
  return j;
}

}  // namespace lagmb::build
