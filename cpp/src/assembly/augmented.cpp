#include "lagmb/assembly/augmented.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>

#include "lagmb/assembly/analysis.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/interrupt.hpp"

namespace lagmb {

AugmentedSystem::AugmentedSystem(const Model& model)
    : n_(model.n_coordinates()),
      m_(model.n_constraints()),
      eps_(1e-9 / model.mass_scale()),
      mass_scale_(model.mass_scale()),
      diagonal_mass_(model.constant_mass()) {
  const SpMat& J = model.jacobian_pattern();
  SparsityPattern p(n_ + m_, n_ + m_);
  for (int i = 0; i < n_ + m_; ++i) p.add(i, i);
  const SpMat& Mp = model.mass_pattern();
  for (int c = 0; c < n_; ++c)
    for (SpMat::InnerIterator it(Mp, c); it; ++it) p.add(int(it.row()), c);
  for (int c = 0; c < J.outerSize(); ++c)
    for (SpMat::InnerIterator it(J, c); it; ++it) {
      p.add(n_ + int(it.row()), c);
      p.add(c, n_ + int(it.row()));
    }
  K_ = p.build();
  mass_slots_ = embed_slots(model.mass_pattern(), K_, 0, 0);
  for (int i = 0; i < m_; ++i) reg_slots_.push_back(slot(K_, n_ + i, n_ + i));
  jac_slots_ = embed_slots(J, K_, n_, 0);
  jact_slots_ = embed_slots(J, K_, 0, n_, true);
  rhs_.resize(n_ + m_);
  x_.resize(n_ + m_);
  r_.resize(n_ + m_);
  dx_.resize(n_ + m_);
  positive_mass_ = model.positive_mass();
  if (positive_mass_ && m_ > 0) setup_schur(model);
}

void AugmentedSystem::setup_schur(const Model& model) {
  const SpMat& J = model.jacobian_pattern();
  m_inv_ = model.mass_pattern();
  w_n_.resize(n_);
  // J M^-1 keeps J's pattern where each block of M^-1 joins columns with the
  // same rows (a spatial body's Euler parameters: every element declares all
  // four); otherwise the LU takes every solve
  for (int c = 0; c < n_; ++c)
    for (SpMat::InnerIterator it(m_inv_, c); it; ++it) {
      const int a = int(it.row());
      const int na = J.outerIndexPtr()[a + 1] - J.outerIndexPtr()[a], nc = J.outerIndexPtr()[c + 1] - J.outerIndexPtr()[c];
      if (na != nc || !std::equal(J.innerIndexPtr() + J.outerIndexPtr()[a], J.innerIndexPtr() + J.outerIndexPtr()[a + 1],
                                  J.innerIndexPtr() + J.outerIndexPtr()[c])) {
        positive_mass_ = false;
        return;
      }
    }
  s_rhs_.resize(m_);
  work_.resize(m_);
  lam_.resize(m_);
  lam_prev_.resize(m_);
  j_values_.resize(J.nonZeros());
  const int* outer = J.outerIndexPtr();
  const int* row = J.innerIndexPtr();
  j_outer_.assign(outer, outer + n_ + 1);
  // S = J M^-1 J^T: entry (r_a, r_b) gathers J(r_a, c) J(r_b, c) / M_c over the columns c
  auto each_pair = [&](auto&& f) {
    for (int c = 0; c < n_; ++c)
      for (int a = outer[c]; a < outer[c + 1]; ++a)
        for (int b = outer[c]; b <= a; ++b) f(c, a, b);
  };
  // AMD on S's pattern in the constraints' own numbering...
  SparsityPattern p(m_, m_);
  for (int i = 0; i < m_; ++i) p.add(i, i);
  each_pair([&](int, int a, int b) { p.add(std::max(row[a], row[b]), std::min(row[a], row[b])); });
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> new_to_old;
  Eigen::AMDOrdering<int>()(p.build(), new_to_old);  // (Eigen's orderings give the inverse permutation)
  old_of_new_.assign(new_to_old.indices().data(), new_to_old.indices().data() + m_);
  new_of_old_.resize(m_);
  for (int k = 0; k < m_; ++k) new_of_old_[old_of_new_[k]] = k;
  // ...then S's upper triangle in that order
  j_row_.resize(J.nonZeros());
  for (Eigen::Index k = 0; k < J.nonZeros(); ++k) j_row_[k] = new_of_old_[row[k]];
  auto entry = [&](int a, int b) {
    return std::pair{std::min(j_row_[a], j_row_[b]), std::max(j_row_[a], j_row_[b])};
  };
  SparsityPattern u(m_, m_);
  for (int i = 0; i < m_; ++i) u.add(i, i);  // eps
  each_pair([&](int, int a, int b) {
    const auto [r, c] = entry(a, b);
    u.add(r, c);
  });
  S_ = u.build();
  // runs of neighbouring columns with the same rows: M^-1's blocks lie
  // within one (their columns share rows: checked above)
  int largest = 0;
  for (int c = 0; c < n_;) {
    const int rows = outer[c + 1] - outer[c];
    int end = c + 1;
    while (end < n_ && outer[end + 1] - outer[end] == rows &&
           std::equal(row + outer[c], row + outer[c + 1], row + outer[end]))
      ++end;
    if (rows > 0) {
      runs_.push_back({outer[c], rows, end - c, int(run_slots_.size())});
      for (int b = 0; b < rows; ++b)
        for (int a = b; a < rows; ++a) {
          const auto [r, s] = entry(outer[c] + a, outer[c] + b);
          run_slots_.push_back(slot(S_, r, s));
        }
      largest = std::max(largest, rows);
    }
    c = end;
  }
  run_product_.resize(largest * (largest + 1) / 2);
  j_scaled_.resize(J.nonZeros());
  for (int i = 0; i < m_; ++i) s_diag_.push_back(slot(S_, i, i));
  chol_.analyzePattern(S_);
  ++symbolic_analyses_;
}

long AugmentedSystem::factor_nonzeros() const {
  return schur_ ? long(chol_.matrixL().nestedExpression().nonZeros()) : 0;
}

void AugmentedSystem::fill_lu_matrix(const Data& d) {
  const double* J = d.Phi_q.valuePtr();
  double* K = K_.valuePtr();
  for (size_t k = 0; k < mass_slots_.size(); ++k) K[mass_slots_[k]] = d.M.valuePtr()[k];
  for (int i = 0; i < m_; ++i) K[reg_slots_[i]] = -eps_;
  for (size_t k = 0; k < jac_slots_.size(); ++k) K[jac_slots_[k]] = K[jact_slots_[k]] = J[k];
}

bool AugmentedSystem::factorize(const Data& d) {
  const double* J = d.Phi_q.valuePtr();
  const Eigen::Index nnz = d.Phi_q.nonZeros();
  ++factorizations_;
  factorized_ = schur_ = false;
  for (Eigen::Index k = 0; k < nnz; ++k)
    if (!std::isfinite(J[k])) return false;
  if (!diagonal_mass_ && !d.M.coeffs().allFinite()) return false;  // (a constant M is finite by construction)
  if (positive_mass_ && m_ > 0) {
    std::copy(J, J + nnz, j_values_.data());  // solve() uses the factorized Phi_q and M^-1
    m_inv_.coeffs() = d.M_inv.coeffs();
    if (factorize_schur(d)) return schur_ = factorized_ = true;
    // not positive definite in rounding (extreme scales): the LU decides
  }
  fill_lu_matrix(d);
  if (!lu_analyzed_) {
    lu_.analyze(K_);
    lu_analyzed_ = true;
  }
  factorized_ = lu_.factorize(K_);
  return factorized_;
}

bool AugmentedSystem::factorize_schur(const Data& d) {
  const double* J = j_values_.data();
  double* S = S_.valuePtr();
  double* Jw = j_scaled_.data();  // J M^-1: column c = sum over a of J's column a times M^-1(a, c)
  const int* mo = m_inv_.outerIndexPtr();
  const int* mi = m_inv_.innerIndexPtr();
  const double* mv = m_inv_.valuePtr();
  for (int c = 0; c < n_; ++c) {
    const int begin = j_outer_[c], count = j_outer_[c + 1] - begin;
    if (diagonal_mass_) {
      for (int k = 0; k < count; ++k) Jw[begin + k] = J[begin + k] * mv[mo[c]];
      continue;
    }
    for (int k = 0; k < count; ++k) Jw[begin + k] = 0.0;
    for (int e = mo[c]; e < mo[c + 1]; ++e) {
      const int a = j_outer_[mi[e]];  // (same rows as column c: setup_schur checked)
      for (int k = 0; k < count; ++k) Jw[begin + k] += J[a + k] * mv[e];
    }
  }
  // S = sum over the runs g of J_g (J M^-1)_g^T: small dense products
  // (the lower triangle, column b = sum over the run's columns of J_g[b.., c] (J M^-1)_g[b, c]:
  // contiguous axpys)
  S_.coeffs().setZero();
  for (const ColumnRun& g : runs_) {
    const int k = g.rows;
    double* P = run_product_.data();
    std::fill(P, P + k * (k + 1) / 2, 0.0);
    for (int c = 0; c < g.width; ++c) {
      const double* Jc = J + g.entry0 + c * k;
      const double* Wc = Jw + g.entry0 + c * k;
      double* column = P;
      for (int b = 0; b < k; ++b) {
        const double w = Wc[b];
        for (int a = b; a < k; ++a) column[a - b] += Jc[a] * w;
        column += k - b;
      }
    }
    const int* slot = run_slots_.data() + g.slot0;
    for (int e = 0; e < k * (k + 1) / 2; ++e) S[slot[e]] += P[e];
  }
  // a dropped (redundant) row has no entries; a unit diagonal keeps S definite, and its
  // right side is zero, so its multiplier stays 0
  for (int r : d.dropped_rows) S[s_diag_[new_of_old_[r]]] = 1.0 / mass_scale_;
  // first S0 itself (eps = 0): exact, no refinement...
  chol_.factorize(S_);
  if (chol_.info() == Eigen::Success && pivots_above(1e-8)) {
    regularized_ = false;
    return true;
  }
  // ...unless a row is (nearly) a combination of others: then S0 + eps I and refinement
  for (int i : s_diag_) S[i] += eps_;
  chol_.factorize(S_);
  regularized_ = true;
  return chol_.info() == Eigen::Success;
}

/// Whether every pivot of S's Cholesky factor keeps more than `ratio` of its
/// row's diagonal: L_kk^2 / S_kk is the part of row k that the rows before
/// it do not explain (1 for an independent row, 0 for a dependent one).
bool AugmentedSystem::pivots_above(double ratio) const {
  const SpMat& L = chol_.matrixL().nestedExpression();
  const double* S = S_.valuePtr();
  for (int k = 0; k < m_; ++k) {
    const double l = L.valuePtr()[L.outerIndexPtr()[k]];  // the diagonal leads each column
    if (!(l * l > ratio * S[s_diag_[k]])) return false;
  }
  return true;
}

void AugmentedSystem::solve_range_space(const VecX& b1, const VecX& b2, VecX& x1, VecX& x2) {
  const double* J = j_values_.data();
  // s = J M^-1 b1 - b2, in S's order
  for (int k = 0; k < m_; ++k) s_rhs_[k] = -b2[old_of_new_[k]];
  const int* mo = m_inv_.outerIndexPtr();
  const double* mv = m_inv_.valuePtr();
  if (diagonal_mass_)
    for (int c = 0; c < n_; ++c) w_n_[c] = mv[mo[c]] * b1[c];
  else
    w_n_.noalias() = m_inv_ * b1;
  for (int c = 0; c < n_; ++c) {
    const double w = w_n_[c];
    for (int k = j_outer_[c]; k < j_outer_[c + 1]; ++k) s_rhs_[j_row_[k]] += J[k] * w;
  }
  lam_ = chol_.solve(s_rhs_);
  // with S0 + eps I, refine against eps = 0: the residual of lam_k is eps (lam_k - lam_{k-1}), lam_{-1} = 0
  const double tol = 1e-15 * (1.0 + std::max(b1.size() ? b1.lpNorm<Eigen::Infinity>() : 0.0,
                                             b2.lpNorm<Eigen::Infinity>()));
  double residual = regularized_ ? eps_ * lam_.lpNorm<Eigen::Infinity>() : 0.0;
  for (int it = 0; it < 3 && residual > tol; ++it) {
    work_ = s_rhs_ + eps_ * lam_;
    lam_prev_.swap(lam_);
    lam_ = chol_.solve(work_);
    residual = eps_ * (lam_ - lam_prev_).lpNorm<Eigen::Infinity>();
  }
  // x2 in the constraints' numbering; x1 = M^-1 (b1 - J^T x2)
  x2.resize(m_);
  for (int k = 0; k < m_; ++k) x2[old_of_new_[k]] = lam_[k];
  x1.resize(n_);
  for (int c = 0; c < n_; ++c) {
    double f = b1[c];
    for (int k = j_outer_[c]; k < j_outer_[c + 1]; ++k) f -= J[k] * lam_[j_row_[k]];
    w_n_[c] = f;
  }
  if (diagonal_mass_)
    for (int c = 0; c < n_; ++c) x1[c] = mv[mo[c]] * w_n_[c];
  else
    x1.noalias() = m_inv_ * w_n_;
}

void AugmentedSystem::solve(const VecX& b1, const VecX& b2, VecX& x1, VecX& x2) {
  // a solve with a failed factorization is undefined in Eigen: refuse it
  if (!factorized_) throw SimulationError("the augmented matrix [M Phi_q^T; Phi_q 0] is singular or not finite", NAN);
  if (schur_) return solve_range_space(b1, b2, x1, x2);
  rhs_ << b1, b2;
  lu_.solve(rhs_, x_);
  // refine against eps = 0: K0 x = K x + eps [0; x2]
  for (int it = 0; it < 3; ++it) {
    r_.noalias() = rhs_ - K_ * x_;
    r_.tail(m_) -= eps_ * x_.tail(m_);
    if (r_.lpNorm<Eigen::Infinity>() <= 1e-15 * (1.0 + rhs_.lpNorm<Eigen::Infinity>())) break;
    lu_.solve(r_, dx_);
    x_ += dx_;
  }
  x1 = x_.head(n_);
  x2 = x_.tail(m_);
}

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
VecX assemble_positions(const Model& model, Data& d, AugmentedSystem& kkt, VecX q, double t) {
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
  q = assemble_positions(model, d, kkt, std::move(q), t);

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
  s.dropped_rows = d.dropped_rows;
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

}  // namespace lagmb
