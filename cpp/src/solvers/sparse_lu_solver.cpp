#include "solvers/sparse_lu_solver.hpp"

#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>  // SUNLS_LUFACT_FAIL

namespace lagmb::sun {

namespace {

SpMat& matrix(SUNMatrix A) { return *static_cast<SpMat*>(A->content); }
SparseLU& state(SUNLinearSolver S) { return *static_cast<SparseLU*>(S->content); }

}  // namespace

SUNMatrix make_matrix_view(SUNContext ctx, SpMat* A) {
  SUNMatrix M = SUNMatNewEmpty(ctx);
  if (!M) return nullptr;
  M->content = A;
  M->ops->getid = [](SUNMatrix) { return SUNMATRIX_CUSTOM; };
  M->ops->zero = [](SUNMatrix A) -> int {
    matrix(A).coeffs().setZero();  // values only: the pattern stays
    return 0;
  };
  M->ops->destroy = [](SUNMatrix A) {
    A->content = nullptr;
    SUNMatFreeEmpty(A);
  };
  return M;
}

SUNLinearSolver make_sparse_lu_solver(SUNContext ctx, SparseLU* st) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  S->content = st;
  S->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  S->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  S->ops->setup = [](SUNLinearSolver S, SUNMatrix A) -> int {
    SparseLU& s = state(S);
    SpMat& J = matrix(A);
    if (!s.lu.analyzed()) s.lu.analyze(J);
    ++s.factorizations;
    if (!s.lu.factorize(J)) {
      ++s.failed_factorizations;
      return SUNLS_LUFACT_FAIL;  // > 0: recoverable
    }
    return 0;
  };
  S->ops->solve = [](SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) -> int {
    const Eigen::Index n = N_VGetLength(b);
    Eigen::Map<Eigen::VectorXd> xv(N_VGetArrayPointer(x), n);
    Eigen::Map<const Eigen::VectorXd> bv(N_VGetArrayPointer(b), n);
    SparseLU& s = state(S);
    if (s.row_scale && s.row_scale->size() == n)
      xv = s.row_scale->cwiseProduct(bv);
    else
      xv = bv;
    s.lu.solve_in_place(xv.data());
    if (s.col_scale && s.col_scale->size() == n) xv.array() *= s.col_scale->array();
    return 0;
  };
  S->ops->free = [](SUNLinearSolver S) -> int {
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return 0;
  };
  return S;
}

}  // namespace lagmb::sun
