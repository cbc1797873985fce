// Finding crossings: the event functions' values, the crossings a step
// passed (missed), and those in and out within one step (grazed: a stop's
// gap or a closed row's force on the interpolant, shapes passing through
// each other).
#include "lagmb/events/event_runner.hpp"

#include <algorithm>
#include <cmath>

#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

void EventRunner::values(double t, const double* q, const double* v, double* g, const double* lam) {
  ++root_evals;
  int offset = 0;
  for (const auto& group : model_.event_groups()) {
    group->values(q, v, t, g + offset);
    for (int k = 0; k < group->size(); ++k) offset += group->roots(k);
  }
  // (a crossing acted on reads on its new side until a step's end finds it
  // there, unless it goes back further than 10 times the restart put it
  // from 0: consistent())
  for (const Pin& p : last_.pins)
    if ((g[p.root] > 0.0) != (p.side > 0) && std::abs(g[p.root]) <= p.within) g[p.root] = p.side * 1e-300;
  if (contacts_.empty() && sticks_.empty()) return;
  if (!d_.closed_rows().empty()) {
    if (lam)
      lam_ = Eigen::Map<const VecX>(lam, model_.n_constraints());
    else
      solve_accelerations(model_, d_, kkt_, q, v, t, qdd_.data(), lam_.data());
    // (a step's start's and end's: grazed() reads them)
    if (t != window_.values_t) {
      window_.values_t_before = window_.values_t;
      window_.values_force_before.swap(window_.values_force);
    }
    window_.values_t = t, window_.values_force = -lam_;
  }
  for (size_t j = 0; j < sticks_.size(); ++j) {
    const double x = model_.constraint_groups()[sticks_[j].group]->stick_root(sticks_[j].element, q, v, d_.at(t),
                                                                           lam_.data());
    g[sticks_base_ + j] = x != 0.0 ? x : -1e-300;
  }
  if (contacts_.empty()) return;
  const Instant at = rows_.at(t);
  for (int gi : unilateral_groups_) model_.constraint_groups()[gi]->phi(q, at, rows_.Phi.data());
  const double at_limit = 1e-10;
  // (the rates of the open rows at their limits: their elements' gradients alone)
  bool rates = false;
  for (const Contact& c : contacts_)
    if (c.info.exists && !is_closed(c.row) && std::abs(rows_.Phi[c.row]) <= at_limit) {
      one_[0] = c.element;
      model_.constraint_groups()[size_t(c.group)]->jacobian(q, at, rows_.Phi_q.valuePtr(), &one_);
      rows_.phi_t[c.row] = rate(c, v);
      rates = true;
    }
  const double at_rest = 1e-9 * (1.0 + Eigen::Map<const VecX>(v, model_.n_coordinates()).lpNorm<Eigen::Infinity>());
  for (const Contact& c : contacts_) {
    double x = !c.info.exists ? 1.0 : is_closed(c.row) ? -lam_[c.row] : rows_.Phi[c.row];
    if (rates && !is_closed(c.row) && c.info.exists && std::abs(x) <= at_limit)
      x = rows_.phi_t[c.row] >= -at_rest || (left(c.row) && (t == last_.restart_t || !rebounding(c.row))) ? at_limit : x;
    g[offset++] = x != 0.0 ? x : -1e-300;
  }
}

bool EventRunner::missed(double t, const double* q, const double* v, std::vector<int>& fired, const double* lam) {
  values(t, q, v, g_.data(), lam);
  fired.assign(g_.size(), 0);
  bool any = false;
  const size_t base = roots_.size();
  const double force_tol = 1e-8 * (1.0 + lam_.lpNorm<Eigen::Infinity>());
  for (size_t i = 0; i < g_.size(); ++i) {
    const bool pulling = i >= base && i < sticks_base_ && is_closed(contacts_[i - base].row);
    if (dir_[i] < 0 && g_[i] < (pulling ? -force_tol : -1e-10)) {
      fired[i] = -1;  // (fell below 0) the action decides: leaving velocities do nothing
      any = true;
    }
  }
  // (a contact's stick state whose function the step's end finds past 0:
  // stuck and released, armed and slow, disarmed and fast; handle_sticks decides)
  for (size_t j = 0; j < sticks_.size(); ++j) {
    const int state = model_.constraint_groups()[sticks_[j].group]->stick_state(sticks_[j].element, d_.run->state.data());
    const double x = g_[sticks_base_ + j];
    if ((state == 1 && x < -force_tol) || (state == 0 && x < 0.0) || (state == -1 && x > 0.0)) {
      fired[sticks_base_ + j] = 1;
      any = true;
    }
  }
  last_.late = any;
  return any;
}

