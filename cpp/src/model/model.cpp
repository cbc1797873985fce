#include "lagmb/model/model.hpp"


#include <algorithm>
#include <iterator>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace lagmb {

void Model::require_open(const std::string& what) const {
  if (finalized_) throw ModelError("cannot " + what + ": the model is finalized");
}

std::uint64_t Model::next_model_id() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

namespace {

/// What a name of a body, element or input may be: printable UTF-8, no
/// control characters (a newline or NUL cannot go in a scene line or the
/// FMU's XML), no space at either end (lost where names are read back).
void check_name_text(const std::string& name, const std::string& what) {
  if (name.empty()) throw ModelError("every " + what + " needs a non-empty name");
  auto refuse = [&](const std::string& why) {
    std::string shown;
    for (unsigned char ch : name) {
      if (ch < 0x20 || ch == 0x7f || ch >= 0x80) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02x", ch);
        shown += hex;
      } else {
        shown += char(ch);
      }
    }
    throw ModelError(what + " name '" + shown + "' " + why);
  };
  if (name.front() == ' ' || name.back() == ' ') refuse("begins or ends with a space");
  for (size_t i = 0; i < name.size();) {
    const unsigned char ch = name[i];
    if (ch < 0x20 || ch == 0x7f) refuse("holds a control character (names must be printable)");
    // UTF-8: a lead byte and its continuation bytes
    const int more = ch < 0x80 ? 0 : (ch >> 5) == 0x6 ? 1 : (ch >> 4) == 0xe ? 2 : (ch >> 3) == 0x1e ? 3 : -1;
    if (more < 0 || i + more > name.size() - 1) refuse("is not valid UTF-8 text");
    for (int k = 1; k <= more; ++k)
      if ((static_cast<unsigned char>(name[i + k]) >> 6) != 0x2) refuse("is not valid UTF-8 text");
    i += 1 + more;
  }
}

}  // namespace

