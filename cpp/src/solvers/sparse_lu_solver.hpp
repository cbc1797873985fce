// A sparse LU (KLU, klu_lu.hpp) as a SUNDIALS direct linear solver, on a
// SUNMatrix that views an Eigen sparse matrix of fixed pattern.
#pragma once

#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include "solvers/klu_lu.hpp"

namespace lagmb::sun {

/// State behind the SUNLinearSolver; owned by the caller, not by SUNDIALS.
struct SparseLU {
  KluLU lu;  // the ordering is computed once per run
  long factorizations = 0;
  long failed_factorizations = 0;
  /// Equilibration: the matrix holds R J C; solve returns x = C (R J C)^-1 R b.
  /// Null or empty: no scaling.
  const Eigen::VectorXd* row_scale = nullptr;
  const Eigen::VectorXd* col_scale = nullptr;
};

/// A SUNMatrix whose content is `A` (not owned). Only the ops IDA and CVODE
/// call on a matrix of a direct solver are set: getid, zero, destroy.
SUNMatrix make_matrix_view(SUNContext ctx, SpMat* A);

/// A DIRECT SUNLinearSolver: setup factorizes the matrix view, solve
/// back-substitutes. A failed factorization is reported as recoverable, so
/// the integrator retries with a smaller step.
SUNLinearSolver make_sparse_lu_solver(SUNContext ctx, SparseLU* state);

}  // namespace lagmb::sun
