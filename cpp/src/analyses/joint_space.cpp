// Joint coordinates read from lagmb's coordinates, and inverse dynamics in
// joint efforts (joint_space.hpp).
#include "lagmb/analyses/joint_space.hpp"

#include <cmath>
#include <sstream>

#include "elements/build.hpp"
#include "lagmb/model/coordinates.hpp"
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/elements/drivers.hpp"
#include "lagmb/model/joint_reading.hpp"
#include "lagmb/errors.hpp"
#include "lagmb/model/data.hpp"
#include "lagmb/solvers/sparse_qr.hpp"

namespace lagmb {

namespace {

/// A joint coordinate g(c) at one state: its value, its gradient over the
/// joint's local coordinates, and that gradient's rate along c' (6 or 14
/// entries, the local layout of `where`).
struct CoordinateTerm {
  double value = 0.0;
  VecX gradient, gradient_rate;
  LocalCoords where;
  int local = 0;
};

/// g of `joint` from the coordinate function its drivers hold (spatial:
/// spatial::joint_slide, or the angle as its turn counter reads it, within
/// half a turn of where the run's `state` has it (null: of its initial
/// angle; model/joint_turns.hpp); plane: phi_j - phi_i or the projected
/// offset).
CoordinateTerm coordinate_term(const Model& model, const std::string& joint, bool slide, const double* q,
                               const double* v, const char* who, const double* state = nullptr) {
  if (!model.finalized()) throw ModelError(std::string(who) + ": the model is not finalized");
  const build::JointOf c = build::joint_coordinate(model, joint, who);
  if (slide && !c.slides)
    throw ModelError(std::string(who) + ": '" + joint + "' does not slide (it turns: ask for its angle)");
  if (!slide && !c.turns)
    throw ModelError(std::string(who) + ": '" + joint + "' does not turn (it slides: ask for its slide)");
  CoordinateTerm g;
  g.where = model.local_coordinates(c.body_i, c.body_j);
  if (model.dimension() == 3) {
    const spatial::Loc cq = gather_q<Spatial>(q, g.where), cv = gather_v<14>(v, g.where);
    spatial::Want want;
    want.rate = &cv;
    const TurnCounter* counter = slide ? nullptr : model.turn_counter(joint);
    const spatial::ScalarTerm s = slide      ? spatial::joint_slide(cq, c.s_i, c.s_j, c.a_i, want)
                                  : counter ? counter->reading(cq, want, Instant{0.0, nullptr, state})
                                            : spatial::joint_angle(cq, c.f_i, c.g_i, c.f_j, want);
    g.local = 14;
    g.value = s.value;
    g.gradient = s.gradient.transpose();
    g.gradient_rate = s.gradient_rate.transpose();
  } else {
    const Local6 cq = gather_q<Planar>(q, g.where), cv = gather_v<6>(v, g.where);
    g.local = 6;
    if (slide) {  // u_i . (p_j - p_i)
      g.value = c.along.value(cq);
      g.gradient = c.along.gradient(cq).transpose();
      g.gradient_rate = c.along.hessian(cq) * cv;
    } else {  // phi_j - phi_i (the bodies' angles are coordinates: not wrapped)
      g.value = cq[5] - cq[2];
      g.gradient = VecX::Zero(6);
      g.gradient[2] = -1.0, g.gradient[5] = 1.0;
      g.gradient_rate = VecX::Zero(6);
    }
  }
  return g;
}

/// The term's gradient (or its rate) times a local vector gathered from x.
double local_dot(const CoordinateTerm& g, const VecX& row, const double* x) {
  double sum = 0.0;
  for (int k = 0; k < g.local; ++k)
    if (g.where[k] >= 0) sum += row[k] * x[g.where[k]];
  return sum;
}

}  // namespace

JointMotion joint_motion(const Model& model, const std::string& joint, bool slide, const double* q, const double* v,
                         const double* a, const double* state) {
  const CoordinateTerm g = coordinate_term(model, joint, slide, q, v, "joint_motion", state);
  JointMotion m;
  m.value = g.value;
  m.rate = local_dot(g, g.gradient, v);
  m.acceleration = (a ? local_dot(g, g.gradient, a) : 0.0) + local_dot(g, g.gradient_rate, v);
  return m;
}

InverseDynamics inverse_dynamics(const Model& model, const std::vector<JointEffort>& joints, const double* q,
                                 const double* v, const double* a, double t) {
  const int n = model.n_coordinates(), m = model.n_constraints(), k = int(joints.size());
  if (!model.finalized()) throw ModelError("inverse_dynamics: the model is not finalized");
  Data d(model);
  assemble_jacobian(model, d, q, t);  // (and M(q))
  assemble_forces(model, d, q, v, t);
  VecX rhs = d.Q;  // Q - M a
  VecX Ma(n);
  mass_times(d, a, Ma.data());
  rhs -= Ma;
  // A = [Phi_q^T, -G^T]: column j < m the constraint row j, column m + i joint i
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(size_t(d.Phi_q.nonZeros()) + size_t(k) * 14);
  for (int c = 0; c < d.Phi_q.outerSize(); ++c)
    for (SpMat::InnerIterator it(d.Phi_q, c); it; ++it) entries.emplace_back(int(it.col()), int(it.row()), it.value());
  for (int i = 0; i < k; ++i) {
    const CoordinateTerm g = coordinate_term(model, joints[i].joint, joints[i].slide, q, v, "inverse_dynamics");
    for (int j = 0; j < g.local; ++j)
      if (g.where[j] >= 0 && g.gradient[j] != 0.0) entries.emplace_back(g.where[j], m + i, -g.gradient[j]);
  }
  SpMat A(n, m + k);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  const SparseQR qr(A);
  if (!qr.ok()) throw SimulationError("inverse_dynamics: the least-squares solve failed", t);
  const VecX x = qr.solve(rhs);
  const VecX missing = A * x - rhs;
  Eigen::Index worst = 0;
  const double gap = n ? missing.cwiseAbs().maxCoeff(&worst) : 0.0;
  if (!(gap <= 1e-9 * (1.0 + rhs.cwiseAbs().maxCoeff())) || !x.allFinite()) {
    std::ostringstream s;
    s << "inverse_dynamics: the motion needs a generalized force of " << gap << " at " << coordinate_label(model, int(worst))
      << " that neither the joints nor the efforts asked for can apply (a free body without an effort, or "
         "a motion the joints do not allow)";
    throw SimulationError(s.str(), t);
  }
  InverseDynamics out;
  out.lam = x.head(m);
  out.efforts = x.tail(k);
  return out;
}

}  // namespace lagmb
