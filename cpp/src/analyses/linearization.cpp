#include "lagmb/analyses/linearization.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/analyses/redundancy.hpp"
#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/model/data.hpp"

namespace lagmb {

namespace {

void check_dropped_rows(const char* who, const std::vector<int>& dropped_rows, int m) {
  for (size_t k = 0; k < dropped_rows.size(); ++k)
    if (dropped_rows[k] < 0 || dropped_rows[k] >= m || (k && dropped_rows[k] <= dropped_rows[k - 1]))
      throw ModelError(std::string(who) + ": dropped rows must be ascending rows of Phi (0 to " +
                       std::to_string(m - 1) + "), got " + std::to_string(dropped_rows[k]));
}

/// dF/du, one column per input, for F(u) affine in u (as forces and motions
/// that take an input's value are): a central difference with a unit step
/// is then exact. Where F bends in u (checked by the second difference) a
/// small step instead.
template <class F>
Eigen::MatrixXd input_derivative(Data& d, int rows, const F& eval) {
  const int p = int(d.run->inputs.size());
  Eigen::MatrixXd D(rows, p);
  VecX f0 = eval(), plus, minus;
  for (int j = 0; j < p; ++j) {
    double& u = d.run->inputs[j];
    const double u0 = u;
    double h = std::max(1.0, std::abs(u0));
    u = u0 + h, plus = eval();
    u = u0 - h, minus = eval();
    const double scale = std::max({f0.size() ? f0.lpNorm<Eigen::Infinity>() : 0.0,
                                   plus.size() ? plus.lpNorm<Eigen::Infinity>() : 0.0, 1e-300});
    if (rows && (plus + minus - 2.0 * f0).lpNorm<Eigen::Infinity>() > 1e-12 * scale) {
      h *= 1e-6;
      u = u0 + h, plus = eval();
      u = u0 - h, minus = eval();
    }
    u = u0;
    D.col(j) = (plus - minus) / (2.0 * h);
  }
  return D;
}

}  // namespace

RestTangent tangent_at_rest(const Model& model, const VecX& q, const VecX& lam, double t,
                            const std::vector<int>& dropped_rows) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  if (q.size() != n || lam.size() != m)
    throw ModelError("tangent_at_rest: q has " + std::to_string(q.size()) + " entries and lam " +
                     std::to_string(lam.size()) + "; the model has " + std::to_string(n) + " coordinates and " +
                     std::to_string(m) + " constraint rows");
  check_dropped_rows("tangent_at_rest", dropped_rows, m);
  Data d(model);
  d.drop_rows(model, dropped_rows);
  const VecX at_rest = VecX::Zero(n);
  assemble_jacobian(model, d, q.data(), t);  // Phi_q and M(q)
  assemble_constraint_hessian(model, d, q.data(), t, lam.data());
  assemble_force_derivatives(model, d, q.data(), at_rest.data(), t);
  RestTangent r;
  r.M = Eigen::MatrixXd(d.M);
  r.K = Eigen::MatrixXd(d.H) - Eigen::MatrixXd(d.Q_q);
  r.C = -Eigen::MatrixXd(d.Q_v);
  r.Phi_q = Eigen::MatrixXd(d.Phi_q);
  return r;
}

/// The rows of the stops `held` that are at a limit at (q, t): the gap row within 1e-8 (1 + |q|) of 0.
std::vector<int> held_rows(const Model& model, const std::vector<std::string>& held, const VecX& q, double t) {
  std::vector<int> rows;
  if (held.empty()) return rows;
  Data gaps(model);
  gaps.close_rows(model, model.unilateral_rows());
  assemble_constraints(model, gaps, q.data(), t);
  const double tol = 1e-8 * (1.0 + q.lpNorm<Eigen::Infinity>());
  for (const std::string& name : held) {
    const ElementRef& ref = model.find(name);
    const ConstraintGroupBase* g =
        ref.type == ElementRef::kConstraint ? model.constraint_groups()[ref.group].get() : nullptr;
    if (!g || !g->unilateral()) throw ModelError("tangent_at: held: '" + name + "' is " + model.describe(name) + ", not a stop");
    const int k = ref.index, row0 = g->placement(k).row0;
    int at = -1;
    std::string gaps_text;
    for (int r = 0; r < g->rows(k); ++r) {
      if (!g->unilateral_row(k, r).exists) continue;
      gaps_text += std::string(gaps_text.empty() ? "" : ", ") + g->unilateral_row(k, r).label + " " +
                   to_text(gaps.Phi[row0 + r]);
      if (std::abs(gaps.Phi[row0 + r]) <= tol) at = row0 + r;
    }
    if (at < 0)
      throw ModelError("tangent_at: held: stop '" + name + "' is at neither limit in this state (its gaps: " +
                       gaps_text + "); a held stop holds its joint where it rests on a limit");
    rows.push_back(at);
  }
  return rows;
}

