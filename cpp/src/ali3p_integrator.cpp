// "ali3p": index-3 Lagrangian equations, trapezoidal rule with a fixed step,
// mass-orthogonal projections of velocities and accelerations (the ALI3-P
// scheme of Bayo & Ledesma 1996 and Cuadrado et al. 2000, with the
// augmented-Lagrangian multiplier iteration carried out by Newton).
//
// Equations of motion at t_{n+1}: M a + Phi_q^T lam = Q(q, v, t), Phi(q, t) = 0.
// Trapezoidal rule with q = q_{n+1} as the unknown:
//   v = 2/h (q - q_n) - v_n,   a = 4/h^2 (q - q_n) - 4/h v_n - a_n.
// Newton on (q, lam), the dynamic equations times b = h^2/4:
//   [ T0      Phi_q^T ] [ dq ]     [ b (M a - Q + Phi_q^T lam) ]
//   [ Phi_q   -eps I  ] [ y  ] = - [ Phi                       ],  lam += y / b,
//   T0 = M - h/2 Q_v + b [ (Phi_q^T lam)_q - Q_q ].
// Eliminating y gives (T0 + Phi_q^T Phi_q / eps) dq = ..., ALI3-P's tangent
// with penalty alpha = 1 / (b eps), and lam += (Phi + Phi_q dq) / (b eps) is
// its multiplier update (linearized): Newton here does the augmented-
// Lagrangian iteration. eps = 1e-12 / (mean body mass) keeps the matrix
// invertible when Phi_q loses rank (a parallelogram passing its horizontal,
// redundant constraints) and is removed by the iteration itself, since the
// residual is exact; the factorization is a sparse LU with partial pivoting
// (ordering once per run). Converged when |dq_i| <= rtol |q_i| + atol_i, or
// when the corrections stop falling within 100 such tolerances (near a
// singular position the near-null directions are fixed only to roundoff).
//
// After convergence, v and a are projected in the metric of T0 onto
// Phi_q v + Phi_t = 0 and Phi_q a = gamma, with the same factorization:
//   [ T0 Phi_q^T; Phi_q -eps I ] [ dv; kappa ] = [ 0; -(Phi_q v + Phi_t) ],
// repeated while the violation halves and is above tolerance (the same for a).
//
// Singular positions: where Phi_q loses rank the exact multipliers may have a
// pole (lam ~ 1 / sigma, sigma the smallest singular value; Phi_q^T lam stays
// finite). A step landing within roundoff of such a position meets a nearly
// unsolvable system: Newton diverges, or converges with multipliers more
// than 10 times those of the step before (and above the size of M a and Q),
// where the local error of the step is large; the step is then retried
// with lengths 0.5, 1.5, 0.25, 1.75 h (counted in Stats::convergence_failures)
// so that it lands beside the singular position; the next steps take h again.
//
// Energy: the trapezoidal rule conserves the energy of a conservative system
// up to an O((omega h)^2) oscillation without drift (it is conjugate to the
// symplectic midpoint rule); accuracy is second order in h.
//
// References: E. Bayo, R. Ledesma, Augmented Lagrangian and mass-orthogonal
// projection methods for constrained multibody dynamics, Nonlinear Dynamics
// 9 (1996) 113-130. J. Cuadrado, J. Cardenal, P. Morer, E. Bayo, Intelligent
// simulation of multibody dynamics: space-state and descriptor methods in
// sequential and parallel computing environments, Multibody System Dynamics
// 4 (2000) 55-73. M. Gonzalez, D. Dopico, U. Lugris, J. Cuadrado, A
// benchmarking system for MBS simulation software, Multibody System Dynamics
// 16 (2006) 179-190 (the IFToMM benchmark; its reference solutions use ALI3-P).
#include <Eigen/SparseLU>
#include <cmath>
#include <sstream>

#include "integrators.hpp"
#include "lagmb/assembly.hpp"

namespace lagmb {

namespace {

class Ali3pStepper final : public Stepper {
 public:
  Ali3pStepper(const Model& model, const ConsistentState& start, const IntegrationPlan& plan, double step)
      : model_(model),
        d_(model),
        kkt_(model),
        plan_(plan),
        n_(model.n_coordinates()),
        m_(model.n_constraints()),
        h_(step),
        t_(plan.t0),
        stop_(plan.t_end),
        t_prev_(plan.t0) {
    if (plan.run) d_.join_run(model, *plan.run);
    q_ = start.q;
    v_ = start.v;
    a_ = start.qdd;
    lam_ = start.lam;
    q_prev_ = q_;
    v_prev_ = v_;
    a_prev_ = a_;
    r_.resize(m_);
    f_.resize(n_);
    x_.resize(n_ + m_);
    rhs_.resize(n_ + m_);
    q_out_.resize(n_);
    v_out_.resize(n_);
    build_pattern();
  }

