#include "lagmb/model.hpp"


#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace lagmb {

namespace {

bool finite(Vec2 v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

std::string fmt(double x) { return to_text(x); }
std::string fmt(Vec2 v) { return to_text(v); }

}  // namespace

void Model::require_open(const std::string& what) const {
  if (finalized_) throw ModelError("cannot " + what + ": the model is finalized");
}

void Model::check_new_name(const std::string& name) const {
  if (name.empty()) throw ModelError("every body and element needs a non-empty name");
  if (name == "ground") throw ModelError("the name 'ground' is reserved for the ground");
  if (names_.count(name)) throw ModelError("duplicate name '" + name + "': names must be unique");
}

void Model::register_name(const std::string& name, ElementRef ref) {
  check_new_name(name);
  names_.emplace(name, ref);
}

void Model::check_pair(const std::string& name, int body_i, int body_j) const {
  const int nb = static_cast<int>(bodies_.size());
  for (int b : {body_i, body_j})
    if (b < kGround || b >= nb)
      throw ModelError("'" + name + "': body index " + std::to_string(b) + " does not exist");
  if (body_i == body_j)
    throw ModelError("'" + name + "' joins " +
                     (body_i == kGround ? std::string("the ground") : "body '" + bodies_[body_i].name + "'") +
                     " to itself");
}

int Model::add_body(const std::string& name, double mass, double inertia, Vec2 position,
                    double angle, Vec2 velocity, double angular_velocity) {
  require_open("add body '" + name + "'");
  check_new_name(name);
  // 0 is allowed (a massless body, for kinematic analysis); simulate refuses it in a dynamic run
  if (!(std::isfinite(mass) && mass >= 0))
    throw ModelError("body '" + name + "': mass must be positive (or 0: massless, kinematics only) and finite, got " +
                     fmt(mass));
  if (!(std::isfinite(inertia) && inertia >= 0))
    throw ModelError("body '" + name + "': inertia must be positive (or 0: massless, kinematics only) and finite, got " +
                     fmt(inertia));
  if (!finite(position)) throw ModelError("body '" + name + "': position is not finite: " + fmt(position));
  if (!std::isfinite(angle)) throw ModelError("body '" + name + "': angle is not finite: " + fmt(angle));
  if (!finite(velocity)) throw ModelError("body '" + name + "': velocity is not finite: " + fmt(velocity));
  if (!std::isfinite(angular_velocity))
    throw ModelError("body '" + name + "': angular_velocity is not finite: " + fmt(angular_velocity));
  Body b;
  b.name = name;
  b.mass = mass;
  b.inertia = inertia;
  b.position = position;
  b.angle = angle;
  b.velocity = velocity;
  b.angular_velocity = angular_velocity;
  const int index = static_cast<int>(bodies_.size());
  register_name(name, {ElementRef::kBody, index, 0});
  bodies_.push_back(std::move(b));
  return index;
}

int Model::add_particle(const std::string& name, double mass, Vec2 position, Vec2 velocity) {
  require_open("add particle '" + name + "'");
  check_new_name(name);
  if (!(std::isfinite(mass) && mass >= 0))
    throw ModelError("particle '" + name + "': mass must be positive (or 0: massless, kinematics only) and finite, got " +
                     fmt(mass));
  if (!finite(position)) throw ModelError("particle '" + name + "': position is not finite: " + fmt(position));
  if (!finite(velocity)) throw ModelError("particle '" + name + "': velocity is not finite: " + fmt(velocity));
  Body b;
  b.name = name;
  b.mass = mass;
  b.inertia = 0.0;
  b.position = position;
  b.velocity = velocity;
  b.particle = true;
  const int index = static_cast<int>(bodies_.size());
  register_name(name, {ElementRef::kBody, index, 0});
  bodies_.push_back(std::move(b));
  return index;
}

void Model::attach(const std::string& element, int body, Vec2 local) {
  attachments_[element].emplace_back(body, local);
  if (body == kGround) return;
  outlines_.resize(bodies_.size());
  std::vector<Vec2>& points = outlines_.at(body);
  for (const Vec2& p : points)
    if ((p - local).cwiseAbs().sum() <= 1e-12) return;
  points.push_back(local);
}

const std::vector<Vec2>& Model::outline(int body) const {
  static const std::vector<Vec2> none;
  if (body < 0 || body >= static_cast<int>(bodies_.size()))
    throw ModelError("outline: no body with index " + std::to_string(body));
  return body < static_cast<int>(outlines_.size()) ? outlines_[body] : none;
}

const std::vector<std::pair<int, Vec2>>& Model::attachments(const std::string& element) const {
  static const std::vector<std::pair<int, Vec2>> none;
  find(element);  // ModelError if there is no such element
  auto it = attachments_.find(element);
  return it == attachments_.end() ? none : it->second;
}

Vec2 Model::to_local(int body, Vec2 p) const {
  if (body == kGround) return p;
  const Body& b = bodies_[body];
  return rotation(b.angle).transpose() * (p - b.position);
}

void Model::add_revolute(const std::string& name, int body_i, int body_j, Vec2 at) {
  if (!finite(at)) throw ModelError("revolute '" + name + "': point 'at' is not finite: " + fmt(at));
  check_pair(name, body_i, body_j);
  add_revolute_local(name, body_i, body_j, to_local(body_i, at), to_local(body_j, at));
}

void Model::add_revolute_local(const std::string& name, int body_i, int body_j, Vec2 s_i, Vec2 s_j) {
  if (!finite(s_i) || !finite(s_j))
    throw ModelError("revolute '" + name + "': local points are not finite: " + fmt(s_i) + ", " + fmt(s_j));
  check_pair(name, body_i, body_j);
  for (auto [b, s] : {std::pair{body_i, s_i}, std::pair{body_j, s_j}})
    if (b != kGround && bodies_[b].particle && s.norm() != 0.0)
      throw ModelError("revolute '" + name + "': particle '" + bodies_[b].name +
                       "' has no extent; its joint point must be the particle itself");
  RevoluteJoint j;
  j.name = name;
  j.body_i = body_i;
  j.body_j = body_j;
  j.s_i = s_i;
  j.s_j = s_j;
  add_constraint(std::move(j));
}

void Model::set_gravity(Vec2 g) {
  require_open("set gravity");
  if (!finite(g)) throw ModelError("gravity is not finite: " + fmt(g));
  for (auto& f : forces_)
    if (auto* grav = dynamic_cast<Gravity*>(f.get())) {
      *grav = Gravity(g);
      return;
    }
  names_.emplace("gravity", ElementRef{ElementRef::kForce, int(forces_.size()), 0});
  forces_.push_back(std::make_unique<Gravity>(g));
}

void Model::finalize() {
  if (finalized_) return;
  // coordinates: bodies in order, 3 (or 2 for particles) each
  n_ = 0;
  for (auto& b : bodies_) {
    b.first_coord = n_;
    n_ += b.n_coordinates();
  }
  mass_diag_.resize(n_);
  coord_owner_.assign(n_, 0);
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const Body& b = bodies_[i];
    mass_diag_[b.first_coord] = mass_diag_[b.first_coord + 1] = b.mass;
    if (!b.particle) mass_diag_[b.first_coord + 2] = b.inertia;
    for (int a = 0; a < b.n_coordinates(); ++a) coord_owner_[b.first_coord + a] = int(i);
  }

