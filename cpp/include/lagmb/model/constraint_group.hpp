// One container per constraint kind and the loops that run over it.
//
// A constraint kind (e.g. RevoluteJoint) is a plain struct that holds its
// parameters and gives, in the local coordinates c of the two bodies it
// joins (L of them: (x_i, y_i, phi_i, x_j, y_j, phi_j) in the plane, (r_i,
// p_i, r_j, p_j) in space; space.hpp):
//   using Space = Spatial;                     (omitted: Planar)
//   static constexpr int rows;                 equations per element
//   static constexpr bool time_dependent;      Phi depends on t explicitly
//   static constexpr const char* kind;         for messages
//   Rows phi(c, t)                             Phi
//   Jac jacobian(c, t)                         Phi_c            (rows x L)
//   void hessians(c, t, MatL H[rows])          d2 Phi_r / dc2
//   Space::Axes axes(c, t)                     the joint's own axes (columns),
//                                              for reactions in joint axes
//   Space::Point origin(c, t)                  (a joint with a point) that point
//                                              on body j, global: the torque of
//                                              reactions about the joint
//   double effort(lam)                         (a driver or stop whose effort is
//                                              not -lam of its one row) what
//                                              Result.effort reads, from its rows' lam
//   and, if time dependent: phi_t, phi_tc (rows x L), phi_tt.
// Everything the integrators need beyond that is derived here, once:
//   gamma_r     = -v^T H_r v - 2 Phi_tc,r v - Phi_tt,r
//   d(Phi_q v + Phi_t)/dq, row r = (H_r v)^T + Phi_tc,r
//   (Phi_q^T w)_q = sum_r w_r H_r.
// Assembly sees only ConstraintGroupBase; it never names a kind.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "lagmb/model/joint_coordinate.hpp"
#include "lagmb/model/contact_reading.hpp"
#include "lagmb/space.hpp"
#include "lagmb/sparsity.hpp"
#include "lagmb/time_function.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// Where an element's local coordinates live in q (-1: ground, a particle's
/// missing angle, or beyond its kind's L) and the first of its rows in Phi.
struct ElementPlacement {
  int row0 = 0;
  LocalCoords coord = filled_coords();
  static LocalCoords filled_coords() {
    LocalCoords c;
    c.fill(-1);
    return c;
  }
};

template <class Kind, class = void>
struct has_coordinate : std::false_type {};
template <class Kind>
struct has_coordinate<Kind, std::void_t<decltype(std::declval<const Kind&>().coordinate())>> : std::true_type {};

/// Per-run state of an element kind (any group): a kind that keeps values
/// during a run (a contact's impact speed) declares
///   static constexpr int run_state_size;   doubles per element (or, where an
///                                          element's count varies, > 0 and
///   int run_state_count() const;           the element's count)
///   int run_state = -1;                    its offset, set by the Model
/// and reads them at run + run_state from the run's Data::run->state. The
/// Model itself is never written during a run.
template <class Kind, class = void>
struct run_state_size_of : std::integral_constant<int, 0> {};
template <class Kind>
struct run_state_size_of<Kind, std::void_t<decltype(Kind::run_state_size)>>
    : std::integral_constant<int, Kind::run_state_size> {};
template <class Kind>
inline constexpr int run_state_size_v = run_state_size_of<Kind>::value;
/// The doubles of run state one element holds: its run_state_count() where
/// the kind has one (a spatial contact: one per contact point), else the
/// kind's run_state_size.
template <class Kind, class = void>
struct has_run_state_count : std::false_type {};
template <class Kind>
struct has_run_state_count<Kind, std::void_t<decltype(std::declval<const Kind&>().run_state_count())>>
    : std::true_type {};
template <class Kind>
int run_state_count(const Kind& element) {
  if constexpr (has_run_state_count<Kind>::value)
    return element.run_state_count();
  else
    return run_state_size_v<Kind>;
}

