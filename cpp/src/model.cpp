#include "lagmb/model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lagmb {

namespace {

bool finite(Vec2 v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

std::string fmt(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

std::string fmt(Vec2 v) { return "(" + fmt(v.x()) + ", " + fmt(v.y()) + ")"; }

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
  if (!(std::isfinite(mass) && mass > 0))
    throw ModelError("body '" + name + "': mass must be positive and finite, got " + fmt(mass));
  if (!(std::isfinite(inertia) && inertia > 0))
    throw ModelError("body '" + name + "': inertia must be positive and finite, got " + fmt(inertia));
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
  if (!(std::isfinite(mass) && mass > 0))
    throw ModelError("particle '" + name + "': mass must be positive and finite, got " + fmt(mass));
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
    for (int side = 0; side < 2; ++side) {
      const int b = bodies[side];
      if (b == kGround) continue;
      const Body& body = bodies_[b];
      p.coord[3 * side] = body.first_coord;
      p.coord[3 * side + 1] = body.first_coord + 1;
      p.coord[3 * side + 2] = body.angle_coord();
    }
    m_ += group.rows(k);
    row_owner_.insert(row_owner_.end(), group.rows(k), int(e));
  }

  SparsityPattern jac(m_, n_), hess(n_, n_), fq(n_, n_), fv(n_, n_);
  for (auto& g : constraints_) g->declare(jac, hess);
  for (auto& f : forces_) {
    f->place(*this);
    f->declare(fq, fv);
  }
  jacobian_pattern_ = jac.build();
  hessian_pattern_ = hess.build();
  force_q_pattern_ = fq.build();
  force_v_pattern_ = fv.build();
  for (auto& g : constraints_) g->bind(jacobian_pattern_, hessian_pattern_);
  for (auto& f : forces_) f->bind(force_q_pattern_, force_v_pattern_);

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
  auto [g, k] = constraint_order_.at(row_owner_.at(row));
  return constraints_[g]->name(k);
}

const Body& Model::body_of_coordinate(int coord) const { return bodies_.at(coord_owner_.at(coord)); }

}  // namespace lagmb