  // rows: constraint elements in the order they were added
  m_ = 0;
  row_owner_.clear();
  for (size_t e = 0; e < constraint_order_.size(); ++e) {
    auto [g, k] = constraint_order_[e];
    ConstraintGroupBase& group = *constraints_[g];
    ElementPlacement& p = group.placement(k);
    p.row0 = m_;
    const auto bodies = group.bodies(k);
    p.coord = local_coordinates(bodies[0], bodies[1]);
    m_ += group.rows(k);
    row_owner_.insert(row_owner_.end(), group.rows(k), int(e));
  }

  SparsityPattern jac(m_, n_), hess(n_, n_), fq(n_, n_), fv(n_, n_);
  for (auto& g : constraints_) g->declare(jac, hess);
  for (auto& f : forces_) {
    f->place(*this);
    f->declare(fq, fv);
  }
  for (auto& f : frictions_) {  // friction's Q_q, Q_v join the force patterns
    f->place(*this);
    f->declare(fq, fv);
  }
  jacobian_pattern_ = jac.build();
  hessian_pattern_ = hess.build();
  force_q_pattern_ = fq.build();
  force_v_pattern_ = fv.build();
  for (auto& g : constraints_) g->bind(jacobian_pattern_, hessian_pattern_);
  for (auto& e : events_) e->place(*this);
  for (auto& f : forces_) f->bind(force_q_pattern_, force_v_pattern_);
  for (auto& f : frictions_) f->bind(force_q_pattern_, force_v_pattern_, jacobian_pattern_);

