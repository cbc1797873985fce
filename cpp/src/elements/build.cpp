// What the builders of element kinds share (build.hpp).
#include "elements/build.hpp"

#include <algorithm>
#include <cmath>


namespace lagmb::build {

std::string label(const Args& args, const std::string& name) {
  std::string kind = args.kind().name;
  std::replace(kind.begin(), kind.end(), '_', ' ');
  return kind + " '" + name + "'";
}

Drive drive(const Model& m, TimeFunctionPtr f) {
  Drive d;
  d.input = m.input_slot(f.get());
  d.f = std::move(f);
  return d;
}

std::array<Drive, 3> drive_triple(const Model& m, const std::array<TimeFunctionPtr, 3>& f) {
  return {drive(m, f[0]), drive(m, f[1]), drive(m, f[2])};
}

void require_positive(double x, const std::string& element, const char* what) {
  if (!(std::isfinite(x) && x > 0))
    throw ModelError(element + ": " + what + " must be positive and finite, got " + to_text(x));
}

void require_squarable(double x, const std::string& element, const char* what) {
  if (!std::isfinite(4.0 * x * x))
    throw ModelError(element + ": " + what + " " + to_text(x) +
                     " is too large: the equations hold its square, which overflows a double");
}

void require_nonnegative(double x, const std::string& element, const char* what) {
  if (!(std::isfinite(x) && x >= 0))
    throw ModelError(element + ": " + what + " must be finite and >= 0, got " + to_text(x));
}

void require_within_largest(double x, const std::string& element, const char* what, const char* unit) {
  if (!(std::abs(x) <= kLargestGiven))
    throw ModelError(element + ": " + what + " = " + to_text(x) + " is beyond " + to_text(kLargestGiven) + " " + unit +
                     ", the largest lagmb takes for a gain or an input: " + largest_given_reason());
}

void require_rigid(const Model& m, int body, const std::string& element, const char* why) {
  if (body != kGround && m.body(body).particle)
    throw ModelError(element + ": particle '" + m.body(body).name + "' " + why);
}

void require_on_particle(const Model& m, int body, Vec2 point, const std::string& element) {
  if (body != kGround && m.body(body).particle && (point - m.body(body).position).norm() > 0)
    throw ModelError(element + ": the point on particle '" + m.body(body).name + "' must be the particle itself");
}

Vec2 local_direction(const Model& m, int body, Vec2 direction, const std::string& element) {
  const double n = direction.norm();
  if (!(n > 0.0)) throw ModelError(element + ": the direction must be a non-zero vector, got " + to_text(direction));
  return rotation(m.initial_angle(body)).transpose() * (direction / n);
}

ProjectedOffset across_line(const Model& m, int body_i, int body_j, Vec2 at, Vec2 axis,
                            const std::string& element) {
  const Vec2 u = local_direction(m, body_i, axis, element);
  ProjectedOffset f;
  f.w = Vec2(-u.y(), u.x());
  f.s_i = m.local_point(body_i, at);
  f.s_j = m.local_point(body_j, at);
  return f;
}

JointOf joint_coordinate(const Model& m, const std::string& joint, const std::string& element) {
  if (!m.has(joint)) throw ModelError(element + ": '" + joint + "' is not a joint of this model");
  const ElementRef& ref = m.find(joint);
  std::optional<JointCoordinate> c;
  if (ref.type == ElementRef::kConstraint) c = m.constraint_groups()[ref.group]->coordinate(ref.index);
  if (!c) {
    // the kinds of this space that have a coordinate, by the names users give them
    std::vector<std::string> kinds;
    for (const KindInfo& k : element_kinds())
      if (k.dimension == m.dimension() && k.coordinate != CoordinateKind::kNone)
        kinds.push_back(k.type.empty() ? k.name : k.type);
    std::string listed;
    for (size_t i = 0; i < kinds.size(); ++i)
      listed += (i == 0 ? "" : i + 1 == kinds.size() ? " or " : ", ") + kinds[i];
    throw ModelError(element + ": '" + joint + "' is " + m.describe(joint) + ", not a " + listed + " joint");
  }
  JointOf out;
  static_cast<JointCoordinate&>(out) = *c;
  out.joint = ref;
  return out;
}

spatial::JointReading joint_reading(const JointCoordinate& c, double center) {
  spatial::JointReading r;
  r.slide = c.slides;
  r.f_i = c.f_i, r.g_i = c.g_i, r.f_j = c.f_j;
  r.s_i = c.s_i, r.s_j = c.s_j, r.a_i = c.a_i;
  r.center = center;
  return r;
}

double initial_joint_value(const Model& m, const JointCoordinate& c, double around) {
  spatial::Loc at;
  for (int side = 0; side < 2; ++side) {
    const int b = side ? c.body_j : c.body_i;
    at.segment<3>(7 * side) = b == kGround ? Vec3::Zero() : Vec3(m.bodies()[b].r0);
    at.segment<4>(7 * side + 3) = b == kGround ? Vec4(1.0, 0.0, 0.0, 0.0) : Vec4(m.bodies()[b].p0);
  }
  return joint_reading(c, around)(at, {}).value;
}

void count_turns(Model& m, const std::string& joint, double angle) {
  const JointOf c = joint_coordinate(m, joint, "'" + joint + "'");
  if (!c.turns) return;
  TurnCounter counter;
  counter.joint = joint;
  counter.body_i = c.body_i, counter.body_j = c.body_j;
  counter.reading = joint_reading(c, initial_joint_value(m, c, angle));
  counter.reading.slide = false;  // (a cylindrical joint's angle)
  m.add_turn_counter(std::move(counter));
}

spatial::JointReading continuous_reading(Model& m, const std::string& joint, const JointCoordinate& c) {
  if (c.slides && !c.turns) return joint_reading(c, 0.0);
  TurnCounter* counter = m.turn_counter(joint);
  if (!counter) throw ModelError("'" + joint + "' turns but has no counter of its turns (a joint kind that does not count them)");
  counter->read = true;
  return counter->reading;
}

/// The stiffest contact a material makes, N/m^1.5: Hertz's k = (4/3) E*
/// sqrt(R) of a ball on a flat (Johnson, Contact Mechanics, 1985, 4.2), for
/// diamond on diamond (E* = E / (2 (1 - nu^2)) = 5.3e11 Pa) reaches 1e13
/// only at R = 200 m; steel on steel (E* = 1.15e11 Pa) at R = 1 m is 1.5e11.
constexpr double kMaxContactStiffness = 1e13;

ContactLaw contact_law(const Args& a, const std::string& label) {
  ContactLaw law;
  law.stiffness = a.real("stiffness");
  law.slip_velocity = a.real("slip_velocity");
  require_positive(law.stiffness, label, "stiffness");
  if (!(law.stiffness <= kMaxContactStiffness))
    throw ModelError(label + ": stiffness " + to_text(law.stiffness) + " N/m^1.5 is stiffer than any material makes a "
                     "contact (Hertz's k = (4/3) E* sqrt(R): steel on steel 1.5e11 at R = 1 m, diamond on diamond "
                     "1e13 at R = 200 m); give at most 1e13");
  require_positive(law.slip_velocity, label, "slip_velocity");
  law.restitution = a.real("restitution");
  // (no finite damping rebounds at 0: its damping c tends to 1/e)
  if (!(law.restitution > 0.0 && law.restitution <= 1.0))
    throw ModelError(label + ": restitution must be in (0, 1], got " + to_text(law.restitution) +
                     " (no finite damping rebounds at 0; restitution 0.01 rebounds at 1 % of the impact speed: "
                     "practically no bounce)");
  law.damping = ContactLaw::damping_for(law.restitution);
  if (!std::isfinite(law.damping))
    throw ModelError(label + ": restitution " + to_text(law.restitution) +
                     " is too small: its damping, about 1 / e, is not a finite number (restitution 0.01 "
                     "rebounds at 1 % of the impact speed: practically no bounce)");
  law.friction = a.real("friction");
  require_nonnegative(law.friction, label, "friction");
  return law;
}

std::vector<Param> contact_law_params() {
  return {
      param::real("stiffness", "N/m^1.5", "contact stiffness k, at most 1e13 (Hertz: (4/3) E* sqrt(R))"),
      param::real("restitution", "", "coefficient of restitution e in (0, 1]: the rebound speed over the impact speed"),
      param::real("friction", 0.0, "", "Coulomb coefficient mu"),
      param::real("slip_velocity", 1e-4, "m/s", "v_s below which friction is smoothed"),
  };
}

StopLimits stop_limits(const Args& a, const std::string& label) {
  const std::optional<double> lower = a.optional_real("lower"), upper = a.optional_real("upper");
  if (!lower && !upper) throw ModelError(label + ": give a lower or an upper limit (or both)");
  if (lower && upper && !(*lower < *upper))
    throw ModelError(label + ": lower = " + to_text(*lower) + " must be below upper = " + to_text(*upper));
  StopLimits v;
  v.has_lower = bool(lower);
  v.has_upper = bool(upper);
  v.lower = lower.value_or(0.0);
  v.upper = upper.value_or(0.0);
  v.restitution = a.real("restitution");
  if (!(v.restitution >= 0.0 && v.restitution <= 1.0))
    throw ModelError(label + ": restitution must be in [0, 1], got " + to_text(v.restitution));
  if (const std::optional<double> rest = a.optional_real("rest_speed")) {
    require_positive(*rest, label, "rest_speed");
    v.rest_speed = *rest;
  }
  // a bounce series must end by capture, never by rebounds shrinking to rounding level
  v.capture_time = a.real("capture_time");
  require_positive(v.capture_time, label, "capture_time");
  return v;
}

std::vector<Param> stop_params() {
  return {
      param::joint("the revolute or translational joint limited"),
      param::optional_real("lower", "rad or m", "lower limit (None: none)"),
      param::optional_real("upper", "rad or m", "upper limit (None: none)"),
      param::real("restitution", 0.0, "", "Newton's coefficient of restitution e in [0, 1]"),
      param::optional_real("rest_speed", "rad/s or m/s",
                           "rebounds slower than this come to rest on the limit (None: capture_time decides)"),
      param::real("capture_time", 1e-6, "s",
                  "a rebound whose remaining bounces would end within this time comes to rest on the limit"),
  };
}

Vec3 unit_direction(const Args& a, const std::string& key, const std::string& label) {
  const Vec3 v = a.vec3(key);
  if (!(v.norm() > 0.0)) throw ModelError(label + ": " + key + " must be a non-zero vector, got " + to_text(v));
  return v.normalized();
}

}  // namespace lagmb::build