void Model::check_new_name(const std::string& name) const {
  check_name_text(name, "body or element");
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

int Model::add_body(Body body) {
  require_open("add body '" + body.name + "'");
  const int index = static_cast<int>(bodies_.size());
  register_name(body.name, {ElementRef::kBody, index, 0});
  bodies_.push_back(std::move(body));
  return index;
}

void Model::attach(const std::string& element, int body, Vec3 local) {
  attachments_[element].emplace_back(body, local);
  if (body == kGround) return;
  outlines_.resize(bodies_.size());
  std::vector<Vec3>& points = outlines_.at(body);
  for (const Vec3& p : points)
    if ((p - local).cwiseAbs().sum() <= 1e-12) return;
  points.push_back(local);
}

const std::vector<Vec3>& Model::outline(int body) const {
  static const std::vector<Vec3> none;
  if (body < 0 || body >= static_cast<int>(bodies_.size()))
    throw ModelError("outline: no body with index " + std::to_string(body));
  return body < static_cast<int>(outlines_.size()) ? outlines_[body] : none;
}

const std::vector<std::pair<int, Vec3>>& Model::attachments(const std::string& element) const {
  static const std::vector<std::pair<int, Vec3>> none;
  find(element);  // ModelError if there is no such element
  auto it = attachments_.find(element);
  return it == attachments_.end() ? none : it->second;
}

Vec2 Model::local_point(int body, Vec2 p) const {
  if (body == kGround) return p;
  const Body& b = bodies_[body];
  return rotation(b.angle).transpose() * (p - b.position);
}

Vec3 Model::local_point(int body, Vec3 p) const {
  if (body == kGround) return p;
  const Body& b = bodies_[body];
  return euler::A(b.p0).transpose() * (p - b.r0);
}

Vec3 Model::local_direction(int body, Vec3 d) const {
  return body == kGround ? d : Vec3(euler::A(bodies_[body].p0).transpose() * d);
}

Vec3 Model::body_direction(int body, Vec3 d) const {
  return body == kGround ? d : Vec3(euler::A(bodies_[body].p0) * d);
}

Vec3 Model::body_position(int body) const { return body == kGround ? Vec3::Zero() : bodies_[body].r0; }

void Model::set_dimension(int dimension) {
  if (dimension != 2 && dimension != 3) throw ModelError("dimension must be 2 or 3, got " + std::to_string(dimension));
  if (dimension == dimension_) return;
  if (!bodies_.empty() || !constraints_.empty() || !forces_.empty() || !events_.empty())
    throw ModelError("set the dimension before adding bodies, elements or gravity");
  dimension_ = dimension;
}

void Model::set_gravity(Vec2 g) {
  if (dimension_ != 2)
    throw ModelError("gravity of a spatial model has three components (x, y, z), got " + to_text(g));
  set_gravity(Vec3(g.x(), g.y(), 0.0));
}

void Model::set_gravity(Vec3 g) {
  require_open("set gravity");
  if (!g.allFinite()) throw ModelError("gravity is not finite: " + to_text(g));
  if (dimension_ == 2 && g.z() != 0.0)
    throw ModelError("gravity of a planar model has two components (x, y), got " + to_text(g));
  given_gravity_ = g;
  for (auto& f : forces_)
    if (auto* grav = dynamic_cast<Gravity*>(f.get())) {
      *grav = Gravity(g);
      return;
    }
  names_.emplace("gravity", ElementRef{ElementRef::kForce, int(forces_.size()), 0});
  forces_.push_back(std::make_unique<Gravity>(g));
}

void Model::add_turn_counter(TurnCounter counter) {
  require_open("count the turns of '" + counter.joint + "'");
  if (turn_counter(counter.joint)) return;
  reserve_run_state(counter);
  counter.reading.turns = counter.run_state;
  turn_counters_.push_back(std::move(counter));
}

const TurnCounter* Model::turn_counter(const std::string& joint) const {
  for (const TurnCounter& c : turn_counters_)
    if (c.joint == joint) return &c;
  return nullptr;
}

TurnCounter* Model::turn_counter(const std::string& joint) {
  return const_cast<TurnCounter*>(std::as_const(*this).turn_counter(joint));
}

void Model::finalize() {
  if (finalized_) return;
  // coordinates: bodies in order, 3 (or 2 for particles) each
  n_ = 0;
  for (auto& b : bodies_) {
    b.first_coord = n_;
    n_ += b.n_coordinates();
  }
  coord_owner_.assign(n_, 0);
  for (size_t i = 0; i < bodies_.size(); ++i)
    for (int a = 0; a < bodies_[i].n_coordinates(); ++a) coord_owner_[bodies_[i].first_coord + a] = int(i);
  build_mass();

  // rows: constraint elements in the order they were added
  m_ = 0;
  row_owner_.clear();
  unilateral_rows_.clear();
  stick_rows_.clear();
  for (size_t e = 0; e < constraint_order_.size(); ++e) {
    auto [g, k] = constraint_order_[e];
    ConstraintGroupBase& group = *constraints_[g];
    ElementPlacement& p = group.placement(k);
    p.row0 = m_;
    p.coord = local_coordinates(group.bodies(k));
    if (group.unilateral())
      for (int r = 0; r < group.rows(k); ++r) unilateral_rows_.push_back(m_ + r);
    if (group.sticks())
      for (int r = 0; r < group.rows(k); ++r) stick_rows_.push_back(m_ + r);
    m_ += group.rows(k);
    row_owner_.insert(row_owner_.end(), group.rows(k), int(e));
  }
  switched_rows_.clear();
  std::set_union(unilateral_rows_.begin(), unilateral_rows_.end(), stick_rows_.begin(), stick_rows_.end(),
                 std::back_inserter(switched_rows_));

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
  for (auto& c : turn_counters_) c.where = local_coordinates(c.body_i, c.body_j);
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

void Model::build_mass() {
  mass_diag_ = VecX::Zero(n_);
  SparsityPattern pattern(n_, n_);
  for (int i = 0; i < n_; ++i) pattern.add(i, i);
  positive_mass_ = true;
  for (const Body& b : bodies_) {
    const int c = b.first_coord;
    positive_mass_ = positive_mass_ && b.has_mass_and_inertia();
    if (b.spatial) {
      mass_diag_.segment<3>(c).setConstant(b.mass);
      for (int r = 0; r < 4; ++r)
        for (int k = 0; k < 4; ++k) pattern.add(c + 3 + r, c + 3 + k);
      continue;
    }
    mass_diag_[c] = mass_diag_[c + 1] = b.mass;
    if (!b.particle) mass_diag_[c + 2] = b.inertia;
  }
  mass_pattern_ = pattern.build();
  mass_diagonal_slots_.resize(n_);
  for (int i = 0; i < n_; ++i) mass_diagonal_slots_[i] = slot(mass_pattern_, i, i);
  spatial_masses_.clear();
  for (const Body& b : bodies_) {
    if (!b.spatial) continue;
    SpatialMass s;
    s.p = b.first_coord + 3;
    for (int k = 0; k < 4; ++k)
      for (int r = 0; r < 4; ++r) s.slots[4 * k + r] = slot(mass_pattern_, s.p + r, s.p + k);
    s.J = b.inertia_tensor;
    s.jbar = b.inertia_tensor.trace() / 3.0;
    // a body without inertia has no inverse: its block of M^-1 is 0 (M^-1 is then used for scales only;
    // the augmented system takes its LU)
    s.J_inverse = b.has_mass_and_inertia() ? Mat3(b.inertia_tensor.inverse()) : Mat3::Zero();
    spatial_masses_.push_back(s);
  }
}

VecX Model::initial_q() const {
  VecX q(n_);
  for (const auto& b : bodies_) {
    if (b.spatial) {
      q.segment<3>(b.first_coord) = b.r0;
      q.segment<4>(b.first_coord + 3) = b.p0;
      continue;
    }
    q.segment<2>(b.first_coord) = b.position;
    if (!b.particle) q[b.first_coord + 2] = b.angle;
  }
  return q;
}

VecX Model::initial_v() const {
  VecX v(n_);
  for (const auto& b : bodies_) {
    if (b.spatial) {
      // p' = E(p)^T omega / 2 (omega = 2 E p', E E^T = I)
      v.segment<3>(b.first_coord) = b.rdot0;
      v.segment<4>(b.first_coord + 3) = 0.5 * euler::E(b.p0).transpose() * b.omega0;
      continue;
    }
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

std::string Model::event_element_name() const {
  if (!events_.empty()) return events_.front()->name(0);
  if (!unilateral_rows_.empty()) return constraint_name_of_row(unilateral_rows_.front());
  return "";
}

const KindInfo* Model::given_kind(const std::string& name) const {
  find(name);  // the message for a name the model does not have
  for (auto e = given_.rbegin(); e != given_.rend(); ++e)
    if (e->name == name) return &e->args.kind();
  return nullptr;
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


// --- for the builders of element kinds ---------------------------------------

namespace lagmb {

double Model::initial_angle(int body) const {
  return body == kGround ? 0.0 : bodies_[body].angle;
}

Vec2 Model::initial_position(int body) const {
  return body == kGround ? Vec2::Zero() : bodies_[body].position;
}

LocalCoords Model::local_coordinates(int body_i, int body_j) const { return local_coordinates({body_i, body_j}); }

LocalCoords Model::local_coordinates(const std::vector<int>& element_bodies) const {
  LocalCoords c;
  c.fill(-1);
  // every body of one element lives in one space: the first that is not the ground says which
  bool spatial = false;
  for (int b : element_bodies)
    if (b != kGround) {
      spatial = bodies_[b].spatial;
      break;
    }
  const int stride = spatial ? 7 : 3;
  for (size_t side = 0; side < element_bodies.size(); ++side) {
    const int b = element_bodies[side];
    if (b == kGround) continue;
    const Body& body = bodies_[b];
    const int at = stride * int(side);
    if (body.spatial) {
      for (int a = 0; a < 7; ++a) c[at + a] = body.first_coord + a;
      continue;
    }
    c[at] = body.first_coord;
    c[at + 1] = body.first_coord + 1;
    c[at + 2] = body.angle_coord();
  }
  return c;
}

void Model::use_time_function(const TimeFunctionPtr& f) {
  if (f && time_function_set_.insert(f.get()).second) time_functions_.push_back(f);
}

void Model::add_input(InputInfo info) {
  require_open("add an input");
  for (const Input* f : input_functions_)
    if (f == info.function) return;  // one input feeding several parameters
  check_name_text(info.name, "input");
  if (input_index(info.name) >= 0)
    throw ModelError("input '" + info.name + "' of " + info.element + ": another input has that name (of " +
                     inputs_[input_index(info.name)].element + ")");
  input_functions_.push_back(info.function);
  inputs_.push_back(std::move(info));
}

int Model::input_slot(const TimeFunction* f) const {
  for (size_t k = 0; k < input_functions_.size(); ++k)
    if (input_functions_[k] == f) return int(k);
  return -1;
}

int Model::input_index(const std::string& name) const {
  for (size_t k = 0; k < inputs_.size(); ++k)
    if (inputs_[k].name == name) return int(k);
  return -1;
}

std::string Model::describe(const std::string& name) const {
  const ElementRef& r = find(name);
  std::string kind;
  switch (r.type) {
    case ElementRef::kBody: kind = bodies_[r.group].particle ? "particle" : "body"; break;  // (spatial too)
    case ElementRef::kConstraint: kind = constraints_[r.group]->kind(); break;
    case ElementRef::kForce: kind = forces_[r.group]->kind(); break;
    case ElementRef::kFriction: kind = frictions_[r.group]->kind(); break;
    case ElementRef::kEvent: kind = events_[r.group]->kind(); break;
  }
  std::replace(kind.begin(), kind.end(), '_', ' ');
  return (kind.find_first_of("aeiou") == 0 ? "an " : "a ") + kind;
}

}  // namespace lagmb
