// The event runner: evaluates the event functions of a model for the
// integrators — those of its event elements (contact switches) and those of
// its unilateral rows (stops: the gap of an open row, the force of a closed
// one) — and applies what happens at their crossings: restarts, impacts,
// and the active set's captures and releases (docs/methods.md, "The active set, step by step"). The
// steppers never name a kind.
//
// Its sources, cpp/src/events/, one job each: event_runner.cpp (the event
// functions' layout, handle(), the Zeno guard), detection.cpp (values,
// missed, grazed), impacts.cpp (the impulse, the LCP of the contacts at
// rest), active_set.cpp (settle, the stops' actions), sticks.cpp (the
// contacts' stick states), restart.cpp (the consistent restart).
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/model/data.hpp"
#include "lagmb/trajectory.hpp"

namespace lagmb {

class EventRunner {
 public:
  /// run: the run's Data (its left-out rows, which the active set changes,
  /// and the run state that crossings write and the run's force kernels
  /// read); position_tol: how accurate the run's positions are (a bounce
  /// lower than that cannot be followed).
  EventRunner(const Model& model, const Data& run, double position_tol);
  /// Number of event functions (0: none).
  int size() const { return int(dir_.size()); }
  /// SUNDIALS root directions (-1: downward crossings only, 0: both).
  int* directions() { return dir_.data(); }
  /// g at (q, v, t), all event functions: the event elements' in their
  /// order, then one per unilateral row (Model::unilateral_rows): an open
  /// row's gap g_r = Phi_r, a closed row's force f_r = -lam_r. `lam`: the
  /// multipliers at (t, q, v) on the run's rows where the caller has them
  /// (the stepper's formulation solved them: Stepper::motion_at); null: they
  /// are solved here (where a row is closed).
  void values(double t, const double* q, const double* v, double* g, const double* lam = nullptr);
  /// Whether values() reads multipliers (a stop is closed): then a caller
  /// that has them solved at (t, q, v) saves it a solve.
  bool reads_multipliers() const { return !d_.closed_rows().empty(); }
  /// The multipliers at (t, q, v) on the run's rows, where the stepper has
  /// them (Stepper::motion_at); null: the runner solves them.
  using Multipliers = std::function<const double*(double t, const double* q, const double* v)>;
  /// At the start: a joint beyond a limit is a ModelError; one at a limit
  /// gets its impact (moving into it) or its capture (pressing on it) now.
  /// Returns true if the state or the active set changed.
  bool start(double t, const VecX& q, VecX& v);
  /// The same where the equations jump (a new input value, a breakpoint of a
  /// time function): closed stops whose force would pull are released,
  /// joints at a limit get their impact or capture. Returns true if the
  /// state or the active set changed, or a joint is beyond a limit (then
  /// restart from consistent(), which puts it back on the limit). `lam`,
  /// `qdd`: the multipliers and accelerations at (t, q, v) on the run's
  /// rows where the caller has them (values(); a joint resting on a limit
  /// that its acceleration does not press on then costs no solve).
  bool settle(double t, const VecX& q, VecX& v, bool at_start = false, const double* lam = nullptr,
              const double* qdd = nullptr);
  /// After a step that found no root: event functions of direction -1 that
  /// are below zero with the motion still going further (a crossing the
  /// integrator missed) are flagged in `fired`. Returns true if any. `lam`
  /// as values().
  bool missed(double t, const double* q, const double* v, std::vector<int>& fired, const double* lam = nullptr);
  /// The state of the last step at a time inside it (the stepper's interpolant).
  using Interpolant = std::function<void(double t, const double*& q, const double*& v)>;
  /// After a step from t0 to t1 that found no root: an open stop whose gap
  /// is positive at both ends but whose joint turned around within the step
  /// (g' < 0 at t0, > 0 at t1) may have crossed its limit and come back
  /// inside between two evaluations of the root functions (a grazing
  /// crossing: the signs at the steps' ends do not show it). Where the
  /// cubic through the ends' gaps and rates dips near 0, the gap's minimum
  /// is found on the interpolant (bisection on g'), and if it is below 0,
  /// the first crossing before it (bisection on g). A closed row's force is
  /// looked at the same way where a force or driver of the model follows a
  /// function of time (a release inside the step, the joints at rest: the
  /// force at the step's middle too, the interpolant sampled where a
  /// parabola through it dips near 0), and sets step_bound(); where none
  /// does, the forces are functions of the state, which the step's error
  /// control resolves as it resolves the accelerations, and are read at
  /// the step's ends (which the root functions read already). Returns that
  /// time (the earliest over the rows, its rows flagged in `fired`), or NaN
  /// if none. `lam`: the stepper's multipliers (null: the runner solves).
  /// After a step that found no root, too: an event element whose functions
  /// are all positive at both ends but whose shapes may have passed through
  /// each other within the step (EventGroupBase::may_pass: a fast ball
  /// across a small one) is looked at on the interpolant (16 samples, then
  /// the first crossing by bisection); the earlier of the two times.
  double grazed(double t0, double t1, const Interpolant& at, std::vector<int>& fired,
                const Multipliers& lam = nullptr);
  /// The time the next step should not pass (INFINITY: none), set by
  /// grazed(): where a closed row's force changes fast for its margin from
  /// 0 (a load's time function moving it while the joints rest), the step
  /// that would let a parabola through its ends and middle miss a release.
  double step_bound() const { return window_.step_bound; }
  /// Applies the actions of the flagged crossings at (t, q, v); v gets the
  /// velocity jump of impacts, the run's Data its new active set. Returns
  /// true if the integrator must restart.
  bool handle(double t, const VecX& q, VecX& v, const std::vector<int>& fired);
  /// q, v with accelerations and multipliers, on the rows now closed: the
  /// state to restart from. An event element's function that this moves
  /// across 0 (not one handle() just acted on) is a crossing here: its
  /// action is taken and recorded.
  ConsistentState consistent(double t, const VecX& q, const VecX& v);