double EventRunner::grazed(double t0, double t1, const Interpolant& at, std::vector<int>& fired,
                           const Multipliers& lam) {
  window_.step_bound = INFINITY;
  if (!(t1 > t0)) return NAN;
  if (!last_.pins.empty()) {  // (a pinned function that a step's end finds on its new side is free again)
    const double *q = nullptr, *v = nullptr;
    at(t1, q, v);
    std::vector<double> g(g_.size());
    const std::vector<Pin> pins = last_.pins;
    last_.pins.clear();
    values(t1, q, v, g.data(), lam ? lam(t1, q, v) : nullptr);
    for (const Pin& p : pins)
      if ((g[size_t(p.root)] > 0.0) != (p.side > 0)) last_.pins.push_back(p);
  }
  std::vector<int> roots, rows;
  const double passed = passed_through(t0, t1, at, roots);
  const double grazing = contacts_.empty() ? NAN : grazed_stops(t0, t1, at, lam, rows);
  const double t_tol = 1e-14 * (std::abs(t1) + (t1 - t0));
  if (std::isnan(passed) && std::isnan(grazing)) return NAN;
  fired.assign(g_.size(), 0);
  // the earlier of the two (both, within rounding of each other)
  if (!(grazing < passed - t_tol))
    for (int i : roots) fired[size_t(i)] = -1;
  if (!(passed < grazing - t_tol))
    for (int c : rows) fired[roots_.size() + size_t(c)] = -1;
  return std::isnan(passed) ? grazing : std::isnan(grazing) ? passed : std::min(passed, grazing);
}

double EventRunner::passed_through(double t0, double t1, const Interpolant& at, std::vector<int>& fired_roots) {
  if (sweeps_.empty()) return NAN;
  const double *q = nullptr, *v = nullptr;
  const int n = model_.n_coordinates();
  if (!(window_.sweep_t == t0)) {
    at(t0, q, v);
    window_.sweep_q = Eigen::Map<const VecX>(q, n);
  }
  const VecX q0 = window_.sweep_q;
  at(t1, q, v);
  window_.sweep_q = Eigen::Map<const VecX>(q, n), window_.sweep_t = t1;
  const VecX& q1 = window_.sweep_q;
  const double h = t1 - t0, t_tol = 1e-14 * (std::abs(t1) + h);
  constexpr int kSamples = 16;
  std::vector<double> g;
  // the least of element s's event functions at t (the interpolant's state)
  auto least = [&](const Sweep& s, double t) {
    at(t, q, v);
    g.resize(size_t(s.count));
    model_.event_groups()[s.group]->element_values(s.element, q, v, t, g.data());
    return *std::min_element(g.begin(), g.end());
  };
  double earliest = NAN;
  for (const Sweep& s : sweeps_) {
    const EventGroupBase& group = *model_.event_groups()[s.group];
    if (!group.may_pass(s.element, q0.data(), q1.data(), -INFINITY)) continue;  // (the bounding spheres stay apart)
    const double gap = std::min(least(s, t0), least(s, t1));
    if (!(gap > 0.0) || !group.may_pass(s.element, q0.data(), q1.data(), gap)) continue;
    double lo = t0, hi = NAN;
    for (int i = 1; i < kSamples && std::isnan(hi); ++i) {
      const double ti = t0 + h * i / kSamples;
      (least(s, ti) < 0.0 ? hi : lo) = ti;
    }
    if (std::isnan(hi)) continue;
    while (hi - lo > t_tol) {
      const double mid = 0.5 * (lo + hi);
      (least(s, mid) < 0.0 ? hi : lo) = mid;
    }
    if (!std::isnan(earliest) && hi > earliest + t_tol) continue;
    if (std::isnan(earliest) || hi < earliest - t_tol) fired_roots.clear();
    earliest = std::isnan(earliest) ? hi : std::min(earliest, hi);
    least(s, hi);
    for (int r = 0; r < s.count; ++r)
      if (g[size_t(r)] < 0.0) fired_roots.push_back(s.root0 + r);
  }
  return earliest;
}

