// The "projection" formulation: the ODE in accelerations, y = (q, v), with
// qdd and lam from the augmented system, its Newton system and the
// projection of q and v onto the constraints. CVODE integrates it
// (cvode_integrator.cpp).
#pragma once

#include "solvers/klu_lu.hpp"

#include "assembly/saddle_point.hpp"
#include "lagmb/assembly/augmented.hpp"

namespace lagmb {

struct Stats;

/// y = (q, v); f(t, y) = (v, qdd) with qdd, lam from the augmented system
///   [ M      Phi_q^T ] [ qdd ]   [ Q     ]
///   [ Phi_q  0       ] [ lam ] = [ gamma ]
/// (with the joint friction's fixed point where the model has friction).
class ProjectionFormulation {
 public:
  /// alpha, beta: Baumgarte terms (for Adams, which CVODE cannot project).
  /// `run`: the run's Data, whose values and dropped rows d_ takes (null: its own).
  ProjectionFormulation(const Model& model, double alpha, double beta, const Data* run = nullptr);
  int n() const { return n_; }
  int n_constraints() const { return nc_; }

  /// f = (v, qdd) at (t, y); false if the augmented matrix is singular or
  /// qdd is not finite (recoverable: the integrator cuts the step).
  bool right_hand_side(double t, const double* y, double* f);
  /// qdd and lam at (t, q, v) from the augmented system (qdd(), lam());
  /// false as right_hand_side. The last solution is remembered with where it
  /// was solved: a call at the same (t, q, v), the run's values (inputs,
  /// element state) and rows unchanged, is answered without a solve (a
  /// step's end, where the root functions, the output and the next step's
  /// first stage all ask).
  bool accelerations(double t, const double* q, const double* v);
  const VecX& qdd() const { return qdd_; }
  const VecX& lam() const { return lam_; }
  /// Whether Baumgarte terms stabilize the accelerations (then qdd and lam
  /// are not the motion's own: Phi_q qdd = gamma holds only as alpha, beta -> 0).
  bool baumgarte() const { return alpha_ != 0.0 || beta_ != 0.0; }
  /// Takes (t, y) and its multipliers as the point the Newton matrix is
  /// linearized at; false as right_hand_side.
  bool linearize(double t, const double* y);
  /// Factorizes the Newton matrix I - gamma J at the linearization point.
  bool setup(double gamma);
  /// x = (I - gamma J)^-1 b with the gamma of the last setup.
  void solve(const double* b, double* x);
  /// Projects (q, v) onto the constraints; corr = the change of (q, v), err
  /// (if given) projected onto the tangent space. 0, or 1 if the augmented
  /// matrix is singular or no position near q satisfies Phi = 0 (Newton
  /// leaves |Phi| above 1e-8 (1 + |q|) after 6 iterations).
  int project(double t, double* q, double* v, double* corr, double* err);
  /// Its counts: lu_factorizations, augmented_factorizations, projections,
  /// element_evaluations.
  void count(Stats& stats) const;

 private:
  /// accelerations() without the memory.
  bool solve_accelerations_at(double t, const double* q, const double* v);
  /// Where accelerations() last solved (qdd_, lam_ hold its solution).
  struct SolvedAt {
    bool valid = false;
    double t = 0.0;
    VecX q, v, inputs, state;
    std::vector<int> rows;  // the rows left out
    bool same(double t, const double* q, const double* v, const Data& d) const;
    void set(double t, const double* q, const double* v, const Data& d);
  };
  /// Phi_q and M at (t, q) in d_, factorized in kkt_; nothing is redone
  /// where the last factorization was at this (t, q) with the same rows left
  /// out (the first stage of a step, at the state the projection ended at).
  bool factorize_at(double t, const double* q);

  const Model& model_;
  Data d_;
  AugmentedSystem kkt_;
  int n_, nc_;
  double alpha_, beta_;
  VecX qdd_, lam_, lam_lin_, q_lin_, v_lin_, qdd_lin_, kappa_, dq_, zero_n_, rhs_, sol_;
  VecX Kb_, q0_, v0_, vnew_, Mv_, w_;  // scratch, sized once: no allocation per solve or projection
  double t_lin_ = 0.0, gamma_setup_ = 0.0;
  bool factored_ = false;  // kkt_ and d_'s Phi_q, M hold (factored_t_, factored_q_, factored_dropped_)
  double factored_t_ = 0.0;
  VecX factored_q_;
  std::vector<int> factored_dropped_;
  SaddlePoint saddle_;
  SpMat N_;
  std::vector<int> diag_;
  KluLU lu_;
  long factorizations_ = 0, projections_ = 0;
  SolvedAt solved_;
};

}  // namespace lagmb
