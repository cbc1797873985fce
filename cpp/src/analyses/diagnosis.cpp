#include "lagmb/analyses/diagnosis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "lagmb/model/coordinates.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/errors.hpp"

namespace lagmb {

namespace {

/// Singular values (descending) and left singular vectors of the
/// independent rows of Phi_q at (q, t), dense.
Eigen::BDCSVD<Eigen::MatrixXd> jacobian_svd(const Model& model, const std::vector<int>& rows, const VecX& q,
                                            double t) {
  Data d(model);
  assemble_jacobian(model, d, q.data(), t);
  const Eigen::MatrixXd full = Eigen::MatrixXd(d.Phi_q);
  Eigen::MatrixXd J(rows.size(), full.cols());
  for (size_t k = 0; k < rows.size(); ++k) J.row(k) = full.row(rows[k]);
  return Eigen::BDCSVD<Eigen::MatrixXd>(J, Eigen::ComputeThinU);
}

double smallest_ratio(const Eigen::VectorXd& s, size_t rows) {
  if (s.size() == 0 || !(s[0] > 0)) return 0.0;
  return s.size() < long(rows) ? 0.0 : s[s.size() - 1] / s[0];
}

}  // namespace

std::string diagnose_failure(const Model& model, const VecX& q, double t, const std::vector<int>& dropped_rows) {
  const int m = model.n_constraints();
  if (m == 0 || m > 1000 || q.size() != model.n_coordinates() || !q.allFinite()) return "";
  // the joints' equations kept (a stop's rows, open in a Data of its own, are zero rows here)
  const std::vector<int>& unilateral = model.switched_rows();  // (and stuck contacts')
  std::vector<int> rows;
  for (int r = 0; r < m; ++r)
    if (!std::binary_search(dropped_rows.begin(), dropped_rows.end(), r) &&
        !std::binary_search(unilateral.begin(), unilateral.end(), r))
      rows.push_back(r);
  if (rows.empty()) return "";
  const auto svd = jacobian_svd(model, rows, q, t);
  const auto& s = svd.singularValues();
  std::ostringstream out;
  if (s.size() == 0) return "";
  const double smallest = s.size() < long(rows.size()) ? 0.0 : s[s.size() - 1];
  // Long chains are ill conditioned everywhere (sigma_min / sigma_max ~ 1/N):
  // call it a singular position only if the ratio has dropped tenfold below
  // its value in the initial configuration (or to rounding level).
  const double ratio = smallest_ratio(s, rows.size());
  const VecX q0 = model.initial_q();
  const double ratio0 = q0.allFinite() ? smallest_ratio(jacobian_svd(model, rows, q0, t).singularValues(), rows.size())
                                       : 1.0;
  if (ratio > 1e-6 && ratio > 0.1 * ratio0) {
    out << " The constraint Jacobian is no worse conditioned there than in the initial configuration "
        << "(smallest singular value " << smallest << " of " << s[0] << "; ratio " << ratio0
        << " at the start): look for fast or stiff dynamics (stiff springs, very light bodies; try max_step), "
        << "a force or driver that changes abruptly, or an atol finer than rounding allows for this model: "
        << "about " << 1e-15 * (1.0 + q.lpNorm<Eigen::Infinity>()) / std::max(ratio, 1e-300)
        << " here (1e-15 x its largest coordinate x the Jacobian's condition number).";
    return out.str();
  }
  // the equations that take part: large entries of the left singular vector
  const Eigen::VectorXd u = svd.matrixU().col(svd.matrixU().cols() - 1);
  const double umax = u.cwiseAbs().maxCoeff();
  std::vector<std::string> names;
  std::set<std::string> seen;
  for (size_t k = 0; k < rows.size(); ++k)
    if (std::abs(u[k]) > 0.1 * umax) {
      const std::string name = model.constraint_name_of_row(rows[k]);
      if (seen.insert(name).second) names.push_back(name);
    }
  out << " At t = " << t << " the constraint Jacobian is (nearly) singular (smallest singular value " << smallest
      << " of " << s[0] << "): the equations of";
  for (size_t k = 0; k < names.size(); ++k) out << (k ? ", '" : " '") << names[k] << "'";
  out << " become dependent. The mechanism is at a dead point, toggle or lock-up: a driver among them cannot "
      << "push it further, and a free mechanism would have to pass a bifurcation. Check the drivers' range of "
      << "motion and the geometry near this position. If the mechanism should pass through it (a free loop "
      << "such as a parallelogram crossing its flat position), run it with formulation=\"ali3p\" and a fixed "
      << "step (e.g. step=1e-4), which runs through singular positions.";
  return out.str();
}

std::string non_finite_source(const Model& model, const Data& run, const double* q, const double* v, double t) {
  const int n = model.n_coordinates();
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(q[i]) || !std::isfinite(v[i]))
      return "the state is not finite at " + coordinate_label(model, i);
  Data d(model, &run, Data::Rows::kEvery);
  try {
    assemble_forces(model, d, q, v, t);
    for (int i = 0; i < n; ++i)
      if (!std::isfinite(d.Q[i])) {
        std::string kinds;
        for (const auto& g : model.force_groups()) {
          VecX Q = VecX::Zero(n);
          g->add_forces(q, v, d.at(t), d.run->state.data(), Q.data());
          if (!std::isfinite(Q[i])) kinds += std::string(kinds.empty() ? "" : ", ") + g->kind();
        }
        return "the applied force on " + coordinate_label(model, i) + " is not finite (from the " + kinds +
               " elements)";
      }
    assemble_gamma(model, d, q, v, t);
    for (int r = 0; r < d.gamma.size(); ++r)
      if (!std::isfinite(d.gamma[r]))
        return "the acceleration equation of '" + model.constraint_name_of_row(r) + "' is not finite";
  } catch (const UserFunctionError& e) {
    return e.what();
  }
  return "the augmented system gave non-finite values (forces or masses out of the range of double precision)";
}

}  // namespace lagmb
