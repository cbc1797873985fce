// What the stops' rows do at a crossing: the impulse of an impact (the
// M-orthogonal jump with restitution), the active set at rest contact (an
// LCP at acceleration level), and the failure where a stop is driven
// through.
#include "lagmb/events/event_runner.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

#include "events/integrator_failure.hpp"
#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

void EventRunner::contact_rows(double t, const VecX& q, const VecX& v, const std::vector<int>& which,
                               std::vector<VecX>& C, VecX& curvature) {
  const Instant at = rows_.at(t);
  C.clear();
  curvature.resize(int(which.size()));
  for (size_t j = 0; j < which.size(); ++j) {
    const Contact& c = contacts_[size_t(which[j])];
    const ConstraintGroupBase& group = *model_.constraint_groups()[size_t(c.group)];
    one_[0] = c.element;
    group.jacobian(q.data(), at, rows_.Phi_q.valuePtr(), &one_);
    group.gamma(q.data(), v.data(), at, rows_.gamma.data(), &one_);
    VecX row = VecX::Zero(model_.n_coordinates());
    for (const auto& [col, slot] : c.entries) row[col] = rows_.Phi_q.valuePtr()[slot];
    C.push_back(std::move(row));
    curvature[int(j)] = rows_.gamma[c.row];
  }
}

void EventRunner::driven_through(int contact, double t, double approach, double tolerance, const char* measure) {
  const int row = contacts_[contact].row;
  const std::string stop = model_.constraint_name_of_row(row);
  // What leaves the stop's gap no motion: its gradient C (rows_.Phi_q, at
  // this q: contact_rows) is a combination of the rows held (the joints,
  // the closed rows of d_, which kkt_ holds factorized), C = Phi_q^T y with
  // M x = C - Phi_q^T y ~ 0; the stops, couplings and drivers with a part
  // in y are the ones to name
  const VecX C = VecX(rows_.Phi_q.transpose().col(row));
  VecX x(model_.n_coordinates()), y(model_.n_constraints());
  kkt_.solve(C, VecX::Zero(model_.n_constraints()), x, y);
  const double y_max = y.lpNorm<Eigen::Infinity>();
  std::vector<std::string> stops, ties;
  for (int r = 0; r < y.size(); ++r) {
    if (!(std::abs(y[r]) > 1e-6 * y_max) || r == row) continue;
    const ConstraintGroupBase& group = *model_.constraint_groups()[model_.group_of_row(r)];
    if (!group.unilateral() && !group.ties_motion()) continue;  // (a joint's rows: the part of C the joints carry)
    const std::string name = model_.constraint_name_of_row(r);
    const std::string text = "'" + name + "' (" + model_.describe(name) + ")";
    std::vector<std::string>& into = group.unilateral() ? stops : ties;
    if (std::find(into.begin(), into.end(), text) == into.end()) into.push_back(text);
  }
  const auto listed = [](const std::vector<std::string>& items) {
    std::string out;
    for (size_t k = 0; k < items.size(); ++k) out += (k == 0 ? "" : k + 1 == items.size() ? " and " : ", ") + items[k];
    return out;
  };
  const std::string moving = "its gap's " + std::string(measure) + " is " + to_text(approach) + " (beyond " +
                             to_text(tolerance) + ")";
  std::string what;
  if (!stops.empty())  // (a closed stop and a coupling allow the gap no rate: only drift gives it one)
    what = "its joint is held by " + listed(stops) +
           (ties.empty() ? "" : ", to which " + listed(ties) + (ties.size() == 1 ? " ties" : " tie") + " it") +
           ": both joints are at their limits, and this one cannot move along its limit apart. Yet " + moving +
           ", which the held rows do not allow: the motion has drifted off them by that much (a violent motion, "
           "such as an unstable controller's, outrunning the run's tolerances)";
  else if (!ties.empty())
    what = listed(ties) + (ties.size() == 1 ? " prescribes" : " prescribe") + " the motion along it and drive" +
           (ties.size() == 1 ? "s" : "") + " the joint through the limit: " + moving;
  else
    what = "the joints leave no motion along it (a singular position, such as a gimbal lock of three revolutes), "
           "and " + moving;
  throw plain_failure("stop '" + stop + "' is reached at t = " + to_text(t) + " where " + what + ". No impact or stop "
                          "force can act along a motion that is held: the run stops here.",
                      t);
}

