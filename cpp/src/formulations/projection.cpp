// The "projection" formulation (projection.hpp): the ODE in accelerations,
// its Newton system and the coordinate projection.
#include "formulations/projection.hpp"

#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

ProjectionFormulation::ProjectionFormulation(const Model& model, double alpha, double beta, const Data* run)
    : model_(model),
      d_(model, run),
      kkt_(model),
      n_(model.n_coordinates()),
      nc_(model.n_constraints()),
      alpha_(alpha),
      beta_(beta),
      saddle_(model, {0, 0, 0, n_, n_}) {
  qdd_.resize(n_);
  lam_.resize(nc_);
  lam_lin_ = VecX::Zero(nc_);
  q_lin_.resize(n_);
  v_lin_.resize(n_);
  qdd_lin_ = VecX::Zero(n_);
  kappa_.resize(nc_);
  dq_.resize(n_);
  zero_n_ = VecX::Zero(n_);
  factored_q_.resize(n_);
  solved_.q.resize(n_);
  solved_.v.resize(n_);
  rhs_.resize(n_ + nc_);
  sol_.resize(n_ + nc_);
  Kb_.resize(n_);
  q0_.resize(n_);
  v0_.resize(n_);
  vnew_.resize(n_);
  Mv_.resize(n_);
  w_.resize(nc_);
}

bool ProjectionFormulation::SolvedAt::same(double t_, const double* q_, const double* v_, const Data& d) const {
  const long n = q.size();
  return valid && t_ == t && std::equal(q_, q_ + n, q.data()) && std::equal(v_, v_ + n, v.data()) &&
         d.run->inputs == inputs && d.run->state == state && d.dropped_rows() == rows;
}

void ProjectionFormulation::SolvedAt::set(double t_, const double* q_, const double* v_, const Data& d) {
  const long n = q.size();
  t = t_;
  std::copy(q_, q_ + n, q.data());
  std::copy(v_, v_ + n, v.data());
  inputs = d.run->inputs;
  state = d.run->state;
  rows = d.dropped_rows();
  valid = true;
}

bool ProjectionFormulation::accelerations(double t, const double* q, const double* v) {
  if (solved_.same(t, q, v, d_)) return true;
  solved_.valid = false;
  if (!solve_accelerations_at(t, q, v)) return false;
  solved_.set(t, q, v, d_);
  return true;
}

/// qdd and lam at (t, q, v) from the augmented system; false if its matrix
/// is singular. With Baumgarte terms:
///   Phi_q qdd = gamma - 2 alpha (Phi_q v + Phi_t) - beta^2 Phi.
bool ProjectionFormulation::solve_accelerations_at(double t, const double* q, const double* v) {
  if (!factorize_at(t, q)) return false;
  assemble_forces(model_, d_, q, v, t);
  assemble_gamma(model_, d_, q, v, t);
  if (alpha_ != 0.0) {
    assemble_phi_t(model_, d_, q, t);
    w_ = d_.phi_t;
    add_jacobian_times(d_, v, w_.data());
    d_.gamma -= 2.0 * alpha_ * w_;
  }
  if (beta_ != 0.0) {
    assemble_constraints(model_, d_, q, t);
    d_.gamma -= beta_ * beta_ * d_.Phi;
  }
  kkt_.solve(d_.Q, d_.gamma, qdd_, lam_);
  if (!model_.friction_groups().empty()) solve_friction(model_, d_, kkt_, q, v, t, qdd_, lam_);
  return qdd_.allFinite();
}

bool ProjectionFormulation::factorize_at(double t, const double* q) {
  if (factored_ && t == factored_t_ && std::equal(q, q + n_, factored_q_.data()) &&
      d_.dropped_rows() == factored_dropped_)
    return true;
  assemble_jacobian(model_, d_, q, t);
  factored_ = kkt_.factorize(d_);
  if (factored_) {
    factored_t_ = t;
    std::copy(q, q + n_, factored_q_.data());
    factored_dropped_ = d_.dropped_rows();
  }
  return factored_;
}

bool ProjectionFormulation::right_hand_side(double t, const double* y, double* f) {
  if (!accelerations(t, y, y + n_)) return false;
  std::copy(y + n_, y + 2 * n_, f);
  std::copy(qdd_.data(), qdd_.data() + n_, f + n_);
  return true;
}

bool ProjectionFormulation::linearize(double t, const double* y) {
  if (!accelerations(t, y, y + n_)) return false;
  t_lin_ = t;
  q_lin_ = Eigen::Map<const VecX>(y, n_);
  v_lin_ = Eigen::Map<const VecX>(y + n_, n_);
  lam_lin_ = lam_;
  qdd_lin_ = qdd_;
  return true;
}