  /// Factorizations of the augmented matrix the runner made (its own solves).
  long factorizations() const { return kkt_.factorizations(); }

  std::vector<EventRecord> records;
  long events = 0, impacts = 0, captures = 0, releases = 0, root_evals = 0;

 private:
  // --- the event functions' layout (fixed at construction) ---------------
  struct Root {
    int group, element, index;
  };
  /// An event element that looks inside steps (may_pass): its group,
  /// element, first event function and their number.
  struct Sweep {
    int group, element, root0, count;
  };
  /// A unilateral row and what its element says it does.
  struct Contact {
    int row;
    UnilateralRow info;
    int group, element;  // its element (Model::constraint_groups, its index there)
    std::vector<std::pair<int, int>> entries;  // its entries in Phi_q: (column, slot in the values)
  };
  /// A contact that can stick (constraint_group.hpp, is_stick): its
  /// group, element and first row, and its points' event functions (the
  /// first, and their number).
  struct Stick {
    int group, element, row0, root0, roots;
  };

  // --- what the runner remembers between calls ----------------------------
  /// What the detection keeps of the last step so that the next one, which
  /// starts at its end, need not evaluate its start again. Valid while the
  /// motion goes on unbroken from that end: every action, restart and jump
  /// of the equations forgets it (forget(): the times NaN, which no step's
  /// start equals, and no step bound).
  struct StepWindow {
    /// passed_through(): the last step's end and its positions.
    double sweep_t = NAN;
    VecX sweep_q;
    /// grazed_stops(): the unilateral rows' gaps and rates at the last
    /// step's end (gaps_t), which start the next step; the step's start's
    /// (buffers kept from step to step).
    double gaps_t = NAN;
    VecX end_gaps, end_rates, start_gaps, start_rates;
    /// grazed_stops(): the closed rows' forces at the last step's start and
    /// end (force_t[0], force_t[1]; force[0], force[1]), and buffers: this
    /// step's end, its middle, a sample (force[2..4]).
    double force_t[2] = {NAN, NAN};
    VecX force[5];
    /// values(): the times of its last two reads of the closed rows' forces,
    /// and those forces (a step's start's and end's: grazed_stops() reads them).
    double values_t = NAN, values_t_before = NAN;
    VecX values_force, values_force_before;
    /// grazed_stops(): see step_bound().
    double step_bound = INFINITY;
    void forget() {
      gaps_t = sweep_t = force_t[0] = force_t[1] = values_t = values_t_before = NAN, step_bound = INFINITY;
    }
  };
  /// An event function whose crossing the last restart acted on: it reads
  /// as on `side` (where the crossing went) while it is on the other within
  /// `within` of 0, until a step's end finds it on `side`.
  struct Pin {
    int root, side;
    double within;
  };
  /// What the last events acted on leave for the restart and the steps
  /// after it (the active set's memory of them).
  struct LastEvents {
    /// The crossings the last handle() or settle() acted on (-1, +1: which
    /// way); consistent() pins them.
    std::vector<int> handled;
    /// Rows whose crossing the last handle() acted on: restart_state() puts
    /// them on their limits (and clears them).
    std::vector<int> on_limit;
    /// Rows the last handle() released: restart_state() starts them at rest.
    std::vector<int> released;
    /// The crossings handle() gets were found by missed(), after the step
    /// passed them (set by missed(), read and cleared by handle_stops()).
    bool late = false;
    /// The rows that rebounded (e > 0) at the last impact, their speeds
    /// g' > 0 after it, and its time (NaN: none yet); cleared where an
    /// active set changes without an impact.
    std::vector<int> rebounded;
    std::vector<double> rebound_speed;
    double rebound_t = NAN;
    /// The last restart's time (consistent(); NaN: none yet) and the rows
    /// it left open on their limits (released or rebounding), until a
    /// step's end finds them off (grazed_stops()).
    double restart_t = NAN;
    std::vector<int> left;
    /// consistent()'s pins, until a step's end finds them on their side (grazed()).
    std::vector<Pin> pins;
  };
  /// The Zeno guard's count: events at (almost) one instant (count_event).
  struct Burst {
    double t_last = -INFINITY;  // the last event's time
    int count = 0;              // events in a row within 1e-9 (1 + |t|) of the one before
  };

