// A DAE form of the equations of motion, F(t, y, y') = 0, for IDA.
#pragma once

#include <memory>

#include "assembly/saddle_point.hpp"
#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/model/data.hpp"

namespace lagmb {

/// What IDA needs of a formulation: size, the algebraic/differential split,
/// consistent starting values, the residual, and the exact Newton matrix
/// dF/dy + cj dF/dy' in a pattern fixed at construction. All formulations
/// share the assembly kernels of assembly.hpp.
class DaeFormulation {
 public:
  virtual ~DaeFormulation() = default;
  virtual const char* name() const = 0;
  virtual int size() const = 0;
  /// id[i] = 1 for differential components, 0 for algebraic ones (which
  /// are left out of the error test).
  virtual void ids(double* id) const = 0;
  /// Index of each component: 1 (ODE-like), 2 or 3. The weights of an
  /// index-k component are divided by h^(k-1), as RADAU5 does.
  virtual void index_levels(int* level) const = 0;
  /// Whether the relative tolerance of index-k components is divided by
  /// h^(k-1) too (needed where they stay in the error test).
  virtual bool scale_relative_tolerance() const { return false; }
  /// Components that belong to rows the run leaves out (their multipliers,
  /// held at 0): the error norms count the others only.
  virtual int left_out_components() const { return 0; }
  /// Per-component absolute tolerances from the user's per-coordinate atol
  /// (for q_i and v_i; multipliers get the mean, scaled). For index-k
  /// components these are in the units of (variable x time^(k-1)): the
  /// integrator divides them by h^(k-1) (see ida_integrator).
  virtual void tolerances(const VecX& atol, double* abstol) const = 0;
  virtual void initial(const ConsistentState& s, double* y, double* yp) const = 0;
  virtual int residual(double t, const double* y, const double* yp, double* F) = 0;
  virtual void newton_matrix(double t, double cj, const double* y, const double* yp) = 0;
  /// The Newton matrix written by newton_matrix(), equilibrated: it holds
  /// R J C, with R and C the diagonal scalings below, so a linear solve is
  /// x = C (R J C)^-1 R b. Empty scalings mean none.
  virtual SpMat& matrix() = 0;
  virtual const VecX& row_scale() const = 0;
  virtual const VecX& col_scale() const = 0;
  /// Positions and velocities inside y.
  virtual const double* q(const double* y) const = 0;
  virtual const double* v(const double* y) const = 0;
  /// Elements the formulation's assembly kernels evaluated so far.
  virtual long element_evaluations() const { return 0; }
  /// Forward sensitivities (IDAS): out_i = F_y s_i + F_y' sp_i for each of
  /// the k directions (s_i, sp_i), with F's exact derivatives at (t, y, y').
  /// `same_state`: (t, y, y') are those of the last call, whose blocks are
  /// reused (IDAS' corrector iterates on s at a converged state). False
  /// where the form does not give them (only GGL does).
  virtual bool sensitivity_products(double t, const double* y, const double* yp, bool same_state, int k,
                                    const double* const* s, const double* const* sp, double* const* out) {
    (void)t, (void)y, (void)yp, (void)same_state, (void)k, (void)s, (void)sp, (void)out;
    return false;
  }
};

/// What the DAE forms of lagmb share: y starts with (q, v, lam), and
///   F1 = q' - v (+ ...)            rows 0..n
///   F2 = M(q) v' + Phi_q^T lam - Q    rows n..2n
/// with Newton blocks F1: [cj I, -I] on (q, v) and F2: [(Phi_q^T lam)_q +
/// (M v')_q - Q_q, cj M - Q_v, Phi_q^T] on (q, v, lam) ((M v')_q only with
/// spatial bodies), and Phi_q in the q columns of the
/// first constraint rows (F3, from row 2n): the saddle point of
/// saddle_point.hpp. Each form adds its constraint rows and picks the
/// equilibration: rows F1, F2 scaled by r1, r2, columns v, lam by cv, cl (see
/// each form), so that every block is O(1) at any step size.
/// Joint friction Q_f(q, v, lam), where present, joins Q, and its exact
/// derivatives join the F2 blocks: -Q_f,q, -Q_f,v, and -Q_f,lam next to
/// Phi_q^T (same pattern: a joint's friction reads only its own multipliers).
class MultiplierDae : public DaeFormulation {
 public:
  int left_out_components() const override {
    return m_ ? int(d_.dropped_rows().size() * (alg_diag_.size() / m_)) : 0;
  }
  int size() const override { return size_; }
  SpMat& matrix() override { return J_; }
  const VecX& row_scale() const override { return row_scale_; }
  const VecX& col_scale() const override { return col_scale_; }
  const double* q(const double* y) const override { return y; }
  const double* v(const double* y) const override { return y + n_; }
  long element_evaluations() const override { return d_.element_evaluations; }
  /// y = (q, v, lam, 0...), y' = (v, qdd, 0...) from the consistent start.
  void initial(const ConsistentState& s, double* y, double* yp) const override;