void EventRunner::impulse(double t, const VecX& q, VecX& v, const std::vector<int>& which,
                          const std::vector<VecX>& C, VecX& e, std::vector<char>& held) {
  // M-orthogonal jump keeping the joints and the closed stops: v+ = v- + X p with
  // [M Phi_q^T; Phi_q 0] [X; Y] = [C^T; 0] and C v+ = -E C v-
  const int n = model_.n_coordinates(), m = model_.n_constraints(), k = int(which.size());
  assemble_jacobian(model_, d_, q.data(), t);
  if (!kkt_.factorize(d_)) throw plain_failure("the augmented matrix is singular at an impact, t = " + to_text(t), t);
  Eigen::MatrixXd X(n, k), A(k, k);
  VecX x(n), y(m), zero_m = VecX::Zero(m), b(k);
  for (int j = 0; j < k; ++j) {
    kkt_.solve(C[j], zero_m, x, y);
    X.col(j) = x;
  }
  held.assign(size_t(k), 0);
  assemble_mass_inverse(model_, d_, q.data());
  const double drift = 1e-6 * (1.0 + v.lpNorm<Eigen::Infinity>());
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) A(i, j) = C[i].dot(X.col(j));
    b[i] = -(1.0 + e[i]) * C[i].dot(v);
    // A(i, i) is the mobility along the limit the joints leave; next to the
    // free body's C M^-1 C^T it is 0 where drivers prescribe that motion,
    // or where the closed rows hold it (a mimic finger whose leader rests on
    // its stop, approaching only by the velocity constraints' drift): such
    // a row takes no impulse
    if (!(A(i, i) > 1e-10 * C[i].dot(d_.M_inv * C[i]))) {
      if (!(std::abs(C[i].dot(v)) <= drift)) driven_through(which[i], t, C[i].dot(v), drift, "rate");
      held[size_t(i)] = 1;
    }
  }
  for (int i = 0; i < k; ++i)
    if (held[size_t(i)]) A.row(i).setZero(), A.col(i).setZero(), A(i, i) = 1.0, b[i] = 0.0;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  lu.setThreshold(1e-9);
  if (lu.rank() < k && e.any()) {
    // dependent rows (a loop's stops, one motion striking both): their
    // rebounds -e g'- cannot all hold; the impact is plastic, g'+ = 0 for
    // each, which they can (no energy from an inconsistent target)
    e.setZero();
    for (int i = 0; i < k; ++i) b[i] = held[size_t(i)] ? 0.0 : -C[i].dot(v);
  }
  v += X * lu.solve(b);
}

