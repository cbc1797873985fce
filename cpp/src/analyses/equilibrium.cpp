#include "lagmb/analyses/equilibrium.hpp"

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "assembly/saddle_point.hpp"
#include "lagmb/model/coordinates.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/interrupt.hpp"
#include "lagmb/analyses/linearization.hpp"
#include "lagmb/analyses/redundancy.hpp"
#include "lagmb/solvers/sparse_qr.hpp"
#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/analyses/diagnosis.hpp"
#include "lagmb/errors.hpp"

namespace lagmb {

namespace {

bool is_dropped(const Data& d, int row) {
  return std::binary_search(d.dropped_rows().begin(), d.dropped_rows().end(), row);
}

/// The state of the Newton iteration at (q, lam).
struct Residual {
  VecX f1;  // Q - Phi_q^T lam
  VecX f2;  // Phi
  double merit = INFINITY;
};

class EquilibriumSolver {
 public:
  EquilibriumSolver(const Model& model, double t)
      : model_(model),
        d_(model),
        t_(t),
        n_(model.n_coordinates()),
        m_(model.n_constraints()),
        saddle_(model, {0, 0, 0, n_, n_}) {
    v0_ = VecX::Zero(n_);
    K_ = saddle_.build_square(diagonal_);  // the pattern once; values each step
  }

  Data& data() { return d_; }

  /// Evaluates F at (q, lam) (leaves Phi_q and Q in d_).
  void residual(const VecX& q, const VecX& lam, Residual& r) {
    assemble_constraints(model_, d_, q.data(), t_);
    assemble_jacobian(model_, d_, q.data(), t_);
    assemble_forces(model_, d_, q.data(), v0_.data(), t_);
    r.f1 = d_.Q;
    add_jacobian_transpose_times(d_, (-lam).eval().data(), r.f1.data());
    r.f2 = d_.Phi;
    r.merit = (r.f1 / force_scale).squaredNorm() + (r.f2 / length_scale).squaredNorm();
    if (!std::isfinite(r.merit)) r.merit = INFINITY;
  }

  /// Least-squares multipliers of Phi_q^T lam = Q at q, and the unbalanced rest Q - Phi_q^T lam.
  VecX balance(const VecX& q, VecX& unbalanced) {
    assemble_jacobian(model_, d_, q.data(), t_);
    assemble_forces(model_, d_, q.data(), v0_.data(), t_);
    VecX lam = VecX::Zero(m_);
    if (m_ > 0) {
      const SparseQR qr(d_.Phi_q.transpose());
      if (qr.ok()) {
        lam = qr.solve(d_.Q);
        if (!lam.allFinite()) lam.setZero();
      }
    }
    unbalanced = d_.Q;
    add_jacobian_transpose_times(d_, (-lam).eval().data(), unbalanced.data());
    return lam;
  }

  /// Solves the Newton system at (q, lam) (Phi_q from the last residual()),
  /// with mu added to the diagonal of the stiffness block (0: plain Newton):
  ///   [ (Phi_q^T lam)_q - Q_q + mu I   Phi_q^T ] [dq  ]   [ Q - Phi_q^T lam ]
  ///   [ Phi_q                          D       ] [dlam] = [ -Phi            ]
  /// the saddle-point block at rest (T0 with s = 1, c = 0, a = 0); D is 1 on
  /// the rows left out as redundant (their dlam = 0), else 0.
  bool newton_step(const VecX& q, const VecX& lam, const Residual& r, double mu, VecX& dq, VecX& dlam) {
    double* x = K_.valuePtr();
    K_.coeffs().setZero();
    saddle_.add_tangent(d_, x, q.data(), v0_.data(), t_, lam.data(), v0_.data(), 1.0, 0.0);
    const std::vector<int>&G = saddle_.jacobian, &GT = saddle_.jacobian_t;
    for (size_t k = 0; k < G.size(); ++k) x[G[k]] = x[GT[k]] = d_.Phi_q.valuePtr()[k];
    for (int i = 0; i < n_; ++i) x[diagonal_[i]] += mu;
    for (int row = 0; row < m_; ++row)
      if (is_dropped(d_, row)) x[diagonal_[n_ + row]] = 1.0;
    stiffness_size = 0.0;
    for (int c = 0; c < d_.H.outerSize(); ++c)
      for (SpMat::InnerIterator it(d_.H, c); it; ++it) stiffness_size = std::max(stiffness_size, std::abs(it.value()));
    if (!model_.state_dependent_forces().empty())
      for (int c = 0; c < d_.Q_q.outerSize(); ++c)
        for (SpMat::InnerIterator it(d_.Q_q, c); it; ++it)
          stiffness_size = std::max(stiffness_size, std::abs(it.value()));
    if (!lu_.compute(K_)) return false;
    VecX rhs(n_ + m_);
    rhs << r.f1, -r.f2;
    VecX x_new;
    lu_.solve(rhs, x_new);
    if (!x_new.allFinite()) return false;
    dq = x_new.head(n_);
    dlam = x_new.tail(m_);
    return true;
  }

