#include "lagmb/analyses/kinematics.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

#include "lagmb/model/coordinates.hpp"
#include "lagmb/model/joint_turns.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/analyses/diagnosis.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/options.hpp"
#include "lagmb/interrupt.hpp"
#include "lagmb/analyses/redundancy.hpp"

namespace lagmb {

Vec3 principal_moments(const Mat3& J) { return Eigen::SelfAdjointEigenSolver<Mat3>(J).eigenvalues(); }

std::vector<int> massless_bodies(const Model& model) {
  std::vector<int> out;
  for (size_t i = 0; i < model.bodies().size(); ++i) {
    const Body& b = model.bodies()[i];
    // (a spatial body needs every principal moment > 0: a rod without a moment about its axis
    // leaves that spin undetermined)
    if (!b.has_mass_and_inertia()) out.push_back(int(i));
  }
  return out;
}

void require_determined_motion(const Model& model, const VecX& q, double t, const std::string& who) {
  const std::vector<int> massless = massless_bodies(model);
  if (massless.empty()) return;
  // regular iff M is positive definite on the motions the constraints allow (the null space N of
  // Phi_q): an LU of a singular matrix may still "succeed" on round-off pivots, so the test is N^T M N's
  // eigenvalues (dense, at the start only, and only for a model with massless bodies)
  Data d(model);
  assemble_mass(model, d, q.data());
  assemble_jacobian(model, d, q.data(), t);
  const int n = model.n_coordinates();
  Eigen::MatrixXd N = Eigen::MatrixXd::Identity(n, n);
  if (model.n_constraints() > 0) {
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Eigen::MatrixXd(d.Phi_q).transpose());
    qr.setThreshold(1e-10);
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
    N = Q.rightCols(n - int(qr.rank()));
  }
  if (N.cols() == 0) return;  // (nothing moves)
  const Eigen::MatrixXd reduced = N.transpose() * Eigen::MatrixXd(d.M) * N;
  const VecX e = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (reduced + reduced.transpose())).eigenvalues();
  if (e[0] > 1e-12 * std::abs(e[e.size() - 1])) return;
  std::ostringstream s;
  s << who << ": the motion is not determined by the forces: the augmented matrix [M Phi_q^T; Phi_q 0] is "
    << "singular, so a body without mass or inertia is free to move where no mass follows it (massless:";
  for (size_t k = 0; k < massless.size() && k < 4; ++k) {
    const Body& b = model.body(massless[k]);
    s << " '" << b.name << "' (mass " << b.mass;
    if (b.spatial) s << ", principal moments " << to_text(principal_moments(b.inertia_tensor));
    else if (!b.particle) s << ", inertia " << b.inertia;
    s << ")";
  }
  if (massless.size() > 4) s << " and " << massless.size() - 4 << " more";
  s << "). Give such a body mass and inertia, or join it to one that has them.";
  throw ModelError(s.str());
}

int degrees_of_freedom(const Model& model, double t) {
  if (!model.finalized()) throw ModelError("degrees_of_freedom: the model is not finalized");
  if (model.n_coordinates() == 0) throw ModelError("degrees_of_freedom: the model has no bodies");
  const int n = model.n_coordinates(), m = model.n_constraints();
  if (m == 0) return n;
  Data d(model);
  AugmentedSystem kkt(model);
  VecX q = model.initial_q();
  try {
    q = solve_positions(model, d, kkt, q, t);
  } catch (const SimulationError&) {
    return constraint_rank(model, q, t).degrees_of_freedom();  // the run itself will report the assembly
  } catch (const UserFunctionError&) {
    return constraint_rank(model, q, t).degrees_of_freedom();
  }
  // the generic rank near the assembled position (a singular start counts as its neighbours)
  // (a stop's rows, unilateral, are no equations of the motion)
  const int equations = m - int(model.switched_rows().size());
  return n - (equations - int(find_redundancy(model, d, kkt, q, t).rows.size()));
}

