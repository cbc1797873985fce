#include "integrators/events.hpp"

#include <Eigen/LU>
#include <cmath>
#include <sstream>

#include "integrators/integrators.hpp"
#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

namespace {

/// Scatters a local row (over c: 6 or 14 entries) into a global row (over q).
VecX global_row(const VecX& local, const LocalCoords& coord, int n) {
  VecX g = VecX::Zero(n);
  for (int a = 0; a < int(local.size()); ++a)
    if (coord[a] >= 0) g[coord[a]] += local[a];
  return g;
}

/// The local entries of a global vector (0 where coord is -1).
VecX local_of(const VecX& x, const LocalCoords& coord, int size) {
  VecX c = VecX::Zero(size);
  for (int a = 0; a < size; ++a)
    if (coord[a] >= 0) c[a] = x[coord[a]];
  return c;
}

std::string fmt(double x) { return to_text(x); }

}  // namespace

EventRunner::EventRunner(const Model& model, const Data& run) : model_(model), d_(model, &run), kkt_(model) {
  const auto& groups = model.event_groups();
  for (int gi = 0; gi < int(groups.size()); ++gi) {
    for (int k = 0; k < groups[gi]->size(); ++k)
      for (int r = 0; r < groups[gi]->roots(k); ++r) {
        roots_.push_back({gi, k, r});
        dir_.push_back(groups[gi]->direction(k, r));
      }
  }
  g_.resize(roots_.size());
}

void EventRunner::values(double t, const double* q, const double* v, double* g) {
  ++root_evals;
  int offset = 0;
  for (const auto& group : model_.event_groups()) {
    group->values(q, v, t, g + offset);
    for (int k = 0; k < group->size(); ++k) offset += group->roots(k);
  }
}

bool EventRunner::start(double t, const VecX& q, VecX& v) {
  values(t, q.data(), v.data(), g_.data());
  std::vector<int> fired(roots_.size(), 0);
  bool any = false;
  const double tol = 1e-9 * (1.0 + q.lpNorm<Eigen::Infinity>());
  for (size_t i = 0; i < roots_.size(); ++i) {
    if (dir_[i] >= 0 || !(g_[i] < 0.0)) continue;
    auto& group = *model_.event_groups()[roots_[i].group];
    if (g_[i] < -tol) {
      const EventAction a = group.crossing(roots_[i].element, roots_[i].index, q.data(), v.data(), t, d_.run->state.data());
      throw ModelError(std::string(group.kind()) + " '" + group.name(roots_[i].element) +
                       "': the initial configuration is beyond its " +
                       (a.label[0] ? a.label : (roots_[i].index == 0 ? "lower" : "upper")) + " limit (by " +
                       fmt(-g_[i]) + ")");
    }
    fired[i] = 1;
    any = true;
  }
  if (!any) return false;
  const VecX v0 = v;
  handle(t, q, v, fired);
  return v != v0;
}

bool EventRunner::missed(double t, const double* q, const double* v, std::vector<int>& fired) {
  values(t, q, v, g_.data());
  fired.assign(roots_.size(), 0);
  bool any = false;
  for (size_t i = 0; i < roots_.size(); ++i)
    if (dir_[i] < 0 && g_[i] < -1e-10) {
      fired[i] = 1;  // the action decides: leaving velocities do nothing
      any = true;
    }
  return any;
}