  const char* name() const override { return "ALI3-P"; }
  void set_stop(double stop) override { stop_ = stop; }

  double step(bool& at_stop) override {
    double h = h_;
    at_stop = false;
    // the last step lands on the stop time, stretched by up to 1 % rather
    // than followed by a sliver (t accumulates rounding over many steps)
    if (stop_ - t_ <= 1.01 * h) {
      h = stop_ - t_;
      at_stop = true;
    }
    q_prev_ = q_;
    v_prev_ = v_;
    a_prev_ = a_;
    lam_prev_ = lam_;
    t_prev_ = t_;
    // A step that lands very close to a singular position (Phi_q loses rank)
    // meets a nearly unsolvable system: the multipliers there grow like
    // 1 / sigma. Newton then stalls or diverges; the step is retried shorter
    // or longer so that it lands elsewhere; the next steps take h again.
    double err = INFINITY;
    int it = 0;
    const double lam_before = m_ ? lam_prev_.lpNorm<Eigen::Infinity>() : 0.0;
    for (int attempt = 0;; ++attempt) {
      // converged, and the multipliers did not jump by a factor > 10 (a
      // landing next to the pole; the last attempt is taken as it is)
      if (newton(h, it, err) &&
          (attempt == max_retries || !(m_ && lam_.lpNorm<Eigen::Infinity>() > lam_jump * lam_before + lam_floor())))
        break;
      q_ = q_prev_;
      lam_ = lam_prev_;
      if (attempt == max_retries) fail(t_prev_ + h, "the Newton iteration did not converge", it, err);
      ++retries_;
      h = h_ * retry_factors[attempt];
      at_stop = false;
      if (t_prev_ + h >= stop_) {  // a longer retry must not pass a breakpoint or t_end
        h = stop_ - t_prev_;
        at_stop = true;
      }
    }
    const double t1 = at_stop ? stop_ : t_prev_ + h;
    const double c1 = 2.0 / h, c2 = 4.0 / (h * h);

    // velocities and accelerations of the converged positions, then projected
    v_ = c1 * (q_ - q_prev_) - v_prev_;
    a_ = c2 * (q_ - q_prev_) - 2.0 * c1 * v_prev_ - a_prev_;
    assemble_jacobian(model_, d_, q_.data(), t1);
    assemble_phi_t(model_, d_, q_.data(), t1);
    project(v_, [&] {
      r_ = d_.phi_t;
      add_jacobian_times(d_, v_.data(), r_.data());
    }, velocity_tolerance());
    assemble_gamma(model_, d_, q_.data(), v_.data(), t1);
    project(a_, [&] {
      r_ = -d_.gamma;
      add_jacobian_times(d_, a_.data(), r_.data());
    }, velocity_tolerance() / h);
    t_ = t1;
    ++steps_;
    return t_;
  }

  /// Newton on the trapezoidal step of length h from (q_prev_, v_prev_,
  /// a_prev_); false if it diverges or does not converge.
  bool newton(double h, int& it, double& err) {
    const double t1 = t_prev_ + h;
    const double c1 = 2.0 / h, c2 = 4.0 / (h * h), b = 0.25 * h * h;
    // predictor: Taylor to second order
    q_ = q_prev_ + h * v_prev_ + 0.5 * h * h * a_prev_;
    err = INFINITY;
    double err_prev = INFINITY;
    for (it = 0; it < max_iterations; ++it) {
      v_ = c1 * (q_ - q_prev_) - v_prev_;
      a_ = c2 * (q_ - q_prev_) - 2.0 * c1 * v_prev_ - a_prev_;
      assemble_constraints(model_, d_, q_.data(), t1);
      assemble_jacobian(model_, d_, q_.data(), t1);
      assemble_forces(model_, d_, q_.data(), v_.data(), t1);
      ++residual_evals_;
      // rhs = -[ h^2/4 (M a - Q + Phi_q^T lam);  Phi ]
      rhs_.head(n_) = d_.Q - mass_.cwiseProduct(a_);
      f_.setZero();
      add_jacobian_transpose_times(d_, lam_.data(), f_.data());
      rhs_.head(n_) -= f_;
      rhs_.head(n_) *= b;
      rhs_.tail(m_) = -d_.Phi;
      if (!rhs_.allFinite()) return false;
      tangent(t1, h);
      if (!factorize()) return false;
      x_ = lu_.solve(rhs_);
      q_ += x_.head(n_);
      lam_ += x_.tail(m_) / b;
      ++iterations_;
      err = 0.0;
      for (int i = 0; i < n_; ++i)
        err = std::max(err, std::abs(x_[i]) / (plan_.rtol * std::abs(q_[i]) + plan_.atol[i]));
      if (!std::isfinite(err)) return false;
      if (err <= 1.0) return true;
      // near a singular position the near-null directions of Phi_q are
      // fixed only to roundoff / sigma^2: a correction that stops falling
      // within 100 tolerances is as converged as rounding allows
      if (it >= 2 && err > 0.5 * err_prev && err <= 100.0) return true;
      if (it >= 3 && err > err_prev) return false;  // diverging
      err_prev = err;
    }
    return false;
  }