 protected:
  /// `run`: the run's Data, whose values and dropped rows d_ takes (null: its own).
  MultiplierDae(const Model& model, int size, const Data* run);
  /// Declares the F1, F2 blocks and Phi_q at (F3, q); call before adding the form's own.
  void declare_common(SparsityPattern& p) const;
  /// Builds J_ from p and binds the common slots.
  void bind_common(const SparsityPattern& p);
  /// F1 = q' - v, F2 = M v' + Phi_q^T lam - Q; leaves Phi_q at q in d_.
  void momentum_residual(double t, const double* y, const double* yp, double* F);
  /// Zeroes J_, writes the F1, F2 blocks with the given equilibration and
  /// sets the row and column scalings; leaves Phi_q at q in d_.
  void momentum_jacobian(double t, double cj, const double* y, const double* yp, double r1, double r2, double cv,
                         double cl);
  /// The multipliers of the rows the run dropped as redundant (their equations
  /// read 0 = 0 and their Jacobian rows are zero) get a unit diagonal, so the
  /// Newton matrix stays invertible and their corrections are zero.
  void pin_dropped_multipliers();
  /// Writes Phi_q (from d_) into the block at (row0, col0), transposed if asked, times `scale`.
  void put_jacobian(const std::vector<int>& slots, double scale);
  std::vector<int> jacobian_slots(int row0, int col0, bool transpose = false) const;
  /// abstol of q_i and v_i = atol_i.
  void coordinate_tolerances(const VecX& atol, double* abstol) const {
    std::copy(atol.data(), atol.data() + n_, abstol);
    std::copy(atol.data(), atol.data() + n_, abstol + n_);
  }
  /// 0 if every residual entry is finite, else 1 (recoverable: IDA cuts the step).
  static int check_finite(const double* F, int n);

  const Model& model_;
  Data d_;
  int n_, m_, size_;
  SpMat J_;
  VecX row_scale_, col_scale_;
  /// T0 and Phi_q^T in the F2 rows, Phi_q in the F3 rows (saddle_.jacobian).
  SaddlePoint saddle_;

 private:
  std::vector<int> q_diag_, qv_diag_, alg_diag_;
};

/// Stabilized index-2 form of Gear, Gupta and Leimkuhler, y = (q, v, lam, mu):
///   F1 = q' - v + Phi_q^T mu           = 0
///   F2 = M v' + Phi_q^T lam - Q        = 0
///   F3 = Phi(q, t)                     = 0
///   F4 = Phi_q v + Phi_t               = 0
/// lam and mu are algebraic (mu = 0 on the exact solution), both index 2.
/// Newton matrix (rows F1..F4, columns q, v, lam, mu):
///   [ cj I + (Phi_q^T mu)_q        -I                 0        Phi_q^T ]
///   [ (Phi_q^T lam)_q - Q_q     cj M - Q_v         Phi_q^T        0    ]
///   [ Phi_q                        0                  0           0    ]
///   [ (Phi_q v + Phi_t)_q        Phi_q                0           0    ]
/// For small steps its entries span cj^2 (cj ~ 1/h), which ruins the LU.
/// Dividing rows F1, F2 by cj and multiplying the lam, mu columns by cj
/// (r1 = r2 = h, cv = 1, cl = cj) brings every block to O(1):
///   [ I + (Phi_q^T mu)_q / cj          -I / cj             0      Phi_q^T ]
///   [ ((Phi_q^T lam)_q - Q_q) / cj    M - Q_v / cj      Phi_q^T      0    ]
///   [ Phi_q                              0                 0         0    ]
///   [ (Phi_q v + Phi_t)_q              Phi_q               0         0    ]
class GglFormulation final : public MultiplierDae {
 public:
  explicit GglFormulation(const Model& model, const Data* run = nullptr);
  const char* name() const override { return "ggl"; }
  void ids(double* id) const override;
  void index_levels(int* level) const override;
  void tolerances(const VecX& atol, double* abstol) const override;
  int residual(double t, const double* y, const double* yp, double* F) override;
  void newton_matrix(double t, double cj, const double* y, const double* yp) override;
  /// With s = (s_q, s_v, s_lam, s_mu), sp = (s_q', s_v', ...):
  ///   out1 = s_q' - s_v + (Phi_q^T mu)_q s_q + Phi_q^T s_mu
  ///   out2 = M s_v' + ((M v')_q + (Phi_q^T lam)_q - Q_q) s_q - Q_v s_v + Phi_q^T s_lam
  ///   out3 = Phi_q s_q
  ///   out4 = (Phi_q v + Phi_t)_q s_q + Phi_q s_v
  /// (the Newton matrix's blocks, unscaled). Without joint friction (its
  /// load makes Q depend on lam: refused by the runs that ask).
  bool sensitivity_products(double t, const double* y, const double* yp, bool same_state, int k,
                            const double* const* s, const double* const* sp, double* const* out) override;