bool EventRunner::handle(double t, const VecX& q, VecX& v, const std::vector<int>& fired) {
  const int n = model_.n_coordinates();
  bool restart = false;
  std::vector<VecX> C;              // impact gradients over q
  std::vector<EventAction> act;
  std::vector<size_t> which;
  for (size_t i = 0; i < roots_.size(); ++i) {
    if (!fired[i]) continue;
    auto& group = *model_.event_groups()[roots_[i].group];
    const EventAction a = group.crossing(roots_[i].element, roots_[i].index, q.data(), v.data(), t, d_.run->state.data());
    if (a.type == EventAction::kNone) continue;
    ++events;
    restart = true;
    // Zeno guard: events piling up at (almost) one instant must not hang the run
    burst_ = (t - t_last_ <= 1e-9 * (1.0 + std::abs(t))) ? burst_ + 1 : 0;
    t_last_ = t;
    if (burst_ >= 1000) {
      IntegratorFailure f(std::string(group.kind()) + " '" + group.name(roots_[i].element) +
                              "': 1000 events in a row at t = " + fmt(t) +
                              " without the time advancing (events accumulating: Zeno behaviour); the run stops here.",
                          t);
      f.diagnose = false;
      throw f;
    }
    if (a.type == EventAction::kRestart) {
      records.push_back({t, group.name(roots_[i].element), "restart", a.label, a.speed, a.speed});
      continue;
    }
    C.push_back(global_row(a.gradient, group.coordinates(roots_[i].element), n));
    act.push_back(a);
    which.push_back(i);
  }
  if (C.empty()) return restart;

  // M-orthogonal jump keeping the joints: v+ = v- + X p with
  // [M Phi_q^T; Phi_q 0] [X; Y] = [C^T; 0] and C v+ = -E C v-.
  const int k = int(C.size()), m = model_.n_constraints();
  assemble_jacobian(model_, d_, q.data(), t);
  if (!kkt_.factorize(d_)) throw IntegratorFailure("the augmented matrix is singular at an impact, t = " + fmt(t), t);
  Eigen::MatrixXd X(n, k), A(k, k);
  VecX x(n), y(m), zero_m = VecX::Zero(m), b(k);
  for (int j = 0; j < k; ++j) {
    kkt_.solve(C[j], zero_m, x, y);
    X.col(j) = x;
  }
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) A(i, j) = C[i].dot(X.col(j));
    b[i] = -(1.0 + act[i].restitution) * C[i].dot(v);
    // A(i, i) is the mobility along the limit left by the joints; next to the
    // free body's C M^-1 C^T it is 0 when drivers prescribe that motion, and
    // no impulse can change it: a driver pushing through its own stop
    const double free_mobility = C[i].dot(d_.M_inv * C[i]);
    if (!(A(i, i) > 1e-10 * free_mobility)) {
      auto& group = *model_.event_groups()[roots_[which[i]].group];
      IntegratorFailure f(std::string(group.kind()) + " '" + group.name(roots_[which[i]].element) +
                              "' is reached at t = " + fmt(t) + " along a motion the joints and drivers prescribe: " +
                              "no impact can change it (a driver pushing through the limit); the run stops here.",
                          t);
      f.diagnose = false;
      throw f;
    }
  }
  const VecX before = v;
  v += X * A.fullPivLu().solve(b);
  impacts += k;

  // coming to rest: a slow rebound while the motion presses on the limit
  VecX qdd(n), lam(m);
  bool have_qdd = false;
  for (int j = 0; j < k; ++j) {
    const auto& r = roots_[which[j]];
    auto& group = *model_.event_groups()[r.group];
    const double s0 = C[j].dot(before), s1 = C[j].dot(v);
    records.push_back({t, group.name(r.element), "impact", act[j].label, s0, s1});
    if (!(s1 < act[j].rest_speed)) continue;
    if (!have_qdd) {
      solve_accelerations(model_, d_, kkt_, q.data(), v.data(), t, qdd.data(), lam.data());
      have_qdd = true;
    }
    const VecX cd = local_of(v, group.coordinates(r.element), int(act[j].gradient.size()));
    const double gdd = C[j].dot(qdd) + cd.dot(act[j].hessian * cd);
    if (gdd < -1e-9 * (1.0 + C[j].norm() * qdd.norm())) {
      records.back().kind = "rest";
      std::ostringstream msg;
      msg << group.kind() << " '" << group.name(r.element) << "' came to rest against its " << act[j].label
          << " limit at t = " << t << ": the rebound speed " << s1 << " is below rest_speed = " << act[j].rest_speed
          << " and the motion presses on the limit (acceleration " << gdd
          << "). Resting contact is not modelled: the run stops here (impact " << impacts
          << "); the events so far are in the partial result.";
      IntegratorFailure f(msg.str(), t);
      f.diagnose = false;
      throw f;
    }
  }
  return true;
}

ConsistentState EventRunner::consistent(double t, const VecX& q, const VecX& v) {
  // the state at a root is interpolated: put the positions back on Phi = 0
  // (least change) and the velocities on Phi_q v + Phi_t = 0 before the
  // index-2 and index-3 forms restart from it
  return make_consistent(model_, d_, kkt_, q, v, t);
}

}  // namespace lagmb
