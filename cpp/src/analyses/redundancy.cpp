#include "lagmb/analyses/redundancy.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "lagmb/assembly/analysis.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/assembly/augmented.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/interrupt.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

namespace {

/// Size of the mechanism (m): the spread of the bodies' centres, at least 0.1.
double extent(const Model& model, const VecX& q) {
  Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const Body& b : model.bodies()) {
    const Vec2 p = q.segment<2>(b.first_coord);
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  // the ground's joints are near the origin in most models: count it too
  lo = lo.cwiseMin(Vec2::Zero()), hi = hi.cwiseMax(Vec2::Zero());
  const double e = (hi - lo).maxCoeff();
  return std::isfinite(e) ? std::max(e, 0.1) : 0.1;
}

}  // namespace

std::string quoted_names(const std::vector<std::string>& names) {
  if (names.empty()) return "the other equations";
  std::string s;
  for (size_t k = 0; k < names.size(); ++k) {
    if (k) s += k + 1 == names.size() ? " and " : ", ";
    s += "'" + names[k] + "'";
  }
  return s;
}

Redundancy find_redundancy(const Model& model, Data& d, AugmentedSystem& kkt, const VecX& q0, double t0) {
  Redundancy out;
  const int n = model.n_coordinates(), m = model.n_constraints();
  if (m == 0) return out;
  d.drop_rows(model, {});
  const std::vector<int> at_start = constraint_rank(model, q0, t0).dependent_rows;
  out.rows = at_start;
  if (at_start.empty()) return out;

  // probes: random moves along the constraint manifold, h = 1 % of the mechanism's size
  const double h = 1e-2 * extent(model, q0);
  assemble_jacobian(model, d, q0.data(), t0);
  if (!kkt.factorize(d)) return out;
  VecX zero_n = VecX::Zero(n), zero_m = VecX::Zero(m), kappa(m), drive(n);
  // the driven motion: least-change velocity with Phi_q w = -Phi_t, run for dt
  double dt = 0.0;
  if (!model.time_dependent_groups().empty()) {
    assemble_phi_t(model, d, q0.data(), t0);
    kkt.solve(zero_n, -d.phi_t, drive, kappa);
    const double w = max_abs(drive);
    dt = std::min(w > 0 ? h / w : INFINITY, 1e-3);
  } else {
    drive.setZero();
  }
  std::mt19937 random(20261123u);  // fixed: the same model decides the same way every run
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  // two directions, each M-orthogonally projected onto the null space of
  // Phi_q at the start (before a probe re-assembles, and re-factorizes, kkt)
  VecX z(n), directions[2];
  for (VecX& dq : directions) {
    for (int i = 0; i < n; ++i) z[i] = uniform(random);
    kkt.solve(d.M * z, zero_m, dq, kappa);  // (M at q0, with Phi_q)
    const double size = max_abs(dq);
    dq *= size > 0 ? h / size : 0.0;
  }
  for (int probe = 0; probe < 4; ++probe) {
    poll_interrupt();
    const VecX dq = (probe % 2 ? -1.0 : 1.0) * directions[probe / 2];  // each direction both ways
    const double t1 = t0 + dt;
    VecX q1;
    try {
      q1 = assemble_positions(model, d, kkt, q0 + dq + dt * drive, t1);
    } catch (const SimulationError&) {
      continue;  // no configuration there (past a reach, or conflicting drivers)
    } catch (const UserFunctionError&) {
      continue;
    }
    const std::vector<int> here = constraint_rank(model, q1, t1).dependent_rows;
    if (here.size() < out.rows.size()) out.rows = here;
  }
  out.singular_start = out.rows.size() < at_start.size();
  return out;
}

void name_partners(const Model& model, const Data& full, AugmentedSystem& kkt, Redundancy& r) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  r.partners.assign(r.rows.size(), {});
  const SpMat Jt = full.Phi_q.transpose();  // column k: row k of Phi_q
  VecX x(n), w(m), zero_m = VecX::Zero(m);
  for (size_t k = 0; k < r.rows.size(); ++k) {
    auto& names = r.partners[k];
    names.push_back(model.constraint_name_of_row(r.rows[k]));
    // row_r^T = Phi_kept^T w (+ x, 0 when it is dependent): the kept rows it combines
    kkt.solve(VecX(Jt.col(r.rows[k])), zero_m, x, w);
    const double wmax = max_abs(w);
    for (int row = 0; row < m; ++row)
      if (wmax > 0 && std::abs(w[row]) > 1e-6 * wmax) {
        const std::string name = model.constraint_name_of_row(row);
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
      }
  }
}

