// One container per constraint kind and the loops that run over it.
//
// A constraint kind (e.g. RevoluteJoint) is a plain struct that holds its
// parameters and gives, in the local coordinates c = (x_i, y_i, phi_i, x_j,
// y_j, phi_j) of the two bodies it joins:
//   static constexpr int rows;                 equations per element
//   static constexpr bool time_dependent;      Phi depends on t explicitly
//   static constexpr const char* kind;         for messages
//   Rows phi(c, t)                             Phi
//   Jac jacobian(c, t)                         Phi_c            (rows x 6)
//   void hessians(c, t, Mat6 H[rows])          d2 Phi_r / dc2
//   Mat2 axes(c, t)                            the joint's own axes (columns),
//                                              for reactions in joint axes
//   and, if time dependent: phi_t, phi_tc (rows x 6), phi_tt.
// Everything the integrators need beyond that is derived here, once:
//   gamma_r     = -v^T H_r v - 2 Phi_tc,r v - Phi_tt,r
//   d(Phi_q v + Phi_t)/dq, row r = (H_r v)^T + Phi_tc,r
//   (Phi_q^T w)_q = sum_r w_r H_r.
// Assembly sees only ConstraintGroupBase; it never names a kind.
#pragma once

#include <array>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "lagmb/sparsity.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// Where an element's local coordinates live in q (-1: ground, or a
/// particle's missing angle) and the first of its rows in Phi.
struct ElementPlacement {
  int row0 = 0;
  std::array<int, 6> coord{-1, -1, -1, -1, -1, -1};
};

inline Local6 gather(const double* x, const std::array<int, 6>& coord) {
  Local6 c;
  for (int a = 0; a < 6; ++a) c[a] = coord[a] >= 0 ? x[coord[a]] : 0.0;
  return c;
}

/// Per-run state of an element kind (any group): a kind that keeps values
/// during a run (a contact's impact speed) declares
///   static constexpr int run_state_size;   doubles per element
///   int run_state = -1;                    its offset, set by the Model
/// and reads them at run + run_state from the run's Data::run_state. The
/// Model itself is never written during a run.
template <class Kind, class = void>
struct run_state_size_of : std::integral_constant<int, 0> {};
template <class Kind>
struct run_state_size_of<Kind, std::void_t<decltype(Kind::run_state_size)>>
    : std::integral_constant<int, Kind::run_state_size> {};
template <class Kind>
inline constexpr int run_state_size_v = run_state_size_of<Kind>::value;

/// A kind may give gamma itself, `Rows gamma(c, cdot, t)`, where the
/// general -cdot^T H_r cdot over full 6 x 6 Hessians costs more than the
/// kind's closed form (the revolute joint of a long chain); tests check it
/// against the Hessians.
template <class Kind, class = void>
struct has_own_gamma : std::false_type {};
template <class Kind>
struct has_own_gamma<Kind, std::void_t<decltype(std::declval<const Kind&>().gamma(
                               std::declval<const Local6&>(), std::declval<const Local6&>(), 0.0))>>
    : std::true_type {};

class ConstraintGroupBase {
 public:
  virtual ~ConstraintGroupBase() = default;
  virtual int size() const = 0;
  virtual int rows(int k) const = 0;
  virtual const std::string& name(int k) const = 0;
  virtual const char* kind() const = 0;
  virtual bool time_dependent() const = 0;
  virtual std::array<int, 2> bodies(int k) const = 0;
  virtual ElementPlacement& placement(int k) = 0;
  virtual const ElementPlacement& placement(int k) const = 0;

  // finalize: declare the entries this kind writes, then bind slots to them
  virtual void declare(SparsityPattern& jacobian, SparsityPattern& hessian) const = 0;
  virtual void bind(const SpMat& jacobian, const SpMat& hessian) = 0;

  // kernels; q, v, lam are global vectors, outputs are written at the
  // element's rows or slots
  virtual void phi(const double* q, double t, double* Phi) const = 0;
  virtual void jacobian(const double* q, double t, double* Phi_q_values) const = 0;
  virtual void add_phi_t(const double* q, double t, double* phi_t) const = 0;
  virtual void gamma(const double* q, const double* v, double t, double* gamma) const = 0;
  virtual void add_hessian(const double* q, double t, const double* w, double* H_values) const = 0;
  virtual void velocity_jacobian(const double* q, const double* v, double t,
                                 double* Vq_values) const = 0;
  /// Generalized force -Phi_c^T lam the element applies on its two bodies,
  /// in local coordinates (force x, y and torque about each centre of mass).
  virtual Local6 generalized_reaction(int k, const double* q, double t,
                                      const double* lam) const = 0;
  /// The element's own axes (columns, global components) at state q.
  virtual Mat2 axes(int k, const double* q, double t) const = 0;
  /// The reaction on the element's second body: force (x, y) and torque
  /// about its centre of mass, the last three of generalized_reaction; with
  /// joint_axes the force in the element's own axes, A^T F.
  Eigen::Vector3d reaction(int k, const double* q, double t, const double* lam, bool joint_axes) const {
    Eigen::Vector3d w = generalized_reaction(k, q, t, lam).tail<3>();
    if (joint_axes) w.head<2>() = axes(k, q, t).transpose() * w.head<2>();
    return w;
  }
};

template <class Kind>
class ConstraintGroup final : public ConstraintGroupBase {
 public:
  static constexpr int R = Kind::rows;
  using Rows = Eigen::Matrix<double, R, 1>;
  using Jac = Eigen::Matrix<double, R, 6>;

