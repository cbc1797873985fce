// A run's outputs: the states recorded at the output times and their
// accelerations and multipliers, solved from the augmented system.
#include "run/recording.hpp"

#include <sstream>

#include "integrators/integrators.hpp"
#include "lagmb/analyses/consistent_state.hpp"
#include "lagmb/analyses/diagnosis.hpp"
#include "lagmb/errors.hpp"

namespace lagmb {

std::string solve_outputs(const Model& model, Data& d, AugmentedSystem& kkt, Trajectory& tr, int first) {
  const int n = tr.n, m = tr.m, k = tr.size();
  for (int i = first; i < k; ++i) {
    tr.a.resize(size_t(i + 1) * n);
    tr.lam.resize(size_t(i + 1) * m);
    double *a = tr.a.data() + size_t(i) * n, *lam = tr.lam.data() + size_t(i) * m;
    const double *q = tr.q.data() + size_t(i) * n, *v = tr.v.data() + size_t(i) * n;
    if (tr.state_size > 0 && tr.run_state.size() >= size_t(i + 1) * tr.state_size)  // what the elements read there
      d.run->state = Eigen::Map<const VecX>(tr.run_state.data() + size_t(i) * tr.state_size, tr.state_size);
    std::string why;
    try {
      solve_accelerations(model, d, kkt, q, v, tr.t[i], a, lam);
      if (!Eigen::Map<const VecX>(a, n).allFinite() || !Eigen::Map<const VecX>(lam, m).allFinite())
        why = non_finite_source(model, d, q, v, tr.t[i]);
    } catch (const UserFunctionError& e) {
      why = e.what();
    } catch (const SimulationError& e) {
      why = e.what();
    }
    if (!why.empty()) {
      tr.a.resize(size_t(i) * n);
      tr.lam.resize(size_t(i) * m);
      std::ostringstream s;
      s << "at the output t = " << tr.t[i] << " the accelerations and multipliers cannot be solved: " << why;
      return s.str();
    }
  }
  return "";
}

void record_output(const Model& model, Data& d, AugmentedSystem& kkt, RedundancyWatch& watch, Trajectory& tr,
                   double t, const double* q, const double* v, const Data::RunValues& values, bool solve,
                   const double* qdd, const double* lam) {
  auto stop = [&](const std::string& why) {
    IntegratorFailure f(why, t);
    f.diagnose = false;  // the message is complete
    throw f;
  };
  if (watch.active())
    if (const std::string why = watch.violation(q, t); !why.empty()) stop(why);
  const int n = tr.n;
  tr.t.push_back(t);
  tr.q.insert(tr.q.end(), q, q + n);
  tr.v.insert(tr.v.end(), v, v + n);
  tr.inputs.insert(tr.inputs.end(), values.inputs.data(), values.inputs.data() + values.inputs.size());
  tr.run_state.insert(tr.run_state.end(), values.state.data(), values.state.data() + values.state.size());
  const int m = tr.m;
  if (solve && qdd && lam && Eigen::Map<const VecX>(qdd, n).allFinite() && Eigen::Map<const VecX>(lam, m).allFinite()) {
    tr.a.insert(tr.a.end(), qdd, qdd + n);
    tr.lam.insert(tr.lam.end(), lam, lam + m);
    return;
  }
  if (solve)
    if (const std::string why = solve_outputs(model, d, kkt, tr, tr.size() - 1); !why.empty()) {
      tr.truncate(solved_outputs(tr));
      stop(why);
    }
}

int solved_outputs(const Trajectory& tr) { return tr.n > 0 ? int(tr.a.size() / size_t(tr.n)) : tr.size(); }

}  // namespace lagmb
