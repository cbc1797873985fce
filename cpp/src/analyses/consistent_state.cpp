#include "lagmb/analyses/consistent_state.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>

#include "lagmb/analyses/diagnosis.hpp"
#include "lagmb/analyses/redundancy.hpp"
#include "lagmb/model/coordinates.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/interrupt.hpp"

namespace lagmb {

namespace {

/// The elements whose rows of Phi exceed tol, each with its largest |Phi|,
/// the largest first.
std::vector<std::pair<std::string, double>> violated(const Model& model, const VecX& Phi, double tol) {
  std::map<std::string, double> worst;
  for (int r = 0; r < Phi.size(); ++r) {
    const double e = std::abs(Phi[r]);
    if (!(e <= tol)) {
      double& w = worst[model.constraint_name_of_row(r)];
      w = std::max(w, std::isfinite(e) ? e : INFINITY);
    }
  }
  std::vector<std::pair<std::string, double>> v(worst.begin(), worst.end());
  std::sort(v.begin(), v.end(), [](auto& a, auto& b) { return a.second > b.second; });
  return v;
}

/// AssemblyError blaming the elements violated in the given configuration
/// (`at_start`, when known: what the user's positions break), and saying
/// which are still violated where Newton stopped (d.Phi), which reflects
/// where the iteration ended more than what was wrong.
[[noreturn]] void fail_assembly(const Model& model, const Data& d, double t, double tol, const std::string& why,
                                const VecX* at_start = nullptr) {
  std::vector<std::pair<std::string, double>> blamed = violated(model, at_start ? *at_start : d.Phi, tol);
  std::ostringstream s;
  s << "the model cannot be assembled at t = " << t << " (" << why << "); constraint equations violated "
    << (at_start ? "by the given positions:" : "still:");
  for (const auto& [name, e] : blamed) s << " '" << name << "' (|Phi| = " << e << ")";
  if (at_start) {
    s << "; still violated where Newton stopped:";
    for (const auto& [name, e] : violated(model, d.Phi, tol)) s << " '" << name << "' (|Phi| = " << e << ")";
  }
  s << ". Check the joint points and the initial positions.";
  throw AssemblyError(s.str(), t, std::move(blamed));
}

}  // namespace

/// Newton least-change on Phi(q, t) = 0 in the M-metric,
///   [M Phi_q^T; Phi_q 0] [dq; kappa] = [0; -Phi],
/// each step halved until max |Phi| decreases, with three safeguards:
///  - a step turns no body by more than 0.5 rad (an Euler parameter by 0.25),
///    so that a long way round is taken in turns the linear model still
///    describes (a full step could land at a collinear, singular position);
///  - each trial's Euler parameters are scaled back to unit length: a step
///    along p itself "stretches" the body (A(p) s grows with p^T p), which the
///    linear model of a distance row takes for a motion, and the rest of the
///    violation then sat in the normalization rows, blamed for it;
///  - where no step reduces |Phi| short of a solution (a singular position
///    where the linear model cannot close the loop: a four-bar started with
///    all its links on one line), the configuration is moved by 1 % of its
///    size along a random direction the joints allow (M-orthogonal to the
///    rows, from a fixed seed: the same model assembles the same way) and
///    Newton goes on; at most 8 times.
VecX solve_positions(const Model& model, Data& d, AugmentedSystem& kkt, VecX q, double t) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  VecX zero_n = VecX::Zero(n), zero_m = VecX::Zero(m), dq(n), kappa(m), q_try(n), z(n);
  const double scale = 1.0 + (n ? q.lpNorm<Eigen::Infinity>() : 0.0);
  const double tol = 1e-12 * scale;
  const std::vector<std::pair<int, double>> turns = turning_coordinates(model);
  const double max_turn = 0.5;  // rad per Newton step
  auto unit_euler_parameters = [&](VecX& x) {
    for (const Body& b : model.bodies())
      if (b.spatial) {
        auto p = x.segment<4>(b.first_coord + 3);
        const double norm = p.norm();
        if (norm > 0.0 && std::isfinite(norm)) p /= norm;
      }
  };
  // the size of the mechanism: the spread of the bodies' centres and the origin
  auto spread = [&](const VecX& x) {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    for (const Body& b : model.bodies())
      for (int k = 0; k < (b.spatial ? 3 : 2); ++k) {
        lo[k] = std::min(lo[k], x[b.first_coord + k]);
        hi[k] = std::max(hi[k], x[b.first_coord + k]);
      }
    const double e = (hi - lo).maxCoeff();
    return std::isfinite(e) ? std::max(e, 0.1) : 0.1;
  };
  std::mt19937 random(20261124u);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);

  assemble_constraints(model, d, q.data(), t);
  const VecX phi_given = d.Phi;  // what the given positions break: the blame if Newton fails
  double err = max_abs(d.Phi);
  const int max_iter = 100, max_moves = 8;
  int iterations = 0, moves = 0;
  while (!(err <= tol)) {  // (NaN: not assembled)
    poll_interrupt();
    if (!std::isfinite(err))
      fail_assembly(model, d, t, 1e3 * tol, "the constraint equations are not finite: they overflow double precision",
                    &phi_given);
    if (iterations++ >= max_iter) fail_assembly(model, d, t, 1e3 * tol, "Newton did not converge", &phi_given);
    assemble_jacobian(model, d, q.data(), t);
    if (!kkt.factorize(d)) fail_assembly(model, d, t, 1e3 * tol, "singular augmented matrix", &phi_given);
    kkt.solve(zero_n, -d.Phi, dq, kappa);
    double step = 1.0, err_try = INFINITY;
    for (const auto& [i, per_unit] : turns)
      if (per_unit * std::abs(dq[i]) * step > max_turn) step = max_turn / (per_unit * std::abs(dq[i]));
    for (int halving = 0; halving < 12; ++halving, step *= 0.5) {
      q_try = q + step * dq;
      unit_euler_parameters(q_try);
      assemble_constraints(model, d, q_try.data(), t);
      err_try = max_abs(d.Phi);
      if (err_try < err) break;
    }
    if (!(err_try < err)) {
      // converged as far as rounding allows?
      if (err <= 1e-9 * scale) {
        assemble_constraints(model, d, q.data(), t);
        break;
      }
      // stuck where the linear model cannot close the loop: move along the
      // joints (kkt and M are those at q) and try again
      for (int i = 0; i < n; ++i) z[i] = uniform(random);
      kkt.solve(d.M * z, zero_m, dq, kappa);
      const double size = max_abs(dq);
      if (moves++ >= max_moves || !(size > 0.0) || !std::isfinite(size)) {
        assemble_constraints(model, d, q.data(), t);
        fail_assembly(model, d, t, 1e3 * tol, "no Newton step reduces |Phi|", &phi_given);
      }
      q_try = q + (1e-2 * spread(q) / size) * dq;
      unit_euler_parameters(q_try);
      assemble_constraints(model, d, q_try.data(), t);
      err_try = max_abs(d.Phi);
    }
    q = q_try;
    err = err_try;
  }
  return q;
}

