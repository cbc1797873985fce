#include "lagmb/analyses/redundancy.hpp"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/model/coordinates.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/assembly/augmented.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/interrupt.hpp"
#include "lagmb/time_function.hpp"
#include "lagmb/solvers/sparse_qr.hpp"

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

ConstraintRank constraint_rank(const Model& model, const VecX& q, double t, double tol) {
  if (!model.finalized()) throw ModelError("constraint_rank: the model is not finalized");
  if (q.size() != model.n_coordinates())
    throw ModelError("constraint_rank: q must have " + std::to_string(model.n_coordinates()) + " entries");
  if (!std::isfinite(t)) throw ModelError("constraint_rank: t must be finite, got " + to_text(t));
  // a q computed from a model whose magnitudes overflow (a probe of find_redundancy)
  for (int i = 0; i < q.size(); ++i)
    if (!std::isfinite(q[i]))
      throw AssemblyError("the positions are not finite at " + coordinate_label(model, i) + " (t = " + to_text(t) +
                              "): the model's magnitudes overflow double precision",
                          t, {});
  ConstraintRank r;
  // a stop's rows (unilateral, open) are not equations of the motion
  const std::vector<int>& unilateral = model.switched_rows();  // (and stuck contacts')
  r.equations = model.n_constraints() - int(unilateral.size());
  r.coordinates = model.n_coordinates();
  if (r.equations == 0) return r;
  Data d(model);
  assemble_jacobian(model, d, q.data(), t);
  const SpMat JT = d.Phi_q.transpose();
  double max_norm = 0.0;
  for (int c = 0; c < JT.cols(); ++c) {
    // an entry past 1e150 overflows what a rank or a solve forms of it (its
    // square): a point 1e200 m from its body, a multiplier of 1e300
    double largest = 0.0;
    for (SpMat::InnerIterator it(JT, c); it; ++it)
      largest = std::isnan(largest + it.value()) ? NAN : std::max(largest, std::abs(it.value()));
    if (!(largest <= 1e150))
      throw AssemblyError("the equations of '" + model.constraint_name_of_row(c) + "' overflow double precision at t = " +
                              to_text(t) + ": their Jacobian has entries up to " + to_text(largest) +
                              ", whose squares, which a solve forms, are past 1e300. A point, length, ratio or "
                              "multiplier of it, or a body's position, is out of range",
                          t, {});
    max_norm = std::max(max_norm, JT.col(c).norm());
  }
  const SparseQR qr(JT, tol * std::max(max_norm, 1e-300));
  if (!qr.ok()) throw std::runtime_error("lagmb: sparse QR of Phi_q^T failed");
  r.rank = qr.rank();
  for (int row : qr.dependent_columns())
    if (!std::binary_search(unilateral.begin(), unilateral.end(), row)) r.dependent_rows.push_back(row);
  return r;
}

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
      q1 = solve_positions(model, d, kkt, q0 + dq + dt * drive, t1);
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
    : model_(model), r_(std::move(redundancy)), full_(model, &run, Data::Rows::kEvery) {}

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

}  // namespace lagmb