  void interpolate(double t, const double*& q, const double*& v) override {
    // cubic Hermite through (q, v) at both ends of the last step
    const double h = t_ - t_prev_;
    if (!(h > 0.0)) {
      q_out_ = q_;
      v_out_ = v_;
    } else {
      const double s = std::clamp((t - t_prev_) / h, 0.0, 1.0), s2 = s * s, s3 = s2 * s;
      const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
      const double d00 = (6 * s2 - 6 * s) / h, d10 = 3 * s2 - 4 * s + 1, d01 = (-6 * s2 + 6 * s) / h,
                   d11 = 3 * s2 - 2 * s;
      q_out_ = h00 * q_prev_ + h * h10 * v_prev_ + h01 * q_ + h * h11 * v_;
      v_out_ = d00 * q_prev_ + d10 * v_prev_ + d01 * q_ + d11 * v_;
    }
    q = q_out_.data();
    v = v_out_.data();
  }

  void restart(double t) override {
    // a derivative of a time function jumps: fresh accelerations and multipliers
    solve_accelerations(model_, d_, kkt_, q_.data(), v_.data(), t, a_.data(), lam_.data());
    t_ = t_prev_ = t;
    q_prev_ = q_;
    v_prev_ = v_;
  }

  const double* positions() const override { return q_.data(); }

  void fill_stats(Stats& s) override {
    s.steps = steps_;
    s.newton_iterations = iterations_;
    s.residual_evals = residual_evals_;
    s.jacobian_evals = iterations_;
    s.lu_factorizations = factorizations_;
    s.projections = projections_;
    s.convergence_failures = retries_;
    s.last_order = 2;
    s.last_step = t_ - t_prev_;
    s.element_evaluations = d_.element_evaluations;
  }

 private:
  static constexpr int max_iterations = 12, max_retries = 4;
  static constexpr double lam_jump = 10.0;
  /// Lengths of the retries of a step, in units of h: shorter, then longer
  /// (stepping over the singular position), then more so.
  static constexpr double retry_factors[max_retries] = {0.5, 1.5, 0.25, 1.75};
  static constexpr int max_projections = 6;
  /// eps of the multiplier block times the mean body mass.
  static constexpr double regularization = 1e-12;

  /// The pattern of K: T0 (M, (Phi_q^T lam)_q, Q_q, Q_v), Phi_q, Phi_q^T, -eps I.
  void build_pattern() {
    SparsityPattern p(n_ + m_, n_ + m_);
    auto add = [&](const SpMat& A, int r0, int c0, bool transpose) {
      for (int c = 0; c < A.outerSize(); ++c)
        for (SpMat::InnerIterator it(A, c); it; ++it)
          transpose ? p.add(r0 + c, c0 + int(it.row())) : p.add(r0 + int(it.row()), c0 + c);
    };
    for (int i = 0; i < n_ + m_; ++i) p.add(i, i);
    add(model_.hessian_pattern(), 0, 0, false);
    add(model_.force_q_pattern(), 0, 0, false);
    add(model_.force_v_pattern(), 0, 0, false);
    add(model_.jacobian_pattern(), n_, 0, false);
    add(model_.jacobian_pattern(), 0, n_, true);
    K_ = p.build();
    for (int i = 0; i < n_ + m_; ++i) diag_.push_back(slot(K_, i, i));
    hess_ = embed_slots(model_.hessian_pattern(), K_, 0, 0);
    force_q_ = embed_slots(model_.force_q_pattern(), K_, 0, 0);
    force_v_ = embed_slots(model_.force_v_pattern(), K_, 0, 0);
    jac_ = embed_slots(model_.jacobian_pattern(), K_, n_, 0);
    jac_t_ = embed_slots(model_.jacobian_pattern(), K_, 0, n_, true);
    lu_.analyzePattern(K_);
    mass_ = model_.mass_diagonal();
    eps_ = regularization / model_.mass_scale();
  }

