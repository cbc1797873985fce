// The turns of spatial joints' angles in a run. A spatial revolute's angle
// is read from its bodies' orientations, atan2 in (-pi, pi]: from one
// configuration alone it is known only up to whole turns. A run counts them:
// per turning joint it keeps the angle the joint had at its last step, and
// every element that reads the angle reads it within pi of that
// (spatial::JointReading), so the angle is continuous however many turns
// the joint makes (a wound torsion spring, a coupling through several
// turns, r.joint(name).angle).
#pragma once

#include <string>

#include "lagmb/model/joint_reading.hpp"
#include "lagmb/model/constraint_group.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

class Model;

/// One spatial joint that turns (a revolute, a cylindrical joint). Its run
/// state (Data::RunValues::state at run_state): the angle at the last step
/// minus reading.center (rad), and the angle's rate there (rad/s); zero at
/// the start of a run: the angle of the initial configuration.
struct TurnCounter {
  static constexpr int run_state_size = 2;
  int run_state = -1;  // set by the Model
  std::string joint;
  int body_i = -1, body_j = -1;
  spatial::JointReading reading;  // center: the angle in the model's initial configuration; turns: run_state
  /// Whether a force or constraint reads the angle in the run's equations
  /// (then a step must turn the joint by less than half a turn).
  bool read = false;
  LocalCoords where = ElementPlacement::filled_coords();  // the bodies' coordinates in q, set by finalize
};

/// After a step of length h that ended at (q, v) (h = 0: at a start, or where
/// a run's state was set): each counter's angle moves to the joint's angle
/// there, read within pi of where it was; the whole turns are the ones that
/// the trapezoid rule on the rates before and after puts nearest (exact for
/// a joint turning at a constant rate, right while the rule errs by less
/// than half a turn: outputs far apart in a kinematic analysis). Returns the
/// first counter that a force or constraint reads whose angle moved by half
/// a turn or more (they read it across the wrap inside the step: the step
/// is wrong), else null.
const TurnCounter* count_turns(const Model& model, const double* q, const double* v, double h, double* state);

}  // namespace lagmb