std::vector<int> EventRunner::rest_contacts(double t, const VecX& q, const VecX& v, const std::vector<int>& which,
                                            const std::vector<int>& leaving, const double* qdd) {
  const int n = model_.n_coordinates(), m = model_.n_constraints(), k = int(which.size());
  std::vector<VecX> C;
  VecX curvature;
  contact_rows(t, q, v, which, C, curvature);
  // every candidate open, the other closed rows held: b = g'' without their forces
  std::vector<int> held;
  for (int row : d_.closed_rows())
    if (std::none_of(which.begin(), which.end(), [&](int c) { return contacts_[c].row == row; })) held.push_back(row);
  if (qdd && held == d_.closed_rows()) {
    // (every candidate open already: the caller's accelerations are b's; if
    // none presses on its limit, none closes and nothing is solved)
    const Eigen::Map<const VecX> a(qdd, n);
    VecX b(k);
    for (int j = 0; j < k; ++j) b[j] = C[j].dot(a) - curvature[j];
    if (k == 0 || b.minCoeff() >= -1e-9 * (1.0 + b.lpNorm<Eigen::Infinity>())) return held;
  }
  if (held != d_.closed_rows()) d_.close_rows(model_, held);
  solve_accelerations(model_, d_, kkt_, q.data(), v.data(), t, qdd_.data(), lam_.data());
  // a force f_j >= 0 along the gradient C_j (f_j = -lam_j) adds X_j f_j to qdd: g'' = b + A f
  Eigen::MatrixXd A(k, k), X(n, k);
  VecX b(k), x(n), y(m), zero_m = VecX::Zero(m);
  for (int j = 0; j < k; ++j) {
    b[j] = C[j].dot(qdd_) - curvature[j];
    kkt_.solve(C[j], zero_m, x, y);
    X.col(j) = x;
  }
  assemble_mass_inverse(model_, d_, q.data());
  // (tolerances in acceleration units)
  const double tol = 1e-9 * (1.0 + b.lpNorm<Eigen::Infinity>());
  std::vector<char> in(k, 0), may_close(k, 1), is_leaving(k, 0);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) A(i, j) = C[i].dot(X.col(j));
    is_leaving[i] = std::find(leaving.begin(), leaving.end(), which[i]) != leaving.end();
    // a motion the drivers prescribe, or the closed rows hold (a mimic
    // finger whose leader rests on its own stop: its g'' is 0 to rounding)
    if (!(A(i, i) > 1e-10 * C[i].dot(d_.M_inv * C[i]))) {
      if (b[i] < -tol) driven_through(which[i], t, b[i], tol, "acceleration");
      may_close[i] = 0;
    }
  }
  // principal pivoting with the least-index rule (Murty 1974), from "all
  // open": it ends for the P-matrices of independent stops, and of stops that
  // depend on each other (a mimic coupling's two fingers on their limits) it
  // closes the first that is needed only: the others' gaps follow it (their
  // g'' = 0), so the closed rows never become dependent. Tolerances in
  // acceleration units; a released row opens at a force within rounding of 0
  VecX f = VecX::Zero(k), w = b;
  for (int iteration = 0;; ++iteration) {
    if (iteration > 50 + 4 * k * k)
      throw plain_failure("the stop forces at t = " + to_text(t) + " could not be resolved: the pivoting over " +
                              std::to_string(k) + " stops in contact did not end (dependent stops?)",
                          t);
    std::vector<int> S;
    for (int i = 0; i < k; ++i)
      if (in[i]) S.push_back(i);
    f.setZero();
    if (!S.empty()) {
      Eigen::MatrixXd A_SS(S.size(), S.size());
      VecX b_S(S.size());
      for (size_t a = 0; a < S.size(); ++a) {
        b_S[a] = -b[S[a]];
        for (size_t c = 0; c < S.size(); ++c) A_SS(a, c) = A(S[a], S[c]);
      }
      const VecX f_S = A_SS.fullPivLu().solve(b_S);
      for (size_t a = 0; a < S.size(); ++a) f[S[a]] = f_S[a];
    }
    w = b + A * f;
    int flip = -1;
    for (int i = 0; i < k && flip < 0; ++i) {
      if (in[i] && f[i] * A(i, i) < (is_leaving[i] ? tol : -tol)) flip = i;
      if (!in[i] && may_close[i] && w[i] < -2.0 * tol) flip = i;
    }
    if (flip < 0) break;
    in[flip] = !in[flip];
  }
  std::vector<int> closed = held;
  for (int i = 0; i < k; ++i)
    if (in[i]) closed.push_back(contacts_[which[i]].row);
  std::sort(closed.begin(), closed.end());
  return closed;
}

}  // namespace lagmb
