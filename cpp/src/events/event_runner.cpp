// The event runner's layout of the event functions (the event elements',
// then one per unilateral row, then one per contact that can stick), the
// entry points that act on crossings (start, handle), and the Zeno guard.
#include "lagmb/events/event_runner.hpp"

#include <algorithm>
#include <string>

#include "events/integrator_failure.hpp"
#include "lagmb/time_function.hpp"

namespace lagmb {

EventRunner::EventRunner(const Model& model, const Data& run, double position_tol)
    : model_(model),
      d_(model, &run),
      rows_(model, &run, Data::Rows::kEvery),
      kkt_(model),
      position_tol_(position_tol) {
  const auto& groups = model.event_groups();
  for (int gi = 0; gi < int(groups.size()); ++gi) {
    for (int k = 0; k < groups[gi]->size(); ++k) {
      if (groups[gi]->sweeps() && groups[gi]->roots(k) > 0)
        sweeps_.push_back({gi, k, int(roots_.size()), groups[gi]->roots(k)});
      for (int r = 0; r < groups[gi]->roots(k); ++r) {
        roots_.push_back({gi, k, r});
        dir_.push_back(groups[gi]->direction(k, r));
      }
    }
  }
  rows_.close_rows(model, model.unilateral_rows());
  const auto& constraints = model.constraint_groups();
  for (int gi = 0; gi < int(constraints.size()); ++gi) {
    if (!constraints[gi]->unilateral()) continue;
    unilateral_groups_.push_back(gi);
    for (int k = 0; k < constraints[gi]->size(); ++k)
      for (int r = 0; r < constraints[gi]->rows(k); ++r)
        contacts_.push_back({constraints[gi]->placement(k).row0 + r, constraints[gi]->unilateral_row(k, r), gi, k, {}});
  }
  std::sort(contacts_.begin(), contacts_.end(), [](const Contact& a, const Contact& b) { return a.row < b.row; });
  const SpMat& J = rows_.Phi_q;
  for (int col = 0; col < J.outerSize(); ++col)
    for (int s = J.outerIndexPtr()[col]; s < J.outerIndexPtr()[col + 1]; ++s) {
      const int row = J.innerIndexPtr()[s];
      auto c = std::lower_bound(contacts_.begin(), contacts_.end(), row,
                                [](const Contact& a, int r) { return a.row < r; });
      if (c != contacts_.end() && c->row == row) c->entries.emplace_back(col, s);
    }
  // a gap crossing to negative (an impact), a force crossing to negative (a release)
  dir_.insert(dir_.end(), contacts_.size(), -1);
  // a contact's stick state: both ways (stick_root)
  sticks_base_ = dir_.size();
  for (int gi = 0; gi < int(constraints.size()); ++gi)
    if (constraints[gi]->sticks())
      for (int k = 0; k < constraints[gi]->size(); ++k) {
        // (its points' event functions: the event element of the same name)
        Stick s{gi, k, constraints[gi]->placement(k).row0, 0, 0};
        for (size_t i = 0; i < roots_.size(); ++i) {
          const EventGroupBase& group = *groups[roots_[i].group];
          if (group.name(roots_[i].element) != constraints[gi]->name(k)) continue;
          if (s.roots == 0) s.root0 = int(i);
          ++s.roots;
        }
        sticks_.push_back(s);
      }
  dir_.insert(dir_.end(), sticks_.size(), 0);
  forces_follow_time_ = !model.time_dependent_groups().empty() ||
                        std::any_of(model.time_functions().begin(), model.time_functions().end(),
                                    [](const TimeFunctionPtr& f) { return f->varies(); });
  g_.resize(dir_.size());
  qdd_.resize(model.n_coordinates());
  lam_.resize(model.n_constraints());
}

bool EventRunner::left(int row) const {
  return std::find(last_.left.begin(), last_.left.end(), row) != last_.left.end();
}

bool EventRunner::rebounding(int row) const {
  return std::find(last_.rebounded.begin(), last_.rebounded.end(), row) != last_.rebounded.end();
}

bool EventRunner::is_closed(int row) const {
  return std::binary_search(d_.closed_rows().begin(), d_.closed_rows().end(), row);
}

bool EventRunner::start(double t, const VecX& q, VecX& v) { return settle(t, q, v, true); }

bool EventRunner::handle(double t, const VecX& q, VecX& v, const std::vector<int>& fired) {
  check_on_constraints(t, q);
  last_.handled = fired;
  const bool restart = handle_stops(t, q, v, fired);
  if (sticks_.empty()) return restart;
  return handle_sticks(t, q, v, fired) || restart;
}

void EventRunner::count_event(double t, const std::string& element, const char* kind) {
  ++events;
  // Zeno guard: events piling up at (almost) one instant must not hang the run
  burst_.count = (t - burst_.t_last <= 1e-9 * (1.0 + std::abs(t))) ? burst_.count + 1 : 0;
  burst_.t_last = t;
  if (burst_.count >= 1000)
    throw plain_failure(std::string(kind) + " '" + element + "': 1000 events in a row at t = " + to_text(t) +
                            " without the time advancing (events accumulating: Zeno behaviour); the run stops here.",
                        t);
}

}  // namespace lagmb
