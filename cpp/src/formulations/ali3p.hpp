// The "ali3p" formulation (ALI3-P: Bayo & Ledesma 1996, Cuadrado et al.
// 2000): the index-3 equations of motion discretized by the trapezoidal rule,
// one step's Newton iteration on (q, lam), and the projections of v and a in
// the metric of the tangent matrix. The fixed-step driver (step lengths,
// retries near singular positions, outputs) is ali3p_integrator.cpp.
#pragma once


#include "lagmb/analyses/consistent_state.hpp"
#include "assembly/saddle_point.hpp"

namespace lagmb {

struct Stats;

/// One trapezoidal step of M a + Phi_q^T lam = Q(q, v, t), Phi(q, t) = 0 from
/// (q_prev, v_prev, a_prev) to (q, v, a, lam) at t_{n+1}.
///
/// Energy: the trapezoidal rule conserves the energy of a conservative system
/// up to an O((omega h)^2) oscillation without drift (it is conjugate to the
/// symplectic midpoint rule); accuracy is second order in h.
///
/// References: E. Bayo, R. Ledesma, Augmented Lagrangian and mass-orthogonal
/// projection methods for constrained multibody dynamics, Nonlinear Dynamics
/// 9 (1996) 113-130. J. Cuadrado, J. Cardenal, P. Morer, E. Bayo, Intelligent
/// simulation of multibody dynamics: space-state and descriptor methods in
/// sequential and parallel computing environments, Multibody System Dynamics
/// 4 (2000) 55-73. M. Gonzalez, D. Dopico, U. Lugris, J. Cuadrado, A
/// benchmarking system for MBS simulation software, Multibody System Dynamics
/// 16 (2006) 179-190 (the IFToMM benchmark; its reference solutions use ALI3-P).
class Ali3pFormulation {
 public:
  /// From a consistent start; rtol, atol are Newton's convergence test and
  /// the projections' target.
  /// `run`: the run's Data, whose values and dropped rows d_ takes (null: its own).
  Ali3pFormulation(const Model& model, const ConsistentState& start, double rtol, const VecX& atol,
                   const Data* run = nullptr);

  /// Takes the current state as the start of the next step.
  void begin_step();
  /// Puts q and lam back to the start of the step (before a retry).
  void undo_step();
  /// Solves the step of length h, ending at t1, for q and lam (the
  /// equations: ali3p.cpp); false if Newton diverges or does not converge.
  bool newton(double t1, double h, int& it, double& err);
  /// v and a at t1 from the converged q, projected onto the constraints.
  void finish_step(double t1, double h);
  /// Fresh a and lam at (q, v, t) from the augmented system (a derivative of
  /// a time function jumps), and the state taken as the start of a step.
  void restart(double t);
  /// The size of M a and Q (N): multipliers below it never count as a jump.
  double force_scale() const;
  /// Its counts: newton_iterations, residual_evals, jacobian_evals,
  /// lu_factorizations, projections, element_evaluations.
  void count(Stats& stats) const;

  /// The state at the end of the step (during newton(): its iterate), and at
  /// its start.
  VecX q, v, a, lam;
  VecX q_prev, v_prev, a_prev, lam_prev;

 private:
  void tangent(double t, double h);
  template <class Residual>
  void project(VecX& x, Residual residual, double tol);
  double velocity_tolerance() const;

  static constexpr int max_iterations = 12;
  static constexpr int max_projections = 6;
  /// eps of the multiplier block times the mean body mass.
  static constexpr double regularization = 1e-12;

  const Model& model_;
  Data d_;
  AugmentedSystem kkt_;
  int n_, m_;
  double rtol_;
  VecX atol_;
  double eps_;
  VecX r_, f_, x_, rhs_;  // scratch
  SaddlePoint saddle_;
  SpMat K_;
  std::vector<int> diag_;
  SupernodalLU lu_;
  long iterations_ = 0, residual_evals_ = 0, factorizations_ = 0, projections_ = 0;
};

}  // namespace lagmb
