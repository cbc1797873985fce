// A run's Data (lagmb/model/data.hpp): a Data made of the run's reads the
// same run values (what a Simulator's inputs or an event change) and leaves
// out the run's dropped rows, or counts every row when asked; a Data made
// on its own has values of its own. The rows a run leaves out are one set:
// a row left out or taken back later reaches the Data made before.
#include "check.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/model/data.hpp"
#include "models.hpp"

using namespace lagmb_test;

TEST_CASE(a_data_of_the_run_shares_its_values_and_dropped_rows) {
  const auto model = slider_crank();
  Data run(*model);
  run.drop_rows(*model, {1});
  const Data scratch(*model, &run);
  CHECK(scratch.run == run.run);
  CHECK(scratch.dropped_rows() == run.dropped_rows());
  CHECK(scratch.dropped_slots() == run.dropped_slots());
  const Data every(*model, &run, Data::Rows::kEvery);
  CHECK(every.run == run.run);
  CHECK(every.dropped_rows().empty());
  const Data own(*model);
  CHECK(own.run != run.run);
  CHECK(own.dropped_rows().empty());
}

// The dropped row reads 0 = 0 in the run's scratch Data, and its own value
// in one that counts every row.
TEST_CASE(the_dropped_rows_are_left_out_where_the_run_leaves_them_out) {
  const auto model = slider_crank();
  Data run(*model);
  run.drop_rows(*model, {1});
  Data scratch(*model, &run), every(*model, &run, Data::Rows::kEvery);
  std::mt19937 random(43);
  const VecX q = model->initial_q() + 0.1 * random_vector(model->n_coordinates(), random);  // off the constraints
  assemble_constraints(*model, scratch, q.data(), 0.0);
  assemble_constraints(*model, every, q.data(), 0.0);
  CHECK(scratch.Phi[1] == 0.0);
  CHECK(every.Phi[1] != 0.0);
  CHECK(scratch.Phi[0] == every.Phi[0]);
}

// What a run decides after its scratch Data exist (its start finds the
// redundant rows; a stop's row opens or closes) reaches them at once.
TEST_CASE(rows_the_run_leaves_out_later_reach_the_data_made_before) {
  const auto model = slider_crank();
  Data run(*model);
  Data scratch(*model, &run), every(*model, &run, Data::Rows::kEvery);
  CHECK(scratch.dropped_rows().empty());
  run.drop_rows(*model, {2, 1, 2});
  CHECK(scratch.dropped_rows() == std::vector<int>({1, 2}));
  CHECK(scratch.dropped_slots() == run.dropped_slots() && !run.dropped_slots().empty());
  CHECK(every.dropped_rows().empty());
  scratch.drop_rows(*model, {});  // one set: taking the rows back through any Data of the run
  CHECK(run.dropped_rows().empty() && run.dropped_slots().empty());
}

LAGMB_TEST_MAIN()