/// A kind that follows a function of time or an input (a driver, an
/// actuated force) declares
///   static constexpr bool reads_inputs = true;
/// and takes the Instant (the time and the run's input values) wherever
/// other kinds take the time t; its Drive reads the value from there.
template <class Kind, class = void>
struct reads_inputs : std::false_type {};
template <class Kind>
struct reads_inputs<Kind, std::void_t<decltype(Kind::reads_inputs)>> : std::bool_constant<Kind::reads_inputs> {};
template <class Kind>
using time_argument_t = std::conditional_t<reads_inputs<Kind>::value, Instant, double>;
/// What Kind's functions take for the time: the Instant, or its t.
template <class Kind>
time_argument_t<Kind> time_argument(const Instant& at) {
  if constexpr (reads_inputs<Kind>::value)
    return at;
  else
    return at.t;
}

/// A joint with a point of its own (a revolute's pin): Kind::origin(c, t).
template <class Kind, class = void>
struct has_origin_of : std::false_type {};
template <class Kind>
struct has_origin_of<Kind, std::void_t<decltype(std::declval<const Kind&>().origin(
                            std::declval<const LocalVec<space_of_t<Kind>::local>&>(),
                            std::declval<time_argument_t<Kind>>()))>> : std::true_type {};

/// A driver or stop that says what its effort is: Kind::effort(lam of its rows).
template <class Kind, class = void>
struct has_row_effort : std::false_type {};
template <class Kind>
struct has_row_effort<Kind, std::void_t<decltype(std::declval<const Kind&>().effort(
                                std::declval<const Eigen::Matrix<double, Kind::rows, 1>&>()))>> : std::true_type {};

/// A kind may give gamma itself, `Rows gamma(c, cdot, t)`, where the
/// general -cdot^T H_r cdot over full L x L Hessians costs more than the
/// kind's closed form (the revolute joint of a long chain); tests check it
/// against the Hessians.
template <class Kind, class = void>
struct has_own_gamma : std::false_type {};
template <class Kind>
struct has_own_gamma<Kind, std::void_t<decltype(std::declval<const Kind&>().gamma(
                               std::declval<const LocalVec<space_of_t<Kind>::local>&>(),
                               std::declval<const LocalVec<space_of_t<Kind>::local>&>(),
                               std::declval<time_argument_t<Kind>>()))>> : std::true_type {};

/// A kind may give the rows (H_r cd)^T itself, `Jac rates(c, cd, t)`: the
/// velocity Jacobian's part and, times cd, minus gamma, for far less than the
/// Hessians cost (the spatial kinds, spatial_terms.hpp); tests check it
/// against the Hessians.
template <class Kind, class = void>
struct has_rates : std::false_type {};
template <class Kind>
struct has_rates<Kind, std::void_t<decltype(std::declval<const Kind&>().rates(
                           std::declval<const LocalVec<space_of_t<Kind>::local>&>(),
                           std::declval<const LocalVec<space_of_t<Kind>::local>&>(),
                               std::declval<time_argument_t<Kind>>()))>> : std::true_type {};

/// A unilateral kind (a joint stop: docs/methods.md, "The active set, step by step") declares
///   static constexpr bool unilateral = true;
///   UnilateralRow unilateral_row(int r) const;
/// Its rows are gaps g_r >= 0 (Phi_r = g_r), open (left out, as a
/// redundant row is: Data::close_rows) unless the run's active set has
/// closed them; while closed, g_r = 0 and the multiplier is the force:
/// f_r = -lam_r >= 0 pushes along +dg_r/dq. The event runner
/// (cpp/src/events/) opens and closes them.
struct UnilateralRow {
  bool exists = true;         // false: a limit the element does not have (the row stays open)
  double restitution = 0.0;   // Newton's e at an impact
  double rest_speed = 0.0;    // > 0: rebounds slower than this are captured (m/s, rad/s)
  double capture_time = 0.0;  // rebounds whose remaining bounces take less than this are captured (s)
  const char* label = "";     // "lower", "upper"
};
/// A kind whose rows hold a stuck contact (elements/spatial_contact.hpp)
/// declares `static constexpr bool stick_rows = true;` and stick_root,
/// stick_hold, stick_set, stick_state and stick_reading: its rows are open
/// (left out) until the event runner closes them.
template <class Kind, class = void>
struct is_stick : std::false_type {};
template <class Kind>
struct is_stick<Kind, std::void_t<decltype(Kind::stick_rows)>> : std::bool_constant<Kind::stick_rows> {};

