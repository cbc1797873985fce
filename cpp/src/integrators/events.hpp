// The event runner: evaluates the event functions of a model's event
// elements for the integrators, and applies the elements' actions at their
// crossings (impacts, restarts). The steppers never name a kind.
#pragma once

#include <cmath>
#include <vector>

#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/model/data.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

class EventRunner {
 public:
  /// run: the run's Data (its dropped rows, and the run state that
  /// crossings write and the run's force kernels read).
  EventRunner(const Model& model, const Data& run);
  /// Number of event functions over all event elements (0: none).
  int size() const { return int(roots_.size()); }
  /// SUNDIALS root directions (-1: downward crossings only, 0: both).
  int* directions() { return dir_.data(); }
  /// g at (q, v, t), all event functions.
  void values(double t, const double* q, const double* v, double* g);
  /// At the start: a joint beyond a limit is a ModelError; one at a limit
  /// with approaching velocity gets its impact now. Returns true if v changed.
  bool start(double t, const VecX& q, VecX& v);
  /// After a step that found no root: event functions of direction -1 that
  /// are below zero with the motion still going further (a crossing the
  /// integrator missed) are flagged in `fired`. Returns true if any.
  bool missed(double t, const double* q, const double* v, std::vector<int>& fired);
  /// Applies the actions of the flagged crossings at (t, q, v); v gets the
  /// velocity jump of impacts. Returns true if the integrator must restart.
  /// Throws IntegratorFailure when a stop comes to rest against its limit.
  bool handle(double t, const VecX& q, VecX& v, const std::vector<int>& fired);
  /// q, v with accelerations and multipliers: the state to restart from.
  ConsistentState consistent(double t, const VecX& q, const VecX& v);

  std::vector<EventRecord> records;
  long events = 0, impacts = 0, root_evals = 0;

 private:
  struct Root {
    int group, element, index;
  };
  const Model& model_;
  Data d_;
  AugmentedSystem kkt_;
  std::vector<Root> roots_;
  std::vector<int> dir_;
  std::vector<double> g_;
  double t_last_ = -INFINITY;
  int burst_ = 0;
};

}  // namespace lagmb