 private:
  std::vector<int> jac_F4v_, jac_F1mu_, vq_F4q_, hess_F1q_;
  // the blocks of the last sensitivity_products state (residual() overwrites d_'s)
  SpMat sens_Phi_q_, sens_M_, sens_Q_v_, sens_Vq_, sens_H_mu_, sens_T_;
};

/// Index-3 form, y = (q, v, lam): F1 = q' - v, F2 as above, F3 = Phi(q, t).
/// lam is index 3, v index 2: their tolerances (relative and absolute) are
/// divided by h^2 and h (RADAU5's strategy); lam is outside the error test,
/// v stays in it. The velocity error is then only O(tol / h): accuracy
/// improves slowly as rtol falls. Known limit: IDA does not recompute the
/// weights when an error-test failure shrinks h, so a run can spiral into
/// repeated failures (the seed pendulum at rtol 1e-6 over 100 s stops at
/// t = 0.92 s). Kept to show what index 3 costs with BDF (work_precision).
/// Equilibration r1 = h, r2 = h^2, cv = cj, cl = cj^2:
///   [ I                          -I              0     ]
///   [ ((Phi_q^T lam)_q - Q_q)/cj^2   M - Q_v/cj   Phi_q^T ]
///   [ Phi_q                       0              0     ]
/// Only position constraints are enforced: velocities satisfy Phi_q v = -Phi_t
/// only as far as the integration error lets them.
class Index3Formulation final : public MultiplierDae {
 public:
  explicit Index3Formulation(const Model& model, const Data* run = nullptr);
  const char* name() const override { return "index3"; }
  bool scale_relative_tolerance() const override { return true; }
  void ids(double* id) const override;
  void index_levels(int* level) const override;
  void tolerances(const VecX& atol, double* abstol) const override;
  int residual(double t, const double* y, const double* yp, double* F) override;
  void newton_matrix(double t, double cj, const double* y, const double* yp) override;
};

/// Index-1 form, y = (q, v, lam), with optional Baumgarte terms:
///   F3 = Phi_q v' - gamma + 2 alpha (Phi_q v + Phi_t) + beta^2 Phi = 0.
/// Positions and velocities are not held on the constraints: without
/// alpha, beta they drift (linearly in t at best). lam is index 1.
/// Newton rows F3: [(Phi_q v')_q + 2 alpha (Phi_q v + Phi_t)_q + beta^2 Phi_q,
///                  (cj + 2 alpha) Phi_q + 2 (Phi_q v + Phi_t)_q, 0]
/// (-gamma_v = 2 (Phi_q v + Phi_t)_q; gamma_q needs third derivatives of Phi
/// and is left out: an O(1) term beside O(cj) ones, which only slows Newton).
/// Equilibration r1 = r2 = r3 = h, cv = 1, cl = cj.
class Index1Formulation final : public MultiplierDae {
 public:
  Index1Formulation(const Model& model, double alpha, double beta, const Data* run = nullptr);
  const char* name() const override { return "index1"; }
  void ids(double* id) const override;
  void index_levels(int* level) const override;
  void tolerances(const VecX& atol, double* abstol) const override;
  int residual(double t, const double* y, const double* yp, double* F) override;
  void newton_matrix(double t, double cj, const double* y, const double* yp) override;

 private:
  double alpha_, beta_;
  VecX scratch_;
  std::vector<int> F3v_;
};

/// The formulation forward sensitivities are integrated with (IDAS): the
/// one whose sensitivity_products give F's exact derivatives (GGL), of
/// `model`, a Data of `run` (the run's Data).
std::unique_ptr<DaeFormulation> make_sensitivity_formulation(const Model& model, const Data& run);

}  // namespace lagmb