double EventRunner::grazed_stops(double t0, double t1, const Interpolant& at, const Multipliers& lam,
                                 std::vector<int>& rows) {
  const double *q = nullptr, *v = nullptr;
  const int n = model_.n_coordinates();
  auto gap = [&](double t, int row, double* rate) {
    at(t, q, v);
    gaps(t, Eigen::Map<const VecX>(q, n), Eigen::Map<const VecX>(v, n));
    if (rate) *rate = rows_.phi_t[row];
    return rows_.Phi[row];
  };
  // the gaps and rates at both ends (the start's are the last step's end's,
  // unless an event acted since: an interpolant's start can cost the
  // explicit stepper two right-hand sides)
  if (!(window_.gaps_t == t0)) {
    at(t0, q, v);
    gaps(t0, Eigen::Map<const VecX>(q, n), Eigen::Map<const VecX>(v, n));
    window_.end_gaps = rows_.Phi, window_.end_rates = rows_.phi_t;
  }
  at(t1, q, v);
  gaps(t1, Eigen::Map<const VecX>(q, n), Eigen::Map<const VecX>(v, n));
  // (buffers kept from step to step)
  window_.start_gaps.swap(window_.end_gaps), window_.start_rates.swap(window_.end_rates);
  window_.end_gaps = rows_.Phi, window_.end_rates = rows_.phi_t, window_.gaps_t = t1;
  std::vector<int>& left = last_.left;
  left.erase(std::remove_if(left.begin(), left.end(), [&](int row) { return window_.end_gaps[row] > 1e-10; }),
             left.end());
  const VecX &g0 = window_.start_gaps, &r0 = window_.start_rates, &g1 = window_.end_gaps, &r1 = window_.end_rates;
  const double h = t1 - t0, t_tol = 1e-14 * (std::abs(t1) + h);
  constexpr int kSamples = 16;
  double earliest = NAN;
  for (size_t c = 0; c < contacts_.size(); ++c) {
    const int row = contacts_[c].row;
    if (!contacts_[c].info.exists || is_closed(row)) continue;
    // (a row starts on its limit after a restart: its gap 0 to rounding)
    if (!(g0[row] > -1e-10 && g1[row] > 0.0)) continue;
    // (one resting on its limit at both ends, held there: a stop duplicating
    // a closed one through a coupling; a grazing crossing must rise beyond
    // 1e-10 first, below)
    if (std::max(g0[row], g1[row]) <= 1e-10 && h * std::max(std::abs(r0[row]), std::abs(r1[row])) <= 1e-10) continue;
    // the cubic Hermite through (g, g') at the ends: a turn far from the limit is passed over
    double cubic_min = INFINITY;
    for (int i = 1; i < 4 * kSamples; ++i) {
      const double s = i / (4.0 * kSamples), s2 = s * s, s3 = s2 * s;
      cubic_min = std::min(cubic_min, (2 * s3 - 3 * s2 + 1) * g0[row] + (s3 - 2 * s2 + s) * h * r0[row] +
                                          (-2 * s3 + 3 * s2) * g1[row] + (s3 - s2) * h * r1[row]);
    }
    if (cubic_min > 0.5 * std::min(std::max(g0[row], 0.0), g1[row])) continue;
    // the gap on the interpolant: samples, then the first one beyond, or the
    // lowest one's turn (g' = 0 by bisection) if that is beyond
    // (a row on its limit must have left it first, beyond the root
    // functions' rounding: one that goes straight on beyond is no grazing)
    double lo = t0, hi = NAN, lowest = INFINITY, t_lowest = t0, highest = g0[row];
    for (int i = 1; i < kSamples && std::isnan(hi); ++i) {
      const double ti = t0 + h * i / kSamples, gi = gap(ti, row, nullptr);
      if (gi < 0.0) hi = ti;
      else if (gi < lowest) lowest = gi, t_lowest = ti;
      if (gi >= 0.0) lo = ti, highest = std::max(highest, gi);
    }
    if (!(highest > 1e-10)) continue;
    if (std::isnan(hi)) {
      double a = std::max(t0, t_lowest - h / kSamples), b = std::min(t1, t_lowest + h / kSamples), ra = 0, rb = 0;
      gap(a, row, &ra), gap(b, row, &rb);
      if (!(ra < 0.0 && rb > 0.0)) continue;
      while (b - a > t_tol) {
        const double mid = 0.5 * (a + b);
        double rate = 0.0;
        gap(mid, row, &rate);
        (rate < 0.0 ? a : b) = mid;
      }
      if (!(gap(b, row, nullptr) < 0.0)) continue;
      lo = std::max(t0, t_lowest - h / kSamples), hi = b;
    }
    // the crossing: g = 0 between lo (inside) and hi (beyond)
    while (hi - lo > t_tol) {
      const double mid = 0.5 * (lo + hi);
      (gap(mid, row, nullptr) > 0.0 ? lo : hi) = mid;
    }
    if (std::isnan(earliest) || hi < earliest - t_tol) {
      earliest = hi;
      rows.assign(1, int(c));
    } else if (hi <= earliest + t_tol) {
      rows.push_back(int(c));
    }
  }
  // a closed row's force dipping below 0 and back within the step (a
  // release shorter than the steps at rest: with the joints at rest the
  // state does not bound the step, a load's time function alone moves the
  // force; where nothing follows time, the force follows the state, which
  // the step resolves): the force at the step's ends and middle (one
  // acceleration solve; the ends' are the root functions' own), candidates
  // where the parabola through them or the cubic through them and the last
  // step's start, less their difference (the parabola's error), dips below
  // half the least of them, then the force on the interpolant (16 samples)
  // and the first crossing by bisection; the next step is bounded so that
  // the parabola's error estimate stays within a quarter of the margin
  // (step_bound())
  if (!d_.closed_rows().empty() && forces_follow_time_) {
    auto force = [&](double t, VecX& f) {
      at(t, q, v);
      const double* solved = lam ? lam(t, q, v) : nullptr;
      if (solved)
        lam_ = Eigen::Map<const VecX>(solved, model_.n_constraints());
      else
        solve_accelerations(model_, d_, kkt_, q, v, t, qdd_.data(), lam_.data());
      f = -lam_;
    };
    VecX &f0 = window_.force[1], &f1 = window_.force[2], &fm = window_.force[3];
    if (!(window_.force_t[1] == t0)) {
      window_.force_t[0] = NAN;
      if (window_.values_t_before == t0) f0 = window_.values_force_before;
      else force(t0, f0);
    }
    if (window_.values_t == t1) f1 = window_.values_force;
    else force(t1, f1);
    const double tm = t0 + 0.5 * h, ta = window_.force_t[0];
    force(tm, fm);
    const bool history = ta < t0;
    const double floor = 1e-6 * (1.0 + f1.lpNorm<Eigen::Infinity>());
    for (size_t c = 0; c < contacts_.size(); ++c) {
      const int row = contacts_[c].row;
      if (!contacts_[c].info.exists || !is_closed(row)) continue;
      const double fb = f0[row], fc = f1[row], fmid = fm[row];
      if (!(fb > 0.0 && fc > 0.0)) continue;  // (a crossing at an end is the root functions')
      bool dips = !(fmid > 0.0);
      const double margin = 0.5 * std::min({fb, fmid, fc});
      // Newton's divided differences over (t0, tm, t1) and, with history, ta
      const double d01 = (fmid - fb) / (tm - t0), d12 = (fc - fmid) / (t1 - tm), d012 = (d12 - d01) / (t1 - t0);
      const double fa = history ? window_.force[0][row] : 0.0;
      const double d3 = history ? (d012 - ((fb - fa) / (t0 - ta) - d01) / (ta - tm)) / (t1 - ta) : 0.0;
      // the next step: the parabola's error over a step h, at most
      // |d3| h^3 max|x (x - 1/2) (x - 1)| (x in [0, 1]), within a quarter of
      // the margin; and while the force moves, at most 4 times this step
      // (without history there is no d3: CVODE's second step at rest can be
      // 40 times its first)
      if (d3 != 0.0)
        window_.step_bound =
            std::min(window_.step_bound, t1 + std::cbrt(0.25 * std::max(margin, floor) / (0.0481 * std::abs(d3))));
      if (std::abs(fc - fb) + std::abs(fmid - fb) > floor)
        window_.step_bound = std::min(window_.step_bound, t1 + 4.0 * h);
      // (and at most to where that parabola, carried on, reaches 0: a cubic
      // term that looks small over the last steps can hide the turn of a
      // harmonic load, one step of 1.65 s stepped over a release)
      for (int i = 1; i <= 4 * kSamples; ++i) {
        const double s = t1 + 4.0 * h * i / (4.0 * kSamples);
        if (fb + (s - t0) * (d01 + (s - tm) * d012) <= 0.0) {
          window_.step_bound = std::min(window_.step_bound, s);
          break;
        }
      }
      for (int i = 1; i < 4 * kSamples && !dips; ++i) {
        const double s = t0 + h * i / (4.0 * kSamples);
        const double quadratic = fb + (s - t0) * (d01 + (s - tm) * d012);
        const double cubic = quadratic + d3 * (s - t0) * (s - tm) * (s - t1);
        dips = std::min(quadratic, cubic) - std::abs(cubic - quadratic) < margin;
      }
      if (!dips) continue;
      double lo = t0, hi = NAN;
      VecX& f = window_.force[4];
      for (int i = 1; i < kSamples && std::isnan(hi); ++i) {
        const double ti = t0 + h * i / kSamples;
        force(ti, f);
        (f[row] < 0.0 ? hi : lo) = ti;
      }
      if (std::isnan(hi)) continue;
      while (hi - lo > t_tol) {
        const double mid = 0.5 * (lo + hi);
        force(mid, f);
        (f[row] > 0.0 ? lo : hi) = mid;
      }
      if (std::isnan(earliest) || hi < earliest - t_tol) {
        earliest = hi;
        rows.assign(1, int(c));
      } else if (hi <= earliest + t_tol) {
        rows.push_back(int(c));
      }
    }
    window_.force_t[0] = t0, window_.force_t[1] = t1;
    window_.force[0].swap(window_.force[1]), window_.force[1].swap(window_.force[2]);
  }
  return earliest;
}

}  // namespace lagmb
