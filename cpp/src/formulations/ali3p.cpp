// The "ali3p" formulation (ali3p.hpp): the trapezoidal step of the index-3
// equations, its Newton iteration with the augmented-Lagrangian multiplier
// update, and the projections of v and a.
#include "formulations/ali3p.hpp"

#include <algorithm>
#include <cmath>

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

Ali3pFormulation::Ali3pFormulation(const Model& model, const ConsistentState& start, double rtol, const VecX& atol,
                                   const Data* run)
    : q(start.q),
      v(start.v),
      a(start.qdd),
      lam(start.lam),
      q_prev(q),
      v_prev(v),
      a_prev(a),
      model_(model),
      d_(model, run),
      kkt_(model),
      n_(model.n_coordinates()),
      m_(model.n_constraints()),
      rtol_(rtol),
      atol_(atol),
      eps_(regularization / model.mass_scale()),
      saddle_(model, {0, 0, 0, n_, n_}) {
  r_.resize(m_);
  f_.resize(n_);
  x_.resize(n_ + m_);
  rhs_.resize(n_ + m_);
  K_ = saddle_.build_square(diag_);
  lu_.analyze(K_);
}

void Ali3pFormulation::begin_step() {
  q_prev = q;
  v_prev = v;
  a_prev = a;
  lam_prev = lam;
}

void Ali3pFormulation::undo_step() {
  q = q_prev;
  lam = lam_prev;
}