  time_dependent_.clear();
  for (auto& g : constraints_)
    if (g->time_dependent()) time_dependent_.push_back(g.get());
  state_dependent_.clear();
  for (auto& f : forces_)
    if (f->has_derivatives()) state_dependent_.push_back(f.get());

  // mass scale: mean body mass (regularization and tolerances scale with it)
  if (!bodies_.empty()) {
    double msum = 0.0;
    for (const auto& b : bodies_) msum += b.mass;
    mass_scale_ = msum / double(bodies_.size());
    if (!(mass_scale_ > 0)) mass_scale_ = 1.0;  // all bodies massless (kinematics only)
  }
  finalized_ = true;
}

VecX Model::initial_q() const {
  VecX q(n_);
  for (const auto& b : bodies_) {
    q.segment<2>(b.first_coord) = b.position;
    if (!b.particle) q[b.first_coord + 2] = b.angle;
  }
  return q;
}

VecX Model::initial_v() const {
  VecX v(n_);
  for (const auto& b : bodies_) {
    v.segment<2>(b.first_coord) = b.velocity;
    if (!b.particle) v[b.first_coord + 2] = b.angular_velocity;
  }
  return v;
}

const ElementRef& Model::find(const std::string& name) const {
  auto it = names_.find(name);
  if (it == names_.end()) throw ModelError("no body or element named '" + name + "'");
  return it->second;
}

std::string Model::constraint_name_of_row(int row) const {
  if (!finalized_) throw ModelError("constraint_name_of_row: the model is not finalized");
  if (row < 0 || row >= m_)
    throw ModelError("row " + std::to_string(row) + " is not a constraint row (the model has " + std::to_string(m_) +
                     ")");
  auto [g, k] = constraint_order_[row_owner_[row]];
  return constraints_[g]->name(k);
}

std::vector<double> Model::breakpoints() const {
  std::vector<double> t;
  for (const auto& f : time_functions_) {
    const auto b = f->breakpoints();
    t.insert(t.end(), b.begin(), b.end());
  }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

const Body& Model::body_of_coordinate(int coord) const {
  if (!finalized_ || coord < 0 || coord >= n_)
    throw ModelError("coordinate " + std::to_string(coord) + " is not a coordinate of the model (it has " +
                     std::to_string(n_) + ")");
  return bodies_[coord_owner_[coord]];
}

}  // namespace lagmb


// --- joints, drivers and forces beyond the revolute ------------------------

