#include "integrators/events.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "integrators/integrators.hpp"
#include "lagmb/assembly/assembly.hpp"

namespace lagmb {

namespace {

std::string fmt(double x) { return to_text(x); }

IntegratorFailure plain_failure(const std::string& message, double t) {
  IntegratorFailure f(message, t);
  f.diagnose = false;
  return f;
}

}  // namespace

EventRunner::EventRunner(const Model& model, const Data& run, double position_tol)
    : model_(model),
      d_(model, &run),
      rows_(model, &run, Data::Rows::kEvery),
      kkt_(model),
      position_tol_(position_tol) {
  const auto& groups = model.event_groups();
  for (int gi = 0; gi < int(groups.size()); ++gi) {
    for (int k = 0; k < groups[gi]->size(); ++k) {
      if (groups[gi]->sweeps() && groups[gi]->roots(k) > 0)
        sweeps_.push_back({gi, k, int(roots_.size()), groups[gi]->roots(k)});
      for (int r = 0; r < groups[gi]->roots(k); ++r) {
        roots_.push_back({gi, k, r});
        dir_.push_back(groups[gi]->direction(k, r));
      }
    }
  }
  rows_.close_rows(model, model.unilateral_rows());
  const auto& constraints = model.constraint_groups();
  for (int gi = 0; gi < int(constraints.size()); ++gi) {
    if (!constraints[gi]->unilateral()) continue;
    unilateral_groups_.push_back(gi);
    for (int k = 0; k < constraints[gi]->size(); ++k)
      for (int r = 0; r < constraints[gi]->rows(k); ++r)
        contacts_.push_back({constraints[gi]->placement(k).row0 + r, constraints[gi]->unilateral_row(k, r)});
  }
  std::sort(contacts_.begin(), contacts_.end(), [](const Contact& a, const Contact& b) { return a.row < b.row; });
  // a gap crossing to negative (an impact), a force crossing to negative (a release)
  dir_.insert(dir_.end(), contacts_.size(), -1);
  // a contact's stick state: both ways (stick_root)
  sticks_base_ = dir_.size();
  for (int gi = 0; gi < int(constraints.size()); ++gi)
    if (constraints[gi]->sticks())
      for (int k = 0; k < constraints[gi]->size(); ++k) {
        // (its points' event functions: the event element of the same name)
        Stick s{gi, k, constraints[gi]->placement(k).row0, 0, 0};
        for (size_t i = 0; i < roots_.size(); ++i) {
          const EventGroupBase& group = *groups[roots_[i].group];
          if (group.name(roots_[i].element) != constraints[gi]->name(k)) continue;
          if (s.roots == 0) s.root0 = int(i);
          ++s.roots;
        }
        sticks_.push_back(s);
      }
  dir_.insert(dir_.end(), sticks_.size(), 0);
  g_.resize(dir_.size());
  qdd_.resize(model.n_coordinates());
  lam_.resize(model.n_constraints());
}

bool EventRunner::left(int row) const { return std::find(left_.begin(), left_.end(), row) != left_.end(); }

bool EventRunner::rebounding(int row) const {
  return std::find(rebounded_.begin(), rebounded_.end(), row) != rebounded_.end();
}

bool EventRunner::is_closed(int row) const {
  return std::binary_search(d_.closed_rows().begin(), d_.closed_rows().end(), row);
}

void EventRunner::values(double t, const double* q, const double* v, double* g) {
  ++root_evals;
  int offset = 0;
  for (const auto& group : model_.event_groups()) {
    group->values(q, v, t, g + offset);
    for (int k = 0; k < group->size(); ++k) offset += group->roots(k);
  }
  // (a crossing acted on reads on its new side until a step's end finds it
  // there, unless it goes back further than 10 times the restart put it
  // from 0: consistent())
  for (const Pin& p : pins_)
    if ((g[p.root] > 0.0) != (p.side > 0) && std::abs(g[p.root]) <= p.within) g[p.root] = p.side * 1e-300;
  if (contacts_.empty() && sticks_.empty()) return;
  if (!d_.closed_rows().empty()) {
    solve_accelerations(model_, d_, kkt_, q, v, t, qdd_.data(), lam_.data());
    values_t_ = t, values_f_ = -lam_;  // (a step's end's: grazed() reads them)
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
  bool rates = false;
  for (const Contact& c : contacts_)
    if (c.info.exists && !is_closed(c.row) && std::abs(rows_.Phi[c.row]) <= at_limit) rates = true;
  double at_rest = 0.0;
  if (rates) {
    for (int gi : unilateral_groups_) model_.constraint_groups()[gi]->jacobian(q, at, rows_.Phi_q.valuePtr());
    rows_.phi_t.setZero();  // (scratch: Phi_q v of the gaps)
    add_jacobian_times(rows_, v, rows_.phi_t.data());
    at_rest = 1e-9 * (1.0 + Eigen::Map<const VecX>(v, model_.n_coordinates()).lpNorm<Eigen::Infinity>());
  }
  for (const Contact& c : contacts_) {
    double x = !c.info.exists ? 1.0 : is_closed(c.row) ? -lam_[c.row] : rows_.Phi[c.row];
    if (rates && !is_closed(c.row) && c.info.exists && std::abs(x) <= at_limit)
      x = rows_.phi_t[c.row] >= -at_rest || (left(c.row) && (t == restart_t_ || !rebounding(c.row))) ? at_limit : x;
    g[offset++] = x != 0.0 ? x : -1e-300;
  }
}

bool EventRunner::start(double t, const VecX& q, VecX& v) { return settle(t, q, v, true); }

void EventRunner::check_on_constraints(double t, const VecX& q) {
  assemble_constraints(model_, d_, q.data(), t);
  if (d_.Phi.size() == 0) return;
  Eigen::Index row = 0;
  const double off = d_.Phi.cwiseAbs().maxCoeff(&row);
  const double limit = 1e-2 * (1.0 + q.lpNorm<Eigen::Infinity>());
  if (off <= limit) return;
  throw plain_failure("the constraints had come apart before the event at t = " + fmt(t) + ": |Phi| = " + fmt(off) +
                          " at '" + model_.constraint_name_of_row(int(row)) + "' (more than 1e-2 (1 + |q|) = " +
                          fmt(limit) +
                          "): the steps before it had lost the motion, and a restart would hide that. The methods "
                          "that hold the constraints only through their second derivatives (index1, "
                          "projection-adams) drift; use one that keeps them (ggl, projection-bdf, projection-erk), "
                          "a smaller rtol, or baumgarte=(alpha, beta)",
                      t);
}

bool EventRunner::settle(double t, const VecX& q, VecX& v, bool at_start) {
  if (!at_start) check_on_constraints(t, q);
  step_end_t_ = sweep_t_ = force_t_[0] = force_t_[1] = values_t_ = NAN, step_bound_ = INFINITY;  // (a new start, or the equations jump here)
  values(t, q.data(), v.data(), g_.data());
  std::vector<int> fired(g_.size(), 0);
  bool any = false, beyond = false;
  const double tol = 1e-9 * (1.0 + q.lpNorm<Eigen::Infinity>());
  const double force_tol = 1e-8 * (1.0 + lam_.lpNorm<Eigen::Infinity>());
  const size_t base = roots_.size();
  for (size_t i = 0; i < g_.size(); ++i) {
    if (dir_[i] >= 0) continue;
    const bool contact = i >= base;
    if (!contact && !at_start) continue;  // (an event element's switch waits for its crossing)
    const bool closed = contact && is_closed(contacts_[i - base].row);
    // a stop at its limit is in contact; a closed one whose force turned to pull lets go
    if (!(g_[i] < (closed ? force_tol : contact ? tol : 0.0))) continue;
    if (at_start && !closed && g_[i] < -tol) {
      std::string kind, name, label;
      if (contact) {
        const Contact& c = contacts_[i - base];
        name = model_.constraint_name_of_row(c.row);
        kind = model_.constraint_groups()[model_.find(name).group]->kind();
        label = c.info.label;
      } else {
        auto& group = *model_.event_groups()[roots_[i].group];
        kind = group.kind(), name = group.name(roots_[i].element), label = roots_[i].index == 0 ? "lower" : "upper";
      }
      throw ModelError(kind + " '" + name + "': the initial configuration is beyond its " + label + " limit (by " +
                       fmt(-g_[i]) + ")");
    }
    // (a jump of the equations, a driver's new value, can put a joint beyond a limit: consistent() puts it back)
    if (contact && !closed && g_[i] < -tol) beyond = true;
    fired[i] = -1;
    any = true;
  }
  const VecX v0 = v;
  const std::vector<int> closed0 = d_.closed_rows();
  handled_ = fired;  // (what consistent() then pins)
  if (any) handle_stops(t, q, v, fired);
  if (!sticks_.empty()) handle_sticks(t, q, v, fired);
  return v != v0 || d_.closed_rows() != closed0 || beyond;
}

bool EventRunner::missed(double t, const double* q, const double* v, std::vector<int>& fired) {
  values(t, q, v, g_.data());
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
  late_ = any;
  return any;
}

double EventRunner::grazed(double t0, double t1, const Interpolant& at, std::vector<int>& fired) {
  step_bound_ = INFINITY;
  if (!(t1 > t0)) return NAN;
  if (!pins_.empty()) {  // (a pinned function that a step's end finds on its new side is free again)
    const double *q = nullptr, *v = nullptr;
    at(t1, q, v);
    std::vector<double> g(g_.size());
    const std::vector<Pin> pins = pins_;
    pins_.clear();
    values(t1, q, v, g.data());
    for (const Pin& p : pins)
      if ((g[size_t(p.root)] > 0.0) != (p.side > 0)) pins_.push_back(p);
  }
  std::vector<int> roots, rows;
  const double passed = passed_through(t0, t1, at, roots);
  const double grazing = contacts_.empty() ? NAN : grazed_stops(t0, t1, at, rows);
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
  if (!(sweep_t_ == t0)) {
    at(t0, q, v);
    sweep_q_ = Eigen::Map<const VecX>(q, n);
  }
  const VecX q0 = sweep_q_;
  at(t1, q, v);
  sweep_q_ = Eigen::Map<const VecX>(q, n), sweep_t_ = t1;
  const VecX& q1 = sweep_q_;
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

double EventRunner::grazed_stops(double t0, double t1, const Interpolant& at, std::vector<int>& rows) {
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
  if (!(step_end_t_ == t0)) {
    at(t0, q, v);
    gaps(t0, Eigen::Map<const VecX>(q, n), Eigen::Map<const VecX>(v, n));
    step_end_g_ = rows_.Phi, step_end_r_ = rows_.phi_t;
  }
  at(t1, q, v);
  gaps(t1, Eigen::Map<const VecX>(q, n), Eigen::Map<const VecX>(v, n));
  step_start_g_.swap(step_end_g_), step_start_r_.swap(step_end_r_);  // (buffers kept from step to step)
  step_end_g_ = rows_.Phi, step_end_r_ = rows_.phi_t, step_end_t_ = t1;
  left_.erase(std::remove_if(left_.begin(), left_.end(), [&](int row) { return step_end_g_[row] > 1e-10; }),
              left_.end());
  const VecX &g0 = step_start_g_, &r0 = step_start_r_, &g1 = step_end_g_, &r1 = step_end_r_;
  const double h = t1 - t0, t_tol = 1e-14 * (std::abs(t1) + h);
  constexpr int kSamples = 16;
  double earliest = NAN;
  for (size_t c = 0; c < contacts_.size(); ++c) {
    const int row = contacts_[c].row;
    if (!contacts_[c].info.exists || is_closed(row)) continue;
    // (a row starts on its limit after a restart: its gap 0 to rounding)
    if (!(g0[row] > -1e-10 && g1[row] > 0.0)) continue;
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
  // force): the force at the step's ends and middle (one acceleration solve;
  // the end's is the root functions' own), candidates where the parabola
  // through them or the cubic through them and the last step's start, less
  // their difference (the parabola's error), dips below half the least of
  // them, then the force on the interpolant (16 samples) and the first
  // crossing by bisection; the next step is bounded so that the parabola's
  // error estimate stays within a quarter of the margin (step_bound())
  if (!d_.closed_rows().empty()) {
    auto force = [&](double t, VecX& f) {
      at(t, q, v);
      solve_accelerations(model_, d_, kkt_, q, v, t, qdd_.data(), lam_.data());
      f = -lam_;
    };
    VecX &f0 = force_f_[1], &f1 = force_f_[2], &fm = force_f_[3];
    if (!(force_t_[1] == t0)) force(t0, f0), force_t_[0] = NAN;
    if (values_t_ == t1) f1 = values_f_;
    else force(t1, f1);
    const double tm = t0 + 0.5 * h, ta = force_t_[0];
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
      const double d3 = history ? (d012 - ((fb - force_f_[0][row]) / (t0 - ta) - d01) / (ta - tm)) / (t1 - ta) : 0.0;
      // the next step: the parabola's error over a step h, at most
      // |d3| h^3 max|x (x - 1/2) (x - 1)| (x in [0, 1]), within a quarter of
      // the margin; and while the force moves, at most 4 times this step
      // (without history there is no d3: CVODE's second step at rest can be
      // 40 times its first)
      if (d3 != 0.0)
        step_bound_ = std::min(step_bound_, t1 + std::cbrt(0.25 * std::max(margin, floor) / (0.0481 * std::abs(d3))));
      if (std::abs(fc - fb) + std::abs(fmid - fb) > floor) step_bound_ = std::min(step_bound_, t1 + 4.0 * h);
      // (and at most to where that parabola, carried on, reaches 0: a cubic
      // term that looks small over the last steps can hide the turn of a
      // harmonic load, one step of 1.65 s stepped over a release)
      for (int i = 1; i <= 4 * kSamples; ++i) {
        const double s = t1 + 4.0 * h * i / (4.0 * kSamples);
        if (fb + (s - t0) * (d01 + (s - tm) * d012) <= 0.0) {
          step_bound_ = std::min(step_bound_, s);
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
      VecX& f = force_f_[4];
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
    force_t_[0] = t0, force_t_[1] = t1;
    force_f_[0].swap(force_f_[1]), force_f_[1].swap(force_f_[2]);
  }
  return earliest;
}

void EventRunner::count_event(double t, const std::string& element, const char* kind) {
  ++events;
  // Zeno guard: events piling up at (almost) one instant must not hang the run
  burst_ = (t - t_last_ <= 1e-9 * (1.0 + std::abs(t))) ? burst_ + 1 : 0;
  t_last_ = t;
  if (burst_ >= 1000)
    throw plain_failure(std::string(kind) + " '" + element + "': 1000 events in a row at t = " + fmt(t) +
                            " without the time advancing (events accumulating: Zeno behaviour); the run stops here.",
                        t);
}

void EventRunner::contact_rows(double t, const VecX& q, const VecX& v, const std::vector<int>& which,
                               std::vector<VecX>& C, VecX& curvature) {
  assemble_jacobian(model_, rows_, q.data(), t);
  assemble_gamma(model_, rows_, q.data(), v.data(), t);
  const SpMat JT = rows_.Phi_q.transpose();  // column r: row r of Phi_q
  C.clear();
  curvature.resize(int(which.size()));
  for (size_t j = 0; j < which.size(); ++j) {
    const int row = contacts_[which[j]].row;
    C.push_back(VecX(JT.col(row)));
    curvature[int(j)] = rows_.gamma[row];
  }
}

void EventRunner::driven_through(int contact, double t, double approach, double tolerance, const char* measure) {
  const int row = contacts_[contact].row;
  const std::string stop = model_.constraint_name_of_row(row);
  // What leaves the stop's gap no motion: its gradient C (rows_.Phi_q, at
  // this q: contact_rows) is a combination of the rows held (the joints,
  // the closed rows of d_, which kkt_ holds factorized), C = Phi_q^T y with
  // M x = C - Phi_q^T y ~ 0; the stops, couplings and drivers with a part
  // in y are the ones to name
  const VecX C = VecX(rows_.Phi_q.transpose().col(row));
  VecX x(model_.n_coordinates()), y(model_.n_constraints());
  kkt_.solve(C, VecX::Zero(model_.n_constraints()), x, y);
  const double y_max = y.lpNorm<Eigen::Infinity>();
  std::vector<std::string> stops, ties;
  for (int r = 0; r < y.size(); ++r) {
    if (!(std::abs(y[r]) > 1e-6 * y_max) || r == row) continue;
    const ConstraintGroupBase& group = *model_.constraint_groups()[model_.group_of_row(r)];
    if (!group.unilateral() && !group.ties_motion()) continue;  // (a joint's rows: the part of C the joints carry)
    const std::string name = model_.constraint_name_of_row(r);
    const std::string text = "'" + name + "' (" + model_.describe(name) + ")";
    std::vector<std::string>& into = group.unilateral() ? stops : ties;
    if (std::find(into.begin(), into.end(), text) == into.end()) into.push_back(text);
  }
  const auto listed = [](const std::vector<std::string>& items) {
    std::string out;
    for (size_t k = 0; k < items.size(); ++k) out += (k == 0 ? "" : k + 1 == items.size() ? " and " : ", ") + items[k];
    return out;
  };
  const std::string moving = "its gap's " + std::string(measure) + " is " + fmt(approach) + " (beyond " +
                             fmt(tolerance) + ")";
  std::string what;
  if (!stops.empty())  // (a closed stop and a coupling allow the gap no rate: only drift gives it one)
    what = "its joint is held by " + listed(stops) +
           (ties.empty() ? "" : ", to which " + listed(ties) + (ties.size() == 1 ? " ties" : " tie") + " it") +
           ": both joints are at their limits, and this one cannot move along its limit apart. Yet " + moving +
           ", which the held rows do not allow: the motion has drifted off them by that much (a violent motion, "
           "such as an unstable controller's, outrunning the run's tolerances)";
  else if (!ties.empty())
    what = listed(ties) + (ties.size() == 1 ? " prescribes" : " prescribe") + " the motion along it and drive" +
           (ties.size() == 1 ? "s" : "") + " the joint through the limit: " + moving;
  else
    what = "the joints leave no motion along it (a singular position, such as a gimbal lock of three revolutes), "
           "and " + moving;
  throw plain_failure("stop '" + stop + "' is reached at t = " + fmt(t) + " where " + what + ". No impact or stop "
                          "force can act along a motion that is held: the run stops here.",
                      t);
}

void EventRunner::impulse(double t, const VecX& q, VecX& v, const std::vector<int>& which,
                          const std::vector<VecX>& C, VecX& e, std::vector<char>& held) {
  // M-orthogonal jump keeping the joints and the closed stops: v+ = v- + X p with
  // [M Phi_q^T; Phi_q 0] [X; Y] = [C^T; 0] and C v+ = -E C v-
  const int n = model_.n_coordinates(), m = model_.n_constraints(), k = int(which.size());
  assemble_jacobian(model_, d_, q.data(), t);
  if (!kkt_.factorize(d_)) throw plain_failure("the augmented matrix is singular at an impact, t = " + fmt(t), t);
  Eigen::MatrixXd X(n, k), A(k, k);
  VecX x(n), y(m), zero_m = VecX::Zero(m), b(k);
  for (int j = 0; j < k; ++j) {
    kkt_.solve(C[j], zero_m, x, y);
    X.col(j) = x;
  }
  held.assign(size_t(k), 0);
  const double drift = 1e-6 * (1.0 + v.lpNorm<Eigen::Infinity>());
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) A(i, j) = C[i].dot(X.col(j));
    b[i] = -(1.0 + e[i]) * C[i].dot(v);
    // A(i, i) is the mobility along the limit the joints leave; next to the
    // free body's C M^-1 C^T it is 0 where drivers prescribe that motion,
    // or where the closed rows hold it (a mimic finger whose leader rests on
    // its stop, approaching only by the velocity constraints' drift): such
    // a row takes no impulse
    if (!(A(i, i) > 1e-10 * C[i].dot(d_.M_inv * C[i]))) {
      if (!(std::abs(C[i].dot(v)) <= drift)) driven_through(which[i], t, C[i].dot(v), drift, "rate");
      held[size_t(i)] = 1;
    }
  }
  for (int i = 0; i < k; ++i)
    if (held[size_t(i)]) A.row(i).setZero(), A.col(i).setZero(), A(i, i) = 1.0, b[i] = 0.0;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  lu.setThreshold(1e-9);
  if (lu.rank() < k && e.any()) {
    // dependent rows (a loop's stops, one motion striking both): their
    // rebounds -e g'- cannot all hold; the impact is plastic, g'+ = 0 for
    // each, which they can (no energy from an inconsistent target)
    e.setZero();
    for (int i = 0; i < k; ++i) b[i] = held[size_t(i)] ? 0.0 : -C[i].dot(v);
  }
  v += X * lu.solve(b);
}

std::vector<int> EventRunner::rest_contacts(double t, const VecX& q, const VecX& v, const std::vector<int>& which,
                                            const std::vector<int>& leaving) {
  const int n = model_.n_coordinates(), m = model_.n_constraints(), k = int(which.size());
  std::vector<VecX> C;
  VecX curvature;
  contact_rows(t, q, v, which, C, curvature);
  // every candidate open, the other closed rows held: b = g'' without their forces
  std::vector<int> held;
  for (int row : d_.closed_rows())
    if (std::none_of(which.begin(), which.end(), [&](int c) { return contacts_[c].row == row; })) held.push_back(row);
  d_.close_rows(model_, held);
  solve_accelerations(model_, d_, kkt_, q.data(), v.data(), t, qdd_.data(), lam_.data());
  // a force f_j >= 0 along the gradient C_j (f_j = -lam_j) adds X_j f_j to qdd: g'' = b + A f
  Eigen::MatrixXd A(k, k), X(n, k);
  VecX b(k), x(n), y(m), zero_m = VecX::Zero(m);
  for (int j = 0; j < k; ++j) {
    b[j] = C[j].dot(qdd_) - curvature[j];
    kkt_.solve(C[j], zero_m, x, y);
    X.col(j) = x;
  }
  // (tolerances in acceleration units)
  const double tol = 1e-9 * (1.0 + b.lpNorm<Eigen::Infinity>());
  std::vector<char> in(k, 0), may_close(k, 1), is_leaving(k, 0);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) A(i, j) = C[i].dot(X.col(j));
    is_leaving[i] = std::find(leaving.begin(), leaving.end(), which[i]) != leaving.end();
    // a motion the drivers prescribe, or the closed rows hold (a mimic
    // finger whose leader rests on its own stop: its g'' is 0 to rounding)
    if (!(A(i, i) > 1e-10 * C[i].dot(d_.M_inv * C[i]))) {
      if (b[i] < -tol) driven_through(which[i], t, b[i], tol, "acceleration");
      may_close[i] = 0;
    }
  }
  // principal pivoting with the least-index rule (Murty 1974), from "all
  // open": it ends for the P-matrices of independent stops, and of stops that
  // depend on each other (a mimic coupling's two fingers on their limits) it
  // closes the first that is needed only: the others' gaps follow it (their
  // g'' = 0), so the closed rows never become dependent. Tolerances in
  // acceleration units; a released row opens at a force within rounding of 0
  VecX f = VecX::Zero(k), w = b;
  for (int iteration = 0;; ++iteration) {
    if (iteration > 50 + 4 * k * k)
      throw plain_failure("the stop forces at t = " + fmt(t) + " could not be resolved: the pivoting over " +
                              std::to_string(k) + " stops in contact did not end (dependent stops?)",
                          t);
    std::vector<int> S;
    for (int i = 0; i < k; ++i)
      if (in[i]) S.push_back(i);
    f.setZero();
    if (!S.empty()) {
      Eigen::MatrixXd A_SS(S.size(), S.size());
      VecX b_S(S.size());
      for (size_t a = 0; a < S.size(); ++a) {
        b_S[a] = -b[S[a]];
        for (size_t c = 0; c < S.size(); ++c) A_SS(a, c) = A(S[a], S[c]);
      }
      const VecX f_S = A_SS.fullPivLu().solve(b_S);
      for (size_t a = 0; a < S.size(); ++a) f[S[a]] = f_S[a];
    }
    w = b + A * f;
    int flip = -1;
    for (int i = 0; i < k && flip < 0; ++i) {
      if (in[i] && f[i] * A(i, i) < (is_leaving[i] ? tol : -tol)) flip = i;
      if (!in[i] && may_close[i] && w[i] < -2.0 * tol) flip = i;
    }
    if (flip < 0) break;
    in[flip] = !in[flip];
  }
  std::vector<int> closed = held;
  for (int i = 0; i < k; ++i)
    if (in[i]) closed.push_back(contacts_[which[i]].row);
  std::sort(closed.begin(), closed.end());
  return closed;
}

bool EventRunner::handle(double t, const VecX& q, VecX& v, const std::vector<int>& fired) {
  check_on_constraints(t, q);
  handled_ = fired;
  const bool restart = handle_stops(t, q, v, fired);
  if (sticks_.empty()) return restart;
  return handle_sticks(t, q, v, fired) || restart;
}

bool EventRunner::handle_sticks(double t, const VecX& q, const VecX& v, const std::vector<int>& fired) {
  step_end_t_ = sweep_t_ = force_t_[0] = force_t_[1] = values_t_ = NAN, step_bound_ = INFINITY;
  double* run = d_.run->state.data();
  const Instant at = d_.at(t);
  if (!d_.closed_rows().empty()) solve_accelerations(model_, d_, kkt_, q.data(), v.data(), t, qdd_.data(), lam_.data());
  const double force_tol = 1e-8 * (1.0 + lam_.lpNorm<Eigen::Infinity>());
  bool changed = false;
  std::vector<int> release;
  for (size_t j = 0; j < sticks_.size(); ++j) {
    const Stick& s = sticks_[j];
    const ConstraintGroupBase& g = *model_.constraint_groups()[s.group];
    const int state = g.stick_state(s.element, run);
    const double x = g.stick_root(s.element, q.data(), v.data(), at, lam_.data());
    if (state == 1) {  // stuck: released where the friction it holds passes its limit (or nothing presses)
      if (x < -force_tol || fired[sticks_base_ + j]) {
        release.push_back(int(j));
      } else if (std::any_of(fired.begin() + s.root0, fired.begin() + s.root0 + s.roots, [](int f) { return f != 0; })) {
        // a point pressing or letting go: held again at the vertices pressing now (rocking
        // from one edge onto another, the old edge's anchor would drag the new one)
        g.stick_hold(s.element, q.data(), v.data(), run);
        changed = true;
      }
    } else if (state == -1) {  // disarmed: armed once it slips faster than 2 v_s
      if (x > 0.0) g.stick_set(s.element, run, 0);
    }
  }
  if (!release.empty()) {
    std::vector<int> closed = d_.closed_rows();
    for (int j : release) {
      const Stick& s = sticks_[size_t(j)];
      const ConstraintGroupBase& g = *model_.constraint_groups()[s.group];
      for (int r = 0; r < g.rows(s.element); ++r) closed.erase(std::remove(closed.begin(), closed.end(), s.row0 + r), closed.end());
      g.stick_set(s.element, run, -1);
      const std::string name = g.name(s.element);
      count_event(t, name, "contact");
      records.push_back({t, name, "friction", "slip", 0.0, 0.0});
    }
    d_.close_rows(model_, closed);
    changed = true;
  }
  // the armed contacts slipping slower than v_s stick, one at a time (each
  // with the ones stuck before it), where the friction then needed holds
  for (size_t j = 0; j < sticks_.size(); ++j) {
    const Stick& s = sticks_[j];
    const ConstraintGroupBase& g = *model_.constraint_groups()[s.group];
    if (g.stick_state(s.element, run) != 0) continue;
    if (!(g.stick_root(s.element, q.data(), v.data(), at, lam_.data()) < 0.0)) continue;
    const std::vector<int> before = d_.closed_rows();
    if (!g.stick_hold(s.element, q.data(), v.data(), run)) continue;
    std::vector<int> closed = before;
    for (int r = 0; r < g.rows(s.element); ++r) closed.push_back(s.row0 + r);
    std::sort(closed.begin(), closed.end());
    d_.close_rows(model_, closed);
    bool holds = false;
    try {
      const ConsistentState held = make_consistent(model_, d_, kkt_, q, v, t);
      holds = g.stick_root(s.element, held.q.data(), held.v.data(), at, held.lam.data()) >= 0.0;
    } catch (const SimulationError&) {
      holds = false;  // (rows that would depend on the ones holding the body already: it slips)
    }
    if (!holds) {
      d_.close_rows(model_, before);
      g.stick_set(s.element, run, -1);
      continue;
    }
    const std::string name = g.name(s.element);
    count_event(t, name, "contact");
    records.push_back({t, name, "friction", "stick", 0.0, 0.0});
    changed = true;
  }
  return changed;
}

bool EventRunner::handle_stops(double t, const VecX& q, VecX& v, const std::vector<int>& fired) {
  bool restart = false;
  step_end_t_ = sweep_t_ = force_t_[0] = force_t_[1] = values_t_ = NAN, step_bound_ = INFINITY;  // (the state may jump here)
  on_limit_.clear();
  released_.clear();
  const bool late = late_;
  late_ = false;
  const std::vector<int> rebounded = rebounded_;  // (of the last event that acted, and their speeds)
  const std::vector<double> rebound_speed = rebound_speed_;
  const double rebound_t = rebound_t_;
  std::vector<int> rebounding;
  for (size_t i = 0; i < roots_.size(); ++i) {
    if (!fired[i]) continue;
    auto& group = *model_.event_groups()[roots_[i].group];
    // (fired[i]: the way it crossed, -1 or +1, as SUNDIALS' root info)
    const EventAction a =
        group.crossing(roots_[i].element, roots_[i].index, q.data(), v.data(), t, d_.run->state.data(), fired[i]);
    if (a.type == EventAction::kNone) continue;
    count_event(t, group.name(roots_[i].element), group.kind());
    restart = true;
    records.push_back({t, group.name(roots_[i].element), "restart", a.label, a.speed, a.speed});
  }
  if (contacts_.empty()) return restart;

  // the stops' crossings: gaps closing (impacts, or a joint arriving at rest) and forces turning to pull
  std::vector<int> arriving, leaving;
  for (size_t c = 0; c < contacts_.size(); ++c)
    if (fired[roots_.size() + c] && contacts_[c].info.exists)
      (is_closed(contacts_[c].row) ? leaving : arriving).push_back(int(c));
  if (arriving.empty() && leaving.empty()) return restart;
  for (int c : arriving) on_limit_.push_back(contacts_[c].row);
  for (int c : leaving) on_limit_.push_back(contacts_[c].row);
  std::vector<VecX> C;
  VecX curvature;
  contact_rows(t, q, v, arriving, C, curvature);
  const double v_scale = 1e-9 * (1.0 + v.lpNorm<Eigen::Infinity>());
  std::vector<int> hit, resting;
  std::vector<VecX> C_hit;
  for (size_t j = 0; j < arriving.size(); ++j) {
    const double s = C[j].dot(v);  // g'
    if (s < -v_scale) {
      hit.push_back(arriving[j]);
      C_hit.push_back(C[j]);
    } else if (s <= v_scale) {
      resting.push_back(arriving[j]);
    }
  }
  const std::vector<int> closed_before = d_.closed_rows();
  std::vector<int> captured;
  std::vector<char> held;  // (of the hit rows: the closed rows hold them)
  const VecX v_before = v;
  // the open stops at their limits (within rounding of the positions) that
  // the velocities v move into them, other than those hit, joined to the
  // impact: their rows, and their limits held at the restart
  auto join_approaching = [&](const VecX& velocities) {
    std::vector<int> at_limit;
    gaps(t, q, velocities);
    const double near = 1e-9 * (1.0 + q.lpNorm<Eigen::Infinity>());
    for (size_t c = 0; c < contacts_.size(); ++c)
      if (contacts_[c].info.exists && !is_closed(contacts_[c].row) && rows_.Phi[contacts_[c].row] <= near &&
          rows_.phi_t[contacts_[c].row] < -v_scale && std::find(hit.begin(), hit.end(), int(c)) == hit.end())
        at_limit.push_back(int(c));
    std::vector<VecX> C_more;
    VecX unused;
    if (!at_limit.empty()) contact_rows(t, q, velocities, at_limit, C_more, unused);
    for (size_t j = 0; j < at_limit.size(); ++j) {
      hit.push_back(at_limit[j]), C_hit.push_back(C_more[j]);
      on_limit_.push_back(contacts_[at_limit[j]].row);
    }
    return !at_limit.empty();
  };
  // stops struck at the same instant, the root functions having flagged
  // some (two pendulums falling onto their own stops, their limits 1e-9 rad
  // apart): each strikes with its own restitution; impulse() makes plastic
  // only rows that depend on each other
  if (!hit.empty()) join_approaching(v_before);
  VecX e(int(hit.size()));
  if (!hit.empty()) {
    for (size_t j = 0; j < hit.size(); ++j) e[int(j)] = contacts_[hit[j]].info.restitution;
    impulse(t, q, v, hit, C_hit, e, held);
    // an impact passes its impulse through the joints: another stop at its
    // limit (an adjacent joint, a coupled finger) that it drives into its
    // limit takes part in it, so that no joint leaves an impact moving
    // beyond a limit; the impact is then plastic
    while (join_approaching(v)) {
      // (plastic for all: Newton's law at several contacts coupled through
      // the joints can give energy; the M-orthogonal jump onto g' = 0 for
      // each cannot)
      e.setZero(int(hit.size()));
      v = v_before;
      impulse(t, q, v, hit, C_hit, e, held);
    }
    // a row the closed rows hold took no impulse: it has no impact
    for (size_t j = hit.size(); j-- > 0;)
      if (held[j]) {
        hit.erase(hit.begin() + long(j)), C_hit.erase(C_hit.begin() + long(j));
        e.segment(long(j), e.size() - long(j) - 1) = e.tail(e.size() - long(j) - 1).eval();
        e.conservativeResize(e.size() - 1);
      }
  }
  if (!hit.empty()) {
    const int k = int(hit.size());
    VecX s0(k);
    for (int j = 0; j < k; ++j) s0[j] = C_hit[j].dot(v_before);
    impacts += k;
    // a rebound ends on the limit (captured) when e = 0, when it is slower
    // than rest_speed (or than what reads as at rest: 1e-9 (1 + |v|)), or
    // when the motion presses on the limit (g'' < 0 with the row open) and
    // the remaining bounces, flights of 2 s1 / |g''| shrinking by e each,
    // add up to less than capture_time
    solve_accelerations(model_, d_, kkt_, q.data(), v.data(), t, qdd_.data(), lam_.data());
    std::vector<VecX> C_after;
    VecX curvature_after;  // gamma_r at the rebound velocity
    contact_rows(t, q, v, hit, C_after, curvature_after);
    bool redo = false;
    for (int j = 0; j < k; ++j) {
      const UnilateralRow& info = contacts_[hit[j]].info;
      const double s1 = C_hit[j].dot(v);
      const double g_dd = C_hit[j].dot(qdd_) - curvature_after[j];
      // (a rebound slower than the speed that reads as at rest: an impact
      // at that speed is a joint pressed on its limit from rest, found where
      // its approach passed that speed; a rebound would return at once)
      const bool slow = s1 < v_scale || (info.rest_speed > 0.0 && s1 < info.rest_speed);
      const bool short_series = g_dd < 0.0 && 2.0 * s1 < info.capture_time * (1.0 - e[j]) * -g_dd;
      // a rebound from the event this segment started at whose return the
      // integrator found only at a step's end (its first step, at order 1,
      // longer than the flight): the steps cannot resolve the series that
      // is left, and each late return would strike faster than the last
      // rebound, a chatter that never ends; it ends here
      // (or one that returns faster than it left, by a fifth, from a flight
      // lower than the positions are accurate, s1^2 / 2|g''| with g'' its
      // mean over the flight: the steps did not resolve it, and each return
      // would strike as fast as the impact before, 1/e times the rebound)
      const auto was = std::find(rebounded.begin(), rebounded.end(), contacts_[hit[j]].row);
      bool unresolved = false;
      if (was != rebounded.end()) {
        const double s1 = rebound_speed[size_t(was - rebounded.begin())], flight = t - rebound_t;
        const double mean_g_dd = flight > 0.0 ? (s0[j] - s1) / flight : 0.0;
        const bool low = mean_g_dd < 0.0 && s1 * s1 < 2.0 * -mean_g_dd * position_tol_;
        unresolved = late || (-s0[j] > 1.2 * s1 && low);
      }
      if (e[j] == 0.0 || slow || short_series || unresolved) {
        captured.push_back(hit[j]);
        if (e[j] != 0.0) redo = true;
        e[j] = 0.0;
      }
    }
    if (redo) {  // the captured ones plastic: no rebound
      v = v_before;
      impulse(t, q, v, hit, C_hit, e, held);
    }
    rebound_speed_.clear();
    for (int j = 0; j < k; ++j)
      if (e[j] > 0.0) rebounding.push_back(contacts_[hit[j]].row), rebound_speed_.push_back(C_hit[j].dot(v));
    rebounded_ = rebounding, rebound_t_ = t;
    for (int j = 0; j < k; ++j) {
      const std::string name = model_.constraint_name_of_row(contacts_[hit[j]].row);
      count_event(t, name, "stop");
      records.push_back({t, name, "impact", contacts_[hit[j]].info.label, s0[j], C_hit[j].dot(v)});
    }
    restart = true;
  }
  if (captured.empty() && resting.empty() && leaving.empty()) return restart;

  // the active set among the stops at rest on their limits: those closed,
  // captured now, or arriving at rest
  std::vector<int> candidates = leaving;
  for (size_t c = 0; c < contacts_.size(); ++c)
    if (is_closed(contacts_[c].row) && std::find(leaving.begin(), leaving.end(), int(c)) == leaving.end())
      candidates.push_back(int(c));
  candidates.insert(candidates.end(), captured.begin(), captured.end());
  candidates.insert(candidates.end(), resting.begin(), resting.end());
  std::sort(candidates.begin(), candidates.end());
  const std::vector<int> closed = rest_contacts(t, q, v, candidates, leaving);
  d_.close_rows(model_, closed);
  for (int c : candidates) {
    const int row = contacts_[c].row;
    const bool was = std::binary_search(closed_before.begin(), closed_before.end(), row);
    const bool now = std::binary_search(closed.begin(), closed.end(), row);
    if (was == now) continue;
    if (!now) on_limit_.push_back(row), released_.push_back(row);  // (on its limit, at rest: see consistent())
    const std::string name = model_.constraint_name_of_row(row);
    count_event(t, name, "stop");
    records.push_back({t, name, now ? "capture" : "release", contacts_[c].info.label, 0.0, 0.0});
    ++(now ? captures : releases);
  }
  if (hit.empty() && closed != closed_before) rebounded_.clear(), rebound_speed_.clear();
  return restart || closed != closed_before;
}

void EventRunner::gaps(double t, const VecX& q, const VecX& v) {
  const Instant at = rows_.at(t);
  for (int gi : unilateral_groups_) {
    model_.constraint_groups()[gi]->phi(q.data(), at, rows_.Phi.data());
    model_.constraint_groups()[gi]->jacobian(q.data(), at, rows_.Phi_q.valuePtr());
  }
  rows_.phi_t.setZero();  // (scratch: Phi_q v of the gaps)
  add_jacobian_times(rows_, v.data(), rows_.phi_t.data());
}

ConsistentState EventRunner::consistent(double t, const VecX& q, const VecX& v) {
  ConsistentState state = restart_state(t, q, v);
  if (roots_.empty()) return state;
  // an event element's function that the restart's projection moved across
  // 0 (two corners crossing together, one found: the other put past its
  // crossing by rounding) crosses here: the steps from the restart would not see it
  const size_t n = roots_.size();
  std::vector<double> before(g_.size()), after(g_.size());
  pins_.clear();  // (the last restart's: these values are the functions' own)
  values(t, q.data(), v.data(), before.data());
  values(t, state.q.data(), state.v.data(), after.data());
  for (size_t i = 0; i < n; ++i) {
    if (i < handled_.size() && handled_[i]) {
      // crossed (handled_[i]: which way): pinned to its new side until a
      // step's end finds it there (the restart's projection, or the first
      // step's error, can put it back by rounding: found again, it would be
      // logged twice, or again and again at a point touching at rest)
      pins_.push_back({int(i), handled_[i] > 0 ? 1 : -1, 10.0 * std::abs(after[i])});
      continue;
    }
    if ((before[i] > 0.0) == (after[i] > 0.0)) continue;
    if (dir_[i] < 0 && !(after[i] < 0.0)) continue;  // (a function counting downward crossings only)
    auto& group = *model_.event_groups()[roots_[i].group];
    const EventAction a = group.crossing(roots_[i].element, roots_[i].index, state.q.data(), state.v.data(), t,
                                         d_.run->state.data(), after[i] > 0.0 ? 1 : -1);
    if (a.type == EventAction::kNone) continue;
    count_event(t, group.name(roots_[i].element), group.kind());
    records.push_back({t, group.name(roots_[i].element), "restart", a.label, a.speed, a.speed});
  }
  return state;
}

ConsistentState EventRunner::restart_state(double t, const VecX& q, const VecX& v) {
  step_end_t_ = sweep_t_ = force_t_[0] = force_t_[1] = values_t_ = NAN, step_bound_ = INFINITY;
  // the state at a root is interpolated: put the positions back on Phi = 0
  // (least change; the closed stops' rows included) and the velocities on
  // Phi_q v + Phi_t = 0 before the index-2 and index-3 forms restart from it.
  // An open stop found beyond its limit (a crossing the steps passed, acted
  // on late) is put back on the limit first: its row held for the positions
  // only, so that the rebound's velocity stays and no joint sinks through
  if (contacts_.empty()) return make_consistent(model_, d_, kkt_, q, v, t);
  std::vector<int> held = d_.closed_rows();
  const std::vector<int> closed = held;
  // (a stop released here leaves its limit at rest, g' = 0: the velocities
  // are projected with its row held too, then the accelerations solved
  // without it; a formulation whose velocities keep only Phi = 0 (index 3)
  // has it approaching by its error, a new impact at once, and a chatter)
  std::vector<int> at_rest = closed;
  at_rest.insert(at_rest.end(), released_.begin(), released_.end());
  std::sort(at_rest.begin(), at_rest.end());
  auto with_rows = [&](const std::vector<int>& rows, auto&& solve) {
    d_.close_rows(model_, rows);
    try {
      auto out = solve();
      d_.close_rows(model_, closed);
      return out;
    } catch (...) {
      d_.close_rows(model_, closed);
      throw;
    }
  };
  auto project = [&]() {
    VecX on_limits = q;
    if (held.size() > closed.size())
      on_limits = with_rows(held, [&] { return solve_positions(model_, d_, kkt_, q, t); });
    if (released_.empty()) return make_consistent(model_, d_, kkt_, on_limits, v, t);
    const ConsistentState resting = with_rows(at_rest, [&] { return make_consistent(model_, d_, kkt_, on_limits, v, t); });
    return make_consistent(model_, d_, kkt_, resting.q, resting.v, t);
  };
  // (so is a stop whose crossing this event acted on: it is at its limit by
  // definition, while the interpolant it was found on, not on Phi = 0, can
  // put it 1e-6 off there)
  gaps(t, q, v);
  for (const Contact& c : contacts_)
    if (c.info.exists && !is_closed(c.row) &&
        (rows_.Phi[c.row] < 0.0 || std::find(on_limit_.begin(), on_limit_.end(), c.row) != on_limit_.end()))
      held.push_back(c.row);
  // (a row the event left open on its limit, released or rebounding, reads
  // as inside at the restart whatever its rate's rounding, and a released
  // one until a step ends with it off the limit: a release at a force the
  // interpolant put 0 a little early starts moving back in, and that is a
  // crossing to find, not one already passed; see values())
  restart_t_ = t;
  left_.clear();
  for (int row : on_limit_)
    if (!is_closed(row)) left_.push_back(row);
  on_limit_.clear();
  std::sort(held.begin(), held.end());
  ConsistentState state = project();
  // The projection moves the other joints too: it can put a stop beyond its
  // limit (a joint held on its limit, or a driver's new value, pushing a
  // coupled one through its own: 0.65 rad beyond in a chain), which is held
  // on its limit too, and the positions projected again, until none is
  // (an active set on the positions). A stop leaving its limit (a rebound,
  // a release) is there to within the interpolant's error: the projection
  // onto the joints can put it just beyond, where its gap reads as crossed
  // already and its next crossing in the first step shows no sign change
  // (missed, acted on late with a larger speed): it is held too. (One just
  // beyond and approaching is left: its crossing is found as missed.)
  const double at_limit = 1e-9 * (1.0 + q.lpNorm<Eigen::Infinity>());
  for (size_t pass = 0; pass < contacts_.size(); ++pass) {
    gaps(t, state.q, state.v);
    const size_t before = held.size();
    for (const Contact& c : contacts_)
      if (c.info.exists && !is_closed(c.row) && rows_.Phi[c.row] < 0.0 &&
          (rows_.Phi[c.row] <= -at_limit || rows_.phi_t[c.row] >= 0.0) &&
          !std::binary_search(held.begin(), held.begin() + long(before), c.row))
        held.push_back(c.row);
    if (held.size() == before) break;
    std::sort(held.begin(), held.end());
    state = project();
  }
  // (so is every open row the restart finds resting on its limit, acted on
  // or not: a stop duplicating a closed one that is released, a coupled one
  // resting open, would strike at its velocity's rounding)
  gaps(t, state.q, state.v);
  const double still = 1e-9 * (1.0 + state.v.lpNorm<Eigen::Infinity>());
  for (const Contact& c : contacts_)
    if (c.info.exists && !is_closed(c.row) && std::abs(rows_.Phi[c.row]) <= 1e-10 &&
        std::abs(rows_.phi_t[c.row]) <= still && !left(c.row))
      left_.push_back(c.row);
  return state;
}

}  // namespace lagmb
