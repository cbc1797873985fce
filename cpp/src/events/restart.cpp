// The state a run restarts from after an event: on its constraints (or a
// failure where the steps had lost them), the stops acted on put on their
// limits, the released ones at rest, and the crossings the projection
// causes acted on.
#include "lagmb/events/event_runner.hpp"

#include <algorithm>
#include <cmath>

#include "events/integrator_failure.hpp"
#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

void EventRunner::check_on_constraints(double t, const VecX& q) {
  assemble_constraints(model_, d_, q.data(), t);
  if (d_.Phi.size() == 0) return;
  Eigen::Index row = 0;
  const double off = d_.Phi.cwiseAbs().maxCoeff(&row);
  const double limit = 1e-2 * (1.0 + q.lpNorm<Eigen::Infinity>());
  if (off <= limit) return;
  throw plain_failure("the constraints had come apart before the event at t = " + to_text(t) + ": |Phi| = " + to_text(off) +
                          " at '" + model_.constraint_name_of_row(int(row)) + "' (more than 1e-2 (1 + |q|) = " +
                          to_text(limit) +
                          "): the steps before it had lost the motion, and a restart would hide that. The methods "
                          "that hold the constraints only through their second derivatives (index1, "
                          "projection-adams) drift; use one that keeps them (ggl, projection-bdf, projection-erk), "
                          "a smaller rtol, or baumgarte=(alpha, beta)",
                      t);
}

void EventRunner::gaps(double t, const VecX& q, const VecX& v) {
  const Instant at = rows_.at(t);
  for (int gi : unilateral_groups_) {
    model_.constraint_groups()[gi]->phi(q.data(), at, rows_.Phi.data());
    model_.constraint_groups()[gi]->jacobian(q.data(), at, rows_.Phi_q.valuePtr());
  }
  rows_.phi_t.setZero();  // (scratch: Phi_q v of the gaps)
  add_jacobian_times(rows_, v.data(), rows_.phi_t.data());
}

double EventRunner::rate(const Contact& c, const double* v) const {
  double r = 0.0;
  for (const auto& [col, slot] : c.entries) r += rows_.Phi_q.valuePtr()[slot] * v[col];
  return r;
}

ConsistentState EventRunner::consistent(double t, const VecX& q, const VecX& v) {
  ConsistentState state = restart_state(t, q, v);
  if (roots_.empty()) return state;
  // an event element's function that the restart's projection moved across
  // 0 (two corners crossing together, one found: the other put past its
  // crossing by rounding) crosses here: the steps from the restart would not see it
  const size_t n = roots_.size();
  std::vector<double> before(g_.size()), after(g_.size());
  last_.pins.clear();  // (the last restart's: these values are the functions' own)
  values(t, q.data(), v.data(), before.data());
  values(t, state.q.data(), state.v.data(), after.data(), state.lam.data());  // (solved on the rows now closed)
  for (size_t i = 0; i < n; ++i) {
    if (i < last_.handled.size() && last_.handled[i]) {
      // crossed (last_.handled[i]: which way): pinned to its new side until a
      // step's end finds it there (the restart's projection, or the first
      // step's error, can put it back by rounding: found again, it would be
      // logged twice, or again and again at a point touching at rest)
      last_.pins.push_back({int(i), last_.handled[i] > 0 ? 1 : -1, 10.0 * std::abs(after[i])});
      continue;
    }
    if ((before[i] > 0.0) == (after[i] > 0.0)) continue;
    if (dir_[i] < 0 && !(after[i] < 0.0)) continue;  // (a function counting downward crossings only)
    auto& group = *model_.event_groups()[roots_[i].group];
    const EventAction a = group.crossing(roots_[i].element, roots_[i].index, state.q.data(), state.v.data(), t,
                                         d_.run->state.data(), after[i] > 0.0 ? 1 : -1);
    if (a.type == EventAction::kNone) continue;
    count_event(t, group.name(roots_[i].element), group.kind());
    records.push_back({t, group.name(roots_[i].element), "restart", a.label, a.speed, a.speed});
  }
  return state;
}