  std::vector<Kind> items;

  int size() const override { return static_cast<int>(items.size()); }
  int rows(int) const override { return R; }
  const std::string& name(int k) const override { return items[k].name; }
  const char* kind() const override { return Kind::kind; }
  bool time_dependent() const override { return Kind::time_dependent; }
  std::array<int, 2> bodies(int k) const override { return {items[k].body_i, items[k].body_j}; }
  ElementPlacement& placement(int k) override { return place_[k]; }
  const ElementPlacement& placement(int k) const override { return place_[k]; }

  void add(Kind item) {
    items.push_back(std::move(item));
    place_.emplace_back();
  }

  void declare(SparsityPattern& jac, SparsityPattern& hess) const override {
    for (const auto& p : place_)
      for (int a = 0; a < 6; ++a) {
        if (p.coord[a] < 0) continue;
        for (int r = 0; r < R; ++r) jac.add(p.row0 + r, p.coord[a]);
        for (int b = 0; b < 6; ++b) hess.add(p.coord[b], p.coord[a]);
      }
  }

  void bind(const SpMat& jac, const SpMat& hess) override {
    slots_.resize(items.size());
    for (size_t k = 0; k < items.size(); ++k) {
      const auto& p = place_[k];
      for (int a = 0; a < 6; ++a) {
        for (int r = 0; r < R; ++r) slots_[k].jac[a * R + r] = slot(jac, p.row0 + r, p.coord[a]);
        for (int b = 0; b < 6; ++b) slots_[k].hess[a * 6 + b] = slot(hess, p.coord[b], p.coord[a]);
      }
    }
  }

  void phi(const double* q, double t, double* Phi) const override {
    for (size_t k = 0; k < items.size(); ++k) {
      const Rows f = items[k].phi(gather(q, place_[k].coord), t);
      for (int r = 0; r < R; ++r) Phi[place_[k].row0 + r] = f[r];
    }
  }

  void jacobian(const double* q, double t, double* values) const override {
    for (size_t k = 0; k < items.size(); ++k) {
      const Jac J = items[k].jacobian(gather(q, place_[k].coord), t);
      scatter_jac(k, J, values);
    }
  }

  void add_phi_t(const double* q, double t, double* out) const override {
    if constexpr (Kind::time_dependent) {
      for (size_t k = 0; k < items.size(); ++k) {
        const Rows f = items[k].phi_t(gather(q, place_[k].coord), t);
        for (int r = 0; r < R; ++r) out[place_[k].row0 + r] += f[r];
      }
    }
  }

  void gamma(const double* q, const double* v, double t, double* out) const override {
    std::array<Mat6, R> H;
    for (size_t k = 0; k < items.size(); ++k) {
      const Local6 c = gather(q, place_[k].coord), cd = gather(v, place_[k].coord);
      Rows g;
      if constexpr (has_own_gamma<Kind>::value) {
        g = items[k].gamma(c, cd, t);
      } else {
        items[k].hessians(c, t, H.data());
        for (int r = 0; r < R; ++r) g[r] = -cd.dot(H[r] * cd);
      }
      if constexpr (Kind::time_dependent)
        g -= 2.0 * items[k].phi_tc(c, t) * cd + items[k].phi_tt(c, t);
      for (int r = 0; r < R; ++r) out[place_[k].row0 + r] = g[r];
    }
  }

  void add_hessian(const double* q, double t, const double* w, double* values) const override {
    std::array<Mat6, R> H;
    for (size_t k = 0; k < items.size(); ++k) {
      items[k].hessians(gather(q, place_[k].coord), t, H.data());
      Mat6 S = Mat6::Zero();
      for (int r = 0; r < R; ++r) S += w[place_[k].row0 + r] * H[r];
      for (int a = 0; a < 36; ++a) {
        const int s = slots_[k].hess[a];
        if (s >= 0) values[s] += S.data()[a];
      }
    }
  }

  void velocity_jacobian(const double* q, const double* v, double t,
                         double* values) const override {
    std::array<Mat6, R> H;
    for (size_t k = 0; k < items.size(); ++k) {
      const Local6 c = gather(q, place_[k].coord), cd = gather(v, place_[k].coord);
      items[k].hessians(c, t, H.data());
      Jac V;
      for (int r = 0; r < R; ++r) V.row(r) = (H[r] * cd).transpose();
      if constexpr (Kind::time_dependent) V += items[k].phi_tc(c, t);
      scatter_jac(k, V, values);
    }
  }

  Local6 generalized_reaction(int k, const double* q, double t,
                              const double* lam) const override {
    const Jac J = items[k].jacobian(gather(q, place_[k].coord), t);
    const Eigen::Map<const Rows> l(lam + place_[k].row0);
    return -J.transpose() * l;
  }

  Mat2 axes(int k, const double* q, double t) const override {
    return items[k].axes(gather(q, place_[k].coord), t);
  }

 private:
  struct Slots {
    std::array<int, R * 6> jac;
    std::array<int, 36> hess;
  };

  void scatter_jac(size_t k, const Jac& J, double* values) const {
    for (int a = 0; a < R * 6; ++a) {
      const int s = slots_[k].jac[a];
      if (s >= 0) values[s] = J.data()[a];
    }
  }

  std::vector<ElementPlacement> place_;
  std::vector<Slots> slots_;
};

}  // namespace lagmb