namespace {

/// The solve times: t0, the breakpoints inside (t0, t_end) and the outputs.
std::vector<double> solve_times(const Model& model, double t0, const std::vector<double>& t_out) {
  std::vector<double> t{t0};
  const double t_end = t_out.empty() ? t0 : t_out.back();
  for (double b : model.breakpoints())
    if (b > t0 && b < t_end) t.push_back(b);
  t.insert(t.end(), t_out.begin(), t_out.end());
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

/// Phi_q restricted to its independent rows (the rows the run does not drop
/// as redundant). At 0 DOF it is square (n x n) and invertible, so
/// positions, velocities and accelerations are solves with it and the
/// multipliers one solve with its transpose, lam = Phi_q^-T (Q - M a): half
/// the size of the augmented matrix [M Phi_q^T; Phi_q 0] and with no
/// regularization to refine away. The pattern and the ordering are fixed
/// once; factorize() is numeric only.
class SquareJacobian {
 public:
  /// Usable when the independent rows number exactly n.
  static bool applies(const Model& model, const std::vector<int>& dropped) {
    return model.n_constraints() - int(dropped.size()) == model.n_coordinates();
  }

  SquareJacobian(const Model& model, const std::vector<int>& dropped)
      : n_(model.n_coordinates()), m_(model.n_constraints()) {
    std::vector<int> compact(m_, 0);
    for (int r : dropped) compact[r] = -1;
    for (int r = 0; r < m_; ++r)
      if (compact[r] == 0) {
        compact[r] = int(row_of_.size());
        row_of_.push_back(r);
      }
    const SpMat& J = model.jacobian_pattern();
    SparsityPattern p(n_, n_);
    for (int c = 0; c < J.outerSize(); ++c)
      for (SpMat::InnerIterator it(J, c); it; ++it)
        if (compact[it.row()] >= 0) p.add(compact[it.row()], c);
    S_ = p.build();
    for (int c = 0; c < J.outerSize(); ++c)
      for (SpMat::InnerIterator it(J, c); it; ++it)
        slots_.push_back(compact[it.row()] >= 0 ? slot(S_, compact[it.row()], c) : -1);
    lu_.analyze(S_);
    b_.resize(n_);
    x_.resize(n_);
  }

  /// Factorizes the independent rows of Phi_q (pattern of the model's Jacobian).
  bool factorize(const SpMat& Phi_q) {
    double* s = S_.valuePtr();
    const double* j = Phi_q.valuePtr();
    for (size_t k = 0; k < slots_.size(); ++k)
      if (slots_[k] >= 0) s[slots_[k]] = j[k];
    ++factorizations_;
    return lu_.factorize(S_);
  }

  /// x (n) solving the independent rows of Phi_q x = b (b: m rows).
  void solve(const VecX& b, VecX& x) {
    for (int i = 0; i < n_; ++i) b_[i] = b[row_of_[i]];
    lu_.solve(b_, x);
  }

  /// lam (m) solving Phi_q^T lam = c with lam = 0 in the dropped rows.
  void solve_transpose(const VecX& c, VecX& lam) {
    lu_.solve_transposed(c, x_);
    lam.setZero(m_);
    for (int i = 0; i < n_; ++i) lam[row_of_[i]] = x_[i];
  }

  int factorizations() const { return factorizations_; }

 private:
  int n_, m_;
  std::vector<int> row_of_;  // compact row -> row of Phi
  std::vector<int> slots_;   // value k of Phi_q -> value of S_, -1 in dropped rows
  SpMat S_;
  SupernodalLU lu_;
  VecX b_, x_;
  int factorizations_ = 0;
};

/// One kinematic state and the work done to get it.
class KinematicSolver {
 public:
  KinematicSolver(const Model& model, Stats& stats)
      : model_(model), d_(model), kkt_(model), stats_(stats), n_(model.n_coordinates()), m_(model.n_constraints()) {
    zero_n_ = VecX::Zero(n_);
    kappa_.resize(m_);
    dq_.resize(n_);
  }

  /// Newton on Phi(q, t) = 0 from q (in place). Returns false if it does not
  /// converge in max_iter iterations or (guard) its first correction exceeds
  /// max_first. The factorization of an earlier Phi_q is reused (chord
  /// iterations) while it contracts well; it is refreshed at the current q
  /// when the contraction slows (ratio > 0.25), the guard trips or |Phi|
  /// stalls above rounding level.
  /// The analysis's run state (the joints' turns, model/joint_turns.hpp),
  /// which the elements read as in a dynamic run.
  double* run_state() { return d_.run->state.data(); }

  bool positions(VecX& q, double t, int max_iter, double max_first) {
    bool fresh = false;  // factorized at an iterate of this solve
    double previous = INFINITY;
    for (int it = 0; it < max_iter; ++it) {
      poll_interrupt();
      assemble_constraints(model_, d_, q.data(), t);
      ++stats_.residual_evals;
      ++stats_.newton_iterations;
      if (!d_.Phi.allFinite()) return false;
      if (!factorized_ && !refactor(q, t, fresh)) return false;
      correction();
      double step = dq_.allFinite() ? max_abs(dq_) : INFINITY;
      const bool slow = (it == 0 && step > max_first) || (it > 0 && step > 0.25 * previous) || !std::isfinite(step);
      if (slow && !fresh) {  // the old factorization is not good enough here: a Newton step
        if (!refactor(q, t, fresh)) return false;
        correction();
        step = dq_.allFinite() ? max_abs(dq_) : INFINITY;
      }
      if (!std::isfinite(step) || (it == 0 && step > max_first)) return false;
      q += dq_;
      // converged when the step, or the error left after it (estimated from the
      // contraction ratio, as in BDF codes), is at the tolerance
      const double ratio = it > 0 ? step / previous : 1.0;
      const double left = ratio < 0.5 ? step * ratio / (1.0 - ratio) : step;
      previous = step;
      if (step <= 1e-12 * (1.0 + max_abs(q)) || left <= 1e-13 * (1.0 + max_abs(q))) {
        // |Phi| must be at rounding level too: near a singular Phi_q the regularized
        // solve takes tiny least-squares steps toward a point that does not solve it
        assemble_constraints(model_, d_, q.data(), t);
        ++stats_.residual_evals;
        if (max_abs(d_.Phi) <= 1e-12 * (1.0 + max_abs(q))) return true;
        if (fresh) return false;
        factorized_ = false;  // stalled on an old factorization: refresh and go on
      }
    }
    return false;
  }

  /// v, then a (and lam with forces) at the solution (q, t) of positions().
  void rates(const VecX& q, double t, bool with_forces, VecX& v, VecX& a, VecX& lam) {
    assemble_jacobian(model_, d_, q.data(), t);  // exact Phi_q at q for the refinement
    ++stats_.jacobian_evals;
    assemble_phi_t(model_, d_, q.data(), t);
    if (square_) {
      solve_square(t, -d_.phi_t, v);
      assemble_gamma(model_, d_, q.data(), v.data(), t);
      solve_square(t, d_.gamma, a);
      if (with_forces) multipliers(q, v, t, a, lam);
      return;
    }
    const VecX Mv = d_.M * v;  // v: the prediction (irrelevant at 0 DOF); M at q
    solve_exact(t, Mv, -d_.phi_t, v, kappa_, false);
    assemble_gamma(model_, d_, q.data(), v.data(), t);
    if (with_forces) {
      assemble_forces(model_, d_, q.data(), v.data(), t);
      solve_exact(t, d_.Q, d_.gamma, a, lam, true);
    } else {
      solve_exact(t, zero_n_, d_.gamma, a, kappa_, false);
    }
  }

  /// Least-change assembly at t0 with every row, as the dynamic runs start;
  /// then the rows redundant there are dropped (redundancy.hpp), and at 0
  /// DOF the kept rows make the square Jacobian.
  VecX assemble(const VecX& q0, double t) {
    d_.drop_rows(model_, {});
    VecX q = solve_positions(model_, d_, kkt_, q0, t);
    redundancy = find_redundancy(model_, d_, kkt_, q, t);
    d_.drop_rows(model_, redundancy.rows);
    if (SquareJacobian::applies(model_, d_.dropped_rows()))
      square_ = std::make_unique<SquareJacobian>(model_, d_.dropped_rows());
    factorized_ = false;
    if (!redundancy.rows.empty()) {
      Data full(model_, &d_, Data::Rows::kEvery);
      assemble_jacobian(model_, full, q.data(), t);
      assemble_jacobian(model_, d_, q.data(), t);
      if (kkt_.factorize(d_)) name_partners(model_, full, kkt_, redundancy);
      else redundancy.partners.assign(redundancy.rows.size(), {model_.constraint_name_of_row(redundancy.rows[0])});
    }
    return q;
  }

  Redundancy redundancy;  // decided by assemble()

  /// Factorizations of the square Jacobian and of the augmented matrix.
  long element_evaluations() const { return d_.element_evaluations; }
  int jacobian_factorizations() const { return square_ ? square_->factorizations() : 0; }
  int augmented_factorizations() const { return kkt_.factorizations(); }

 private:
  bool refactor(const VecX& q, double t, bool& fresh) {
    assemble_jacobian(model_, d_, q.data(), t);
    ++stats_.jacobian_evals;
    factorized_ = square_ ? square_->factorize(d_.Phi_q) : kkt_.factorize(d_);
    fresh = factorized_;
    return factorized_;
  }

  /// dq_ = the Newton correction for d_.Phi with the current factorization.
  void correction() {
    if (square_) {
      d_.Phi = -d_.Phi;
      square_->solve(d_.Phi, dq_);
    } else {
      kkt_.solve(zero_n_, -d_.Phi, dq_, kappa_);
    }
  }

  /// Iterative refinement of x toward the exact solution of a linear system
  /// whose residual is residual(x) (m or n entries): corrections solve(r, c)
  /// with the current factorization, a fresh factorization at the exact
  /// Phi_q (in d_) when they stop contracting, until the residual is at the
  /// rounding level of `size`.
  template <class Solve, class Residual>
  void refine(double t, VecX& x, double size_b, const Solve& solve, const Residual& residual) {
    const double jmax = d_.Phi_q.nonZeros() ? Eigen::Map<const VecX>(d_.Phi_q.valuePtr(), d_.Phi_q.nonZeros())
                                                  .lpNorm<Eigen::Infinity>()
                                            : 0.0;
    double previous = INFINITY;
    bool refreshed = false;
    for (int it = 0; it < 16; ++it) {
      const VecX& r = residual(x);
      const double size = size_b + jmax * max_abs(x);
      const double res = max_abs(r);
      if (!(res > 1e-14 * size)) return;
      if (res > 0.25 * previous || it == 8) {
        if (res <= 1e-12 * size || refreshed) return;  // at the rounding floor
        if (!square_->factorize(d_.Phi_q))
          throw SimulationError("the constraint Jacobian is singular at t = " + std::to_string(t), t);
        factorized_ = refreshed = true;
        previous = INFINITY;
        solve(r, c1_);
        x += c1_;
        continue;
      }
      previous = res;
      solve(r, c1_);
      x += c1_;
    }
  }

  /// x solving Phi_q x = b (independent rows), Phi_q exact in d_.
  void solve_square(double t, const VecX& b, VecX& x) {
    square_->solve(b, x);
    refine(t, x, max_abs(b), [&](const VecX& r, VecX& c) { square_->solve(r, c); },
           [&](const VecX& y) -> const VecX& {
             r2_ = b;
             add_jacobian_times(d_, (-y).eval().data(), r2_.data());
             return r2_;
           });
  }

  /// Inverse dynamics: lam solving Phi_q^T lam = Q + Q_f(lam) - M a (joint
  /// friction, if any, by fixed point on the load it takes from lam).
  void multipliers(const VecX& q, const VecX& v, double t, const VecX& a, VecX& lam) {
    assemble_forces(model_, d_, q.data(), v.data(), t);
    const VecX inertia = d_.M * a;  // M at q (rates() assembled Phi_q there)
    const VecX base = d_.Q - inertia;
    auto solve_for = [&](const VecX& c) {
      square_->solve_transpose(c, lam);
      refine(t, lam, max_abs(c), [&](const VecX& r, VecX& x) { square_->solve_transpose(r, x); },
             [&](const VecX& y) -> const VecX& {
               r1_ = c;
               add_jacobian_transpose_times(d_, (-y).eval().data(), r1_.data());
               return r1_;
             });
    };
    solve_for(base);
    if (model_.friction_groups().empty()) return;
    iterate_friction_load(model_, d_, q.data(), v.data(), t, lam, [&](VecX&) { solve_for(d_.Q - inertia); });
  }

  /// [M Phi_q^T; Phi_q 0] [x1; x2] = [b1; b2] with Phi_q = d_.Phi_q (exact at
  /// q), by iterative refinement on the factorization of an earlier Phi_q;
  /// refactorized at q if that does not converge quickly.
  /// Without need_x2 only x1 is wanted: at 0 DOF it follows from the second
  /// block row alone (Phi_q x1 = b2), so only that residual is refined.
  void solve_exact(double t, const VecX& b1, const VecX& b2, VecX& x1, VecX& x2, bool need_x2) {
    const SpMat& M = d_.M;  // at q, with Phi_q
    const double jmax = d_.Phi_q.nonZeros() ? Eigen::Map<const VecX>(d_.Phi_q.valuePtr(), d_.Phi_q.nonZeros())
                                                  .lpNorm<Eigen::Infinity>()
                                            : 0.0;
    kkt_.solve(b1, b2, x1, x2);
    double previous = INFINITY;
    bool refreshed = false;
    for (int it = 0; it < 16; ++it) {
      r1_ = b1 - M * x1;
      add_jacobian_transpose_times(d_, (-x2).eval().data(), r1_.data());
      r2_ = b2;
      add_jacobian_times(d_, (-x1).eval().data(), r2_.data());
      // rounding level of the residual: sizes of the terms it is computed from
      const double size = max_abs(b1) + max_abs(b2) + max_abs(M * x1) + jmax * (max_abs(x1) + max_abs(x2));
      const double res = need_x2 ? std::max(max_abs(r1_), max_abs(r2_)) : max_abs(r2_);
      if (!(res > 1e-14 * size)) return;
      if (res > 0.25 * previous || it == 8) {
        if (res <= 1e-12 * size || refreshed) return;  // stalled at the rounding floor
        // the old factorization is too far off: a fresh one, and refine on it
        factorized_ = kkt_.factorize(d_);  // d_.Phi_q is at q already
        if (!factorized_) throw SimulationError("the augmented matrix is singular at t = " + std::to_string(t), t);
        refreshed = true;
        kkt_.solve(b1, b2, x1, x2);
        previous = INFINITY;
        continue;
      }
      previous = res;
      kkt_.solve(r1_, r2_, c1_, c2_);
      x1 += c1_;
      x2 += c2_;
    }
  }

  const Model& model_;
  Data d_;
  AugmentedSystem kkt_;
  Stats& stats_;
  int n_, m_;
  bool factorized_ = false;
  std::unique_ptr<SquareJacobian> square_;  // at 0 DOF (kept rows: n)
  VecX zero_n_, kappa_, dq_, r1_, r2_, c1_, c2_;
};

}  // namespace

Trajectory kinematic_analysis(const Model& model, double t0, const std::vector<double>& t_out,
                              bool inverse_dynamics, const std::function<void(double)>& progress,
                              double progress_interval, long max_steps) {
  if (!model.finalized()) throw ModelError("kinematic_analysis: the model is not finalized");
  const auto wall0 = std::chrono::steady_clock::now();
  const int n = model.n_coordinates(), m = model.n_constraints();
  Trajectory tr;
  tr.n = n;
  tr.m = m;
  tr.state_size = model.run_state_size();
  tr.stats.analysis = name_of(inverse_dynamics ? Analysis::kInverseDynamics : Analysis::kKinematic);
  tr.stats.formulation = "kinematic";
  tr.stats.method_choice = "none: a kinematic analysis integrates no equations of motion";
  tr.stats.integrator = "newton";
  tr.stats.method = "kinematic";
  tr.t.reserve(t_out.size());
  tr.q.reserve(t_out.size() * n);
  tr.v.reserve(t_out.size() * n);
  tr.a.reserve(t_out.size() * n);
  tr.lam.reserve(t_out.size() * m);
  KinematicSolver* solver_ptr = nullptr;
  auto finish = [&] {
    if (solver_ptr) {
      tr.stats.lu_factorizations = solver_ptr->jacobian_factorizations();
      tr.stats.element_evaluations = solver_ptr->element_evaluations();
      tr.stats.augmented_factorizations = solver_ptr->augmented_factorizations();
    }
    tr.stats.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  };

  KinematicSolver solver(model, tr.stats);
  solver_ptr = &solver;
  VecX q(n), v = VecX::Zero(n), a = VecX::Zero(n), lam = VecX::Zero(m);
  VecX lam_nan = VecX::Constant(m, NAN);
  size_t k = 0;  // next output
  std::unique_ptr<RedundancyWatch> watch;
  std::string violated;
  auto record = [&](double t) {
    if (watch && !(violated = watch->violation(q.data(), t)).empty()) return;  // fail() reports it
    tr.t.push_back(t);
    tr.q.insert(tr.q.end(), q.data(), q.data() + n);
    tr.v.insert(tr.v.end(), v.data(), v.data() + n);
    tr.a.insert(tr.a.end(), a.data(), a.data() + n);
    const VecX& l = inverse_dynamics ? lam : lam_nan;
    tr.lam.insert(tr.lam.end(), l.data(), l.data() + m);
    tr.run_state.insert(tr.run_state.end(), solver.run_state(), solver.run_state() + model.run_state_size());
  };
  auto is_output = [&](double t) { return k < t_out.size() && t_out[k] == t; };

  // t0: least-change assembly from the given positions, as the dynamic runs start
  try {
    q = solver.assemble(model.initial_q(), t0);
  } catch (const UserFunctionError& e) {
    throw SimulationError(e.what(), t0);
  }
  tr.dropped_rows = solver.redundancy.rows;
  if (!tr.dropped_rows.empty()) watch = std::make_unique<RedundancyWatch>(model, Data(model), solver.redundancy);
  double t = t0;
  // diagnose: ask the Jacobian why Newton failed (not when the cause is known)
  auto fail = [&](const std::string& why, bool diagnose = true) {
    finish();
    std::ostringstream msg;
    msg << "kinematic analysis: " << why
        << (diagnose && violated.empty() ? diagnose_failure(model, q, t, tr.dropped_rows) : "")
        << " Outputs up to t = " << (tr.t.empty() ? t0 : tr.t.back()) << " are kept in the partial result.";
    throw SimulationError(msg.str(), t, std::move(tr));
  };

  // the joints' turns, counted at every sub-step as a dynamic run counts them
  auto count = [&](double dt) {
    if (const TurnCounter* c = count_turns(model, q.data(), v.data(), dt, solver.run_state()))
      fail("joint '" + c->joint + "' turned by half a turn or more in one sub-step after t = " + std::to_string(t) +
               ": the elements that act on its angle read it within half a turn of the last sub-step's.",
           false);
  };

  // a sub-step turns no body by more than 0.25 rad (predicted): the Newton
  // start then stays near the branch it came from, and angles stay continuous
  const std::vector<std::pair<int, double>> angles = turning_coordinates(model);
  auto angle_step = [&](const VecX& vel, const VecX& acc) {
    double w = 0.0, al = 0.0;
    for (const auto& [i, per] : angles) {
      w = std::max(w, per * std::abs(vel[i]));
      al = std::max(al, per * std::abs(acc[i]));
    }
    const double root = w + std::sqrt(w * w + 0.5 * al);  // w h + al h^2 / 2 = 0.25
    return root > 0 ? 0.5 / root : INFINITY;
  };
  const std::vector<double> times = solve_times(model, t0, t_out);
  long sub_steps = 0;
  auto clock = std::chrono::steady_clock::now();
  try {
    if (!solver.positions(q, t0, 10, INFINITY)) fail("Newton on Phi(q, t0) = 0 did not converge.");
    ++tr.stats.kinematic_solves;
    solver.rates(q, t0, inverse_dynamics && is_output(t0), v, a, lam);
    count(0.0);
    if (is_output(t0)) {
      record(t0);
      if (!violated.empty()) fail(violated);
      ++k;
    }
    VecX q_try(n), v_try(n), a_try(n), lam_try(m);
    for (size_t s = 1; s < times.size(); ++s) {
      const double target = times[s];
      const double h_min = 1e-12 * (1.0 + std::abs(target));
      double h = target - t;
      const double from = t;
      sub_steps = 0;  // max_steps bounds the sub-steps between two solve times
      while (t < target) {
        h = std::min(h, angle_step(v, a));
        const bool last = t + h >= target;
        const double t_next = last ? target : t + h;
        const double dt = t_next - t;
        if (dt < h_min && !last) {  // the drivers turn a body faster than time can be resolved
          std::ostringstream why;
          why << "a body turns by more than 0.25 rad in " << dt << " s after t = " << t
              << ", less than the shortest sub-step " << h_min << " s: check the drivers' rates.";
          fail(why.str(), false);
        }
        if (max_steps > 0 && ++sub_steps > max_steps) {
          std::ostringstream why;
          why << "following the drivers from t = " << from << " to t = " << target << " takes more than max_steps = "
              << max_steps << " sub-steps (each turns no body by more than 0.25 rad; the sub-step is now " << dt
              << " s): check the drivers' rates, or raise max_steps.";
          fail(why.str(), false);
        }
        const VecX motion = v * dt + 0.5 * dt * dt * a;
        q_try = q + motion;
        const double guard = 0.5 * max_abs(motion) + 1e-8 * (1.0 + max_abs(q));
        if (!solver.positions(q_try, t_next, 10, guard)) {
          h = 0.5 * dt;
          if (h < h_min) {
            std::ostringstream why;
            why << "no configuration satisfies the constraints just after t = " << t
                << " (Newton on Phi(q, t) = 0 fails for every step down to " << h_min << " s)."
                << " The last configuration found is at t = " << t << ".";
            fail(why.str());
          }
          continue;
        }
        ++tr.stats.kinematic_solves;
        const bool out = last && is_output(t_next);
        v_try = v;
        solver.rates(q_try, t_next, inverse_dynamics && out, v_try, a_try, lam_try);
        q.swap(q_try);
        v.swap(v_try);
        a.swap(a_try);
        if (out) lam.swap(lam_try);
        count(dt);
        t = t_next;
        h = std::min(2.0 * h, target - t);  // grow back after a halving
        if (last) t = target;
      }
      if (is_output(t)) {
        record(t);
        if (!violated.empty()) fail(violated);
        ++k;
      }
      if (progress) {
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - clock).count() >= progress_interval) {
          clock = now;
          progress(t);
        }
      }
    }
  } catch (Interrupted& e) {
    finish();
    e.t = t;
    e.partial = std::move(tr);
    throw;
  } catch (const UserFunctionError& e) {
    finish();
    throw SimulationError(std::string(e.what()) + " Outputs up to t = " +
                              std::to_string(tr.t.empty() ? t0 : tr.t.back()) + " are kept in the partial result.",
                          t, std::move(tr));
  }
  finish();
  return tr;
}

}  // namespace lagmb