ConsistentState make_consistent(const Model& model, Data& d, AugmentedSystem& kkt, VecX q,
                                VecX v, double t) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  ConsistentState s;
  VecX kappa(m);

  // 1. positions
  q = solve_positions(model, d, kkt, std::move(q), t);

  // 2. velocities: M-orthogonal projection onto Phi_q v = -Phi_t
  assemble_jacobian(model, d, q.data(), t);
  if (!kkt.factorize(d)) fail_assembly(model, d, t, INFINITY, "singular augmented matrix");
  assemble_phi_t(model, d, q.data(), t);
  VecX Mv(n);
  mass_times(d, v.data(), Mv.data());
  kkt.solve(Mv, -d.phi_t, v, kappa);

  // 3. accelerations and multipliers
  s.qdd.resize(n);
  s.lam.resize(m);
  assemble_forces(model, d, q.data(), v.data(), t);
  assemble_gamma(model, d, q.data(), v.data(), t);
  kkt.solve(d.Q, d.gamma, s.qdd, s.lam);
  if (!model.friction_groups().empty()) solve_friction(model, d, kkt, q.data(), v.data(), t, s.qdd, s.lam);
  s.q = std::move(q);
  s.v = std::move(v);
  s.dropped_rows = d.redundant_rows();
  // a start, a restart after an input's jump or an event: never hand an
  // integrator what it cannot weigh
  if (!(s.q.allFinite() && s.v.allFinite() && s.qdd.allFinite() && s.lam.allFinite())) {
    std::ostringstream why;
    why << "the consistent start at t = " << t << " is not finite: " << non_finite_source(model, d, s.q.data(), s.v.data(), t);
    throw AssemblyError(why.str(), t, {});
  }
  return s;
}


