// What a run's outputs give beyond q, v, a and lam: reactions, driver
// efforts, joint friction, energy and constraint residuals, output by output
// (free functions over the model and the outputs, as Python's Result and
// C++ users call them).
#pragma once

#include <string>
#include <vector>

#include "lagmb/analyses/joint_space.hpp"
#include "lagmb/model/model.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

/// Row-major numbers, one row per output.
using OutputRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The outputs of a run as arrays, one row per output time: a Trajectory's
/// (OutputView::of) or arrays a binding holds (not copied). q, v, lam may be
/// null where a function does not read them; inputs null: the inputs at
/// their initial values (simulate's); state null: the elements' state at the
/// start of a run (each spatial joint's angle within half a turn of its
/// initial one).
struct OutputView {
  int k = 0;  // outputs
  const double* t = nullptr;       // (k)
  const double* q = nullptr;       // (k, n)
  const double* v = nullptr;       // (k, n)
  const double* lam = nullptr;     // (k, m)
  const double* inputs = nullptr;  // (k, p): Model::inputs() at each output
  const double* state = nullptr;   // (k, Model::run_state_size()): the run's element state (null: the initial)
  static OutputView of(const Trajectory& tr);
};

/// Force and torque that the joint or driver `element` applies to its second
/// body, about that body's centre of mass, at each output: (k, 3) in the
/// plane (force x, y and the torque), (k, 6) in space (force, torque); in
/// global axes, or in the element's own axes with joint_axes (the planar
/// torque unchanged). From -Phi_c^T lam of the element's rows. With
/// about_joint the torque is about the joint's point on that body instead
/// (its kind's origin: a revolute's pin), M_P = M_G + (r_G - r_P) x F;
/// ModelError for a kind without a point (a driver, a gear).
OutputRows reactions(const Model& model, const std::string& element, const OutputView& out, bool joint_axes = false,
                     bool about_joint = false);

/// The names of reactions()' columns, as an output name ends
/// ("hinge.reaction.torque"): x, y, torque in the plane (dimension 2);
/// x, y, z, torque.x, torque.y, torque.z in space (3).
const std::vector<std::string>& reaction_components(int dimension);

/// (k, width) what `element` applies at each output, as its kind's registry
/// entry says (KindInfo::effort, effort_components: width 1 unless it names
/// several): a driver's force or torque along what it drives (-lam of its
/// row), a stop's along its joint, a force element's as applied (a spring's
/// tension, a servo's torque after its limit, an applied force's vector in
/// global axes), a joint friction's torque or force. A force element's
/// reading needs q and v (and the inputs and state it reads); a driver's,
/// stop's and friction's lam. ModelError for an element whose kind has none
/// (a joint: its reaction; a contact: contacts()).
OutputRows efforts(const Model& model, const std::string& element, const OutputView& out);

/// (k, 2) the joint friction `element`: its torque (N m) or force (N) on the
/// joint's second body and the joint's relative rate (rad/s or m/s).
OutputRows friction(const Model& model, const std::string& element, const OutputView& out);

/// (k, 4 + 3 dimension) the contact `element` (ContactReading) at each
/// output: the normal force (N), the friction force (dimension columns, N),
/// the contact point (m), the normal, the penetration (m; negative: the gap),
/// the slip speed (m/s) and the state (0 open, 1 slip, 2 stick).
OutputRows contacts(const Model& model, const std::string& element, const OutputView& out);

/// (k) kinetic plus potential energy (J) of the conservative forces.
VecX energy(const Model& model, const OutputView& out);

/// (k) max |Phi(q, t)| over every row, the ones a run left out as redundant
/// included (0 without constraints).
VecX constraint_residual(const Model& model, const OutputView& out);

/// (k) max |Phi_q v + Phi_t| over every row.
VecX velocity_residual(const Model& model, const OutputView& out);

}  // namespace lagmb
