#include "lagmb/assembly/assembly.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace lagmb {

Data::Data(const Model& model, const Data* of_run, Rows rows)
    : Phi(VecX::Zero(model.n_constraints())),
      phi_t(VecX::Zero(model.n_constraints())),
      gamma(VecX::Zero(model.n_constraints())),
      Q(VecX::Zero(model.n_coordinates())),
      Phi_q(model.jacobian_pattern()),
      Vq(model.jacobian_pattern()),
      H(model.hessian_pattern()),
      Q_q(model.force_q_pattern()),
      Q_v(model.force_v_pattern()),
      M(model.mass_pattern()),
      M_inv(model.mass_pattern()),
      M_qa(model.mass_pattern()),
      run(of_run ? of_run->run : std::make_shared<RunValues>()),
      left_out_(of_run && rows == Rows::kRun ? of_run->left_out_ : std::make_shared<LeftOutRows>()) {
  if (!model.finalized()) throw std::logic_error("lagmb: Data needs a finalized Model");
  init_mass(model, *this);
  if (left_out_ != (of_run ? of_run->left_out_ : nullptr)) {
    // a set of its own: every row but the unilateral ones (those a run has
    // closed, for a Data of every row of that run)
    if (of_run) left_out_->closed = of_run->left_out_->closed;
    leave_out(model);
  }
  if (!of_run) {
    run->inputs.resize(int(model.inputs().size()));
    for (int k = 0; k < run->inputs.size(); ++k) run->inputs[k] = model.inputs()[k].initial;
    run->state = VecX::Zero(model.run_state_size());
  }
  if (!model.friction_groups().empty()) {
    friction_Q_q = model.force_q_pattern();
    friction_Q_v = model.force_v_pattern();
    friction_Q_lam = model.jacobian_pattern();
    friction_Q0.resize(model.n_coordinates());
    friction_lam.resize(model.n_constraints());
  }
}

namespace {

std::vector<int> sorted_rows(const Model& model, std::vector<int> rows) {
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  for (int r : rows)
    if (r < 0 || r >= model.n_constraints()) throw std::logic_error("lagmb: dropped row out of range");
  return rows;
}

}  // namespace

void Data::drop_rows(const Model& model, std::vector<int> rows) {
  left_out_->redundant = sorted_rows(model, std::move(rows));
  leave_out(model);
}

void Data::close_rows(const Model& model, std::vector<int> rows) {
  rows = sorted_rows(model, std::move(rows));
  const auto& switched = model.switched_rows();
  for (int r : rows)
    if (!std::binary_search(switched.begin(), switched.end(), r))
      throw std::logic_error("lagmb: only a unilateral or stick row can be closed");
  left_out_->closed = std::move(rows);
  leave_out(model);
}

void Data::leave_out(const Model& model) {
  LeftOutRows& l = *left_out_;
  std::vector<int> open;  // (of the rows a run opens and closes: stops and stuck contacts)
  std::set_difference(model.switched_rows().begin(), model.switched_rows().end(), l.closed.begin(), l.closed.end(),
                      std::back_inserter(open));
  l.rows.clear();
  std::set_union(l.redundant.begin(), l.redundant.end(), open.begin(), open.end(), std::back_inserter(l.rows));
  // (the groups of switched rows: their elements with a closed row)
  l.evaluated.assign(model.constraint_groups().size(), {});
  for (int r : model.switched_rows()) l.evaluated[size_t(model.group_of_row(r))].switched = true;
  for (int r : l.closed) {
    auto& e = l.evaluated[size_t(model.group_of_row(r))].elements;
    const int k = model.element_in_group_of_row(r);
    if (e.empty() || e.back() != k) e.push_back(k);
  }
  for (auto& e : l.evaluated) std::sort(e.elements.begin(), e.elements.end());
  l.slots.clear();
  if (l.rows.empty()) return;
  const SpMat& J = model.jacobian_pattern();
  for (int c = 0; c < J.outerSize(); ++c)
    for (int k = J.outerIndexPtr()[c]; k < J.outerIndexPtr()[c + 1]; ++k)
      if (std::binary_search(l.rows.begin(), l.rows.end(), J.innerIndexPtr()[k])) l.slots.push_back(k);
}

namespace {

// rows dropped for the run read 0 = 0 (a no-op for most models)
void drop_rows(const Data& d, VecX& x) {
  for (int r : d.dropped_rows()) x[r] = 0.0;
}
void drop_rows(const Data& d, SpMat& A) {
  for (int s : d.dropped_slots()) A.valuePtr()[s] = 0.0;
}

/// Of a group of switched rows (stops, stuck contacts), only the elements
/// with a closed row are evaluated: an open one's rows read 0 = 0, and it
/// costs its gap functions only, which the event runner evaluates. True if
/// none is (the group is skipped).
bool all_open(const Data& d, int group) {
  const std::vector<int>* only = d.evaluated_elements(group);
  return only && only->empty();
}

/// How many elements of group gi the kernels evaluate in d (of its `size`).
int evaluated_count(const Data& d, int group, int size) {
  const std::vector<int>* only = d.evaluated_elements(group);
  return only ? int(only->size()) : size;
}

}  // namespace

void assemble_constraints(const Model& model, Data& d, const double* q, double t) {
  for (int gi = 0; gi < int(model.constraint_groups().size()); ++gi) {
    if (all_open(d, gi)) continue;
    const auto& g = model.constraint_groups()[gi];
    g->phi(q, d.at(t), d.Phi.data(), d.evaluated_elements(gi));
    d.element_evaluations += evaluated_count(d, gi, g->size());
  }
  drop_rows(d, d.Phi);
}

