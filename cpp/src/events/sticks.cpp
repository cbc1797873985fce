// The contacts' stick states: a stuck contact released where its friction
// passes its limit, an armed one slipping slowly stuck where the friction
// it then needs holds, a disarmed one armed again.
#include "lagmb/events/event_runner.hpp"

#include <algorithm>
#include <string>

#include "lagmb/assembly/assembly.hpp"
#include "lagmb/errors.hpp"

namespace lagmb {

bool EventRunner::handle_sticks(double t, const VecX& q, const VecX& v, const std::vector<int>& fired) {
  window_.forget();
  double* run = d_.run->state.data();
  const Instant at = d_.at(t);
  if (!d_.closed_rows().empty()) solve_accelerations(model_, d_, kkt_, q.data(), v.data(), t, qdd_.data(), lam_.data());
  const double force_tol = 1e-8 * (1.0 + lam_.lpNorm<Eigen::Infinity>());
  bool changed = false;
  std::vector<int> release;
  for (size_t j = 0; j < sticks_.size(); ++j) {
    const Stick& s = sticks_[j];
    const ConstraintGroupBase& g = *model_.constraint_groups()[s.group];
    const int state = g.stick_state(s.element, run);
    const double x = g.stick_root(s.element, q.data(), v.data(), at, lam_.data());
    if (state == 1) {  // stuck: released where the friction it holds passes its limit (or nothing presses)
      if (x < -force_tol || fired[sticks_base_ + j]) {
        release.push_back(int(j));
      } else if (std::any_of(fired.begin() + s.root0, fired.begin() + s.root0 + s.roots, [](int f) { return f != 0; })) {
        // a point pressing or letting go: held again at the vertices pressing now (rocking
        // from one edge onto another, the old edge's anchor would drag the new one)
        g.stick_hold(s.element, q.data(), v.data(), run);
        changed = true;
      }
    } else if (state == -1) {  // disarmed: armed once it slips faster than 2 v_s
      if (x > 0.0) g.stick_set(s.element, run, 0);
    }
  }
  if (!release.empty()) {
    std::vector<int> closed = d_.closed_rows();
    for (int j : release) {
      const Stick& s = sticks_[size_t(j)];
      const ConstraintGroupBase& g = *model_.constraint_groups()[s.group];
      for (int r = 0; r < g.rows(s.element); ++r) closed.erase(std::remove(closed.begin(), closed.end(), s.row0 + r), closed.end());
      g.stick_set(s.element, run, -1);
      const std::string name = g.name(s.element);
      count_event(t, name, "contact");
      records.push_back({t, name, "friction", "slip", 0.0, 0.0});
    }
    d_.close_rows(model_, closed);
    changed = true;
  }
  // the armed contacts slipping slower than v_s stick, one at a time (each
  // with the ones stuck before it), where the friction then needed holds
  for (size_t j = 0; j < sticks_.size(); ++j) {
    const Stick& s = sticks_[j];
    const ConstraintGroupBase& g = *model_.constraint_groups()[s.group];
    if (g.stick_state(s.element, run) != 0) continue;
    if (!(g.stick_root(s.element, q.data(), v.data(), at, lam_.data()) < 0.0)) continue;
    const std::vector<int> before = d_.closed_rows();
    if (!g.stick_hold(s.element, q.data(), v.data(), run)) continue;
    std::vector<int> closed = before;
    for (int r = 0; r < g.rows(s.element); ++r) closed.push_back(s.row0 + r);
    std::sort(closed.begin(), closed.end());
    d_.close_rows(model_, closed);
    bool holds = false;
    try {
      const ConsistentState held = make_consistent(model_, d_, kkt_, q, v, t);
      holds = g.stick_root(s.element, held.q.data(), held.v.data(), at, held.lam.data()) >= 0.0;
    } catch (const SimulationError&) {
      holds = false;  // (rows that would depend on the ones holding the body already: it slips)
    }
    if (!holds) {
      d_.close_rows(model_, before);
      g.stick_set(s.element, run, -1);
      continue;
    }
    const std::string name = g.name(s.element);
    count_event(t, name, "contact");
    records.push_back({t, name, "friction", "stick", 0.0, 0.0});
    changed = true;
  }
  return changed;
}

}  // namespace lagmb