namespace lagmb {

namespace {

std::string fmt2(Vec2 v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ")";
  return s.str();
}

void require_finite(Vec2 v, const std::string& element, const char* what) {
  if (!std::isfinite(v.x()) || !std::isfinite(v.y()))
    throw ModelError("'" + element + "': " + what + " is not finite: " + fmt2(v));
}

void require_finite(double x, const std::string& element, const char* what) {
  if (!std::isfinite(x))
    throw ModelError("'" + element + "': " + what + " is not finite: " + std::to_string(x));
}

void require_function(const TimeFunctionPtr& f, const std::string& element, const char* what) {
  if (!f) throw ModelError("'" + element + "': " + what + " is missing");
}

}  // namespace

double Model::initial_angle(int body) const {
  return body == kGround ? 0.0 : bodies_[body].angle;
}

Vec2 Model::initial_position(int body) const {
  return body == kGround ? Vec2::Zero() : bodies_[body].position;
}

Vec2 Model::direction_to_local(int body, Vec2 axis, const std::string& element) const {
  require_finite(axis, element, "axis");
  const double n = axis.norm();
  if (!(n > 0.0)) throw ModelError("'" + element + "': axis must be a non-zero vector, got " + fmt2(axis));
  return rotation(initial_angle(body)).transpose() * (axis / n);
}

void Model::require_rigid(int body, const std::string& element, const char* why) const {
  if (body != kGround && bodies_[body].particle)
    throw ModelError("'" + element + "': particle '" + bodies_[body].name + "' " + why);
}

ProjectedOffset Model::across_line(int body_i, int body_j, Vec2 at, Vec2 axis,
                                   const std::string& element) const {
  const Vec2 u = direction_to_local(body_i, axis, element);
  ProjectedOffset f;
  f.w = Vec2(-u.y(), u.x());
  f.s_i = to_local(body_i, at);
  f.s_j = to_local(body_j, at);
  return f;
}

void Model::require_on_particle(int body, Vec2 point, const std::string& element) const {
  if (body != kGround && bodies_[body].particle && (point - bodies_[body].position).norm() > 0)
    throw ModelError("'" + element + "': the point on particle '" + bodies_[body].name +
                     "' must be the particle itself");
}

std::array<int, 6> Model::local_coordinates(int body_i, int body_j) const {
  std::array<int, 6> c{-1, -1, -1, -1, -1, -1};
  for (int side = 0; side < 2; ++side) {
    const int b = side ? body_j : body_i;
    if (b == kGround) continue;
    const Body& body = bodies_[b];
    c[3 * side] = body.first_coord;
    c[3 * side + 1] = body.first_coord + 1;
    c[3 * side + 2] = body.angle_coord();
  }
  return c;
}

void Model::add_translational(const std::string& name, int body_i, int body_j, Vec2 at, Vec2 axis) {
  require_open("add translational '" + name + "'");
  check_new_name(name);
  check_pair(name, body_i, body_j);
  require_finite(at, name, "point 'at'");
  for (int b : {body_i, body_j}) require_rigid(b, name, "cannot take a translational joint (it has no angle)");
  TranslationalJoint j;
  j.name = name;
  j.body_i = body_i;
  j.body_j = body_j;
  j.across = across_line(body_i, body_j, at, axis, name);
  j.phi0 = initial_angle(body_j) - initial_angle(body_i);
  add_constraint(std::move(j));
}

void Model::add_weld(const std::string& name, int body_i, int body_j) {
  require_open("add weld '" + name + "'");
  check_new_name(name);
  check_pair(name, body_i, body_j);
  for (int b : {body_i, body_j}) require_rigid(b, name, "cannot be welded (it has no angle)");
  WeldJoint j;
  j.name = name;
  j.body_i = body_i;
  j.body_j = body_j;
  j.s_i = to_local(body_i, initial_position(body_j));
  j.phi0 = initial_angle(body_j) - initial_angle(body_i);
  add_constraint(std::move(j));
}

void Model::add_distance(const std::string& name, int body_i, Vec2 point_i, int body_j, Vec2 point_j,
                         std::optional<double> length) {
  require_open("add distance '" + name + "'");
  check_new_name(name);
  check_pair(name, body_i, body_j);
  require_finite(point_i, name, "point_i");
  require_finite(point_j, name, "point_j");
  const double L = length ? *length : (point_j - point_i).norm();
  if (!(std::isfinite(L) && L > 0))
    throw ModelError("'" + name + "': length must be positive and finite, got " + std::to_string(L));
  DistanceJoint j;
  j.name = name;
  j.body_i = body_i;
  j.body_j = body_j;
  j.s_i = to_local(body_i, point_i);
  j.s_j = to_local(body_j, point_j);
  require_on_particle(body_i, point_i, name);
  require_on_particle(body_j, point_j, name);
  j.length = L;
  add_constraint(std::move(j));
}

void Model::add_pin_in_slot(const std::string& name, int body_i, int body_j, Vec2 at, Vec2 axis) {
  require_open("add pin_in_slot '" + name + "'");
  check_new_name(name);
  check_pair(name, body_i, body_j);
  require_finite(at, name, "point 'at'");
  require_rigid(body_i, name, "cannot carry a slot (it has no angle)");
  require_on_particle(body_j, at, name);
  PinInSlotJoint j;
  j.name = name;
  j.body_i = body_i;
  j.body_j = body_j;
  j.across = across_line(body_i, body_j, at, axis, name);
  add_constraint(std::move(j));
}

void Model::add_gear(const std::string& name, int body_i, int body_j, double ratio,
                     std::optional<Vec2> center_i, std::optional<Vec2> center_j) {
  require_open("add gear '" + name + "'");
  check_new_name(name);
  check_pair(name, body_i, body_j);
  for (int b : {body_i, body_j}) require_rigid(b, name, "cannot be a gear (it has no angle)");
  if (!std::isfinite(ratio) || ratio == 0.0 || ratio == 1.0)
    throw ModelError("'" + name + "': ratio must be finite, non-zero and not 1, got " + std::to_string(ratio));
  for (auto [b, c, label] : {std::tuple{body_i, center_i, "center_i"}, std::tuple{body_j, center_j, "center_j"}}) {
    if (b == kGround && !c)
      throw ModelError("'" + name + "': a gear on the ground needs its centre (" + label + ")");
    if (c) require_finite(*c, name, label);
  }
  const Vec2 ci = center_i ? *center_i : initial_position(body_i);
  const Vec2 cj = center_j ? *center_j : initial_position(body_j);
  const double D = (cj - ci).norm();
  if (!(D > 0)) throw ModelError("'" + name + "': the gear centres coincide at " + fmt2(ci));
  GearPair g;
  g.name = name;
  g.body_i = body_i;
  g.body_j = body_j;
  g.c_i = to_local(body_i, ci);
  g.c_j = to_local(body_j, cj);
  const double a = std::abs(ratio);
  g.s = ratio < 0 ? 1.0 : -1.0;
  g.r_j = ratio < 0 ? D / (a + 1.0) : D / std::abs(a - 1.0);
  g.r_i = a * g.r_j;
  Local6 c0;
  c0 << initial_position(body_i), initial_angle(body_i), initial_position(body_j), initial_angle(body_j);
  g.c0 = g.rolled(c0);
  add_constraint(std::move(g));
}

void Model::add_rack_pinion(const std::string& name, int pinion, int rack, double radius, Vec2 axis) {
  require_open("add rack_pinion '" + name + "'");
  check_new_name(name);
  check_pair(name, pinion, rack);
  for (int b : {pinion, rack}) require_rigid(b, name, "cannot be a rack or pinion (it has no angle)");
  if (pinion == kGround) throw ModelError("'" + name + "': the pinion cannot be the ground");
  if (!(std::isfinite(radius) && radius > 0))
    throw ModelError("'" + name + "': radius must be positive and finite, got " + std::to_string(radius));
  RackPinion r;
  r.name = name;
  r.body_i = pinion;
  r.body_j = rack;
  r.radius = radius;
  r.along.w = direction_to_local(rack, axis, name);
  r.along.s_i = to_local(rack, initial_position(pinion));  // on swapped coordinates: the rack is "i"
  r.along.s_j = Vec2::Zero();
  r.c0 = radius * (initial_angle(pinion) - initial_angle(rack));
  add_constraint(std::move(r));
}

void Model::drive_joint(const std::string& name, const std::string& joint, TimeFunctionPtr f) {
  require_open("add driver '" + name + "'");
  check_new_name(name);
  require_function(f, name, "the time function");
  if (const auto* rev = find_constraint<RevoluteJoint>(joint)) {
    AngleDriver d;
    d.name = name;
    d.body_i = rev->body_i;
    d.body_j = rev->body_j;
    d.f = std::move(f);
    note(d.f);
    add_constraint(std::move(d));
  } else if (const auto* tr = find_constraint<TranslationalJoint>(joint)) {
    SlideDriver d;
    d.name = name;
    d.body_i = tr->body_i;
    d.body_j = tr->body_j;
    d.along = tr->across;
    d.along.w = tr->across.line_direction();
    d.f = std::move(f);
    note(d.f);
    add_constraint(std::move(d));
  } else {
    throw ModelError("driver '" + name + "': '" + joint +
                     (names_.count(joint) ? "' is not a revolute or translational joint"
                                          : "' is not a joint of this model"));
  }
}

void Model::drive_body(const std::string& name, int body, const std::string& coordinate, TimeFunctionPtr f) {
  require_open("add driver '" + name + "'");
  check_new_name(name);
  check_pair(name, kGround, body);
  require_function(f, name, "the time function");
  CoordinateDriver d;
  if (coordinate == "x") d.coordinate = 0;
  else if (coordinate == "y") d.coordinate = 1;
  else if (coordinate == "angle") d.coordinate = 2;
  else throw ModelError("driver '" + name + "': coordinate must be \"x\", \"y\" or \"angle\", got \"" + coordinate + "\"");
  if (d.coordinate == 2) require_rigid(body, name, "has no angle to drive");
  d.name = name;
  d.body_i = kGround;
  d.body_j = body;
  d.f = std::move(f);
  note(d.f);
  add_constraint(std::move(d));
}

void Model::add_spring_damper(const std::string& name, int body_i, Vec2 point_i, int body_j, Vec2 point_j,
                              double stiffness, double damping, std::optional<double> free_length,
                              TimeFunctionPtr actuator) {
  require_open("add spring_damper '" + name + "'");
  check_new_name(name);
  check_pair(name, body_i, body_j);
  require_finite(point_i, name, "point_i");
  require_finite(point_j, name, "point_j");
  require_finite(stiffness, name, "stiffness");
  require_finite(damping, name, "damping");
  if (stiffness < 0 || damping < 0)
    throw ModelError("'" + name + "': stiffness and damping must not be negative, got " + std::to_string(stiffness) +
                     " and " + std::to_string(damping));
  const double l0 = free_length ? *free_length : (point_j - point_i).norm();
  if (!(std::isfinite(l0) && l0 >= 0)) throw ModelError("'" + name + "': free_length must be finite and >= 0");
  if (!((point_j - point_i).norm() > 0))
    throw ModelError("'" + name + "': the two points coincide; the line of action is undefined");
  require_on_particle(body_i, point_i, name);
  require_on_particle(body_j, point_j, name);
  SpringDamper e;
  e.name = name;
  e.body_i = body_i;
  e.body_j = body_j;
  e.s_i = to_local(body_i, point_i);
  e.s_j = to_local(body_j, point_j);
  e.stiffness = stiffness;
  e.damping = damping;
  e.free_length = l0;
  e.actuator = std::move(actuator);
  note(e.actuator);
  add_force_element(std::move(e));
}

void Model::add_rotational_spring_damper(const std::string& name, int body_i, int body_j, double stiffness,
                                         double damping, std::optional<double> free_angle, TimeFunctionPtr torque) {
  require_open("add rotational_spring_damper '" + name + "'");
  check_new_name(name);
  check_pair(name, body_i, body_j);
  for (int b : {body_i, body_j}) require_rigid(b, name, "has no angle");
  require_finite(stiffness, name, "stiffness");
  require_finite(damping, name, "damping");
  if (stiffness < 0 || damping < 0)
    throw ModelError("'" + name + "': stiffness and damping must not be negative");
  RotationalSpringDamper e;
  e.name = name;
  e.body_i = body_i;
  e.body_j = body_j;
  e.stiffness = stiffness;
  e.damping = damping;
  e.free_angle = free_angle ? *free_angle : initial_angle(body_j) - initial_angle(body_i);
  require_finite(e.free_angle, name, "free_angle");
  e.actuator = std::move(torque);
  note(e.actuator);
  add_force_element(std::move(e));
}

void Model::add_force(const std::string& name, int body, TimeFunctionPtr fx, TimeFunctionPtr fy,
                      std::optional<Vec2> point, bool local) {
  require_open("add force '" + name + "'");
  check_new_name(name);
  check_pair(name, body, kGround);
  require_function(fx, name, "fx");
  require_function(fy, name, "fy");
  if (point) require_finite(*point, name, "point");
  if (point) require_on_particle(body, *point, name);
  AppliedForce e;
  e.name = name;
  e.body_i = body;
  e.s = point ? to_local(body, *point) : Vec2::Zero();
  e.fx = std::move(fx);
  e.fy = std::move(fy);
  e.local = local;
  note(e.fx);
  note(e.fy);
  add_force_element(std::move(e));
}

void Model::add_torque(const std::string& name, int body, TimeFunctionPtr torque) {
  require_open("add torque '" + name + "'");
  check_new_name(name);
  check_pair(name, body, kGround);
  require_rigid(body, name, "cannot take a torque");
  require_function(torque, name, "the torque");
  AppliedTorque e;
  e.name = name;
  e.body_i = body;
  e.torque = std::move(torque);
  note(e.torque);
  add_force_element(std::move(e));
}

void Model::add_joint_friction(const std::string& name, const std::string& joint,
                               const JointFrictionParameters& p) {
  require_open("add joint friction '" + name + "'");
  check_new_name(name);
  const std::string what = "joint friction '" + name + "': ";
  auto nonnegative = [&](double x, const char* key) {
    if (!(std::isfinite(x) && x >= 0))
      throw ModelError(what + key + " must be finite and >= 0, got " + fmt(x));
  };
  nonnegative(p.mu, "mu");
  nonnegative(p.viscous, "viscous");
  nonnegative(p.preload, "preload");
  nonnegative(p.pin_radius, "pin_radius");
  nonnegative(p.bearing_length, "bearing_length");
  for (auto [x, key] : {std::pair{p.slip_velocity, "slip_velocity"}, std::pair{p.load_smoothing, "load_smoothing"}})
    if (!(std::isfinite(x) && x > 0)) throw ModelError(what + key + " must be positive and finite, got " + fmt(x));
  auto named = names_.find(joint);
  if (named == names_.end()) throw ModelError(what + "'" + joint + "' is not a joint of this model");
  const ElementRef ref = named->second;
  if (const auto* rev = find_constraint<RevoluteJoint>(joint)) {
    if (p.bearing_length != 0.0)
      throw ModelError(what + "bearing_length applies to translational joints; '" + joint + "' is revolute");
    if (p.mu > 0.0 && !(p.pin_radius > 0.0))
      throw ModelError(what + "mu = " + fmt(p.mu) + " needs the pin radius (pin_radius > 0) of revolute '" +
                       joint + "'");
    for (int b : {rev->body_i, rev->body_j}) require_rigid(b, name, "cannot take revolute friction (it has no angle)");
    RevoluteFriction f;
    f.name = name;
    f.body_i = rev->body_i;
    f.body_j = rev->body_j;
    f.joint_group = ref.group;
    f.joint_index = ref.index;
    f.law.p = p;
    f.law.arm = p.pin_radius;
    add_friction(std::move(f));
  } else if (const auto* tr = find_constraint<TranslationalJoint>(joint)) {
    if (p.pin_radius != 0.0)
      throw ModelError(what + "pin_radius applies to revolute joints; '" + joint + "' is translational");
    TranslationalFriction f;
    f.name = name;
    f.body_i = tr->body_i;
    f.body_j = tr->body_j;
    f.joint_group = ref.group;
    f.joint_index = ref.index;
    f.law.p = p;
    f.law.arm = 1.0;
    f.along = tr->across;
    f.along.w = tr->across.line_direction();
    add_friction(std::move(f));
  } else {
    const char* kind = ref.type == ElementRef::kConstraint ? constraints_[ref.group]->kind()
                       : ref.type == ElementRef::kBody     ? "body"
                       : ref.type == ElementRef::kForce    ? "force element"
                                                           : "joint friction";
    throw ModelError(what + "'" + joint + "' is a " + kind +
                     "; friction needs a revolute or translational joint");
  }
}

}  // namespace lagmb


