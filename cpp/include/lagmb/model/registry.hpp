// The registry of element kinds: what a user may add to a model, each kind
// declared once, in the source file next to its equations
// (cpp/src/elements/<kind>.cpp). The Python add_* methods and their checks,
// the scene schema, `lagmb info`, the plotting roles and the element tables
// of docs/modelling.md are all read from here (docs/design.md, section 2.3).
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "lagmb/collision/shape.hpp"
#include "lagmb/time_function.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

class Model;

/// The kind of value a parameter takes.
enum class ParamType {
  kText,          // a name
  kReal,          // a finite number
  kVec2,          // (x, y): a point, a direction, a velocity
  kBool,          // a flag
  kBody,          // a body of the model, or the ground
  kJoint,         // a joint of the model, by name
  kChoice,        // one of a few words (Param::choices)
  kMotion,        // f(t) with f' and f'' (a driver's prescribed motion)
  kFunction,      // f(t), values only (an actuator force or torque)
  kFunctionPair,  // (fx(t), fy(t))
  kVec3,          // (x, y, z): a point, a direction, a velocity in space
  kOrientation,   // a unit quaternion (w, x, y, z) or a 3 x 3 rotation matrix
  kInertia,       // principal moments (Ixx, Iyy, Izz) or a 3 x 3 inertia tensor
  kFunctionTriple,  // (fx(t), fy(t), fz(t))
  kShape,         // a collision shape on a body (collision/shape.hpp)
};

/// The body index of a kBody value (kGround for the ground).
struct BodyIndex {
  int index;
};

/// A parameter's value; std::monostate: absent (Python's None).
using Value = std::variant<std::monostate, double, Vec2, bool, std::string, BodyIndex, TimeFunctionPtr,
                           std::pair<TimeFunctionPtr, TimeFunctionPtr>, Vec3, Vec4, Mat3,
                           std::array<TimeFunctionPtr, 3>, CollisionShape>;

/// One type of parameter, as the table of types (param_types()) lists it:
/// its name where Python, scenes and docs name it, what a user gives, and
/// which values hold it. A new type is a line of that table (registry.cpp),
/// its conversion in the binding (cpp/python/model.cpp, to_value), its check
/// in Python (lagmb/model.py) and its value kind in scenes; the tests of the
/// registry fail until each exists.
struct ParamTypeInfo {
  ParamType type;
  const char* name;                 // "real", "vec2", "function_pair", ...
  const char* takes;                // what a user gives, as docstrings and the element reference say it
  bool (*holds)(const Value& value);  // whether a value is of this type
};
/// Every parameter type, in the order of ParamType.
const std::vector<ParamTypeInfo>& param_types();
const ParamTypeInfo& param_type(ParamType type);

/// One parameter of an element kind.
struct Param {
  std::string name;
  ParamType type = ParamType::kReal;
  bool required = true;
  Value fallback;            // the default when not required (monostate: None)
  std::string unit;          // SI unit ("" for none: ratios, directions, names)
  std::string doc;           // one line
  std::vector<std::string> choices;  // kChoice
  /// A point: the body parameters it attaches to (for the outline of each
  /// body), given as a global point of the initial configuration, or in the
  /// axes of its one body if `local`.
  std::vector<std::string> on;
  bool local = false;
  bool keyword_only = false;  // Python: after `*` (alternatives to an earlier argument)
  std::string scene_key;      // its key in a scene file, if not `name`
};

/// What an element stands for: where its handle may go, how results and
/// drawings count it, which elements have an effort (kDriver; never found
/// by a kind's name: Model::given_kind).
enum class Role { kBody, kJoint, kDriver, kForce, kFriction, kStop, kContact };
const char* role_name(Role role);

/// The scalar coordinate a joint kind has, as its kind's coordinate() gives
/// it (joint_coordinate.hpp); kNone for the kinds without one.
enum class CoordinateKind { kNone, kAngle, kSlide, kAngleAndSlide };
/// "angle", "slide", "angle and slide", "" (kNone): what Python, scenes and
/// the FMU read.
const char* coordinate_name(CoordinateKind coordinate);

class Args;

/// One element kind. Each kind declares its entry with every field named
/// (build::kind in cpp/src/elements/build.hpp).
struct KindInfo {
  std::string name;    // "revolute"
  std::string method;  // the Python Model method that adds one: "add_revolute"
  std::string table;   // its scene table: "joints"
  std::string type;    // its `type` there ("" if the table has this one kind)
  Role role = Role::kJoint;
  std::string doc;     // what it is and does (a paragraph; the parameters document themselves)
  std::vector<Param> params;  // after the name, in the order of the Python signature
  /// Adds an element of this kind: checks the values and calls the Model.
  std::function<void(Model&, const std::string& name, const Args&)> build;
  /// The space of the models it goes in: 2 (planar) or 3 (spatial). A
  /// method name (add_revolute) may have a kind in each.
  int dimension = 2;
  /// A joint's scalar coordinate, as its kind's coordinate() gives it
  /// (joint_coordinate.hpp). Messages name the kinds that have one; Python
  /// (Result.joint, JointSpace, drawings: coordinate_name) and the FMU's
  /// units read it here, never a kind's name.
  CoordinateKind coordinate = CoordinateKind::kNone;
  /// What Result.effort reads of an element of this kind, said next to its
  /// equations (one line, with its unit); "" for a kind without one (a body,
  /// a joint: its reaction; a contact: Result.contact). The kind's group
  /// gives the numbers (outputs.hpp, efforts).
  std::string effort = {};
  /// The names of that reading's columns where it has several ("x", "y",
  /// ...); none: one number per output.
  std::vector<std::string> effort_components = {};