/// A kind whose rows prescribe or tie the motion of joints (a driver, a
/// coupling, a gear, a rack and pinion) declares
/// `static constexpr bool ties_motion = true;`: where a stop is driven
/// through, the event runner names these beside the stops that hold it.
template <class Kind, class = void>
struct is_tie : std::false_type {};
template <class Kind>
struct is_tie<Kind, std::void_t<decltype(Kind::ties_motion)>> : std::bool_constant<Kind::ties_motion> {};

template <class Kind, class = void>
struct is_unilateral : std::false_type {};
template <class Kind>
struct is_unilateral<Kind, std::void_t<decltype(Kind::unilateral)>> : std::bool_constant<Kind::unilateral> {};

class ConstraintGroupBase {
 public:
  virtual ~ConstraintGroupBase() = default;
  virtual int size() const = 0;
  virtual int rows(int k) const = 0;
  virtual const std::string& name(int k) const = 0;
  virtual const char* kind() const = 0;
  virtual bool time_dependent() const = 0;
  /// The bodies element k joins, in the order of its local coordinates
  /// (two; four for a coupling of two joints, space.hpp).
  virtual std::vector<int> bodies(int k) const = 0;
  virtual ElementPlacement& placement(int k) = 0;
  virtual const ElementPlacement& placement(int k) const = 0;

  // finalize: declare the entries this kind writes, then bind slots to them
  virtual void declare(SparsityPattern& jacobian, SparsityPattern& hessian) const = 0;
  virtual void bind(const SpMat& jacobian, const SpMat& hessian) = 0;

  // kernels; q, v, lam are global vectors, outputs are written at the
  // element's rows or slots; `at` is the time and the run's inputs;
  // `only`: the elements to evaluate (ascending; null: every one), e.g. a
  // group of stops whose open ones' rows read 0 = 0 (assembly.hpp)
  virtual void phi(const double* q, const Instant& at, double* Phi, const std::vector<int>* only = nullptr) const = 0;
  virtual void jacobian(const double* q, const Instant& at, double* Phi_q_values,
                        const std::vector<int>* only = nullptr) const = 0;
  virtual void add_phi_t(const double* q, const Instant& at, double* phi_t) const = 0;
  virtual void gamma(const double* q, const double* v, const Instant& at, double* gamma,
                     const std::vector<int>* only = nullptr) const = 0;
  virtual void add_hessian(const double* q, const Instant& at, const double* w, double* H_values) const = 0;
  virtual void velocity_jacobian(const double* q, const double* v, const Instant& at, double* Vq_values,
                                 const std::vector<int>* only = nullptr) const = 0;
  /// Generalized force -Phi_c^T lam the element applies on its two bodies,
  /// in local coordinates (L of them).
  virtual VecX generalized_reaction(int k, const double* q, const Instant& at, const double* lam) const = 0;
  /// The reaction on the element's second body from its generalized force
  /// (space.hpp): in the plane force (x, y) and torque, in space force and
  /// torque (3 + 3), about its centre of mass in global axes; with
  /// joint_axes in the element's own axes (the planar torque unchanged);
  /// with about_joint the torque about the joint's point on that body (its
  /// kind's origin; ModelError for a kind without one).
  virtual VecX reaction(int k, const double* q, const Instant& at, const double* lam, bool joint_axes,
                        bool about_joint = false) const = 0;
  /// Whether the kind has a point of its own (origin) to take that torque about.
  virtual bool has_origin() const = 0;
  /// What Result.effort reads of element k, a driver or a stop, from the
  /// global multipliers: its kind's effort(lam of its rows) where it gives
  /// one, else -lam of its one row (the force or torque along what it drives).
  virtual double effort(int k, const double* lam) const = 0;
  /// 2 for planar kinds, 3 for spatial ones.
  virtual int dimension() const = 0;
  /// The scalar coordinate of element k (a revolute's angle, a
  /// translational's slide), if its kind has one.
  virtual std::optional<JointCoordinate> coordinate(int k) const = 0;
  /// Whether the kind's rows are unilateral (gaps), and what row r of element k does at contact.
  virtual bool unilateral() const = 0;
  /// Whether the kind's rows prescribe or tie joints' motion (is_tie).
  virtual bool ties_motion() const = 0;
  virtual UnilateralRow unilateral_row(int k, int r) const = 0;
  /// Whether the kind's rows hold stuck contacts (is_stick), and, for
  /// element k at (q, v) with the run's values `at` (its state) and the
  /// global multipliers lam: the event runner's function of its stick state
  /// (stick_root), anchoring it (stick_hold: false if nothing presses), its
  /// state (0 armed, 1 stuck, -1 disarmed) and setting it, and the friction
  /// its rows hold added to a reading of it.
  virtual bool sticks() const { return false; }
  virtual double stick_root(int k, const double* q, const double* v, const Instant& at, const double* lam) const {
    (void)k, (void)q, (void)v, (void)at, (void)lam;
    return 1.0;
  }
  virtual bool stick_hold(int k, const double* q, const double* v, double* run) const {
    (void)k, (void)q, (void)v, (void)run;
    return false;
  }
  virtual int stick_state(int k, const double* run) const { (void)k, (void)run; return 0; }
  virtual void stick_set(int k, double* run, int state) const { (void)k, (void)run, (void)state; }
  virtual void stick_reading(int k, const double* q, const double* run, const double* lam, ContactReading& r) const {
    (void)k, (void)q, (void)run, (void)lam, (void)r;
  }
};