ConsistentState EventRunner::restart_state(double t, const VecX& q, const VecX& v) {
  window_.forget();
  // the state at a root is interpolated: put the positions back on Phi = 0
  // (least change; the closed stops' rows included) and the velocities on
  // Phi_q v + Phi_t = 0 before the index-2 and index-3 forms restart from it.
  // An open stop found beyond its limit (a crossing the steps passed, acted
  // on late) is put back on the limit first: its row held for the positions
  // only, so that the rebound's velocity stays and no joint sinks through
  if (contacts_.empty()) return make_consistent(model_, d_, kkt_, q, v, t);
  std::vector<int> held = d_.closed_rows();
  const std::vector<int> closed = held;
  // (a stop released here leaves its limit at rest, g' = 0: the velocities
  // are projected with its row held too, then the accelerations solved
  // without it; a formulation whose velocities keep only Phi = 0 (index 3)
  // has it approaching by its error, a new impact at once, and a chatter)
  std::vector<int> at_rest = closed;
  at_rest.insert(at_rest.end(), last_.released.begin(), last_.released.end());
  std::sort(at_rest.begin(), at_rest.end());
  auto with_rows = [&](const std::vector<int>& rows, auto&& solve) {
    d_.close_rows(model_, rows);
    try {
      auto out = solve();
      d_.close_rows(model_, closed);
      return out;
    } catch (...) {
      d_.close_rows(model_, closed);
      throw;
    }
  };
  auto project = [&]() {
    VecX on_limits = q;
    if (held.size() > closed.size())
      on_limits = with_rows(held, [&] { return solve_positions(model_, d_, kkt_, q, t); });
    if (last_.released.empty()) return make_consistent(model_, d_, kkt_, on_limits, v, t);
    const ConsistentState resting = with_rows(at_rest, [&] { return make_consistent(model_, d_, kkt_, on_limits, v, t); });
    return make_consistent(model_, d_, kkt_, resting.q, resting.v, t);
  };
  // (so is a stop whose crossing this event acted on: it is at its limit by
  // definition, while the interpolant it was found on, not on Phi = 0, can
  // put it 1e-6 off there)
  gaps(t, q, v);
  for (const Contact& c : contacts_)
    if (c.info.exists && !is_closed(c.row) &&
        (rows_.Phi[c.row] < 0.0 || std::find(last_.on_limit.begin(), last_.on_limit.end(), c.row) != last_.on_limit.end()))
      held.push_back(c.row);
  // (a row the event left open on its limit, released or rebounding, reads
  // as inside at the restart whatever its rate's rounding, and a released
  // one until a step ends with it off the limit: a release at a force the
  // interpolant put 0 a little early starts moving back in, and that is a
  // crossing to find, not one already passed; see values())
  last_.restart_t = t;
  last_.left.clear();
  for (int row : last_.on_limit)
    if (!is_closed(row)) last_.left.push_back(row);
  last_.on_limit.clear();
  std::sort(held.begin(), held.end());
  ConsistentState state = project();
  // The projection moves the other joints too: it can put a stop beyond its
  // limit (a joint held on its limit, or a driver's new value, pushing a
  // coupled one through its own: 0.65 rad beyond in a chain), which is held
  // on its limit too, and the positions projected again, until none is
  // (an active set on the positions). A stop leaving its limit (a rebound,
  // a release) is there to within the interpolant's error: the projection
  // onto the joints can put it just beyond, where its gap reads as crossed
  // already and its next crossing in the first step shows no sign change
  // (missed, acted on late with a larger speed): it is held too. (One just
  // beyond and approaching is left: its crossing is found as missed.)
  const double at_limit = 1e-9 * (1.0 + q.lpNorm<Eigen::Infinity>());
  for (size_t pass = 0; pass < contacts_.size(); ++pass) {
    gaps(t, state.q, state.v);
    const size_t before = held.size();
    for (const Contact& c : contacts_)
      if (c.info.exists && !is_closed(c.row) && rows_.Phi[c.row] < 0.0 &&
          (rows_.Phi[c.row] <= -at_limit || rows_.phi_t[c.row] >= 0.0) &&
          !std::binary_search(held.begin(), held.begin() + long(before), c.row))
        held.push_back(c.row);
    if (held.size() == before) break;
    std::sort(held.begin(), held.end());
    state = project();
  }
  // (so is every open row the restart finds resting on its limit, acted on
  // or not: a stop duplicating a closed one that is released, a coupled one
  // resting open, would strike at its velocity's rounding)
  gaps(t, state.q, state.v);
  const double still = 1e-9 * (1.0 + state.v.lpNorm<Eigen::Infinity>());
  for (const Contact& c : contacts_)
    if (c.info.exists && !is_closed(c.row) && std::abs(rows_.Phi[c.row]) <= 1e-10 &&
        std::abs(rows_.phi_t[c.row]) <= still && !left(c.row))
      last_.left.push_back(c.row);
  return state;
}

}  // namespace lagmb
