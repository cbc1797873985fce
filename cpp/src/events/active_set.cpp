// The active set of the unilateral rows at an event (docs/methods.md, "The active set, step by step"):
// settle() where the equations jump, handle_stops() at crossings (the event
// elements' actions, impacts, captures and releases).
#include "lagmb/events/event_runner.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

bool EventRunner::settle(double t, const VecX& q, VecX& v, bool at_start, const double* lam, const double* qdd) {
  if (!at_start) check_on_constraints(t, q);
  window_.forget();  // (a new start, or the equations jump here)
  values(t, q.data(), v.data(), g_.data(), lam);
  std::vector<int> fired(g_.size(), 0);
  bool any = false, beyond = false;
  const double tol = 1e-9 * (1.0 + q.lpNorm<Eigen::Infinity>());
  const double force_tol = 1e-8 * (1.0 + lam_.lpNorm<Eigen::Infinity>());
  const size_t base = roots_.size();
  for (size_t i = 0; i < g_.size(); ++i) {
    if (dir_[i] >= 0) continue;
    const bool contact = i >= base;
    if (!contact && !at_start) continue;  // (an event element's switch waits for its crossing)
    const bool closed = contact && is_closed(contacts_[i - base].row);
    // a stop at its limit is in contact; a closed one whose force turned to pull lets go
    if (!(g_[i] < (closed ? force_tol : contact ? tol : 0.0))) continue;
    if (at_start && !closed && g_[i] < -tol) {
      std::string kind, name, label;
      if (contact) {
        const Contact& c = contacts_[i - base];
        name = model_.constraint_name_of_row(c.row);
        kind = model_.constraint_groups()[model_.find(name).group]->kind();
        label = c.info.label;
      } else {
        auto& group = *model_.event_groups()[roots_[i].group];
        kind = group.kind(), name = group.name(roots_[i].element), label = roots_[i].index == 0 ? "lower" : "upper";
      }
      throw ModelError(kind + " '" + name + "': the initial configuration is beyond its " + label + " limit (by " +
                       to_text(-g_[i]) + ")");
    }
    // (a jump of the equations, a driver's new value, can put a joint beyond a limit: consistent() puts it back)
    if (contact && !closed && g_[i] < -tol) beyond = true;
    fired[i] = -1;
    any = true;
  }
  const VecX v0 = v;
  const std::vector<int> closed0 = d_.closed_rows();
  last_.handled = fired;  // (what consistent() then pins)
  if (any) handle_stops(t, q, v, fired, qdd);
  if (!sticks_.empty()) handle_sticks(t, q, v, fired);
  return v != v0 || d_.closed_rows() != closed0 || beyond;
}