template <class Kind>
class ConstraintGroup final : public ConstraintGroupBase {
 public:
  using S = space_of_t<Kind>;
  static constexpr int R = Kind::rows;
  static constexpr int L = S::local;
  using Rows = Eigen::Matrix<double, R, 1>;
  using Jac = Eigen::Matrix<double, R, L>;
  using Loc = LocalVec<L>;
  using MatL = LocalMat<L>;

  std::vector<Kind> items;

  int size() const override { return static_cast<int>(items.size()); }
  int rows(int) const override { return R; }
  const std::string& name(int k) const override { return items[k].name; }
  const char* kind() const override { return Kind::kind; }
  bool time_dependent() const override { return Kind::time_dependent; }
  std::vector<int> bodies(int k) const override {
    if constexpr (S::bodies == 2) {
      return {items[k].body_i, items[k].body_j};
    } else {
      const auto b = items[k].bodies();
      return std::vector<int>(b.begin(), b.end());
    }
  }
  int dimension() const override { return S::dimension; }
  std::optional<JointCoordinate> coordinate(int k) const override {
    if constexpr (has_coordinate<Kind>::value)
      return items[k].coordinate();
    else
      return std::nullopt;
  }
  bool unilateral() const override { return is_unilateral<Kind>::value; }
  bool ties_motion() const override { return is_tie<Kind>::value; }
  UnilateralRow unilateral_row(int k, int r) const override {
    if constexpr (is_unilateral<Kind>::value)
      return items[k].unilateral_row(r);
    else
      return {false};
  }
  ElementPlacement& placement(int k) override { return place_[k]; }
  const ElementPlacement& placement(int k) const override { return place_[k]; }

  bool sticks() const override { return is_stick<Kind>::value; }
  double stick_root(int k, const double* q, const double* v, const Instant& at, const double* lam) const override {
    if constexpr (is_stick<Kind>::value)
      return items[k].stick_root(at_q(k, q), at_v(k, v), at, lam + place_[k].row0);
    else
      return ConstraintGroupBase::stick_root(k, q, v, at, lam);
  }
  bool stick_hold(int k, const double* q, const double* v, double* run) const override {
    if constexpr (is_stick<Kind>::value)
      return items[k].stick_hold(at_q(k, q), at_v(k, v), run);
    else
      return ConstraintGroupBase::stick_hold(k, q, v, run);
  }
  int stick_state(int k, const double* run) const override {
    if constexpr (is_stick<Kind>::value)
      return items[k].stick_state(run);
    else
      return ConstraintGroupBase::stick_state(k, run);
  }
  void stick_set(int k, double* run, int state) const override {
    if constexpr (is_stick<Kind>::value)
      items[k].stick_set(run, typename Kind::StickState(state));
    else
      ConstraintGroupBase::stick_set(k, run, state);
  }
  void stick_reading(int k, const double* q, const double* run, const double* lam, ContactReading& r) const override {
    if constexpr (is_stick<Kind>::value)
      items[k].stick_reading(at_q(k, q), run, lam + place_[k].row0, r);
    else
      ConstraintGroupBase::stick_reading(k, q, run, lam, r);
  }