// --- stops (event elements) --------------------------------------------------

namespace lagmb {

void Model::add_stop(const std::string& name, const std::string& joint, std::optional<double> lower,
                     std::optional<double> upper, double restitution, double rest_speed) {
  require_open("add stop '" + name + "'");
  check_new_name(name);
  JointStop s;
  s.name = name;
  if (const auto* rev = find_constraint<RevoluteJoint>(joint)) {
    s.body_i = rev->body_i;
    s.body_j = rev->body_j;
  } else if (const auto* tr = find_constraint<TranslationalJoint>(joint)) {
    s.body_i = tr->body_i;
    s.body_j = tr->body_j;
    s.slide = true;
    s.along = tr->across;
    s.along.w = tr->across.line_direction();
  } else {
    throw ModelError("stop '" + name + "': '" + joint +
                     (names_.count(joint) ? "' is not a revolute or translational joint"
                                          : "' is not a joint of this model"));
  }
  if (!lower && !upper) throw ModelError("stop '" + name + "': give a lower or an upper limit (or both)");
  if (lower && !std::isfinite(*lower)) throw ModelError("stop '" + name + "': lower is not finite: " + fmt(*lower));
  if (upper && !std::isfinite(*upper)) throw ModelError("stop '" + name + "': upper is not finite: " + fmt(*upper));
  if (lower && upper && !(*lower < *upper))
    throw ModelError("stop '" + name + "': lower = " + fmt(*lower) + " must be below upper = " + fmt(*upper));
  if (!(std::isfinite(restitution) && restitution >= 0.0 && restitution <= 1.0))
    throw ModelError("stop '" + name + "': restitution must be in [0, 1], got " + fmt(restitution));
  // 0 would let rebounds shrink to rounding level (Zeno) before the rest test fires
  if (!(std::isfinite(rest_speed) && rest_speed > 0.0))
    throw ModelError("stop '" + name + "': rest_speed must be finite and > 0, got " + fmt(rest_speed));
  s.has_lower = bool(lower);
  s.has_upper = bool(upper);
  s.lower = lower.value_or(0.0);
  s.upper = upper.value_or(0.0);
  s.restitution = restitution;
  s.rest_speed = rest_speed;
  add_event_element(std::move(s));
}

}  // namespace lagmb