StateTangent tangent_at(const Model& model, const VecX& q, const VecX& v, double t, const VecX& u,
                        const std::optional<std::vector<int>>& dropped_rows, const std::vector<std::string>& held) {
  const int n = model.n_coordinates(), m = model.n_constraints(), p = int(model.inputs().size());
  if (q.size() != n || v.size() != n || u.size() != p)
    throw ModelError("tangent_at: q and v have " + std::to_string(q.size()) + " and " + std::to_string(v.size()) +
                     " entries and the inputs " + std::to_string(u.size()) + "; the model has " + std::to_string(n) +
                     " coordinates and " + std::to_string(p) + " inputs");
  if (!q.allFinite() || !v.allFinite() || !u.allFinite() || !std::isfinite(t))
    throw ModelError("tangent_at: the state (q, v, t) and the inputs must be finite");
  Data d(model);
  d.run->inputs = u;
  d.close_rows(model, held_rows(model, held, q, t));
  StateTangent r;
  if (dropped_rows) {
    check_dropped_rows("tangent_at", *dropped_rows, m);
    r.dropped_rows = *dropped_rows;
  } else {
    AugmentedSystem scratch(model);
    r.dropped_rows = find_redundancy(model, d, scratch, q, t).rows;
  }
  d.drop_rows(model, r.dropped_rows);
  r.dropped_rows = d.dropped_rows();  // (and the stops' rows, open here)
  r.a.resize(n);
  r.lam.resize(m);
  AugmentedSystem kkt(model);
  try {
    solve_accelerations(model, d, kkt, q.data(), v.data(), t, r.a.data(), r.lam.data());
  } catch (const SimulationError&) {
    throw ModelError("tangent_at: the augmented matrix [M Phi_q^T; Phi_q 0] is singular at the state (t = " +
                     to_text(t) + ")");
  }
  r.Q = d.Q;
  r.gamma = d.gamma;
  assemble_constraints(model, d, q.data(), t);
  r.Phi = d.Phi;
  assemble_phi_t(model, d, q.data(), t);
  add_jacobian_times(d, v.data(), d.phi_t.data());
  r.velocity_residual = d.phi_t;
  r.M = d.M;
  r.Phi_q = d.Phi_q;

  // K = (M a)_q + (Phi_q^T lam)_q - Q_q, C = -Q_v
  assemble_mass_derivative(model, d, q.data(), r.a.data());
  assemble_constraint_hessian(model, d, q.data(), t, r.lam.data());
  assemble_force_derivatives(model, d, q.data(), v.data(), t);
  r.K = d.M_qa + d.H - d.Q_q;
  r.C = -d.Q_v;

  // G_v = -2 Vq(v); (Phi_q a)_q = Vq(a) - Vq(0), as Vq is affine in its velocity
  const VecX zero = VecX::Zero(n);
  assemble_velocity_jacobian(model, d, q.data(), v.data(), t);
  r.G_v = -2.0 * d.Vq;
  assemble_velocity_jacobian(model, d, q.data(), r.a.data(), t);
  SpMat Phi_q_a = d.Vq;
  assemble_velocity_jacobian(model, d, q.data(), zero.data(), t);
  Phi_q_a -= d.Vq;

  // gamma_q by central differences, column by column (0 where gamma is
  // identically 0 near the state: v = 0 and no constraint moves with time)
  SpMat gamma_q(m, n);
  if (v.lpNorm<Eigen::Infinity>() > 0.0 || !model.time_dependent_groups().empty()) {
    std::vector<Eigen::Triplet<double>> entries;
    VecX qh = q;
    for (int j = 0; j < n; ++j) {
      const double h = 1e-6 * std::max(1.0, std::abs(q[j]));
      qh[j] = q[j] + h;
      assemble_gamma(model, d, qh.data(), v.data(), t);
      VecX plus = d.gamma;
      qh[j] = q[j] - h;
      assemble_gamma(model, d, qh.data(), v.data(), t);
      qh[j] = q[j];
      plus -= d.gamma;
      for (int i = 0; i < m; ++i)
        if (plus[i] != 0.0) entries.emplace_back(i, j, plus[i] / (2.0 * h));
    }
    gamma_q.setFromTriplets(entries.begin(), entries.end());
  }
  // the dropped rows are 0 = 0: their G rows zero too
  SpMat kept(m, m);
  kept.setIdentity();
  for (int row : d.dropped_rows()) kept.coeffRef(row, row) = 0.0;
  r.G_q = kept * (gamma_q - Phi_q_a);
  r.G_v = kept * r.G_v;

  r.Q_u = input_derivative(d, n, [&] {
    assemble_forces(model, d, q.data(), v.data(), t);
    return VecX(d.Q);
  });
  r.Phi_u = input_derivative(d, m, [&] {
    assemble_constraints(model, d, q.data(), t);
    return VecX(d.Phi);
  });
  for (int row : d.dropped_rows()) r.Phi_u.row(row).setZero();
  return r;
}

}  // namespace lagmb