  void add(Kind item) {
    items.push_back(std::move(item));
    place_.emplace_back();
  }

  void declare(SparsityPattern& jac, SparsityPattern& hess) const override {
    for (const auto& p : place_)
      for (int a = 0; a < L; ++a) {
        if (p.coord[a] < 0) continue;
        for (int r = 0; r < R; ++r) jac.add(p.row0 + r, p.coord[a]);
        for (int b = 0; b < L; ++b) hess.add(p.coord[b], p.coord[a]);
      }
  }

  void bind(const SpMat& jac, const SpMat& hess) override {
    slots_.resize(items.size());
    for (size_t k = 0; k < items.size(); ++k) {
      const auto& p = place_[k];
      Slots& s = slots_[k];
      s.repeats = false;
      for (int a = 0; a < L; ++a) {
        // a body an element reaches twice (space.hpp, SpatialJointPair): its
        // Jacobian columns are summed into the first (scatter_jac); the
        // Hessian slots are added to, so they may repeat
        s.first[a] = a;
        for (int b = 0; b < a && p.coord[a] >= 0; ++b)
          if (p.coord[b] == p.coord[a]) {
            s.first[a] = b;
            s.repeats = true;
            break;
          }
        for (int r = 0; r < R; ++r)
          s.jac[a * R + r] = s.first[a] == a ? slot(jac, p.row0 + r, p.coord[a]) : -1;
        for (int b = 0; b < L; ++b) s.hess[a * L + b] = slot(hess, p.coord[b], p.coord[a]);
      }
    }
  }

  void phi(const double* q, const Instant& at, double* Phi, const std::vector<int>* only) const override {
    const auto t = time_argument<Kind>(at);
    each(only, [&](size_t k) {
      const Rows f = items[k].phi(at_q(k, q), t);
      for (int r = 0; r < R; ++r) Phi[place_[k].row0 + r] = f[r];
    });
  }

  void jacobian(const double* q, const Instant& at, double* values, const std::vector<int>* only) const override {
    const auto t = time_argument<Kind>(at);
    each(only, [&](size_t k) {
      const Jac J = items[k].jacobian(at_q(k, q), t);
      scatter_jac(k, J, values);
    });
  }

  void add_phi_t(const double* q, const Instant& at, double* out) const override {
    if constexpr (Kind::time_dependent) {
      const auto t = time_argument<Kind>(at);
      for (size_t k = 0; k < items.size(); ++k) {
        const Rows f = items[k].phi_t(at_q(k, q), t);
        for (int r = 0; r < R; ++r) out[place_[k].row0 + r] += f[r];
      }
    }
  }

  void gamma(const double* q, const double* v, const Instant& at, double* out,
             const std::vector<int>* only) const override {
    const auto t = time_argument<Kind>(at);
    std::array<MatL, R> H;
    each(only, [&](size_t k) {
      const Loc c = at_q(k, q), cd = at_v(k, v);
      Rows g;
      if constexpr (has_own_gamma<Kind>::value) {
        g = items[k].gamma(c, cd, t);
      } else if constexpr (has_rates<Kind>::value) {
        g = -items[k].rates(c, cd, t) * cd;
      } else {
        items[k].hessians(c, t, H.data());
        for (int r = 0; r < R; ++r) g[r] = -cd.dot(H[r] * cd);
      }
      if constexpr (Kind::time_dependent)
        g -= 2.0 * items[k].phi_tc(c, t) * cd + items[k].phi_tt(c, t);
      for (int r = 0; r < R; ++r) out[place_[k].row0 + r] = g[r];
    });
  }