// --- circle-line contact (a force and an event element) ------------------------

namespace lagmb {

void Model::add_contact(const std::string& name, int circle_body, Vec2 center, double radius, int line_body,
                        Vec2 point, Vec2 direction, double stiffness, double restitution, double friction,
                        double slip_velocity) {
  require_open("add contact '" + name + "'");
  check_new_name(name);
  check_pair(name, circle_body, line_body);
  require_finite(center, name, "center");
  require_finite(point, name, "point");
  auto positive = [&](double x, const char* what) {
    if (!(std::isfinite(x) && x > 0))
      throw ModelError("contact '" + name + "': " + what + " must be positive and finite, got " + fmt(x));
  };
  positive(radius, "radius");
  positive(stiffness, "stiffness");
  positive(slip_velocity, "slip_velocity");
  if (!(std::isfinite(restitution) && restitution > 0.0 && restitution <= 1.0))
    throw ModelError("contact '" + name + "': restitution must be in (0, 1] (the damping is 8 (1 - e) / (5 e)), got " +
                     fmt(restitution));
  if (!(std::isfinite(friction) && friction >= 0.0))
    throw ModelError("contact '" + name + "': friction must be finite and >= 0, got " + fmt(friction));
  require_on_particle(circle_body, center, name);
  CircleLineContact c;
  c.name = name;
  c.body_i = circle_body;
  c.body_j = line_body;
  c.s_c = to_local(circle_body, center);
  c.s_p = to_local(line_body, point);
  c.u = direction_to_local(line_body, direction, name);
  c.radius = radius;
  c.stiffness = stiffness;
  c.restitution = restitution;
  c.friction = friction;
  c.slip_velocity = slip_velocity;
  reserve_run_state(c);  // one offset for both entries of the same contact
  add_event_element(c, false);
  add_force_element(std::move(c));
}

}  // namespace lagmb
