// One container per joint-friction kind: forces Q(q, v, lam) that depend on
// the multipliers, and the loop that runs over them.
//
// A kind (elements/joint_friction.hpp) names a joint and gives, in the
// joint's local coordinates c:
//   static constexpr int rows;                the joint's rows (multipliers)
//   Local6 direction(c)                       g = ds/dc of its relative coordinate s
//   Mat6 direction_derivative(c)              dg/dc (symmetric)
//   double load(lam_rows, dN)                 the load N >= 0 and dN/dlam
//   JointFrictionLaw law                      F(N, sd)
// With sd = g . cd and F = law(N, sd), the group derives, once:
//   Q       = F g
//   Q_c     = F dg/dc + dF/dsd g (dg/dc cd)^T
//   Q_cd    = dF/dsd g g^T
//   Q_lam   = dF/dN g (dN/dlam)^T   (6 x rows: the joint's own Phi_q^T slots)
// Only models with friction have such groups; without them nothing here runs.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "lagmb/model/constraint_group.hpp"
#include "lagmb/sparsity.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

class Model;

class FrictionGroupBase {
 public:
  virtual ~FrictionGroupBase() = default;
  virtual int size() const = 0;
  virtual const std::string& name(int k) const = 0;
  virtual const char* kind() const = 0;

  // finalize: the joint's coordinates and rows, derivative slots
  virtual void place(const Model& model) = 0;
  virtual void declare(SparsityPattern& Q_q, SparsityPattern& Q_v) const = 0;
  virtual void bind(const SpMat& Q_q, const SpMat& Q_v, const SpMat& jacobian) = 0;

  /// Q += Q_f(q, v, lam).
  virtual void add_forces(const double* q, const double* v, const double* lam, double* Q) const = 0;
  /// Adds Q_f,q and Q_f,v (patterns of Q_q, Q_v) and Q_f,lam^T (pattern of Phi_q).
  virtual void add_derivatives(const double* q, const double* v, const double* lam, double* Q_q,
                               double* Q_v, double* Q_lam_t) const = 0;
  /// Element k's friction F (torque or force) and slip rate sd.
  virtual std::array<double, 2> friction(int k, const double* q, const double* v,
                                         const double* lam) const = 0;
};

template <class Kind>
class FrictionGroup final : public FrictionGroupBase {
 public:
  static constexpr int R = Kind::rows;
  std::vector<Kind> items;

  void add(Kind item) { items.push_back(std::move(item)); }
  int size() const override { return static_cast<int>(items.size()); }
  const std::string& name(int k) const override { return items[k].name; }
  const char* kind() const override { return Kind::kind; }

  void place(const Model& model) override;

  void declare(SparsityPattern& Q_q, SparsityPattern& Q_v) const override {
    for (const auto& p : place_)
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) {
          Q_q.add(p.coord[b], p.coord[a]);
          Q_v.add(p.coord[b], p.coord[a]);
        }
  }

  void bind(const SpMat& Q_q, const SpMat& Q_v, const SpMat& jac) override {
    slots_.resize(items.size());
    for (size_t k = 0; k < items.size(); ++k) {
      const auto& p = place_[k];
      for (int a = 0; a < 6; ++a) {
        for (int b = 0; b < 6; ++b) {
          slots_[k].q[a * 6 + b] = slot(Q_q, p.coord[b], p.coord[a]);
          slots_[k].v[a * 6 + b] = slot(Q_v, p.coord[b], p.coord[a]);
        }
        // dQ_a / dlam_r sits where Phi_q holds dPhi_r / dq_a
        for (int r = 0; r < R; ++r) slots_[k].lam[a * R + r] = slot(jac, p.row0 + r, p.coord[a]);
      }
    }
  }

  void add_forces(const double* q, const double* v, const double* lam, double* Q) const override {
    for (size_t k = 0; k < items.size(); ++k) {
      const auto& p = place_[k];
      const Local6 c = gather_q<Planar>(q, p.coord), cd = gather_v<6>(v, p.coord);
      const Local6 g = items[k].direction(c);
      double dN[R], dF_dN, dF_dsd;
      const double N = items[k].load(lam + p.row0, dN);
      const double F = items[k].law.value(N, g.dot(cd), dF_dN, dF_dsd);
      for (int a = 0; a < 6; ++a)
        if (p.coord[a] >= 0) Q[p.coord[a]] += F * g[a];
    }
  }

  void add_derivatives(const double* q, const double* v, const double* lam, double* Qq, double* Qv,
                       double* Ql) const override {
    for (size_t k = 0; k < items.size(); ++k) {
      const auto& p = place_[k];
      const Local6 c = gather_q<Planar>(q, p.coord), cd = gather_v<6>(v, p.coord);
      const Local6 g = items[k].direction(c);
      double dN[R], dF_dN, dF_dsd;
      const double N = items[k].load(lam + p.row0, dN);
      const double F = items[k].law.value(N, g.dot(cd), dF_dN, dF_dsd);
      Mat6 dq = Mat6::Zero();
      if constexpr (!Kind::constant_direction) {
        const Mat6 G = items[k].direction_derivative(c);
        dq = F * G + dF_dsd * g * (G * cd).transpose();
      }
      const Mat6 dv = dF_dsd * g * g.transpose();
      for (int a = 0; a < 36; ++a) {
        if (slots_[k].q[a] >= 0) Qq[slots_[k].q[a]] += dq.data()[a];
        if (slots_[k].v[a] >= 0) Qv[slots_[k].v[a]] += dv.data()[a];
      }
      for (int a = 0; a < 6; ++a)
        for (int r = 0; r < R; ++r) {
          const int s = slots_[k].lam[a * R + r];
          if (s >= 0) Ql[s] += dF_dN * dN[r] * g[a];
        }
    }
  }

  std::array<double, 2> friction(int k, const double* q, const double* v,
                                 const double* lam) const override {
    const auto& p = place_[k];
    const Local6 c = gather_q<Planar>(q, p.coord), cd = gather_v<6>(v, p.coord);
    const Local6 g = items[k].direction(c);
    double dN[R], dF_dN, dF_dsd;
    const double sd = g.dot(cd);
    return {items[k].law.value(items[k].load(lam + p.row0, dN), sd, dF_dN, dF_dsd), sd};
  }

 private:
  struct Slots {
    std::array<int, 36> q, v;
    std::array<int, 6 * R> lam;
  };
  std::vector<ElementPlacement> place_;  // the joint's
  std::vector<Slots> slots_;
};

}  // namespace lagmb