  // --- detection.cpp ---------------------------------------------------------
  /// grazed()'s part for the stops (rows: indices into contacts_) and for
  /// the event elements passed through (roots: their event functions).
  double grazed_stops(double t0, double t1, const Interpolant& at, const Multipliers& lam, std::vector<int>& rows);
  double passed_through(double t0, double t1, const Interpolant& at, std::vector<int>& roots);

  // --- restart.cpp -----------------------------------------------------------
  /// At an event or a jump of the equations: the state the run restarts
  /// from is the motion's, on its constraints; one off them by more than
  /// 1e-2 (1 + |q|) is an IntegratorFailure naming the row (a method that
  /// holds Phi only through Phi'' = 0, index1 or projection-adams, can
  /// drift until its steps follow nothing: a spatial rod at 50 rad/s
  /// under Adams at rtol 1e-3, 0.2 m off in 0.44 s, its joint rate read
  /// at 1e5 rad/s through quaternions far from unit; the restart's
  /// projection would hide it and the run go on from a motion it lost).
  void check_on_constraints(double t, const VecX& q);
  /// rows_.Phi and rows_.phi_t (= Phi_q v) of the unilateral rows at (t, q, v).
  void gaps(double t, const VecX& q, const VecX& v);
  /// g_r' = Phi_q,r v of contact c, from its entries of rows_.Phi_q (evaluated).
  double rate(const Contact& c, const double* v) const;
  /// consistent()'s projection, without the crossings it causes.
  ConsistentState restart_state(double t, const VecX& q, const VecX& v);

  // --- active_set.cpp --------------------------------------------------------
  /// The stops' and event elements' part of handle(); `qdd`: the
  /// accelerations at (t, q, v) on the run's rows, if the caller has them.
  bool handle_stops(double t, const VecX& q, VecX& v, const std::vector<int>& fired, const double* qdd = nullptr);

