#include "lagmb/analyses/linearization.hpp"

#include <string>

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/model/data.hpp"

namespace lagmb {

RestTangent tangent_at_rest(const Model& model, const VecX& q, const VecX& lam, double t,
                            const std::vector<int>& dropped_rows) {
  const int n = model.n_coordinates(), m = model.n_constraints();
  if (q.size() != n || lam.size() != m)
    throw ModelError("tangent_at_rest: q has " + std::to_string(q.size()) + " entries and lam " +
                     std::to_string(lam.size()) + "; the model has " + std::to_string(n) + " coordinates and " +
                     std::to_string(m) + " constraint rows");
  for (size_t k = 0; k < dropped_rows.size(); ++k)
    if (dropped_rows[k] < 0 || dropped_rows[k] >= m || (k && dropped_rows[k] <= dropped_rows[k - 1]))
      throw ModelError("tangent_at_rest: dropped rows must be ascending rows of Phi (0 to " + std::to_string(m - 1) +
                       "), got " + std::to_string(dropped_rows[k]));
  Data d(model);
  d.drop_rows(model, dropped_rows);
  const VecX at_rest = VecX::Zero(n);
  assemble_jacobian(model, d, q.data(), t);  // Phi_q and M(q)
  assemble_constraint_hessian(model, d, q.data(), t, lam.data());
  assemble_force_derivatives(model, d, q.data(), at_rest.data(), t);
  RestTangent r;
  r.M = Eigen::MatrixXd(d.M);
  r.K = Eigen::MatrixXd(d.H) - Eigen::MatrixXd(d.Q_q);
  r.C = -Eigen::MatrixXd(d.Q_v);
  r.Phi_q = Eigen::MatrixXd(d.Phi_q);
  return r;
}

}  // namespace lagmb
