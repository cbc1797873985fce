// One container per force kind and the loop that runs over it.
#pragma once

#include <array>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "lagmb/model/constraint_group.hpp"
#include "lagmb/model/contact_reading.hpp"
#include "lagmb/sparsity.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

class Model;

/// A kind of applied force. Each contributes to Q(q, v, t) and, where Q
/// depends on the state, to its exact derivatives Q_q and Q_v, which the
/// Newton matrix needs (stiff springs). Kinds whose Q is constant say so in
/// has_derivatives() and are skipped when the Newton matrix is assembled.
class ForceGroupBase {
 public:
  virtual ~ForceGroupBase() = default;
  virtual int size() const = 0;
  virtual const std::string& name(int k) const = 0;
  virtual const char* kind() const = 0;
  virtual bool has_derivatives() const = 0;

  // finalize: find coordinates, declare and bind derivative slots
  virtual void place(const Model& model) = 0;
  virtual void declare(SparsityPattern& Q_q, SparsityPattern& Q_v) const = 0;
  virtual void bind(const SpMat& Q_q, const SpMat& Q_v) = 0;

  /// at: the time and the run's inputs; run: the run's element state
  /// (Data::RunValues::state), read by kinds that keep one.
  virtual void add_forces(const double* q, const double* v, const Instant& at, const double* run,
                          double* Q) const = 0;
  virtual void add_derivatives(const double* q, const double* v, const Instant& at, const double* run,
                               double* Q_q_values, double* Q_v_values) const = 0;
  /// Potential energy of the conservative part; 0 for dissipative kinds.
  virtual double potential(const double* q, const Instant& at) const = 0;
  /// The numbers of what the kind applies that Result.effort reads (its
  /// `effort`; KindInfo::effort says what they are): 0 for a kind without.
  virtual int effort_size() const { return 0; }
  /// Element k's effort at (q, v), `at` the time, the run's inputs and
  /// state, into out (effort_size() numbers).
  virtual void effort(int k, const double* q, const double* v, const Instant& at, double* out) const {
    (void)k, (void)q, (void)v, (void)at, (void)out;
  }
  /// Whether the kind is a contact (it has `reading`, ContactReading).
  virtual bool contact() const { return false; }
  /// A contact's element k at (q, v) with the run's state `run` (false: not a contact).
  virtual bool contact_reading(int k, const double* q, const double* v, const double* run,
                               ContactReading& out) const {
    (void)k, (void)q, (void)v, (void)run, (void)out;
    return false;
  }
};

/// Whether a force kind is a contact: it has reading(c, cd, run) (ContactReading).
template <class Kind, class Loc, class = void>
struct has_reading : std::false_type {};
template <class Kind, class Loc>
struct has_reading<Kind, Loc,
                   std::void_t<decltype(std::declval<const Kind&>().reading(std::declval<const Loc&>(),
                                                                             std::declval<const Loc&>(),
                                                                             std::declval<const double*>()))>>
    : std::true_type {};

/// A force kind's effort (Result.effort): effort(c, cd, t) returning a
/// number or a fixed-size vector; effort_size_of, how many numbers (0: the
/// kind has none).
template <class Kind, class Loc>
using effort_t = std::decay_t<decltype(std::declval<const Kind&>().effort(
    std::declval<const Loc&>(), std::declval<const Loc&>(), std::declval<time_argument_t<Kind>>()))>;
template <class T>
constexpr int count_of() {
  if constexpr (std::is_arithmetic_v<T>)
    return 1;
  else
    return T::RowsAtCompileTime;
}
template <class Kind, class Loc, class = void>
struct effort_size_of : std::integral_constant<int, 0> {};
template <class Kind, class Loc>
struct effort_size_of<Kind, Loc, std::void_t<effort_t<Kind, Loc>>>
    : std::integral_constant<int, count_of<effort_t<Kind, Loc>>()> {};

/// Forces acting on (at most) two bodies, one container per kind. A kind is a
/// plain struct with, in the L local coordinates c and velocities cd of its
/// bodies (as in constraint_group.hpp; space.hpp):
///   using Space = Spatial;                   (omitted: Planar)
///   static constexpr bool state_dependent;   Q depends on c or cd
///   static constexpr const char* kind;
///   std::string name; int body_i, body_j;    (-1: ground / unused)
///   Loc force(c, cd, t)                      generalized force on c (L)
///   void derivatives(c, cd, t, MatL& Q_c, MatL& Q_cd)   if state_dependent
///   double potential(c, t)                   0 for non-conservative kinds
/// A kind with per-run state (see run_state_size in constraint_group.hpp)
/// takes the run's state as a last argument of force and derivatives; a
/// kind that reads_inputs (an actuator) takes the Instant for t. A contact
/// kind has ContactReading reading(c, cd, run) (its readers: Result.contact);
/// any other kind may give what Result.effort reads of it,
///   double effort(c, cd, t)  or  Eigen::Matrix<double, N, 1> effort(c, cd, t)
/// (its registry entry, KindInfo::effort, says what and in which unit).
template <class Kind>
class ForceGroup final : public ForceGroupBase {
 public:
  using S = space_of_t<Kind>;
  static constexpr int L = S::local;
  using Loc = LocalVec<L>;
  using MatL = LocalMat<L>;

