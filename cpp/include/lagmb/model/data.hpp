// Data: the state-dependent values and scratch of one model (cf. mjData).
#pragma once

#include <memory>

#include "lagmb/model/model.hpp"

namespace lagmb {

/// Values the kernels write, sized and patterned once from a finalized
/// Model, and everything a run decides or changes: the dropped rows, the
/// input values and the elements' run state. Kernels never allocate: they write into these arrays
/// in place. A Model is never written by a run: one Model may be run by
/// several threads at once, each with its own Data.
struct Data {
  /// Which rows a Data of a run counts: the run's (its dropped rows left
  /// out), or every row (to check or name the dropped ones).
  enum class Rows { kRun, kEvery };
  /// A Data with run values of its own (the inputs at their initial values,
  /// no element state): a run's own, or one outside any run. With `run`, a
  /// Data of that run instead: it reads the run's values (what a
  /// Simulator's inputs or an event change, every Data of the run sees)
  /// and with Rows::kRun leaves out the run's dropped rows. A run's
  /// scratch Data (each formulation's, the event runner's, the checks') are
  /// made so, from the run's Data: none joins later, so none reads stale
  /// values.
  explicit Data(const Model& model, const Data* run = nullptr, Rows rows = Rows::kRun);

  VecX Phi;     // constraint residual Phi(q, t)                   (m)
  VecX phi_t;   // partial time derivative Phi_t                  (m)
  VecX gamma;   // right side of Phi_q qdd = gamma                (m)
  VecX Q;       // applied generalized forces Q(q, v, t)          (n)
  SpMat Phi_q;  // constraint Jacobian                            (m x n)
  SpMat Vq;     // d(Phi_q v + Phi_t)/dq, same pattern as Phi_q  (m x n)
  SpMat H;      // sum_r w_r d2Phi_r/dq2 for a weight vector w    (n x n)
  SpMat Q_q;    // dQ/dq                                          (n x n)
  SpMat Q_v;    // dQ/dv                                          (n x n)
  SpMat M;      // mass matrix M(q), pattern Model::mass_pattern() (n x n)
  SpMat M_inv;  // M(q)^-1 (assemble_mass_inverse), M's pattern  (n x n)
  SpMat M_qa;   // d(M(q) a)/dq for a vector a, the same pattern   (n x n)

  // joint friction Q_f(q, v, lam) (sized only if the model has friction)
  SpMat friction_Q_q;    // dQ_f/dq, pattern of Q_q                 (n x n)
  SpMat friction_Q_v;    // dQ_f/dv, pattern of Q_v                 (n x n)
  SpMat friction_Q_lam;  // (dQ_f/dlam)^T, pattern of Phi_q         (m x n)
  VecX friction_Q0, friction_lam;  // scratch of the augmented fixed-point solve

  /// Elements evaluated by the assembly kernels (added per group call).
  long element_evaluations = 0;

  /// Rows of Phi this run leaves out: those found consistently redundant
  /// where it started (redundancy.hpp) and the open unilateral rows (a
  /// stop not in contact: Model::unilateral_rows not closed). The kernels
  /// write them as 0 = 0 with a zero Jacobian row, so their multipliers are
  /// 0 and the other rows of each redundant set carry its reaction. A Data
  /// of its own leaves out every unilateral row and nothing else.
  /// A Data of a run (Rows::kRun) shares the run's set: rows the run leaves
  /// out or takes back at any time, every Data of the run sees at once.
  const std::vector<int>& dropped_rows() const { return left_out_->rows; }
  /// Their entries in the values of Phi_q.
  const std::vector<int>& dropped_slots() const { return left_out_->slots; }
  /// The rows left out as redundant (sorted), and the unilateral rows closed.
  const std::vector<int>& redundant_rows() const { return left_out_->redundant; }
  const std::vector<int>& closed_rows() const { return left_out_->closed; }
  /// Of constraint group `group` (Model::constraint_groups), the elements
  /// the kernels evaluate (assembly.hpp): null for every one; for a group
  /// whose rows a run opens and closes (stops, stuck contacts) those with a
  /// closed row (ascending; empty: none, every row open reads 0 = 0).
  const std::vector<int>* evaluated_elements(int group) const {
    const auto& e = left_out_->evaluated;
    return size_t(group) < e.size() && e[size_t(group)].switched ? &e[size_t(group)].elements : nullptr;
  }
  /// Sets the rows left out as redundant, in the set this Data reads: for a
  /// Data of a run (Rows::kRun), the run's. The closed rows stay closed.
  void drop_rows(const Model& model, std::vector<int> rows);
  /// Sets the unilateral rows that are closed (the active set); the others
  /// of Model::unilateral_rows are left out. The redundant rows stay.
  void close_rows(const Model& model, std::vector<int> rows);

  Data(Data&&) = default;
  Data& operator=(Data&&) = default;
  // no copies: a copy would share or not share the run's rows by accident
  Data(const Data&) = delete;
  Data& operator=(const Data&) = delete;

  /// What the run sets and the kernels read beside q, v and t (cf.
  /// mjData::ctrl): the input values and the elements' run state. Shared by
  /// the Data objects of one run (each formulation and solver keeps its own
  /// Data for scratch): what an event records or a Simulator's set_input
  /// changes, every kernel of the run sees.
  struct RunValues {
    /// One per Model::inputs(), the initial values until a Simulator sets them.
    VecX inputs;
    /// Per-run state of the elements that keep one (e.g. the approach speed
    /// of a contact in progress, the turns of a spatial joint's angle), at
    /// the offsets the Model assigned (Model::run_state_size); zero at the
    /// start of a run, written by event crossings and after each step
    /// (count_turns), read by the kernels.
    VecX state;
  };
  std::shared_ptr<RunValues> run;
  /// The instant t of this run, as the kernels take it (time, inputs and state).
  Instant at(double t) const { return {t, run->inputs.data(), run->state.data()}; }

 private:
  struct LeftOutRows {
    std::vector<int> redundant;  // sorted
    std::vector<int> closed;     // sorted unilateral rows in contact
    struct Evaluated {
      bool switched = false;  // a group of switched rows (Model::switched_rows)
      std::vector<int> elements;  // then its elements with a closed row
    };
    std::vector<Evaluated> evaluated;  // per constraint group
    std::vector<int> rows;       // redundant and open unilateral rows, sorted
    std::vector<int> slots;      // their entries in the values of Phi_q
  };
  /// rows and slots from redundant and closed.
  void leave_out(const Model& model);
  std::shared_ptr<LeftOutRows> left_out_;
};

}  // namespace lagmb