void solve_accelerations(const Model& model, Data& d, AugmentedSystem& kkt, const double* q,
                         const double* v, double t, double* qdd, double* lam) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  assemble_jacobian(model, d, q, t);
  if (!kkt.factorize(d))
    throw SimulationError("the augmented matrix is singular at t = " + to_text(t), t);
  assemble_forces(model, d, q, v, t);
  assemble_gamma(model, d, q, v, t);
  VecX a(n), l(m);
  kkt.solve(d.Q, d.gamma, a, l);
  if (!model.friction_groups().empty()) solve_friction(model, d, kkt, q, v, t, a, l);
  Eigen::Map<VecX>(qdd, n) = a;
  Eigen::Map<VecX>(lam, m) = l;
}

void iterate_friction_load(const Model& model, Data& d, const double* q, const double* v, double t, VecX& lam,
                           const std::function<void(VecX& lam)>& solve) {
  const int max_iterations = 2000;  // linear convergence; a gain near 1 needs many
  VecX& Q0 = d.friction_Q0;
  VecX& previous = d.friction_lam;
  Q0 = d.Q;
  double change = 0.0;
  for (int it = 0; it < max_iterations; ++it) {
    poll_interrupt();
    previous = lam;
    d.Q = Q0;
    add_friction_forces(model, d, q, v, previous.data());
    solve(lam);
    change = lam.size() ? (lam - previous).lpNorm<Eigen::Infinity>() : 0.0;
    if (!std::isfinite(change)) break;
    if (change <= 1e-12 * (lam.lpNorm<Eigen::Infinity>() + model.mass_scale())) return;
  }
  std::ostringstream s;
  s << "joint friction: the multipliers do not converge at t = " << t << " (fixed-point iteration: change "
    << change << " after " << max_iterations
    << " iterations). The friction load comes from the joint reactions, which the friction itself "
       "changes; with friction coefficients this large (mu times pin radius or moment arm) that loop "
       "locks. Reduce mu or pin_radius.";
  throw SimulationError(s.str(), t);
}

void solve_friction(const Model& model, Data& d, AugmentedSystem& kkt, const double* q, const double* v,
                    double t, VecX& qdd, VecX& lam) {
  // the matrix does not depend on lam, only the right side: one factorization
  iterate_friction_load(model, d, q, v, t, lam, [&](VecX& l) { kkt.solve(d.Q, d.gamma, qdd, l); });
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
  q = solve_positions(model, d, kkt, std::move(q), t);
  Redundancy r = find_redundancy(model, d, kkt, q, t);
  d.drop_rows(model, r.rows);
  ConsistentState s = make_consistent(model, d, kkt, std::move(q), std::move(v), t);
  if (!r.rows.empty()) {
    // kkt holds the kept rows at s.q; the dropped ones from a full evaluation
    Data full(model, &d, Data::Rows::kEvery);
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