  std::vector<Kind> items;

  void add(Kind item) { items.push_back(std::move(item)); }
  int size() const override { return static_cast<int>(items.size()); }
  const std::string& name(int k) const override { return items[k].name; }
  const char* kind() const override { return Kind::kind; }
  bool has_derivatives() const override { return Kind::state_dependent; }

  void place(const Model& model) override;

  void declare(SparsityPattern& Q_q, SparsityPattern& Q_v) const override {
    if constexpr (Kind::state_dependent)
      for (const auto& p : coord_)
        for (int a = 0; a < L; ++a)
          for (int b = 0; b < L; ++b) {
            if (p[a] < 0 || p[b] < 0) continue;
            Q_q.add(p[b], p[a]);
            Q_v.add(p[b], p[a]);
          }
  }

  void bind(const SpMat& Q_q, const SpMat& Q_v) override {
    if constexpr (Kind::state_dependent) {
      slots_q_.resize(items.size());
      slots_v_.resize(items.size());
      for (size_t k = 0; k < items.size(); ++k)
        for (int a = 0; a < L; ++a)
          for (int b = 0; b < L; ++b) {
            slots_q_[k][a * L + b] = slot(Q_q, coord_[k][b], coord_[k][a]);
            slots_v_[k][a * L + b] = slot(Q_v, coord_[k][b], coord_[k][a]);
          }
    }
  }

  void add_forces(const double* q, const double* v, const Instant& at, const double* run,
                  double* Q) const override {
    const auto t = time_argument<Kind>(at);
    for (size_t k = 0; k < items.size(); ++k) {
      const Loc c = gather_q<S>(q, coord_[k]), cd = gather_v<L>(v, coord_[k]);
      Loc f;
      if constexpr (run_state_size_v<Kind> > 0)
        f = items[k].force(c, cd, t, run);
      else
        f = items[k].force(c, cd, t);
      for (int a = 0; a < L; ++a)
        if (coord_[k][a] >= 0) Q[coord_[k][a]] += f[a];
    }
  }

  void add_derivatives(const double* q, const double* v, const Instant& at, const double* run, double* Qq,
                       double* Qv) const override {
    if constexpr (Kind::state_dependent) {
      const auto t = time_argument<Kind>(at);
      MatL dq, dv;
      for (size_t k = 0; k < items.size(); ++k) {
        const Loc c = gather_q<S>(q, coord_[k]), cd = gather_v<L>(v, coord_[k]);
        if constexpr (run_state_size_v<Kind> > 0)
          items[k].derivatives(c, cd, t, run, dq, dv);
        else
          items[k].derivatives(c, cd, t, dq, dv);
        for (int a = 0; a < L * L; ++a) {
          if (slots_q_[k][a] >= 0) Qq[slots_q_[k][a]] += dq.data()[a];
          if (slots_v_[k][a] >= 0) Qv[slots_v_[k][a]] += dv.data()[a];
        }
      }
    }
  }

  double potential(const double* q, const Instant& at) const override {
    const auto t = time_argument<Kind>(at);
    double V = 0.0;
    for (size_t k = 0; k < items.size(); ++k) V += items[k].potential(gather_q<S>(q, coord_[k]), t);
    return V;
  }

  int effort_size() const override { return effort_size_of<Kind, Loc>::value; }
  void effort(int k, const double* q, const double* v, const Instant& at, double* out) const override {
    if constexpr (effort_size_of<Kind, Loc>::value > 0) {
      const auto e = items[k].effort(gather_q<S>(q, coord_[k]), gather_v<L>(v, coord_[k]), time_argument<Kind>(at));
      if constexpr (std::is_arithmetic_v<effort_t<Kind, Loc>>)
        out[0] = e;
      else
        for (int a = 0; a < int(e.size()); ++a) out[a] = e[a];
    } else {
      (void)k, (void)q, (void)v, (void)at, (void)out;
    }
  }

  bool contact() const override { return has_reading<Kind, Loc>::value; }
  bool contact_reading(int k, const double* q, const double* v, const double* run,
                       ContactReading& out) const override {
    if constexpr (has_reading<Kind, Loc>::value) {
      out = items[k].reading(gather_q<S>(q, coord_[k]), gather_v<L>(v, coord_[k]), run);
      return true;
    } else {
      (void)k, (void)q, (void)v, (void)run, (void)out;
      return false;
    }
  }

 private:
  std::vector<LocalCoords> coord_;
  std::vector<std::array<int, L * L>> slots_q_, slots_v_;
};

}  // namespace lagmb