void assemble_jacobian(const Model& model, Data& d, const double* q, double t) {
  for (int gi = 0; gi < int(model.constraint_groups().size()); ++gi) {
    if (all_open(d, gi)) continue;
    const auto& g = model.constraint_groups()[gi];
    g->jacobian(q, d.at(t), d.Phi_q.valuePtr(), d.evaluated_elements(gi));
    d.element_evaluations += evaluated_count(d, gi, g->size());
  }
  drop_rows(d, d.Phi_q);
  if (!model.constant_mass()) assemble_mass(model, d, q);
}

void assemble_phi_t(const Model& model, Data& d, const double* q, double t) {
  d.phi_t.setZero();
  for (const auto* g : model.time_dependent_groups()) {
    g->add_phi_t(q, d.at(t), d.phi_t.data());
    d.element_evaluations += g->size();
  }
  drop_rows(d, d.phi_t);
}

void assemble_gamma(const Model& model, Data& d, const double* q, const double* v, double t) {
  for (int gi = 0; gi < int(model.constraint_groups().size()); ++gi) {
    if (all_open(d, gi)) continue;
    const auto& g = model.constraint_groups()[gi];
    g->gamma(q, v, d.at(t), d.gamma.data(), d.evaluated_elements(gi));
    d.element_evaluations += evaluated_count(d, gi, g->size());
  }
  drop_rows(d, d.gamma);
}

void assemble_velocity_jacobian(const Model& model, Data& d, const double* q, const double* v,
                                double t) {
  for (int gi = 0; gi < int(model.constraint_groups().size()); ++gi) {
    if (all_open(d, gi)) continue;
    const auto& g = model.constraint_groups()[gi];
    g->velocity_jacobian(q, v, d.at(t), d.Vq.valuePtr(), d.evaluated_elements(gi));
    d.element_evaluations += evaluated_count(d, gi, g->size());
  }
  drop_rows(d, d.Vq);
}

void assemble_constraint_hessian(const Model& model, Data& d, const double* q, double t,
                                 const double* w) {
  // (the weights of dropped rows are their multipliers: zero)
  d.H.coeffs().setZero();
  for (int gi = 0; gi < int(model.constraint_groups().size()); ++gi) {
    if (all_open(d, gi)) continue;
    const auto& g = model.constraint_groups()[gi];
    g->add_hessian(q, d.at(t), w, d.H.valuePtr());
    d.element_evaluations += g->size();
  }
}

void assemble_forces(const Model& model, Data& d, const double* q, const double* v, double t) {
  d.Q.setZero();
  for (const auto& f : model.force_groups()) {
    f->add_forces(q, v, d.at(t), d.run->state.data(), d.Q.data());
    d.element_evaluations += f->size();
  }
}

void assemble_force_derivatives(const Model& model, Data& d, const double* q, const double* v,
                                double t) {
  if (model.state_dependent_forces().empty()) return;
  d.Q_q.coeffs().setZero();
  d.Q_v.coeffs().setZero();
  for (const auto* f : model.state_dependent_forces()) {
    f->add_derivatives(q, v, d.at(t), d.run->state.data(), d.Q_q.valuePtr(), d.Q_v.valuePtr());
    d.element_evaluations += f->size();
  }
}

void add_friction_forces(const Model& model, Data& d, const double* q, const double* v,
                         const double* lam) {
  for (const auto& f : model.friction_groups()) {
    f->add_forces(q, v, lam, d.Q.data());
    d.element_evaluations += f->size();
  }
}

void assemble_friction_derivatives(const Model& model, Data& d, const double* q, const double* v,
                                   const double* lam) {
  if (model.friction_groups().empty()) return;
  d.friction_Q_q.coeffs().setZero();
  d.friction_Q_v.coeffs().setZero();
  d.friction_Q_lam.coeffs().setZero();
  for (const auto& f : model.friction_groups()) {
    f->add_derivatives(q, v, lam, d.friction_Q_q.valuePtr(), d.friction_Q_v.valuePtr(),
                       d.friction_Q_lam.valuePtr());
    d.element_evaluations += f->size();
  }
}

void add_jacobian_transpose_times(const Data& d, const double* w, double* y) {
  const SpMat& J = d.Phi_q;
  const int* outer = J.outerIndexPtr();
  const int* inner = J.innerIndexPtr();
  const double* val = J.valuePtr();
  for (int c = 0; c < J.cols(); ++c) {
    double s = 0.0;
    for (int k = outer[c]; k < outer[c + 1]; ++k) s += val[k] * w[inner[k]];
    y[c] += s;
  }
}

void add_jacobian_times(const Data& d, const double* x, double* y) {
  const SpMat& J = d.Phi_q;
  const int* outer = J.outerIndexPtr();
  const int* inner = J.innerIndexPtr();
  const double* val = J.valuePtr();
  for (int c = 0; c < J.cols(); ++c) {
    const double xc = x[c];
    for (int k = outer[c]; k < outer[c + 1]; ++k) y[inner[k]] += val[k] * xc;
  }
}

double potential_energy(const Model& model, const double* q, const Instant& at) {
  double V = 0.0;
  for (const auto& f : model.force_groups()) V += f->potential(q, at);
  return V;
}

}  // namespace lagmb
