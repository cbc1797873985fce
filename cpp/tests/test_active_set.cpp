// The active set of unilateral rows (docs/design.md 5.1): a stop's two rows
// (its gaps) are rows of Phi that a Data leaves out until a run closes them;
// the closed set sits beside the redundant rows, shared by the run's Data;
// the rank and the degrees of freedom count the joints' equations only.
#include "check.hpp"
#include "lagmb/analyses/kinematics.hpp"
#include "lagmb/analyses/redundancy.hpp"
#include "lagmb/assembly/assembly.hpp"
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

LAGMB_TEST_MAIN()
