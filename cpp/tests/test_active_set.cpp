// The active set of unilateral rows (docs/methods.md, "The active set, step by step"): a stop's two rows
// (its gaps) are rows of Phi that a Data leaves out until a run closes them;
// the closed set sits beside the redundant rows, shared by the run's Data;
// the rank and the degrees of freedom count the joints' equations only.
#include "check.hpp"
#include "lagmb/analyses/kinematics.hpp"
#include "lagmb/analyses/redundancy.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/elements/drivers.hpp"
#include "lagmb/elements/gear.hpp"
#include "lagmb/elements/joint_coupling.hpp"
#include "lagmb/elements/rack_pinion.hpp"
#include "lagmb/elements/revolute.hpp"
#include "lagmb/elements/spatial_body_driver.hpp"
#include "lagmb/elements/spatial_joint_driver.hpp"
#include "lagmb/elements/spatial_stop.hpp"
#include "lagmb/elements/stop.hpp"
#include "lagmb/model/data.hpp"
#include "models.hpp"

using namespace lagmb_test;

// rows: the pin's two, then the stop's gaps g_lower = s + pi/4, g_upper = pi/4 - s
TEST_CASE(a_stop_adds_two_unilateral_rows_left_out_until_closed) {
  const auto model = pendulum_with_stop();
  CHECK(model->n_constraints() == 4);
  CHECK(model->unilateral_rows() == std::vector<int>({2, 3}));
  CHECK(model->has_events());
  Data run(*model);
  CHECK(run.dropped_rows() == std::vector<int>({2, 3}));
  CHECK(run.closed_rows().empty() && run.redundant_rows().empty());
  run.close_rows(*model, {2});
  CHECK(run.dropped_rows() == std::vector<int>({3}));
  const Data scratch(*model, &run);
  CHECK(scratch.closed_rows() == std::vector<int>({2}) && scratch.dropped_rows() == std::vector<int>({3}));
  run.drop_rows(*model, {0});  // a redundant row beside the open gap: both left out, the closed row kept
  CHECK(scratch.dropped_rows() == std::vector<int>({0, 3}));
  CHECK(scratch.closed_rows() == std::vector<int>({2}));
  CHECK_THROWS(std::logic_error, run.close_rows(*model, {1}), "only a unilateral or stick row");  // a joint's row is no gap
}

// Closed, the lower gap reads s - lower with the gradient ds/dq; open, 0 = 0.
TEST_CASE(a_closed_gap_reads_the_distance_to_its_limit) {
  const auto model = pendulum_with_stop();
  Data run(*model);
  VecX q = model->initial_q();
  q[2] = -0.5;  // the rod's angle: s = -0.5
  assemble_constraints(*model, run, q.data(), 0.0);
  CHECK(run.Phi[2] == 0.0 && run.Phi[3] == 0.0);
  run.close_rows(*model, {2, 3});
  assemble_constraints(*model, run, q.data(), 0.0);
  CHECK_NEAR(run.Phi[2], -0.5 + 0.7853981633974483, 1e-15);
  CHECK_NEAR(run.Phi[3], 0.7853981633974483 + 0.5, 1e-15);
  assemble_jacobian(*model, run, q.data(), 0.0);
  CHECK(run.Phi_q.coeff(2, 2) == 1.0 && run.Phi_q.coeff(3, 2) == -1.0);
}

TEST_CASE(the_rank_counts_the_joints_equations_only) {
  const auto model = pendulum_with_stop();
  const ConstraintRank r = constraint_rank(*model, model->initial_q(), 0.0);
  CHECK(r.equations == 2 && r.rank == 2 && r.dependent_rows.empty());
  CHECK(degrees_of_freedom(*model, 0.0) == 1);
}

// Where a stop is driven through its limit, the event runner names what holds
// it: the stops (unilateral) and the kinds that prescribe or tie the joints'
// motion (is_tie), never a joint's own rows; the kinds say which they are.
TEST_CASE(drivers_couplings_gears_and_racks_tie_motion_joints_and_stops_do_not) {
  CHECK(is_tie<AngleDriver>::value && is_tie<SlideDriver>::value && is_tie<CoordinateDriver>::value);
  CHECK(is_tie<SpatialAngleDriver>::value && is_tie<SpatialSlideDriver>::value && is_tie<SpatialPositionDriver>::value);
  CHECK(is_tie<JointCoupling>::value && is_tie<GearPair>::value && is_tie<RackPinion>::value);
  CHECK(!is_tie<RevoluteJoint>::value && !is_tie<JointStop>::value && !is_tie<SpatialJointStop>::value);
  CHECK(is_unilateral<JointStop>::value && !is_unilateral<GearPair>::value);
  const auto model = pendulum_with_stop();  // a pin and a stop
  CHECK(!model->constraint_groups()[model->group_of_row(0)]->ties_motion());
  CHECK(!model->constraint_groups()[model->group_of_row(2)]->ties_motion());
}

LAGMB_TEST_MAIN()