RedundancyWatch::RedundancyWatch(const Model& model, const Data& run, Redundancy redundancy)
    : model_(model), r_(std::move(redundancy)), full_(model) {
  full_.share_values(run);
}

std::string RedundancyWatch::violation(const double* q, double t) {
  if (r_.rows.empty()) return "";
  assemble_constraints(model_, full_, q, t);
  const int n = model_.n_coordinates();
  const double q_max = Eigen::Map<const VecX>(q, n).lpNorm<Eigen::Infinity>();
  double kept = 0.0;
  for (int row = 0, k = 0; row < model_.n_constraints(); ++row) {
    if (k < int(r_.rows.size()) && r_.rows[k] == row) {
      ++k;
      continue;
    }
    kept = std::max(kept, std::abs(full_.Phi[row]));
  }
  const double tol = 1e-6 * (1.0 + q_max) + 100.0 * kept;
  for (size_t k = 0; k < r_.rows.size(); ++k) {
    const double e = std::abs(full_.Phi[r_.rows[k]]);
    if (e <= tol) continue;
    std::ostringstream s;
    s << "at t = " << t << " the equation of '" << r_.partners[k][0]
      << "' left out as redundant at the start is violated (|Phi| = " << e << ", allowed " << tol
      << "): it was dependent on " << quoted_names({r_.partners[k].begin() + 1, r_.partners[k].end()})
      << " only there, so these elements conflict. Check the drivers and the geometry "
      << "(a loop closed at a toggle or dead point, or drivers that prescribe the same motion differently).";
    return s.str();
  }
  return "";
}

namespace {

/// AssemblyError if a dropped row's equation at velocity or acceleration
/// level, residual[row], exceeds tol: its dependent set conflicts.
void check_dropped(const Redundancy& r, const VecX& residual, double tol, double t,
                   const char* level) {
  for (size_t k = 0; k < r.rows.size(); ++k) {
    const double e = std::abs(residual[r.rows[k]]);
    if (e <= tol) continue;
    std::ostringstream s;
    s << "the model cannot start at t = " << t << ": the equation of '" << r.partners[k][0]
      << "' depends on " << quoted_names({r.partners[k].begin() + 1, r.partners[k].end()})
      << " at the initial position, but its " << level << " constraint conflicts with them (residual " << e
      << "). Two elements prescribe the same motion differently (e.g. a joint and a body driven at "
         "different rates): remove or reconcile one.";
    std::vector<std::pair<std::string, double>> violated;
    for (const auto& name : r.partners[k]) violated.emplace_back(name, e);
    throw AssemblyError(s.str(), t, std::move(violated));
  }
}

}  // namespace

ConsistentState start_state(const Model& model, Data& d, AugmentedSystem& kkt, VecX q, VecX v, double t,
                            Redundancy* redundancy) {
  d.drop_rows(model, {});
  q = assemble_positions(model, d, kkt, std::move(q), t);
  Redundancy r = find_redundancy(model, d, kkt, q, t);
  d.drop_rows(model, r.rows);
  ConsistentState s = make_consistent(model, d, kkt, std::move(q), std::move(v), t);
  if (!r.rows.empty()) {
    // kkt holds the kept rows at s.q; the dropped ones from a full evaluation
    Data full(model);
    full.share_values(d);
    assemble_jacobian(model, full, s.q.data(), t);
    name_partners(model, full, kkt, r);
    assemble_phi_t(model, full, s.q.data(), t);
    VecX rv = full.phi_t;
    add_jacobian_times(full, s.v.data(), rv.data());
    const double tol_v = 1e-8 * (1.0 + max_abs(s.v) + max_abs(full.phi_t));
    check_dropped(r, rv, tol_v, t, "velocity");
    assemble_gamma(model, full, s.q.data(), s.v.data(), t);
    VecX ra = -full.gamma;
    add_jacobian_times(full, s.qdd.data(), ra.data());
    const double tol_a = 1e-8 * (1.0 + max_abs(s.qdd) + max_abs(full.gamma));
    check_dropped(r, ra, tol_a, t, "acceleration");
    d.element_evaluations += full.element_evaluations;
  }
  if (redundancy) *redundancy = std::move(r);
  return s;
}

}  // namespace lagmb
