// A DAE form of the equations of motion, F(t, y, y') = 0, for IDA.
#pragma once

#include "lagmb/augmented.hpp"
#include "lagmb/data.hpp"

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
  /// id[i] = 1 for differential components, 0 for algebraic ones.
  virtual void ids(double* id) const = 0;
  /// Per-component absolute tolerances from the user's atol. For the
  /// algebraic components these are in the units of (variable x time): the
  /// integrator divides them by the current step size (see ida_integrator).
  virtual void tolerances(double atol, double* abstol) const = 0;
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
};

/// Stabilized index-2 form of Gear, Gupta and Leimkuhler, y = (q, v, lam, mu):
///   F1 = q' - v + Phi_q^T mu           = 0
///   F2 = M v' + Phi_q^T lam - Q        = 0
///   F3 = Phi(q, t)                     = 0
///   F4 = Phi_q v + Phi_t               = 0
/// lam and mu are algebraic (mu = 0 on the exact solution). Newton matrix
/// (rows F1..F4, columns q, v, lam, mu):
///   [ cj I + (Phi_q^T mu)_q        -I                 0        Phi_q^T ]
///   [ (Phi_q^T lam)_q - Q_q     cj M - Q_v         Phi_q^T        0    ]
///   [ Phi_q                        0                  0           0    ]
///   [ (Phi_q v + Phi_t)_q        Phi_q                0           0    ]
/// For small steps its entries span cj^2 (cj ~ 1/h), which ruins the LU.
/// Dividing rows F1, F2 by cj and multiplying the lam, mu columns by cj
/// brings every block to O(1):
///   [ I + (Phi_q^T mu)_q / cj          -I / cj             0      Phi_q^T ]
///   [ ((Phi_q^T lam)_q - Q_q) / cj    M - Q_v / cj      Phi_q^T      0    ]
///   [ Phi_q                              0                 0         0    ]
///   [ (Phi_q v + Phi_t)_q              Phi_q               0         0    ]
class GglFormulation final : public DaeFormulation {
 public:
  explicit GglFormulation(const Model& model);
  const char* name() const override { return "ggl"; }
  int size() const override { return 2 * n_ + 2 * m_; }
  void ids(double* id) const override;
  void tolerances(double atol, double* abstol) const override;
  void initial(const ConsistentState& s, double* y, double* yp) const override;
  int residual(double t, const double* y, const double* yp, double* F) override;
  void newton_matrix(double t, double cj, const double* y, const double* yp) override;
  SpMat& matrix() override { return J_; }
  const VecX& row_scale() const override { return row_scale_; }
  const VecX& col_scale() const override { return col_scale_; }
  const double* q(const double* y) const override { return y; }
  const double* v(const double* y) const override { return y + n_; }

 private:
  const Model& model_;
  Data d_;
  int n_, m_;
  SpMat J_;
  VecX row_scale_, col_scale_;
  // slots of the blocks in J_
  std::vector<int> q_diag_, qv_diag_, v_diag_;
  std::vector<int> jac_F3q_, jac_F4v_, jac_F1mu_, jac_F2lam_, vq_F4q_, hess_F1q_, hess_F2q_;
  std::vector<int> Qq_F2q_, Qv_F2v_;
};

}  // namespace lagmb