  // --- sticks.cpp ------------------------------------------------------------
  /// The contacts' stick states at (t, q, v) after the other events acted
  /// (fired: this call's crossings): a stuck contact whose friction margin
  /// is negative, or that nothing presses, is released (its rows opened,
  /// disarmed), one whose points press or let go is anchored again at the
  /// vertices pressing now; an armed one whose pressing points all slip slower than
  /// v_s is anchored and its rows closed, if the friction it then needs
  /// is within its limit (else disarmed); a disarmed one crossing up to 2 v_s
  /// is armed. Returns true if a row opened or closed.
  bool handle_sticks(double t, const VecX& q, const VecX& v, const std::vector<int>& fired);

  // --- impacts.cpp -----------------------------------------------------------
  /// Rows of the contacts `which` (indices into contacts_) of Phi_q at q, and
  /// their curvature terms (gamma_r at q, v): g_r'' = C_r qdd - gamma_r
  /// (their elements evaluated alone, in rows_).
  void contact_rows(double t, const VecX& q, const VecX& v, const std::vector<int>& which,
                    std::vector<VecX>& C, VecX& curvature);
  /// The impulse at an impact of the contacts `which` (approaching),
  /// restitution e each: v += X p with C v+ = -e C v-, the closed rows and
  /// joints held (the M-orthogonal jump). Rows that depend on each other
  /// get e = 0 (a plastic impact: their rebounds could not all hold).
  /// held[j] = 1 for a row the closed rows hold (no mobility, approaching
  /// by drift only): it takes no impulse.
  void impulse(double t, const VecX& q, VecX& v, const std::vector<int>& which, const std::vector<VecX>& C,
               VecX& e, std::vector<char>& held);
  /// The active set at rest contact: of the contacts `which` (all at g = 0,
  /// g' = 0), those whose force f >= 0 holds them while the others'
  /// accelerations g'' >= 0 (an LCP at acceleration level, solved by
  /// principal pivoting); `leaving`: contacts whose release was found,
  /// which open where their force is within rounding of 0. `qdd`: the
  /// accelerations at (t, q, v) on the run's rows, if the caller has them:
  /// where every contact of `which` is open and none presses (g'' >= 0),
  /// they are the answer (none closes) without a solve.
  std::vector<int> rest_contacts(double t, const VecX& q, const VecX& v, const std::vector<int>& which,
                                 const std::vector<int>& leaving, const double* qdd = nullptr);
  /// Fails naming the stop `contact` reached where nothing can move along
  /// it and what holds it (closed stops, couplings, drivers); `approach`:
  /// its gap's rate or acceleration (`measure`), beyond `tolerance`.
  [[noreturn]] void driven_through(int contact, double t, double approach, double tolerance, const char* measure);

  // --- event_runner.cpp ------------------------------------------------------
  bool is_closed(int row) const;
  /// Whether the last restart left `row` open on its limit (released or
  /// rebounding) and no step's end has found it off the limit since.
  bool left(int row) const;
  /// Whether `row` rebounded (e > 0) at the last impact.
  bool rebounding(int row) const;
  /// Counts an event at t; IntegratorFailure after 1000 at one instant (Zeno).
  void count_event(double t, const std::string& element, const char* kind);

  const Model& model_;
  Data d_;      // of the run: its left-out rows
  Data rows_;   // every row, unilateral ones closed: the gaps and their gradients
  AugmentedSystem kkt_;
  double position_tol_;
  std::vector<Root> roots_;        // of the event elements
  std::vector<Sweep> sweeps_;      // of those that may be passed through
  std::vector<Contact> contacts_;  // the unilateral rows, ascending
  std::vector<int> unilateral_groups_;
  std::vector<Stick> sticks_;      // the contacts that can stick; their event functions follow the stops'
  size_t sticks_base_ = 0;         // the first of those
  bool forces_follow_time_ = false;  // a force or driver follows a varying function of time (grazed_stops)
  std::vector<int> dir_;
  // scratch of the last values() or acceleration solve: settle() and
  // missed() read lam_ (its tolerance) right after their values()
  std::vector<double> g_;
  VecX qdd_, lam_;
  std::vector<int> one_ = std::vector<int>(1);  // scratch: one element for a group's kernels (`only`)
  StepWindow window_;
  LastEvents last_;
  Burst burst_;
};

}  // namespace lagmb