  void tangent(double t, double h) {
    const double b = 0.25 * h * h;
    double* x = K_.valuePtr();
    K_.coeffs().setZero();
    for (int i = 0; i < n_; ++i) x[diag_[i]] = mass_[i];
    for (int i = 0; i < m_; ++i) x[diag_[n_ + i]] = -eps_;
    assemble_constraint_hessian(model_, d_, q_.data(), t, lam_.data());
    for (size_t k = 0; k < hess_.size(); ++k) x[hess_[k]] += b * d_.H.valuePtr()[k];
    if (!model_.state_dependent_forces().empty()) {
      assemble_force_derivatives(model_, d_, q_.data(), v_.data(), t);
      for (size_t k = 0; k < force_q_.size(); ++k) x[force_q_[k]] -= b * d_.Q_q.valuePtr()[k];
      for (size_t k = 0; k < force_v_.size(); ++k) x[force_v_[k]] -= 0.5 * h * d_.Q_v.valuePtr()[k];
    }
    const double* g = d_.Phi_q.valuePtr();
    for (size_t k = 0; k < jac_.size(); ++k) x[jac_[k]] = x[jac_t_[k]] = g[k];
  }

  /// Multipliers below this (N) never count as a jump: the size of M a and Q.
  double lam_floor() const {
    return (mass_.cwiseProduct(a_)).lpNorm<Eigen::Infinity>() + d_.Q.lpNorm<Eigen::Infinity>();
  }

  bool factorize() {
    ++factorizations_;
    return factorize_finite(lu_, K_);
  }

  /// T0-orthogonal projection of x onto r(x) = Phi_q x + c = 0 with the
  /// factorized K: [T0 Phi_q^T; Phi_q -eps I] [dx; kappa] = [0; -r], x += dx,
  /// repeated (which also removes the effect of eps) while |r| falls by half
  /// and exceeds tol.
  template <class Residual>
  void project(VecX& x, Residual residual, double tol) {
    residual();
    double norm = r_.size() ? r_.lpNorm<Eigen::Infinity>() : 0.0;
    for (int k = 0; k < max_projections && norm > tol; ++k) {
      rhs_.head(n_).setZero();
      rhs_.tail(m_) = -r_;
      x_ = lu_.solve(rhs_);
      x += x_.head(n_);
      ++projections_;
      residual();
      const double next = r_.lpNorm<Eigen::Infinity>();
      if (!(next < 0.5 * norm)) break;
      norm = next;
    }
  }

  /// Violation of Phi_q v + Phi_t the projection aims below (m/s).
  double velocity_tolerance() const {
    double s = 0.0;
    for (int i = 0; i < n_; ++i) s = std::max(s, plan_.rtol * std::abs(v_[i]) + plan_.atol[i]);
    return 1e-2 * s;
  }

  [[noreturn]] void fail(double t, const char* why, int iterations, double err) const {
    std::ostringstream msg;
    msg << "ALI3-P failed in the step from t = " << t_prev_ << " to " << t << ": " << why << " after "
        << iterations << " Newton iterations (weighted |dq| = " << err << ", 1 needed; step " << h_
        << " s). Try a smaller step.";
    throw IntegratorFailure(msg.str(), t_prev_);
  }

  const Model& model_;
  Data d_;
  AugmentedSystem kkt_;
  const IntegrationPlan& plan_;
  int n_, m_;
  double h_, eps_ = 0.0;
  double t_, stop_, t_prev_;
  VecX q_, v_, a_, lam_, lam_prev_, q_prev_, v_prev_, a_prev_, r_, f_, x_, rhs_, q_out_, v_out_, mass_;
  SpMat K_;
  std::vector<int> diag_, hess_, force_q_, force_v_, jac_, jac_t_;
  Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>> lu_;
  long steps_ = 0, iterations_ = 0, residual_evals_ = 0, factorizations_ = 0, projections_ = 0, retries_ = 0;
};

}  // namespace

void integrate_ali3p(const Model& model, double step, const ConsistentState& start,
                     const IntegrationPlan& plan,
                     const std::function<void(const double* q, const double* v)>& record, Stats& stats) {
  Ali3pStepper stepper(model, start, plan, step);
  run_steps(stepper, plan, start, record, stats);
}

}  // namespace lagmb