  double force_scale = 1.0, length_scale = 1.0;
  double stiffness_size = 0.0;  // max |entry| of H - Q_q at the last newton_step

 private:
  const Model& model_;
  Data d_;
  double t_;
  int n_, m_;
  VecX v0_;  // at rest: velocities and accelerations 0
  SaddlePoint saddle_;
  SpMat K_;
  std::vector<int> diagonal_;  // slots of K_'s diagonal
  SupernodalLU lu_;
};

/// The largest entries of a generalized force, by coordinate.
std::vector<std::pair<std::string, double>> largest(const Model& model, const VecX& f, double floor) {
  std::vector<std::pair<std::string, double>> out;
  std::vector<int> idx(f.size());
  for (int i = 0; i < f.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](int a, int b) { return std::abs(f[a]) > std::abs(f[b]); });
  for (int i : idx) {
    if (!(std::abs(f[i]) > floor) || out.size() >= 4) break;
    out.emplace_back(coordinate_label(model, i), f[i]);
  }
  return out;
}

[[noreturn]] void no_equilibrium(const Model& model, EquilibriumSolver& solver, const VecX& q, double t,
                                 int iterations, const std::string& why) {
  VecX unbalanced;
  solver.balance(q, unbalanced);
  auto worst = largest(model, unbalanced, 1e-9 * std::max(solver.force_scale, 1e-300));
  std::ostringstream s;
  s << "no static equilibrium found at t = " << t << " (" << why << ", after " << iterations
    << " Newton iterations).";
  if (!worst.empty()) {
    s << " Largest unbalanced generalized forces (Q - Phi_q^T lam, N or N m) at the last configuration:";
    for (size_t k = 0; k < worst.size(); ++k)
      s << (k ? ", " : " ") << worst[k].first << " " << worst[k].second;
    s << ". Nothing holds these coordinates against the applied forces there: a free body under gravity, "
      << "or a load larger than the springs and joints can balance.";
  }
  throw EquilibriumError(s.str(), std::move(worst));
}

/// Stability: eigenvalues of the tangent stiffness K = (Phi_q^T lam)_q - Q_q
/// (tangent_at_rest, linearization.hpp) reduced to the null space of Phi_q.
void stability(const Model& model, const Data& d, double t, Equilibrium& e) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  e.stability_checked = true;
  const RestTangent rest = tangent_at_rest(model, e.q, e.lam, t, d.dropped_rows());
  const Eigen::MatrixXd K = 0.5 * (rest.K + rest.K.transpose());
  Eigen::MatrixXd Z;
  if (m == 0) {
    Z = Eigen::MatrixXd::Identity(n, n);
  } else {
    const Eigen::MatrixXd JT = rest.Phi_q.transpose();  // n x m
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(JT);
    qr.setThreshold(1e-10);
    const int rank = int(qr.rank());
    const Eigen::MatrixXd Qfull = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
    Z = Qfull.rightCols(n - rank);
  }
  if (Z.cols() == 0) {
    e.stable = true;  // fully constrained: nothing can move
    return;
  }
  const Eigen::MatrixXd Kr = Z.transpose() * K * Z;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Kr);
  e.stiffness_eigenvalues = eig.eigenvalues();
  e.softest_mode = Z * eig.eigenvectors().col(0);
  const double scale = std::max(e.stiffness_eigenvalues.cwiseAbs().maxCoeff(), K.cwiseAbs().maxCoeff());
  e.stable = e.stiffness_eigenvalues[0] > 1e-9 * scale;
}

}  // namespace

