// One container per event kind and the loops that run over it.
//
// An event kind (e.g. a planar contact's onset) owns event functions g_r(q, v, t), r = 0 ..
// roots - 1, whose zero crossings the integrators locate (IDARootInit /
// CVodeRootInit), and says what happens at a crossing. It is a plain struct
// with, in the local coordinates c and velocities cd of its two bodies (as in
// constraint_group.hpp; the plane's 6 or, for a kind with `using Space =
// Spatial;`, space's 14):
//   static constexpr int roots;                event functions per element, or
//   int root_count() const                     where they vary by element (then
//   void root_values(c, cd, t, double* g)      gives them all at once, for
//                                              kinds that compute them together)
//   static constexpr const char* kind;
//   std::string name; int body_i, body_j;
//   double root(r, c, cd, t)                   g_r
//   int direction(r)                           -1: only downward crossings
//                                              (+ to -) count; 0: both
//   EventAction crossing(r, c, cd, t, direction)  what to do at a crossing of g_r
//                                              (direction: -1 g_r falling, +1
//                                              rising, 0 not known)
//   or, for a kind with per-run state (run_state_size, constraint_group.hpp),
//   EventAction crossing(r, c, cd, t, run, direction)  which may record in run[run_state ..]
// and, optionally,
//   bool may_pass(c0, c1, gap)                 whether the motion from c0 to c1
//                                              (a step's ends, every g_r > 0 at
//                                              both, the least gap) may have
//                                              passed through a g_r < 0 and out
//                                              again: the runner then looks
//                                              inside the step
// The runner (cpp/src/events/) applies the actions; the steppers only see
// "a root was found" and restart from the state the runner hands back. A
// model without event elements has no group: no root functions are given to
// SUNDIALS and nothing is evaluated. (Stops are not event kinds: their
// limits are unilateral constraint rows, constraint_group.hpp, whose
// events the runner derives from the rows themselves.)
#pragma once

#include <array>
#include <string>
#include <vector>

#include "lagmb/model/constraint_group.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

class Model;

/// What an element asks for at a crossing of one of its event functions.
struct EventAction {
  enum Type {
    kNone,    // nothing (e.g. the velocity is leaving): continue, no restart needed
    kRestart  // the equations change here (a force switches): restart at order 1
  } type = kNone;
  /// The event function's rate g' at the crossing, for the record.
  double speed = 0.0;
  /// Which switch, for the record ("onset", ...).
  const char* label = "";
};

class EventGroupBase {
 public:
  virtual ~EventGroupBase() = default;
  virtual int size() const = 0;
  virtual const std::string& name(int k) const = 0;
  virtual const char* kind() const = 0;
  virtual int roots(int k) const = 0;
  /// Whether a negative event function marks a forbidden place (a limit)
  /// rather than a switch of a force law (contact).
  virtual bool bounds_motion() const = 0;
  virtual void place(const Model& model) = 0;
  /// Position of element k's coordinates in q (-1: ground / missing angle).
  virtual const LocalCoords& coordinates(int k) const = 0;
  /// All event functions of the group, in element order, written at g.
  virtual void values(const double* q, const double* v, double t, double* g) const = 0;
  virtual int direction(int k, int r) const = 0;
  /// run: the run's element state (Data::run->state), which the crossing
  /// may write; direction: -1 the function fell through 0, +1 rose, 0 not known.
  virtual EventAction crossing(int k, int r, const double* q, const double* v, double t, double* run,
                               int direction) const = 0;
  /// Whether the kind can say where a step may have passed through a
  /// crossing and out again (may_pass), and element k's say between the
  /// positions q0 and q1.
  virtual bool sweeps() const = 0;
  virtual bool may_pass(int k, const double* q0, const double* q1, double gap) const = 0;
  /// Element k's event functions alone (roots(k) of them) at g.
  virtual void element_values(int k, const double* q, const double* v, double t, double* g) const = 0;
};

/// Whether an event kind's elements have roots of their own number (root_count()).
template <class Kind, class = void>
struct has_root_count : std::false_type {};
template <class Kind>
struct has_root_count<Kind, std::void_t<decltype(std::declval<const Kind&>().root_count())>> : std::true_type {};

/// Whether an event kind looks inside steps for a crossing passed through (may_pass()).
template <class Kind, class = void>
struct has_may_pass : std::false_type {};
template <class Kind>
struct has_may_pass<Kind, std::void_t<decltype(std::declval<const Kind&>().may_pass(
                              std::declval<const LocalVec<space_of_t<Kind>::local>&>(),
                              std::declval<const LocalVec<space_of_t<Kind>::local>&>(), 0.0))>> : std::true_type {};

template <class Kind>
class EventGroup final : public EventGroupBase {
 public:
  std::vector<Kind> items;

  void add(Kind item) { items.push_back(std::move(item)); }
  int size() const override { return static_cast<int>(items.size()); }
  const std::string& name(int k) const override { return items[k].name; }
  const char* kind() const override { return Kind::kind; }
  bool bounds_motion() const override { return Kind::bounds_motion; }
  int roots(int k) const override {
    if constexpr (has_root_count<Kind>::value)
      return items[k].root_count();
    else
      return Kind::roots;
  }
  void place(const Model& model) override;
  const LocalCoords& coordinates(int k) const override { return coord_[k]; }
  void values(const double* q, const double* v, double t, double* g) const override {
    for (size_t k = 0; k < items.size(); ++k) {
      element_values(int(k), q, v, t, g);
      g += roots(int(k));
    }
  }
  void element_values(int k, const double* q, const double* v, double t, double* g) const override {
    const auto c = gather_q<S>(q, coord_[k]);
    const auto cd = gather_v<S::local>(v, coord_[k]);
    if constexpr (has_root_count<Kind>::value)
      items[k].root_values(c, cd, t, g);
    else
      for (int r = 0; r < Kind::roots; ++r) g[r] = items[k].root(r, c, cd, t);
  }
  bool sweeps() const override { return has_may_pass<Kind>::value; }
  bool may_pass(int k, const double* q0, const double* q1, double gap) const override {
    if constexpr (has_may_pass<Kind>::value)
      return items[k].may_pass(gather_q<S>(q0, coord_[k]), gather_q<S>(q1, coord_[k]), gap);
    else
      return false;
  }
  int direction(int k, int r) const override { return items[k].direction(r); }
  EventAction crossing(int k, int r, const double* q, const double* v, double t, double* run,
                       int direction) const override {
    const auto c = gather_q<S>(q, coord_[k]);
    const auto cd = gather_v<S::local>(v, coord_[k]);
    if constexpr (run_state_size_v<Kind> > 0)
      return items[k].crossing(r, c, cd, t, run, direction);
    else
      return items[k].crossing(r, c, cd, t, direction);
  }

 private:
  using S = space_of_t<Kind>;  // the plane's 6 local coordinates, or space's 14
  std::vector<LocalCoords> coord_;
};

}  // namespace lagmb
