// The registry of element kinds (registry.hpp): the list, the values given
// for one element, and the one way every element is added.
#include "lagmb/model/registry.hpp"

#include <limits>

#include "lagmb/model/model.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>

#include "lagmb/spatial.hpp"

namespace lagmb {

const char* role_name(Role role) {
  switch (role) {
    case Role::kBody: return "body";
    case Role::kJoint: return "joint";
    case Role::kDriver: return "driver";
    case Role::kForce: return "force";
    case Role::kFriction: return "friction";
    case Role::kStop: return "stop";
    case Role::kContact: return "contact";
  }
  return "?";
}

const char* coordinate_name(CoordinateKind coordinate) {
  switch (coordinate) {
    case CoordinateKind::kNone: return "";
    case CoordinateKind::kAngle: return "angle";
    case CoordinateKind::kSlide: return "slide";
    case CoordinateKind::kAngleAndSlide: return "angle and slide";
  }
  return "";
}

const Param* KindInfo::param(const std::string& key) const {
  for (const Param& p : params)
    if (p.name == key) return &p;
  return nullptr;
}

// Each kind's declaration, in cpp/src/elements/<file>.cpp.
KindInfo body_kind();
KindInfo particle_kind();
KindInfo revolute_kind();
KindInfo translational_kind();
KindInfo weld_kind();
KindInfo distance_kind();
KindInfo pin_in_slot_kind();
KindInfo gear_kind();
KindInfo rack_pinion_kind();
KindInfo joint_driver_kind();
KindInfo body_driver_kind();
KindInfo spring_damper_kind();
KindInfo rotational_spring_damper_kind();
KindInfo force_kind();
KindInfo torque_kind();
KindInfo joint_friction_kind();
KindInfo contact_kind();
KindInfo stop_kind();
KindInfo spatial_body_kind();
KindInfo spherical_kind();
KindInfo spatial_revolute_kind();
KindInfo cylindrical_kind();
KindInfo spatial_translational_kind();
KindInfo universal_kind();
KindInfo planar_joint_kind();
KindInfo spatial_weld_kind();
KindInfo spatial_distance_kind();
KindInfo spatial_joint_driver_kind();
KindInfo spatial_body_driver_kind();
KindInfo spatial_spring_damper_kind();
KindInfo spatial_rotational_spring_damper_kind();
KindInfo spatial_joint_servo_kind();
KindInfo bushing_kind();
KindInfo spatial_force_kind();
KindInfo spatial_torque_kind();
KindInfo spatial_stop_kind();
KindInfo joint_coupling_kind();
KindInfo spatial_joint_friction_kind();
KindInfo spatial_contact_kind();

const std::vector<KindInfo>& element_kinds() {
  // the order of scene tables and docs; a new kind adds its line here and above
  static const std::vector<KindInfo> kinds = {
      body_kind(),          particle_kind(),
      revolute_kind(),      translational_kind(),
      weld_kind(),          distance_kind(),
      pin_in_slot_kind(),   gear_kind(),
      rack_pinion_kind(),   joint_driver_kind(),
      body_driver_kind(),   spring_damper_kind(),
      rotational_spring_damper_kind(), force_kind(),
      torque_kind(),        joint_friction_kind(),
      contact_kind(),       stop_kind(),
      // spatial (dimension 3)
      spatial_body_kind(),  spherical_kind(),
      spatial_revolute_kind(), cylindrical_kind(),
      spatial_translational_kind(), universal_kind(),
      planar_joint_kind(),  spatial_weld_kind(),
      spatial_distance_kind(), spatial_joint_driver_kind(),
      spatial_body_driver_kind(), spatial_spring_damper_kind(),
      spatial_rotational_spring_damper_kind(), spatial_joint_servo_kind(),
      bushing_kind(),
      spatial_force_kind(), spatial_torque_kind(),
      spatial_stop_kind(),  joint_coupling_kind(),
      spatial_joint_friction_kind(), spatial_contact_kind(),
  };
  return kinds;
}

namespace {
template <class... T>
bool holds_one_of(const Value& v) {
  return (std::holds_alternative<T>(v) || ...);
}
}  // namespace

const std::vector<ParamTypeInfo>& param_types() {
  using P = ParamType;
  static const std::vector<ParamTypeInfo> types = {
      {P::kText, "text", "text", holds_one_of<std::string>},
      {P::kReal, "real", "number", holds_one_of<double>},
      {P::kVec2, "vec2", "(x, y)", holds_one_of<Vec2>},
      {P::kBool, "bool", "bool", holds_one_of<bool>},
      // a body by index, or by name from C++
      {P::kBody, "body", "body handle or name", holds_one_of<BodyIndex, std::string>},
      {P::kJoint, "joint", "joint handle or name", holds_one_of<std::string>},
      {P::kChoice, "choice", "one of", holds_one_of<std::string>},
      {P::kMotion, "motion", "number, time function or callable t -> (y, dy, ddy)",
       holds_one_of<TimeFunctionPtr>},
      {P::kFunction, "function", "number, time function or callable t -> y", holds_one_of<TimeFunctionPtr>},
      {P::kFunctionPair, "function_pair", "(fx, fy) of numbers or time functions, or a callable t -> (fx, fy)",
       holds_one_of<std::pair<TimeFunctionPtr, TimeFunctionPtr>>},
      {P::kVec3, "vec3", "(x, y, z)", holds_one_of<Vec3>},
      {P::kOrientation, "orientation", "(w, x, y, z) or 3 x 3 rotation matrix", holds_one_of<Vec4, Mat3>},
      {P::kInertia, "inertia", "(Ixx, Iyy, Izz) or 3 x 3 tensor", holds_one_of<Vec3, Mat3>},
      {P::kFunctionTriple, "function_triple", "(x, y, z) of numbers or time functions, or a callable t -> (x, y, z)",
       holds_one_of<std::array<TimeFunctionPtr, 3>>},
      {P::kShape, "shape", "a collision shape (Model.add_shape)", holds_one_of<CollisionShape>},
  };
  return types;
}

const ParamTypeInfo& param_type(ParamType type) {
  for (const ParamTypeInfo& t : param_types())
    if (t.type == type) return t;
  throw std::logic_error("lagmb: a parameter type without an entry in param_types()");
}

const KindInfo& find_kind(const std::string& name) {
  std::string known;
  for (const KindInfo& k : element_kinds()) {
    if (k.name == name) return k;
    known += (known.empty() ? "" : ", ") + k.name;
  }
  throw ModelError("no element kind '" + name + "'; the kinds are " + known);
}

namespace {

/// Whether `value` is of the C++ type a parameter of `type` holds.
bool fits(ParamType type, const Value& value) { return param_type(type).holds(value); }

template <class T>
const T& as(const Args& a, const std::string& key) {
  const Value& v = a.get(key);
  if (const T* x = std::get_if<T>(&v)) return *x;
  throw ModelError(a.kind().name + ": '" + key + "' is required");
}

}  // namespace

void Args::set(const std::string& key, Value value) {
  const Param* p = kind_->param(key);
  if (!p) throw ModelError(kind_->name + " has no parameter '" + key + "'");
  if (!std::holds_alternative<std::monostate>(value) && !fits(p->type, value))
    throw ModelError(kind_->name + ": '" + key + "' is of the wrong type");
  if (p->type == ParamType::kChoice && std::holds_alternative<std::string>(value)) {
    const std::string& word = std::get<std::string>(value);
    bool known = false;
    std::string list;
    for (const std::string& c : p->choices) {
      known = known || c == word;
      list += (list.empty() ? "'" : ", '") + c + "'";
    }
    if (!known) throw ModelError(kind_->name + ": " + key + " must be one of " + list + ", got '" + word + "'");
  }
  values_[key] = std::move(value);
}

const Value& Args::get(const std::string& key) const {
  auto it = values_.find(key);
  if (it != values_.end() && !std::holds_alternative<std::monostate>(it->second)) return it->second;
  const Param* p = kind_->param(key);
  if (!p) throw ModelError(kind_->name + " has no parameter '" + key + "'");  // a builder's typo
  return p->fallback;
}

bool Args::given(const std::string& key) const { return !std::holds_alternative<std::monostate>(get(key)); }
double Args::real(const std::string& key) const { return as<double>(*this, key); }
Vec2 Args::vec2(const std::string& key) const { return as<Vec2>(*this, key); }
bool Args::flag(const std::string& key) const { return as<bool>(*this, key); }
const std::string& Args::text(const std::string& key) const { return as<std::string>(*this, key); }
int Args::body(const std::string& key) const { return as<BodyIndex>(*this, key).index; }

Vec3 Args::vec3(const std::string& key) const { return as<Vec3>(*this, key); }

Vec4 Args::orientation(const std::string& key) const {
  const Value& v = get(key);
  const std::string what = kind_->name + ": " + key;
  if (const Vec4* p = std::get_if<Vec4>(&v)) {
    // written by hand to a few digits it is a little off: normalized within 1e-3
    if (!(std::abs(p->norm() - 1.0) <= 1e-3))
      throw ModelError(what + " must be a unit quaternion (w, x, y, z), got length " + to_text(p->norm()));
    return p->normalized();
  }
  const Mat3& R = as<Mat3>(*this, key);
  const double off = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (!(off <= 1e-6) || !(R.determinant() > 0.0))  // (a matrix is not normalized: it must be one)
    throw ModelError(what + " must be a rotation matrix (orthonormal columns, determinant +1); R^T R - I is off by " +
                     to_text(off) + ", det R = " + to_text(R.determinant()));
  return euler::from_matrix(R);
}

Mat3 Args::inertia(const std::string& key, bool triangle) const {
  const Value& v = get(key);
  const std::string what = kind_->name + ": " + key;
  Mat3 J;
  if (const Vec3* d = std::get_if<Vec3>(&v))
    J = d->asDiagonal();
  else
    J = as<Mat3>(*this, key);
  const double scale = J.cwiseAbs().maxCoeff();
  if (!((J - J.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * scale))
    throw ModelError(what + " must be a symmetric tensor");
  J = 0.5 * (J + J.transpose());
  // the mass matrix holds 4 G^T J G (elements/spatial_body.hpp): keep it finite
  if (!(8.0 * scale <= std::numeric_limits<double>::max()))
    throw ModelError(what + " is too large: its largest entry " + to_text(scale) + " kg m^2 overflows the mass matrix");
  // solved scaled: the solver squares entries
  Eigen::SelfAdjointEigenSolver<Mat3> eig(scale > 0.0 ? Mat3(J / scale) : J);
  const Vec3 m = eig.eigenvalues() * (scale > 0.0 ? scale : 1.0);  // ascending
  // (a zero moment comes out of the eigensolver as -1e-17 of the largest: round-off, not negative)
  if (!(m[0] >= -1e-12 * std::abs(m[2])))
    throw ModelError(what + " must be positive semi-definite; its principal moments are " + to_text(m));
  if (triangle && !(m[2] <= (m[0] + m[1]) * (1.0 + 1e-9)))
    throw ModelError(what + ": principal moments " + to_text(m) +
                     " break the triangle inequality (no rigid body has them: each must be at most the sum of the "
                     "other two; rigid_inertia=False accepts them)");
  return J;
}

std::optional<double> Args::optional_real(const std::string& key) const {
  if (!given(key)) return std::nullopt;
  return real(key);
}

std::optional<Vec2> Args::optional_vec2(const std::string& key) const {
  if (!given(key)) return std::nullopt;
  return vec2(key);
}

TimeFunctionPtr Args::function(const std::string& key) const {
  if (!given(key)) return nullptr;
  return as<TimeFunctionPtr>(*this, key);
}

std::pair<TimeFunctionPtr, TimeFunctionPtr> Args::function_pair(const std::string& key) const {
  return as<std::pair<TimeFunctionPtr, TimeFunctionPtr>>(*this, key);
}

std::array<TimeFunctionPtr, 3> Args::function_triple(const std::string& key) const {
  return as<std::array<TimeFunctionPtr, 3>>(*this, key);
}

const CollisionShape& Args::shape(const std::string& key) const { return as<CollisionShape>(*this, key); }

namespace {

bool finite(const Value& v) {
  if (const double* x = std::get_if<double>(&v)) return std::isfinite(*x);
  if (const Vec2* p = std::get_if<Vec2>(&v)) return p->allFinite();
  if (const Vec3* p = std::get_if<Vec3>(&v)) return p->allFinite();
  if (const Vec4* p = std::get_if<Vec4>(&v)) return p->allFinite();
  if (const Mat3* p = std::get_if<Mat3>(&v)) return p->allFinite();
  return true;
}

std::string shown(const Value& v) {
  if (const double* x = std::get_if<double>(&v)) return to_text(*x);
  if (const Vec2* p = std::get_if<Vec2>(&v)) return to_text(*p);
  if (const Vec3* p = std::get_if<Vec3>(&v)) return to_text(*p);
  std::ostringstream s;
  if (const Vec4* p = std::get_if<Vec4>(&v)) s << p->transpose();
  if (const Mat3* p = std::get_if<Mat3>(&v)) s << *p;
  return "(" + s.str() + ")";
}

/// The values with each body given by name replaced by its index; ModelError
/// for a body index or name the model does not have.
Args resolved(const Model& model, const std::string& label, const Args& args) {
  Args out = args;
  for (const Param& p : args.kind().params) {
    if (p.type != ParamType::kBody || !args.given(p.name)) continue;
    const Value& v = args.get(p.name);
    int index = kGround;
    if (const auto* name = std::get_if<std::string>(&v)) {
      if (*name != "ground") {
        if (!model.has(*name)) throw ModelError(label + ": " + p.name + " '" + *name + "' is not a body of this model");
        const ElementRef& r = model.find(*name);
        if (r.type != ElementRef::kBody)
          throw ModelError(label + ": " + p.name + " '" + *name + "' is " + model.describe(*name) + ", not a body");
        index = r.group;
      }
    } else {
      index = std::get<BodyIndex>(v).index;
      if (index < kGround || index >= int(model.bodies().size()))
        throw ModelError(label + ": " + p.name + ": body index " + std::to_string(index) + " does not exist");
    }
    out.set(p.name, BodyIndex{index});
  }
  return out;
}

}  // namespace

void add_element(Model& model, const std::string& name, const Args& given) {
  const KindInfo& kind = given.kind();
  const std::string label = kind.name + " '" + name + "'";
  if (kind.dimension != model.dimension())
    throw ModelError(label + ": a " + (kind.dimension == 2 ? "planar" : "spatial") + " kind does not go in a " +
                     (model.dimension() == 2 ? "planar" : "spatial") + " model (dimension " +
                     std::to_string(model.dimension()) + ")");
  for (const Param& p : kind.params) {
    if (p.required && !given.given(p.name)) throw ModelError(label + ": '" + p.name + "' is required");
    const Value& v = given.get(p.name);
    if (!finite(v)) throw ModelError(label + ": " + p.name + " is not finite: " + shown(v));
  }
  const Args args = resolved(model, label, given);
  model.record_given(name, given);
  // the functions of time: their breakpoints are the run's; its inputs are
  // named after the element (with the parameter where it has several) and
  // added first, so that the builder finds their slots (build::drive)
  std::vector<InputInfo> inputs;
  for (const Param& p : kind.params) {
    if (!args.given(p.name)) continue;
    std::vector<std::pair<TimeFunctionPtr, std::string>> functions;  // with the parameter's name
    if (p.type == ParamType::kMotion || p.type == ParamType::kFunction) functions.push_back({args.function(p.name), p.name});
    if (p.type == ParamType::kFunctionPair) {
      auto [f, g] = args.function_pair(p.name);
      functions = {{f, p.name + ".x"}, {g, p.name + ".y"}};
    }
    if (p.type == ParamType::kFunctionTriple) {
      const auto f = args.function_triple(p.name);
      functions = {{f[0], p.name + ".x"}, {f[1], p.name + ".y"}, {f[2], p.name + ".z"}};
    }
    for (const auto& [f, parameter] : functions) {
      model.use_time_function(f);
      if (const auto* in = dynamic_cast<const Input*>(f.get()))
        inputs.push_back({in->name(), name, parameter, p.unit, in->initial(), in});
    }
  }
  for (InputInfo& in : inputs) {
    if (in.name.empty()) in.name = inputs.size() == 1 ? name : name + "." + in.parameter;
    model.add_input(std::move(in));
  }
  kind.build(model, name, args);
  for (const Param& p : kind.params) {
    if (!args.given(p.name)) continue;
    // where the element's points sit on its bodies: what a drawing of each body joins
    for (const std::string& on : p.on) {
      const int body = args.body(on);
      if (p.type == ParamType::kVec3) {
        model.attach(name, body, p.local ? args.vec3(p.name) : model.local_point(body, args.vec3(p.name)));
      } else {
        const Vec2 s = p.local ? args.vec2(p.name) : model.local_point(body, args.vec2(p.name));
        model.attach(name, body, Vec3(s.x(), s.y(), 0.0));
      }
    }
  }
}

// --- declaring kinds -------------------------------------------------------
namespace param {

namespace {
Param make(const std::string& name, ParamType type, bool required, Value fallback, const std::string& unit,
           const std::string& doc) {
  Param p;
  p.name = name;
  p.type = type;
  p.required = required;
  p.fallback = std::move(fallback);
  p.unit = unit;
  p.doc = doc;
  return p;
}
}  // namespace

Param body(const std::string& name, const std::string& doc) {
  return make(name, ParamType::kBody, true, {}, "", doc);
}
Param joint(const std::string& doc) { return joint("joint", doc); }
Param joint(const std::string& name, const std::string& doc) {
  return make(name, ParamType::kJoint, true, {}, "", doc);
}
Param real(const std::string& name, const std::string& unit, const std::string& doc) {
  return make(name, ParamType::kReal, true, {}, unit, doc);
}
Param real(const std::string& name, double fallback, const std::string& unit, const std::string& doc) {
  return make(name, ParamType::kReal, false, fallback, unit, doc);
}
Param optional_real(const std::string& name, const std::string& unit, const std::string& doc) {
  return make(name, ParamType::kReal, false, {}, unit, doc);
}
Param point(const std::string& name, std::vector<std::string> on, const std::string& doc) {
  Param p = make(name, ParamType::kVec2, true, {}, "m", doc + " (global, initial configuration)");
  p.on = std::move(on);
  return p;
}
Param optional_point(const std::string& name, std::vector<std::string> on, const std::string& doc) {
  Param p = point(name, std::move(on), doc);
  p.required = false;
  return p;
}
Param local_point(const std::string& name, const std::string& on, const std::string& doc) {
  Param p = make(name, ParamType::kVec2, false, {}, "m", doc + " (in " + on + "'s axes)");
  p.on = {on};
  p.local = true;
  p.keyword_only = true;
  return p;
}
Param direction(const std::string& name, const std::string& doc) {
  return make(name, ParamType::kVec2, true, {}, "", doc + " (global, initial configuration; any length)");
}
Param vec2(const std::string& name, Vec2 fallback, const std::string& unit, const std::string& doc) {
  return make(name, ParamType::kVec2, false, fallback, unit, doc);
}
Param flag(const std::string& name, bool fallback, const std::string& doc) {
  return make(name, ParamType::kBool, false, fallback, "", doc);
}
Param choice(const std::string& name, std::vector<std::string> choices, const std::string& doc) {
  Param p = make(name, ParamType::kChoice, true, {}, "", doc);
  p.choices = std::move(choices);
  return p;
}
Param motion(const std::string& name, const std::string& unit, const std::string& doc,
             const std::string& scene_key) {
  Param p = make(name, ParamType::kMotion, true, {}, unit, doc);
  p.scene_key = scene_key;
  return p;
}
Param function(const std::string& name, const std::string& unit, const std::string& doc, bool required) {
  return make(name, ParamType::kFunction, required, {}, unit, doc);
}
Param function_pair(const std::string& name, const std::string& unit, const std::string& doc) {
  return make(name, ParamType::kFunctionPair, true, {}, unit, doc);
}
Param point3(const std::string& name, std::vector<std::string> on, const std::string& doc) {
  Param p = make(name, ParamType::kVec3, true, {}, "m", doc + " (global, initial configuration)");
  p.on = std::move(on);
  return p;
}
Param optional_point3(const std::string& name, std::vector<std::string> on, const std::string& doc) {
  Param p = point3(name, std::move(on), doc);
  p.required = false;
  return p;
}
Param local_point3(const std::string& name, const std::string& on, const std::string& doc) {
  Param p = make(name, ParamType::kVec3, false, {}, "m", doc + " (in " + on + "'s axes)");
  p.on = {on};
  p.local = true;
  p.keyword_only = true;
  return p;
}
Param direction3(const std::string& name, const std::string& doc) {
  return make(name, ParamType::kVec3, true, {}, "", doc + " (global, initial configuration; any length)");
}
Param optional_direction3(const std::string& name, const std::string& doc) {
  return make(name, ParamType::kVec3, false, {}, "", doc + " (global, initial configuration; any length)");
}
Param vec3(const std::string& name, Vec3 fallback, const std::string& unit, const std::string& doc) {
  return make(name, ParamType::kVec3, false, fallback, unit, doc);
}
Param orientation(const std::string& name, const std::string& doc) {
  return make(name, ParamType::kOrientation, false, Vec4(1.0, 0.0, 0.0, 0.0), "", doc);
}
Param function_triple(const std::string& name, const std::string& unit, const std::string& doc) {
  return make(name, ParamType::kFunctionTriple, true, {}, unit, doc);
}
Param shape(const std::string& name, const std::string& doc) {
  return make(name, ParamType::kShape, true, {}, "", doc);
}
Param inertia(const std::string& name, const std::string& doc) {
  return make(name, ParamType::kInertia, true, {}, "kg m^2", doc);
}

}  // namespace param
}  // namespace lagmb