Equilibrium find_equilibrium(const Model& model, const EquilibriumOptions& o) {
  if (!model.finalized()) throw ModelError("equilibrium: the model is not finalized");
  if (model.n_coordinates() == 0) throw ModelError("equilibrium: the model has no bodies");
  if (!std::isfinite(o.t)) throw ModelError("equilibrium: t is not finite");
  if (!(std::isfinite(o.tol) && o.tol > 0 && o.tol < 1))
    throw ModelError("equilibrium: tol must be in (0, 1), got " + std::to_string(o.tol));
  if (o.max_iterations < 1)
    throw ModelError("equilibrium: max_iterations must be at least 1, got " + std::to_string(o.max_iterations));
  const int n = model.n_coordinates(), m = model.n_constraints();

  // start: the assembled initial configuration, least-squares multipliers
  EquilibriumSolver solver(model, o.t);
  VecX q;
  {
    // every row assembled, then the rows redundant there left out (redundancy.hpp)
    AugmentedSystem kkt(model);
    q = solve_positions(model, solver.data(), kkt, model.initial_q(), o.t);
    solver.data().drop_rows(model, find_redundancy(model, solver.data(), kkt, q, o.t).rows);
  }
  VecX unbalanced;
  VecX lam = solver.balance(q, unbalanced);

  // scales: forces by the applied load, lengths by the model's extent
  // (centres of mass and the points elements attach to)
  VecX per_unit = VecX::Zero(n);  // angle per unit of a coordinate that turns
  for (const auto& [i, angle] : turning_coordinates(model)) per_unit[i] = angle;
  double extent = 0.0;
  for (int k = 0; k < int(model.bodies().size()); ++k) {
    const Body& b = model.body(k);
    const int positions = b.spatial ? 3 : 2;
    extent = std::max(extent, max_abs(q.segment(b.first_coord, positions)));
    for (const Vec3& s : model.outline(k)) extent = std::max(extent, s.norm());
  }
  solver.force_scale = std::max(max_abs(solver.data().Q), 1e-300);
  solver.length_scale = std::max(extent, 1e-3);
  // a turn of 0.5 rad; half the model's extent in a position (none when
  // everything sits at the origin: no length to go by)
  auto max_step = [&](int i) {
    if (per_unit[i] > 0.0) return 0.5 / per_unit[i];
    return extent > 0.0 ? 0.5 * extent : INFINITY;
  };

  Residual r, r_try;
  solver.residual(q, lam, r);
  VecX dq(n), dlam(m), q_try(n), lam_try(m);
  int it = 0;
  auto converged = [&](const Residual& x, const VecX& qx) {
    return max_abs(x.f2) <= o.tol * (1.0 + max_abs(qx)) && max_abs(x.f1) <= o.tol * solver.force_scale;
  };
  while (!converged(r, q)) {
    poll_interrupt();
    if (it >= o.max_iterations) no_equilibrium(model, solver, q, o.t, it, "Newton did not converge");
    ++it;
    if (!solver.newton_step(q, lam, r, 0.0, dq, dlam)) {
      // singular stiffness (e.g. a spring at its free length gives no lateral stiffness):
      // regularize the stiffness block, Levenberg-Marquardt style, and let the line search judge
      double mu = 1e-6 * std::max(solver.stiffness_size, solver.force_scale / solver.length_scale);
      bool solved = false;
      for (int attempt = 0; attempt < 4 && !solved; ++attempt, mu *= 100.0)
        solved = solver.newton_step(q, lam, r, mu, dq, dlam);
      if (!solved) no_equilibrium(model, solver, q, o.t, it, "the Newton matrix is singular");
    }
    // step limitation
    double limit = 1.0;
    for (int i = 0; i < n; ++i) {
      const double cap = max_step(i);
      if (std::abs(dq[i]) * limit > cap) limit = cap / std::abs(dq[i]);
    }
    const bool tiny = max_abs(dq) <= o.tol * (1.0 + max_abs(q)) &&
                      max_abs(dlam) <= o.tol * (1.0 + max_abs(lam));
    // line search on the merit
    double s = limit;
    bool accepted = false;
    for (int halving = 0; halving < 30; ++halving, s *= 0.5) {
      q_try = q + s * dq;
      lam_try = lam + s * dlam;
      solver.residual(q_try, lam_try, r_try);
      if (r_try.merit < r.merit || (tiny && r_try.merit <= r.merit)) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      solver.residual(q, lam, r);
      // at the rounding floor of the residual: as converged as it gets
      if (max_abs(r.f2) <= 1e3 * o.tol * (1.0 + max_abs(q)) && max_abs(r.f1) <= 1e3 * o.tol * solver.force_scale)
        break;
      no_equilibrium(model, solver, q, o.t, it, "no Newton step reduces the unbalanced forces");
    }
    q.swap(q_try);
    lam.swap(lam_try);
    std::swap(r, r_try);
    if (tiny) break;  // the step is at rounding level: converged
  }

  Equilibrium e;
  e.q = q;
  e.lam = lam;
  e.iterations = it;
  e.force_residual = max_abs(r.f1);
  e.constraint_residual = max_abs(r.f2);
  // what is returned holds finite numbers (a force of 1e308 kg x g overflows)
  if (!std::isfinite(e.force_residual) || !std::isfinite(e.constraint_residual) || !q.allFinite() ||
      !lam.allFinite()) {
    const VecX rest = VecX::Zero(model.n_coordinates());
    throw EquilibriumError("equilibrium: the forces at the position found are not finite: " +
                           non_finite_source(model, solver.data(), q.data(), rest.data(), o.t));
  }
  e.dropped_rows = solver.data().dropped_rows();  // (redundant rows and the stops' open rows)
  if (o.stability) stability(model, solver.data(), o.t, e);
  // the search holds no stop: an equilibrium beyond a limit is not one the
  // mechanism can reach
  if (!model.unilateral_rows().empty()) {
    Data gaps(model);
    gaps.close_rows(model, model.unilateral_rows());
    assemble_constraints(model, gaps, q.data(), o.t);
    for (const auto& g : model.constraint_groups()) {
      if (!g->unilateral()) continue;
      for (int k = 0; k < g->size(); ++k)
        for (int r = 0; r < g->rows(k); ++r) {
          const double gap = gaps.Phi[g->placement(k).row0 + r];
          if (!g->unilateral_row(k, r).exists || !(gap < 0.0)) continue;
          std::ostringstream s;
          s << "the static equilibrium found at t = " << o.t << " lies beyond the " << g->unilateral_row(k, r).label
            << " limit of '" << g->name(k) << "' (by " << -gap << "): the search does not hold stops, so this "
            << "mechanism has no equilibrium it can find within its limits (a run with damping comes to rest on "
            << "the stop).";
          throw EquilibriumError(s.str());
        }
    }
  }
  if (e.stability_checked && !e.stable && !o.allow_unstable && e.stiffness_eigenvalues.size() && e.stiffness_eigenvalues[0] < 0 &&
      e.stiffness_eigenvalues[0] < -1e-9 * e.stiffness_eigenvalues.cwiseAbs().maxCoeff()) {
    std::ostringstream s;
    s << "the static equilibrium found at t = " << o.t << " is unstable: the tangent stiffness reduced to the "
      << "motions the joints allow has the negative eigenvalue " << e.stiffness_eigenvalues[0]
      << " (N/m or N m/rad), so a small displacement grows. Its mode moves";
    const auto mode = largest(model, e.softest_mode, 0.3 * max_abs(e.softest_mode));
    for (size_t k = 0; k < mode.size(); ++k) s << (k ? ", " : " ") << mode[k].first << " (" << mode[k].second << ")";
    s << ". Pass allow_unstable=True to get it anyway, or start nearer a stable position.";
    throw EquilibriumError(s.str());
  }
  return e;
}

}  // namespace lagmb
