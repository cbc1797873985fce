#include "lagmb/analysis.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseQR>
#include <algorithm>

#include "lagmb/assembly.hpp"

namespace lagmb {

ConstraintRank constraint_rank(const Model& model, const VecX& q, double t, double tol) {
  if (!model.finalized()) throw ModelError("constraint_rank: the model is not finalized");
  if (q.size() != model.n_coordinates())
    throw ModelError("constraint_rank: q must have " + std::to_string(model.n_coordinates()) + " entries");
  ConstraintRank r;
  r.equations = model.n_constraints();
  r.coordinates = model.n_coordinates();
  if (r.equations == 0) return r;
  Data d(model);
  assemble_jacobian(model, d, q.data(), t);
  SpMat JT = d.Phi_q.transpose();
  JT.makeCompressed();
  double max_norm = 0.0;
  for (int c = 0; c < JT.cols(); ++c) max_norm = std::max(max_norm, JT.col(c).norm());
  Eigen::SparseQR<SpMat, Eigen::COLAMDOrdering<int>> qr;
  qr.setPivotThreshold(tol * std::max(max_norm, 1e-300));
  qr.compute(JT);
  if (qr.info() != Eigen::Success) throw std::runtime_error("lagmb: sparse QR of Phi_q^T failed");
  r.rank = static_cast<int>(qr.rank());
  const auto& perm = qr.colsPermutation().indices();
  for (int k = r.rank; k < r.equations; ++k) r.dependent_rows.push_back(perm[k]);
  std::sort(r.dependent_rows.begin(), r.dependent_rows.end());
  return r;
}

}  // namespace lagmb