/// Newton on the trapezoidal step of length h from (q_prev, v_prev, a_prev)
/// to t1, with q = q_{n+1} as the unknown:
///   v = 2/h (q - q_n) - v_n,   a = 4/h^2 (q - q_n) - 4/h v_n - a_n,
/// the dynamic equations times b = h^2/4:
///   [ T0      Phi_q^T ] [ dq ]     [ b (M a - Q + Phi_q^T lam) ]
///   [ Phi_q   -eps I  ] [ y  ] = - [ Phi                       ],  lam += y / b.
/// Eliminating y gives (T0 + Phi_q^T Phi_q / eps) dq = ..., ALI3-P's tangent
/// with penalty alpha = 1 / (b eps), and lam += (Phi + Phi_q dq) / (b eps) is
/// its multiplier update (linearized): Newton here does the augmented-
/// Lagrangian iteration. Starts from the Taylor predictor; converged when
/// |dq_i| <= rtol |q_i| + atol_i, or when the corrections stop falling within
/// 100 such tolerances (near a singular position the near-null directions
/// are fixed only to roundoff). it and err: the iterations and the last
/// weighted |dq|; false if Newton diverges or does not converge.
bool Ali3pFormulation::newton(double t1, double h, int& it, double& err) {
  const double c1 = 2.0 / h, c2 = 4.0 / (h * h), b = 0.25 * h * h;
  // predictor: Taylor to second order
  q = q_prev + h * v_prev + 0.5 * h * h * a_prev;
  err = INFINITY;
  double err_prev = INFINITY;
  for (it = 0; it < max_iterations; ++it) {
    v = c1 * (q - q_prev) - v_prev;
    a = c2 * (q - q_prev) - 2.0 * c1 * v_prev - a_prev;
    assemble_constraints(model_, d_, q.data(), t1);
    assemble_jacobian(model_, d_, q.data(), t1);
    assemble_forces(model_, d_, q.data(), v.data(), t1);
    ++residual_evals_;
    // rhs = -[ h^2/4 (M a - Q + Phi_q^T lam);  Phi ]
    mass_times(d_, a.data(), f_.data());  // (M at q: assemble_jacobian)
    add_jacobian_transpose_times(d_, lam.data(), f_.data());
    rhs_.head(n_) = d_.Q - f_;
    rhs_.head(n_) *= b;
    rhs_.tail(m_) = -d_.Phi;
    if (!rhs_.allFinite()) return false;
    tangent(t1, h);
    ++factorizations_;
    if (!lu_.factorize(K_)) return false;
    lu_.solve(rhs_, x_);
    q += x_.head(n_);
    lam += x_.tail(m_) / b;
    ++iterations_;
    err = 0.0;
    for (int i = 0; i < n_; ++i) err = std::max(err, std::abs(x_[i]) / (rtol_ * std::abs(q[i]) + atol_[i]));
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

/// The Newton matrix K of newton():
///   [ T0      Phi_q^T ]    T0 = M - h/2 Q_v + b [ (Phi_q^T lam)_q + (M a)_q - Q_q ],
///   [ Phi_q   -eps I  ]    b = h^2/4, eps = 1e-12 / (mean body mass).
/// eps keeps K invertible when Phi_q loses rank (a parallelogram passing its
/// horizontal, redundant constraints) and is removed by the iteration itself,
/// since the residual is exact; the factorization is a sparse LU with partial
/// pivoting (ordering once per run). Phi_q is the one newton() assembled.
void Ali3pFormulation::tangent(double t, double h) {
  const double b = 0.25 * h * h;
  double* x = K_.valuePtr();
  K_.coeffs().setZero();
  saddle_.add_mass(d_, x, 1.0);
  for (int i = 0; i < m_; ++i) x[diag_[n_ + i]] = -eps_;
  saddle_.add_tangent(d_, x, q.data(), v.data(), t, lam.data(), a.data(), b, 0.5 * h);
  const std::vector<int>&G = saddle_.jacobian, &GT = saddle_.jacobian_t;
  for (size_t k = 0; k < G.size(); ++k) x[G[k]] = x[GT[k]] = d_.Phi_q.valuePtr()[k];
}

/// v and a of the converged positions at t1, projected in the metric of T0
/// onto Phi_q v + Phi_t = 0 and Phi_q a = gamma with newton()'s factorization.
void Ali3pFormulation::finish_step(double t1, double h) {
  const double c1 = 2.0 / h, c2 = 4.0 / (h * h);
  v = c1 * (q - q_prev) - v_prev;
  a = c2 * (q - q_prev) - 2.0 * c1 * v_prev - a_prev;
  assemble_jacobian(model_, d_, q.data(), t1);
  assemble_phi_t(model_, d_, q.data(), t1);
  project(v, [&] {
    r_ = d_.phi_t;
    add_jacobian_times(d_, v.data(), r_.data());
  }, velocity_tolerance());
  assemble_gamma(model_, d_, q.data(), v.data(), t1);
  project(a, [&] {
    r_ = -d_.gamma;
    add_jacobian_times(d_, a.data(), r_.data());
  }, velocity_tolerance() / h);
}

/// T0-orthogonal projection of x onto r(x) = Phi_q x + c = 0 with the
/// factorized K: [T0 Phi_q^T; Phi_q -eps I] [dx; kappa] = [0; -r], x += dx,
/// repeated (which also removes the effect of eps) while |r| falls by half
/// and exceeds tol.
template <class Residual>
void Ali3pFormulation::project(VecX& x, Residual residual, double tol) {
  residual();
  double norm = r_.size() ? r_.lpNorm<Eigen::Infinity>() : 0.0;
  for (int k = 0; k < max_projections && norm > tol; ++k) {
    rhs_.head(n_).setZero();
    rhs_.tail(m_) = -r_;
    lu_.solve(rhs_, x_);
    x += x_.head(n_);
    ++projections_;
    residual();
    const double next = r_.lpNorm<Eigen::Infinity>();
    if (!(next < 0.5 * norm)) break;
    norm = next;
  }
}

/// Violation of Phi_q v + Phi_t the projection aims below (m/s).
double Ali3pFormulation::velocity_tolerance() const {
  double s = 0.0;
  for (int i = 0; i < n_; ++i) s = std::max(s, rtol_ * std::abs(v[i]) + atol_[i]);
  return 1e-2 * s;
}

void Ali3pFormulation::restart(double t) {
  solve_accelerations(model_, d_, kkt_, q.data(), v.data(), t, a.data(), lam.data());
  q_prev = q;
  v_prev = v;
}

double Ali3pFormulation::force_scale() const {
  return VecX(d_.M * a).lpNorm<Eigen::Infinity>() + d_.Q.lpNorm<Eigen::Infinity>();
}

void Ali3pFormulation::count(Stats& s) const {
  s.newton_iterations = iterations_;
  s.residual_evals = residual_evals_;
  s.jacobian_evals = iterations_;
  s.lu_factorizations = factorizations_;
  s.projections = projections_;
  s.element_evaluations = d_.element_evaluations;
}

}  // namespace lagmb
