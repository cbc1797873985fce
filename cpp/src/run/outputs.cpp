// Reactions, efforts, friction, energy and residuals at a run's outputs (outputs.hpp).
#include "lagmb/run/outputs.hpp"

#include <algorithm>
#include <stdexcept>

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/model/data.hpp"

namespace lagmb {

namespace {

/// ModelError unless the model is compiled and the view holds what `need` lists.
void require(const Model& model, const OutputView& out, bool q, bool v, bool lam) {
  if (!model.finalized()) throw ModelError("outputs: the model is not finalized");
  if (out.k < 0 || (out.k > 0 && !out.t)) throw ModelError("outputs: no output times");
  if (out.k > 0 && ((q && !out.q) || (v && !out.v) || (lam && !out.lam && model.n_constraints() > 0)))
    throw ModelError(std::string("outputs: this needs ") + (q ? "q " : "") + (v ? "v " : "") +
                     (lam ? "lam " : "") + "at every output");
}

/// A Data whose run values hold the inputs and the element state of output
/// s (or the initial ones).
void set_run_values(Data& d, const OutputView& out, int s) {
  const int p = int(d.run->inputs.size()), z = int(d.run->state.size());
  if (out.inputs)
    for (int j = 0; j < p; ++j) d.run->inputs[j] = out.inputs[size_t(s) * p + j];
  if (out.state)
    for (int j = 0; j < z; ++j) d.run->state[j] = out.state[size_t(s) * z + j];
}

const ElementRef& constraint_element(const Model& model, const std::string& element, const char* what) {
  const ElementRef& r = model.find(element);
  if (r.type != ElementRef::kConstraint)
    throw ModelError("'" + element + "' is " + model.describe(element) + ", not " + what);
  return r;
}

}  // namespace

const std::vector<std::string>& reaction_components(int dimension) {
  static const std::vector<std::string> planar = {"x", "y", "torque"};
  static const std::vector<std::string> spatial = {"x", "y", "z", "torque.x", "torque.y", "torque.z"};
  if (dimension != 2 && dimension != 3)
    throw ModelError("reaction_components: dimension must be 2 or 3, got " + std::to_string(dimension));
  return dimension == 2 ? planar : spatial;
}

OutputView OutputView::of(const Trajectory& tr) {
  OutputView o;
  o.k = tr.size();
  o.t = tr.t.data();
  o.q = tr.q.data();
  o.v = tr.v.data();
  // a and lam may be solved for fewer outputs than recorded (a failed run)
  o.lam = tr.lam.size() >= size_t(o.k) * size_t(tr.m) ? tr.lam.data() : nullptr;
  o.inputs = tr.p > 0 && tr.inputs.size() == size_t(o.k) * size_t(tr.p) ? tr.inputs.data() : nullptr;
  o.state = tr.state_size > 0 && tr.run_state.size() == size_t(o.k) * size_t(tr.state_size) ? tr.run_state.data()
                                                                                             : nullptr;
  return o;
}

OutputRows reactions(const Model& model, const std::string& element, const OutputView& out, bool joint_axes,
                     bool about_joint) {
  require(model, out, true, false, true);
  const ElementRef& r = constraint_element(model, element, "a joint or driver");
  const ConstraintGroupBase& g = *model.constraint_groups()[r.group];
  if (about_joint && !g.has_origin()) {
    const KindInfo* kind = model.given_kind(element);
    std::string what = kind ? kind->name : g.kind();
    std::replace(what.begin(), what.end(), '_', ' ');
    throw ModelError("'" + element + "' (" + what + ") has no point of its own to take its reaction's torque about "
                     "(drivers, stops, gears, racks and couplings have none): its torque is about its second "
                     "body's centre of mass");
  }
  const int n = model.n_coordinates(), m = model.n_constraints();
  Data d(model);
  OutputRows R(out.k, g.dimension() == 2 ? 3 : 6);
  for (int s = 0; s < out.k; ++s) {
    set_run_values(d, out, s);
    R.row(s) = g.reaction(r.index, out.q + size_t(s) * n, d.at(out.t[s]), out.lam + size_t(s) * m, joint_axes,
                          about_joint)
                   .transpose();
  }
  return R;
}

OutputRows efforts(const Model& model, const std::string& element, const OutputView& out) {
  const ElementRef& r = model.find(element);
  const KindInfo* kind = model.given_kind(element);
  if (!kind || kind->effort.empty())
    throw ModelError("'" + element + "' is " + model.describe(element) + ", which has no effort (drivers, stops, "
                     "force elements and joint friction have one)");
  const int width = kind->effort_components.empty() ? 1 : int(kind->effort_components.size());
  OutputRows E(out.k, width);
  if (r.type == ElementRef::kFriction) {
    E.col(0) = friction(model, element, out).col(0);
    return E;
  }
  const int n = model.n_coordinates(), m = model.n_constraints();
  if (r.type == ElementRef::kConstraint) {
    require(model, out, false, false, true);
    const ConstraintGroupBase& g = *model.constraint_groups()[r.group];
    for (int s = 0; s < out.k; ++s) E(s, 0) = g.effort(r.index, out.lam + size_t(s) * m);
    return E;
  }
  const ForceGroupBase* g = r.type == ElementRef::kForce ? model.force_groups()[r.group].get() : nullptr;
  if (!g || g->effort_size() != width)
    throw std::logic_error("efforts: '" + element + "' (" + kind->name + ") reads " +
                           std::to_string(g ? g->effort_size() : 0) + " numbers, its registry entry names " +
                           std::to_string(width));
  require(model, out, true, true, false);
  Data d(model);
  for (int s = 0; s < out.k; ++s) {
    set_run_values(d, out, s);
    g->effort(r.index, out.q + size_t(s) * n, out.v + size_t(s) * n, d.at(out.t[s]), E.row(s).data());
  }
  return E;
}

OutputRows friction(const Model& model, const std::string& element, const OutputView& out) {
  require(model, out, true, true, true);
  const ElementRef& r = model.find(element);
  if (r.type != ElementRef::kFriction)
    throw ModelError("'" + element + "' is " + model.describe(element) + ", not a joint friction");
  const FrictionGroupBase& g = *model.friction_groups()[r.group];
  const int n = model.n_coordinates(), m = model.n_constraints();
  OutputRows F(out.k, 2);
  for (int s = 0; s < out.k; ++s) {
    const auto f = g.friction(r.index, out.q + size_t(s) * n, out.v + size_t(s) * n, out.lam + size_t(s) * m);
    F(s, 0) = f[0];
    F(s, 1) = f[1];
  }
  return F;
}

OutputRows contacts(const Model& model, const std::string& element, const OutputView& out) {
  require(model, out, true, true, false);
  const ElementRef& r = model.find(element);
  ContactReading reading;
  const ForceGroupBase* g = r.type == ElementRef::kForce ? model.force_groups()[r.group].get() : nullptr;
  if (!g || !g->contact())
    throw ModelError("'" + element + "' is " + model.describe(element) + ", not a contact");
  const int n = model.n_coordinates(), m = model.n_constraints(), dim = model.dimension();
  // where it sticks, its rows (an element of a stick group of the same name) hold the friction
  const ConstraintGroupBase* stick = nullptr;
  int stick_index = -1;
  for (const auto& c : model.constraint_groups())
    if (c->sticks())
      for (int k = 0; k < c->size(); ++k)
        if (c->name(k) == element) stick = c.get(), stick_index = k;
  if (stick) require(model, out, true, true, true);
  Data d(model);
  OutputRows R(out.k, 4 + 3 * dim);
  for (int s = 0; s < out.k; ++s) {
    set_run_values(d, out, s);
    const double* q = out.q + size_t(s) * n;
    g->contact_reading(r.index, q, out.v + size_t(s) * n, d.run->state.data(), reading);
    if (stick) stick->stick_reading(stick_index, q, d.run->state.data(), out.lam + size_t(s) * m, reading);
    R(s, 0) = reading.normal_force;
    for (int a = 0; a < dim; ++a) {
      R(s, 1 + a) = reading.friction_force[a];
      R(s, 1 + dim + a) = reading.point[a];
      R(s, 1 + 2 * dim + a) = reading.normal[a];
    }
    R(s, 1 + 3 * dim) = reading.penetration;
    R(s, 2 + 3 * dim) = reading.slip_speed;
    R(s, 3 + 3 * dim) = reading.state;
  }
  return R;
}

VecX energy(const Model& model, const OutputView& out) {
  require(model, out, true, true, false);
  const int n = model.n_coordinates();
  Data d(model);
  VecX E(out.k);
  for (int s = 0; s < out.k; ++s) {
    set_run_values(d, out, s);
    const double *q = out.q + size_t(s) * n, *v = out.v + size_t(s) * n;
    E[s] = kinetic_energy(model, q, v) + potential_energy(model, q, d.at(out.t[s]));
  }
  return E;
}

VecX constraint_residual(const Model& model, const OutputView& out) {
  require(model, out, true, false, false);
  const int n = model.n_coordinates();
  Data d(model);  // every row, the ones a run dropped as redundant included
  VecX r(out.k);
  for (int s = 0; s < out.k; ++s) {
    set_run_values(d, out, s);
    assemble_constraints(model, d, out.q + size_t(s) * n, out.t[s]);
    r[s] = d.Phi.size() ? d.Phi.lpNorm<Eigen::Infinity>() : 0.0;
  }
  return r;
}

VecX velocity_residual(const Model& model, const OutputView& out) {
  require(model, out, true, true, false);
  const int n = model.n_coordinates();
  Data d(model);
  VecX r(out.k);
  for (int s = 0; s < out.k; ++s) {
    set_run_values(d, out, s);
    const double *q = out.q + size_t(s) * n, *v = out.v + size_t(s) * n;
    assemble_jacobian(model, d, q, out.t[s]);
    assemble_phi_t(model, d, q, out.t[s]);
    add_jacobian_times(d, v, d.phi_t.data());
    r[s] = d.phi_t.size() ? d.phi_t.lpNorm<Eigen::Infinity>() : 0.0;
  }
  return r;
}

}  // namespace lagmb