  void add_hessian(const double* q, const Instant& at, const double* w, double* values) const override {
    const auto t = time_argument<Kind>(at);
    std::array<MatL, R> H;
    for (size_t k = 0; k < items.size(); ++k) {
      items[k].hessians(at_q(k, q), t, H.data());
      MatL sum = MatL::Zero();
      for (int r = 0; r < R; ++r) sum += w[place_[k].row0 + r] * H[r];
      for (int a = 0; a < L * L; ++a) {
        const int s = slots_[k].hess[a];
        if (s >= 0) values[s] += sum.data()[a];
      }
    }
  }

  void velocity_jacobian(const double* q, const double* v, const Instant& at, double* values,
                         const std::vector<int>* only) const override {
    const auto t = time_argument<Kind>(at);
    std::array<MatL, R> H;
    each(only, [&](size_t k) {
      const Loc c = at_q(k, q), cd = at_v(k, v);
      Jac V;
      if constexpr (has_rates<Kind>::value) {
        V = items[k].rates(c, cd, t);
      } else {
        items[k].hessians(c, t, H.data());
        for (int r = 0; r < R; ++r) V.row(r) = (H[r] * cd).transpose();
      }
      if constexpr (Kind::time_dependent) V += items[k].phi_tc(c, t);
      scatter_jac(k, V, values);
    });
  }

  VecX generalized_reaction(int k, const double* q, const Instant& at, const double* lam) const override {
    return local_reaction(k, q, at, lam);
  }

  VecX reaction(int k, const double* q, const Instant& at, const double* lam, bool joint_axes,
                bool about_joint) const override {
    const Loc c = at_q(k, q);
    const auto t = time_argument<Kind>(at);
    typename S::Point P;
    if (about_joint) {
      if constexpr (has_origin_of<Kind>::value)
        P = items[k].origin(c, t);
      else
        throw std::logic_error(std::string("reaction: a ") + Kind::kind + " has no origin (ask has_origin)");
    }
    std::optional<typename S::Axes> E;
    if (joint_axes) E = items[k].axes(c, t);
    return S::reaction(local_reaction(k, q, at, lam), c, E ? &*E : nullptr, about_joint ? &P : nullptr);
  }

  bool has_origin() const override { return has_origin_of<Kind>::value; }

  double effort(int k, const double* lam) const override {
    const Eigen::Map<const Rows> l(lam + place_[k].row0);
    if constexpr (has_row_effort<Kind>::value)
      return items[k].effort(Rows(l));
    else if constexpr (R == 1)
      return -l[0];
    else
      throw std::logic_error(std::string("effort: a ") + Kind::kind + " has none (its registry entry says so)");
  }

 private:
  struct Slots {
    std::array<int, R * L> jac;
    std::array<int, L * L> hess;
    std::array<int, L> first;  // the first local coordinate at the same place in q
    bool repeats = false;
  };

  Loc at_q(size_t k, const double* q) const { return gather_q<S>(q, place_[k].coord); }
  Loc at_v(size_t k, const double* v) const { return gather_v<L>(v, place_[k].coord); }
  /// f(k) for the elements `only` (null: every one).
  template <class F>
  void each(const std::vector<int>* only, F&& f) const {
    if (only)
      for (int k : *only) f(size_t(k));
    else
      for (size_t k = 0; k < items.size(); ++k) f(k);
  }

  Loc local_reaction(int k, const double* q, const Instant& at, const double* lam) const {
    const Jac J = items[k].jacobian(at_q(k, q), time_argument<Kind>(at));
    const Eigen::Map<const Rows> l(lam + place_[k].row0);
    return -J.transpose() * l;
  }

  void scatter_jac(size_t k, const Jac& J, double* values) const {
    const Slots& slots = slots_[k];
    if (slots.repeats) {
      Jac folded = Jac::Zero();
      for (int a = 0; a < L; ++a) folded.col(slots.first[a]) += J.col(a);
      return scatter_folded(slots, folded, values);
    }
    scatter_folded(slots, J, values);
  }
  static void scatter_folded(const Slots& slots, const Jac& J, double* values) {
    for (int a = 0; a < R * L; ++a) {
      const int s = slots.jac[a];
      if (s >= 0) values[s] = J.data()[a];
    }
  }

  std::vector<ElementPlacement> place_;
  std::vector<Slots> slots_;
};

}  // namespace lagmb