  const Param* param(const std::string& key) const;
};

/// The values given for one element, with the kind's defaults for the rest.
class Args {
 public:
  explicit Args(const KindInfo& kind) : kind_(&kind) {}
  Args(KindInfo&&) = delete;  // the kind must outlive its values: one of element_kinds()
  /// Sets a parameter; ModelError if the kind has no such parameter or the
  /// value's type does not fit it.
  void set(const std::string& key, Value value);

  const Value& get(const std::string& key) const;  // given (not None), else the default
  bool given(const std::string& key) const;        // not None
  double real(const std::string& key) const;
  std::optional<double> optional_real(const std::string& key) const;
  Vec2 vec2(const std::string& key) const;
  std::optional<Vec2> optional_vec2(const std::string& key) const;
  Vec3 vec3(const std::string& key) const;
  /// Unit Euler parameters (w, x, y, z) from a quaternion (of length 1 to
  /// 1e-3, normalized) or a rotation matrix (orthonormal, det +1, to 1e-6).
  Vec4 orientation(const std::string& key) const;
  /// A symmetric positive semi-definite inertia tensor from principal
  /// moments or a 3 x 3 tensor; with `triangle`, one that satisfies the
  /// triangle inequalities (as the inertia of every rigid body does).
  Mat3 inertia(const std::string& key, bool triangle = true) const;
  bool flag(const std::string& key) const;
  const std::string& text(const std::string& key) const;
  int body(const std::string& key) const;
  TimeFunctionPtr function(const std::string& key) const;  // null if None
  std::pair<TimeFunctionPtr, TimeFunctionPtr> function_pair(const std::string& key) const;
  std::array<TimeFunctionPtr, 3> function_triple(const std::string& key) const;
  const CollisionShape& shape(const std::string& key) const;

  const KindInfo& kind() const { return *kind_; }
  const std::map<std::string, Value>& values() const { return values_; }

 private:
  const KindInfo* kind_;
  std::map<std::string, Value> values_;
};

/// Every element kind, in the order scenes, messages and docs list them.
const std::vector<KindInfo>& element_kinds();
/// The kind called `name` ("revolute"); ModelError listing the kinds if none.
const KindInfo& find_kind(const std::string& name);

/// Adds an element of kind args.kind() called `name`: refuses a missing
/// required parameter, builds the element, and records where its points
/// attach to its bodies (Model::outline).
void add_element(Model& model, const std::string& name, const Args& args);

// --- declaring kinds (in cpp/src/elements/*.cpp) ---------------------------
namespace param {
Param body(const std::string& name, const std::string& doc);
Param joint(const std::string& doc);  // called "joint"
Param joint(const std::string& name, const std::string& doc);
Param real(const std::string& name, const std::string& unit, const std::string& doc);
Param real(const std::string& name, double fallback, const std::string& unit, const std::string& doc);
Param optional_real(const std::string& name, const std::string& unit, const std::string& doc);
/// A global point of the initial configuration on the bodies `on`.
Param point(const std::string& name, std::vector<std::string> on, const std::string& doc);
Param optional_point(const std::string& name, std::vector<std::string> on, const std::string& doc);
/// A point in the axes of body `on` (optional, keyword-only).
Param local_point(const std::string& name, const std::string& on, const std::string& doc);
Param direction(const std::string& name, const std::string& doc);
Param vec2(const std::string& name, Vec2 fallback, const std::string& unit, const std::string& doc);
Param flag(const std::string& name, bool fallback, const std::string& doc);
Param choice(const std::string& name, std::vector<std::string> choices, const std::string& doc);
/// A driver's motion; `scene_key`: its key in a scene if not `name`.
Param motion(const std::string& name, const std::string& unit, const std::string& doc,
             const std::string& scene_key = "");
Param function(const std::string& name, const std::string& unit, const std::string& doc,
               bool required = false);
Param function_pair(const std::string& name, const std::string& unit, const std::string& doc);
// spatial kinds
/// A global point of the initial configuration on the bodies `on` (x, y, z).
Param point3(const std::string& name, std::vector<std::string> on, const std::string& doc);
Param optional_point3(const std::string& name, std::vector<std::string> on, const std::string& doc);
/// A point in the axes of body `on` (optional, keyword-only).
Param local_point3(const std::string& name, const std::string& on, const std::string& doc);
Param direction3(const std::string& name, const std::string& doc);
Param optional_direction3(const std::string& name, const std::string& doc);
Param vec3(const std::string& name, Vec3 fallback, const std::string& unit, const std::string& doc);
Param orientation(const std::string& name, const std::string& doc);
Param inertia(const std::string& name, const std::string& doc);
Param function_triple(const std::string& name, const std::string& unit, const std::string& doc);
/// A collision shape (collision/shape.hpp) on a body of the model or the ground.
Param shape(const std::string& name, const std::string& doc);
}  // namespace param

}  // namespace lagmb