bool EventRunner::handle_stops(double t, const VecX& q, VecX& v, const std::vector<int>& fired, const double* qdd) {
  bool restart = false;
  window_.forget();  // (the state may jump here)
  last_.on_limit.clear();
  last_.released.clear();
  const bool late = last_.late;
  last_.late = false;
  const std::vector<int> rebounded = last_.rebounded;  // (of the last event that acted, and their speeds)
  const std::vector<double> rebound_speed = last_.rebound_speed;
  const double rebound_t = last_.rebound_t;
  std::vector<int> rebounding;
  for (size_t i = 0; i < roots_.size(); ++i) {
    if (!fired[i]) continue;
    auto& group = *model_.event_groups()[roots_[i].group];
    // (fired[i]: the way it crossed, -1 or +1, as SUNDIALS' root info)
    const EventAction a =
        group.crossing(roots_[i].element, roots_[i].index, q.data(), v.data(), t, d_.run->state.data(), fired[i]);
    if (a.type == EventAction::kNone) continue;
    count_event(t, group.name(roots_[i].element), group.kind());
    restart = true;
    records.push_back({t, group.name(roots_[i].element), "restart", a.label, a.speed, a.speed});
  }
  if (contacts_.empty()) return restart;

  // the stops' crossings: gaps closing (impacts, or a joint arriving at rest) and forces turning to pull
  std::vector<int> arriving, leaving;
  for (size_t c = 0; c < contacts_.size(); ++c)
    if (fired[roots_.size() + c] && contacts_[c].info.exists)
      (is_closed(contacts_[c].row) ? leaving : arriving).push_back(int(c));
  if (arriving.empty() && leaving.empty()) return restart;
  for (int c : arriving) last_.on_limit.push_back(contacts_[c].row);
  for (int c : leaving) last_.on_limit.push_back(contacts_[c].row);
  std::vector<VecX> C;
  VecX curvature;
  contact_rows(t, q, v, arriving, C, curvature);
  const double v_scale = 1e-9 * (1.0 + v.lpNorm<Eigen::Infinity>());
  std::vector<int> hit, resting;
  std::vector<VecX> C_hit;
  for (size_t j = 0; j < arriving.size(); ++j) {
    const double s = C[j].dot(v);  // g'
    if (s < -v_scale) {
      hit.push_back(arriving[j]);
      C_hit.push_back(C[j]);
    } else if (s <= v_scale) {
      resting.push_back(arriving[j]);
    }
  }
  const std::vector<int> closed_before = d_.closed_rows();
  std::vector<int> captured;
  std::vector<char> held;  // (of the hit rows: the closed rows hold them)
  const VecX v_before = v;
  // the open stops at their limits (within rounding of the positions) that
  // the velocities v move into them, other than those hit, joined to the
  // impact: their rows, and their limits held at the restart
  auto join_approaching = [&](const VecX& velocities) {
    std::vector<int> at_limit;
    gaps(t, q, velocities);
    const double near = 1e-9 * (1.0 + q.lpNorm<Eigen::Infinity>());
    for (size_t c = 0; c < contacts_.size(); ++c)
      if (contacts_[c].info.exists && !is_closed(contacts_[c].row) && rows_.Phi[contacts_[c].row] <= near &&
          rows_.phi_t[contacts_[c].row] < -v_scale && std::find(hit.begin(), hit.end(), int(c)) == hit.end())
        at_limit.push_back(int(c));
    std::vector<VecX> C_more;
    VecX unused;
    if (!at_limit.empty()) contact_rows(t, q, velocities, at_limit, C_more, unused);
    for (size_t j = 0; j < at_limit.size(); ++j) {
      hit.push_back(at_limit[j]), C_hit.push_back(C_more[j]);
      last_.on_limit.push_back(contacts_[at_limit[j]].row);
    }
    return !at_limit.empty();
  };
  // stops struck at the same instant, the root functions having flagged
  // some (two pendulums falling onto their own stops, their limits 1e-9 rad
  // apart): each strikes with its own restitution; impulse() makes plastic
  // only rows that depend on each other
  if (!hit.empty()) join_approaching(v_before);
  VecX e(int(hit.size()));
  if (!hit.empty()) {
    for (size_t j = 0; j < hit.size(); ++j) e[int(j)] = contacts_[hit[j]].info.restitution;
    impulse(t, q, v, hit, C_hit, e, held);
    // an impact passes its impulse through the joints: another stop at its
    // limit (an adjacent joint, a coupled finger) that it drives into its
    // limit takes part in it, so that no joint leaves an impact moving
    // beyond a limit; the impact is then plastic
    while (join_approaching(v)) {
      // (plastic for all: Newton's law at several contacts coupled through
      // the joints can give energy; the M-orthogonal jump onto g' = 0 for
      // each cannot)
      e.setZero(int(hit.size()));
      v = v_before;
      impulse(t, q, v, hit, C_hit, e, held);
    }
    // a row the closed rows hold took no impulse: it has no impact
    for (size_t j = hit.size(); j-- > 0;)
      if (held[j]) {
        hit.erase(hit.begin() + long(j)), C_hit.erase(C_hit.begin() + long(j));
        e.segment(long(j), e.size() - long(j) - 1) = e.tail(e.size() - long(j) - 1).eval();
        e.conservativeResize(e.size() - 1);
      }
  }
  if (!hit.empty()) {
    const int k = int(hit.size());
    VecX s0(k);
    for (int j = 0; j < k; ++j) s0[j] = C_hit[j].dot(v_before);
    impacts += k;
    // a rebound ends on the limit (captured) when e = 0, when it is slower
    // than rest_speed (or than what reads as at rest: 1e-9 (1 + |v|)), or
    // when the motion presses on the limit (g'' < 0 with the row open) and
    // the remaining bounces, flights of 2 s1 / |g''| shrinking by e each,
    // add up to less than capture_time
    solve_accelerations(model_, d_, kkt_, q.data(), v.data(), t, qdd_.data(), lam_.data());
    std::vector<VecX> C_after;
    VecX curvature_after;  // gamma_r at the rebound velocity
    contact_rows(t, q, v, hit, C_after, curvature_after);
    bool redo = false;
    for (int j = 0; j < k; ++j) {
      const UnilateralRow& info = contacts_[hit[j]].info;
      const double s1 = C_hit[j].dot(v);
      const double g_dd = C_hit[j].dot(qdd_) - curvature_after[j];
      // (a rebound slower than the speed that reads as at rest: an impact
      // at that speed is a joint pressed on its limit from rest, found where
      // its approach passed that speed; a rebound would return at once)
      const bool slow = s1 < v_scale || (info.rest_speed > 0.0 && s1 < info.rest_speed);
      const bool short_series = g_dd < 0.0 && 2.0 * s1 < info.capture_time * (1.0 - e[j]) * -g_dd;
      // a rebound from the event this segment started at whose return the
      // integrator found only at a step's end (its first step, at order 1,
      // longer than the flight): the steps cannot resolve the series that
      // is left, and each late return would strike faster than the last
      // rebound, a chatter that never ends; it ends here
      // (or one that returns faster than it left, by a fifth, from a flight
      // lower than the positions are accurate, s1^2 / 2|g''| with g'' its
      // mean over the flight: the steps did not resolve it, and each return
      // would strike as fast as the impact before, 1/e times the rebound)
      const auto was = std::find(rebounded.begin(), rebounded.end(), contacts_[hit[j]].row);
      bool unresolved = false;
      if (was != rebounded.end()) {
        const double s1 = rebound_speed[size_t(was - rebounded.begin())], flight = t - rebound_t;
        const double mean_g_dd = flight > 0.0 ? (s0[j] - s1) / flight : 0.0;
        const bool low = mean_g_dd < 0.0 && s1 * s1 < 2.0 * -mean_g_dd * position_tol_;
        unresolved = late || (-s0[j] > 1.2 * s1 && low);
      }
      if (e[j] == 0.0 || slow || short_series || unresolved) {
        captured.push_back(hit[j]);
        if (e[j] != 0.0) redo = true;
        e[j] = 0.0;
      }
    }
    if (redo) {  // the captured ones plastic: no rebound
      v = v_before;
      impulse(t, q, v, hit, C_hit, e, held);
    }
    last_.rebound_speed.clear();
    for (int j = 0; j < k; ++j)
      if (e[j] > 0.0) rebounding.push_back(contacts_[hit[j]].row), last_.rebound_speed.push_back(C_hit[j].dot(v));
    last_.rebounded = rebounding, last_.rebound_t = t;
    for (int j = 0; j < k; ++j) {
      const std::string name = model_.constraint_name_of_row(contacts_[hit[j]].row);
      count_event(t, name, "stop");
      records.push_back({t, name, "impact", contacts_[hit[j]].info.label, s0[j], C_hit[j].dot(v)});
    }
    restart = true;
  }
  if (captured.empty() && resting.empty() && leaving.empty()) return restart;

  // the active set among the stops at rest on their limits: those closed,
  // captured now, or arriving at rest
  std::vector<int> candidates = leaving;
  for (size_t c = 0; c < contacts_.size(); ++c)
    if (is_closed(contacts_[c].row) && std::find(leaving.begin(), leaving.end(), int(c)) == leaving.end())
      candidates.push_back(int(c));
  candidates.insert(candidates.end(), captured.begin(), captured.end());
  candidates.insert(candidates.end(), resting.begin(), resting.end());
  std::sort(candidates.begin(), candidates.end());
  // (qdd holds for the state before any impact and the rows closed before it)
  const std::vector<int> closed =
      rest_contacts(t, q, v, candidates, leaving, hit.empty() && captured.empty() ? qdd : nullptr);
  if (closed != d_.closed_rows()) d_.close_rows(model_, closed);
  for (int c : candidates) {
    const int row = contacts_[c].row;
    const bool was = std::binary_search(closed_before.begin(), closed_before.end(), row);
    const bool now = std::binary_search(closed.begin(), closed.end(), row);
    if (was == now) continue;
    if (!now) last_.on_limit.push_back(row), last_.released.push_back(row);  // (on its limit, at rest: see consistent())
    const std::string name = model_.constraint_name_of_row(row);
    count_event(t, name, "stop");
    records.push_back({t, name, now ? "capture" : "release", contacts_[c].info.label, 0.0, 0.0});
    ++(now ? captures : releases);
  }
  if (hit.empty() && closed != closed_before) last_.rebounded.clear(), last_.rebound_speed.clear();
  return restart || closed != closed_before;
}

}  // namespace lagmb