/// The Newton matrix I - gamma J, J = [[0, I], [A_q, A_v]] with A the
/// derivative of qdd. We take the part that comes from the forces and the
/// multipliers' curvature, A_q ~ P M^-1 (Q_q - (Phi_q^T lam)_q), A_v ~ P M^-1
/// Q_v (P the M-orthogonal projector on Phi_q a = 0), and leave out the
/// derivatives of gamma and the friction's dependence on lam (through the
/// reactions). Solving (I - gamma J) x = b then reduces to one sparse
/// saddle-point system of the size of the augmented matrix, factorized here:
///   [ M - gamma Q_v - gamma^2 K   Phi_q^T ] [ x_v ]   [ M b_v + gamma K b_q ]
///   [ Phi_q                       0       ] [ mu  ] = [ Phi_q b_v           ]
///   x_q = b_q + gamma x_v,    K = Q_q - (Phi_q^T lam)_q - (M(q) qdd)_q.
bool ProjectionFormulation::setup(double gamma) {
  if (N_.nonZeros() == 0) {  // (the first implicit step: an explicit method never needs it)
    N_ = saddle_.build_square(diag_);
    lu_.analyze(N_);
  }
  const double* q = q_lin_.data();
  const double* v = v_lin_.data();
  double* x = N_.valuePtr();
  N_.coeffs().setZero();
  assemble_jacobian(model_, d_, q, t_lin_);  // (and M(q))
  factored_ = false;  // (d_'s Phi_q and M are q_lin_'s now, kkt_ not refactorized)
  saddle_.add_mass(d_, x, 1.0);
  const std::vector<int>&G = saddle_.jacobian, &GT = saddle_.jacobian_t;
  for (size_t k = 0; k < G.size(); ++k) x[G[k]] = x[GT[k]] = d_.Phi_q.valuePtr()[k];
  // -gamma^2 K - gamma Q_v; K's values stay in d_ for solve()
  saddle_.add_tangent(d_, x, q, v, t_lin_, lam_lin_.data(), qdd_lin_.data(), gamma * gamma, gamma);
  // a row left out (redundant, or an open stop) has no entries: its mu is 0
  for (int r : d_.dropped_rows()) x[diag_[n_ + r]] = 1.0;
  ++factorizations_;
  gamma_setup_ = gamma;
  return lu_.factorize(N_);
}

/// The right side and back substitution of setup()'s system.
void ProjectionFormulation::solve(const double* b, double* x) {
  const double g = gamma_setup_;
  Eigen::Map<const VecX> bq(b, n_), bv(b + n_, n_);
  Eigen::Map<VecX> xq(x, n_), xv(x + n_, n_);
  // K b_q = (Q_q - H - (M a)_q) b_q, from the values still in d_ (same linearization)
  stiffness_times(model_, d_, bq.data(), Kb_.data());
  mass_times(d_, bv.data(), rhs_.data());
  rhs_.head(n_) += g * Kb_;
  rhs_.tail(nc_).setZero();
  add_jacobian_times(d_, bv.data(), rhs_.data() + n_);
  sol_ = rhs_;
  lu_.solve_in_place(sol_.data());
  xv = sol_.head(n_);
  xq = bq + g * xv;
}

/// q onto Phi = 0 (up to 3 Newton steps) and v onto Phi_q v + Phi_t = 0,
/// each the least change in the M metric:
///   [ M Phi_q^T; Phi_q 0 ] [ dq; kappa ] = [ 0; -Phi ],
///   [ M Phi_q^T; Phi_q 0 ] [ v; kappa ] = [ M v; -Phi_t ];
/// the error estimate's q and v parts onto Phi_q e = 0 the same way.
int ProjectionFormulation::project(double t, double* q, double* v, double* corr, double* err) {
  Eigen::Map<VecX> Q(q, n_), V(v, n_);
  q0_ = Q;
  v0_ = V;
  // Newton on Phi(q) = 0 (a step's end lies close: 1 or 2 iterations); a
  // state no position near it satisfies (a dead point passed, a driver
  // pulling a linkage apart) is a failed projection, not a step accepted
  // off the constraints
  for (int it = 0;; ++it) {
    assemble_constraints(model_, d_, q, t);
    const double e = nc_ ? d_.Phi.lpNorm<Eigen::Infinity>() : 0.0;
    const double size = 1.0 + Q.lpNorm<Eigen::Infinity>();
    if (e <= 1e-14 * size) break;
    if (it == 6) {
      if (!(e <= 1e-8 * size)) return 1;
      break;
    }
    if (!factorize_at(t, q)) return 1;
    d_.Phi = -d_.Phi;  // in place: no temporary
    kkt_.solve(zero_n_, d_.Phi, dq_, kappa_);
    Q += dq_;
  }
  if (!factorize_at(t, q)) return 1;
  assemble_phi_t(model_, d_, q, t);
  mass_times(d_, v, Mv_.data());
  d_.phi_t = -d_.phi_t;
  kkt_.solve(Mv_, d_.phi_t, vnew_, kappa_);
  V = vnew_;
  Eigen::Map<VecX>(corr, n_) = Q - q0_;
  Eigen::Map<VecX>(corr + n_, n_) = V - v0_;
  if (err) {
    for (int part = 0; part < 2; ++part) {
      Eigen::Map<VecX> e(err + part * n_, n_);
      w_.setZero();
      add_jacobian_times(d_, e.data(), w_.data());
      w_ = -w_;
      kkt_.solve(zero_n_, w_, dq_, kappa_);
      e += dq_;
    }
  }
  ++projections_;
  return 0;
}

void ProjectionFormulation::count(Stats& stats) const {
  stats.lu_factorizations = factorizations_;
  stats.lu_nonzeros = lu_.factor_nonzeros();
  stats.augmented_factorizations = kkt_.factorizations();
  stats.symbolic_analyses = kkt_.symbolic_analyses();
  stats.factor_nonzeros = kkt_.factor_nonzeros();
  stats.projections = projections_;
  stats.element_evaluations = d_.element_evaluations;
}

}  // namespace lagmb
