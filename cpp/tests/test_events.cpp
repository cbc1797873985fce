// The event runner (lagmb/events/event_runner.hpp) driven directly, on
// motions known in closed form: where its event functions cross (a block
// falling onto its stop, a throw grazing a limit, a ball passing through a
// post within one step), what an impact does (g'+ = -e g'-, no energy
// gained), the active set's capture and release (the stop's force m g - c t
// letting go at m g / c), and a stuck contact slipping where the push
// reaches mu_s times its weight. Two runs through simulate() check that the
// integrators find the crossings where the closed forms say.
#include <cmath>
#include <vector>

#include "check.hpp"
#include "lagmb/events/event_runner.hpp"
#include "lagmb/model/data.hpp"
#include "lagmb/run/simulate.hpp"
#include "models.hpp"

using namespace lagmb_test;

namespace {

/// The runner's event functions at (t, q, v).
std::vector<double> values_at(EventRunner& events, double t, const VecX& q, const VecX& v) {
  std::vector<double> g(size_t(events.size()));
  events.values(t, q.data(), v.data(), g.data());
  return g;
}

/// The planar block on its guide at height s moving at s' (q = (x, y, theta)).
VecX block_at(double s) { return VecX((VecX(3) << 0.0, s, 0.0).finished()); }

/// The root of f in [a, b] (f(a) > 0 >= f(b)) by bisection to rounding.
template <class F>
double first_root(F f, double a, double b) {
  while (b - a > 1e-15 * (1.0 + std::abs(b))) {
    const double mid = 0.5 * (a + b);
    (f(mid) > 0.0 ? a : b) = mid;
  }
  return b;
}

std::vector<int> rows_closed(const Data& run) { return run.closed_rows(); }

}  // namespace

// --- detection ---------------------------------------------------------------

// Falling from rest at s = 0 onto its limit at -h: g_lower(t) = h - g t^2 / 2
// on the free fall; the absent upper limit reads 1 always. After the step
// that passed t* = sqrt(2 h / g), missed() flags the lower gap alone; before
// it, nothing.
TEST_CASE(a_falling_block_reads_its_gap_and_a_passed_crossing_is_flagged) {
  const double h = 0.2, t_star = std::sqrt(2.0 * h / kG);
  const auto model = block_on_a_guide(-h, NAN, 0.5);
  Data run(*model);
  EventRunner events(*model, run, 1e-10);
  CHECK(events.size() == 2 && events.directions()[0] == -1 && events.directions()[1] == -1);
  for (double t : {0.0, 0.1, 0.9 * t_star, 1.1 * t_star}) {
    const std::vector<double> g = values_at(events, t, block_at(-0.5 * kG * t * t), block_at(-kG * t));
    CHECK_NEAR(g[0], h - 0.5 * kG * t * t, 1e-15);
    CHECK(g[1] == 1.0);
  }
  const double at_crossing = first_root(
      [&](double t) { return values_at(events, t, block_at(-0.5 * kG * t * t), block_at(-kG * t))[0]; }, 0.0, 1.0);
  CHECK_NEAR(at_crossing, t_star, 1e-14);
  std::vector<int> fired;
  const double before = 0.99 * t_star, after = 1.01 * t_star;
  CHECK(!events.missed(before, block_at(-0.5 * kG * before * before).data(), block_at(-kG * before).data(), fired));
  CHECK(events.missed(after, block_at(-0.5 * kG * after * after).data(), block_at(-kG * after).data(), fired));
  CHECK(fired == std::vector<int>({-1, 0}));
}

// The same fall integrated (simulate): the impact is recorded at
// t* = sqrt(2 h / g) with the approach speed -sqrt(2 g h), and the rebound
// leaves at e times it.
TEST_CASE(a_falling_block_strikes_its_stop_at_the_free_fall_time) {
  const double h = 0.2, e = 0.5;
  const auto model = block_on_a_guide(-h, NAN, e);
  SimulationOptions o;
  o.t_end = 0.25, o.rtol = 1e-10, o.atol = 1e-12;
  const Trajectory r = simulate(*model, o);
  CHECK(!r.events.empty() && r.events[0].kind == "impact" && r.events[0].label == "lower");
  if (r.events.empty()) return;
  CHECK_NEAR(r.events[0].t, std::sqrt(2.0 * h / kG), 1e-9);
  CHECK_NEAR(r.events[0].speed_before, -std::sqrt(2.0 * kG * h), 1e-7);
  CHECK_NEAR(r.events[0].speed_after, e * std::sqrt(2.0 * kG * h), 1e-7);
}

// The seed rod pendulum released horizontal falls onto its stop at -pi/4:
// theta'^2 = -(3 g / L) sin(theta), so t* = sqrt(L / 3g) * integral from 0
// to pi/4 of d(phi) / sqrt(sin phi) (with phi = psi^2 a smooth integrand,
// Simpson's rule), and it arrives at theta' = -sqrt(3 g sin(pi/4) / L).
TEST_CASE(a_pendulum_falls_onto_its_stop_when_its_energy_integral_says) {
  const double L = 1.0, end = std::sqrt(0.7853981633974483);
  const int n = 4000;
  auto integrand = [](double psi) { return psi == 0.0 ? 2.0 : 2.0 * psi / std::sqrt(std::sin(psi * psi)); };
  double sum = integrand(0.0) + integrand(end);
  for (int k = 1; k < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * integrand(end * k / n);
  const double t_star = std::sqrt(L / (3.0 * kG)) * sum * end / (3.0 * n);
  const auto model = pendulum_with_stop();  // (restitution 0: the impact is plastic and captures)
  SimulationOptions o;
  o.t_end = 0.5, o.rtol = 1e-10, o.atol = 1e-12;
  const Trajectory r = simulate(*model, o);
  CHECK(r.events.size() >= 2 && r.events[0].kind == "impact" && r.events[1].kind == "capture");
  if (r.events.empty()) return;
  CHECK_NEAR(r.events[0].t, t_star, 1e-8);
  CHECK_NEAR(r.events[0].speed_before, -std::sqrt(3.0 * kG * std::sin(0.7853981633974483) / L), 1e-6);
  CHECK(r.events[0].speed_after == 0.0);
}

// A throw up from s = 0 at v0, the upper limit u at 1/1.0201 of its peak
// v0^2 / 2g: within the one step from 0 to 2 v0 / g (the gap u at both
// ends) it is beyond u between the roots of u - v0 t + g t^2 / 2, and
// grazed() finds the first, t = (v0 - sqrt(v0^2 - 2 g u)) / g, on the
// step's interpolant (here the exact parabola). A throw to below u grazes
// nothing.
TEST_CASE(a_throw_just_past_the_upper_limit_grazes_it_within_one_step) {
  const double u = 0.1;
  for (double scale : {1.01, 0.99}) {
    const auto model = block_on_a_guide(-1.0, u, 0.5);
    Data run(*model);
    EventRunner events(*model, run, 1e-10);
    const double v0 = scale * std::sqrt(2.0 * kG * u), t1 = 2.0 * v0 / kG;
    VecX q, v;
    const EventRunner::Interpolant parabola = [&](double t, const double*& qt, const double*& vt) {
      q = block_at(v0 * t - 0.5 * kG * t * t), v = block_at(v0 - kG * t);
      qt = q.data(), vt = v.data();
    };
    std::vector<int> fired;
    const double t = events.grazed(0.0, t1, parabola, fired);
    if (scale > 1.0) {
      CHECK_NEAR(t, (v0 - std::sqrt(v0 * v0 - 2.0 * kG * u)) / kG, 1e-13);
      CHECK(fired == std::vector<int>({0, -1}));
    } else {
      CHECK(std::isnan(t));
    }
  }
}

// A ball of radius R flung at V = 10 m/s along x from (-1, 0, 0) through a
// post of radius r at the origin: one step from 0 to 2/V takes it from one
// side to the other, its gap 1 - R - r at both ends; grazed() finds the
// ball entering the post at t = (1 - R - r) / V on the (exact, straight)
// interpolant and flags its event function.
TEST_CASE(a_ball_passing_through_a_post_within_one_step_is_found) {
  const double R = 0.05, r = 0.02, V = 10.0;
  const auto model = ball_and_post(R, r);
  Data run(*model);
  EventRunner events(*model, run, 1e-10);
  CHECK(events.size() >= 1);
  VecX q = model->initial_q(), v = VecX::Zero(model->n_coordinates());
  CHECK(q.size() == 7 && q[0] == -1.0 && q[3] == 1.0);
  const EventRunner::Interpolant straight = [&](double t, const double*& qt, const double*& vt) {
    q[0] = -1.0 + V * t, v[0] = V;
    qt = q.data(), vt = v.data();
  };
  std::vector<int> fired;
  const double t = events.grazed(0.0, 2.0 / V, straight, fired);
  CHECK_NEAR(t, (1.0 - R - r) / V, 1e-13);
  CHECK(!fired.empty() && fired[0] == -1);
}

// --- impacts -----------------------------------------------------------------

// The block on its lower limit (s = -h) arriving at -w: handle() jumps its
// velocity to +e w (the gap's rate g'+ = -e g'-), the guide's other
// velocities untouched; its kinetic energy becomes e^2 times what it was
// (never more); the impact is recorded with both rates, and consistent()
// restarts from it on the limit.
TEST_CASE(an_impact_with_restitution_e_rebounds_at_minus_e_times_its_speed) {
  const double h = 0.2, w = 2.0;
  for (double e : {0.0, 0.3, 0.8, 1.0}) {
    const auto model = block_on_a_guide(-h, NAN, e);
    Data run(*model);
    EventRunner events(*model, run, 1e-10);
    const VecX q = block_at(-h);
    VecX v = block_at(-w);
    CHECK(values_at(events, 0.3, q, v)[0] == -1e-300 || std::abs(values_at(events, 0.3, q, v)[0]) <= 1e-15);
    const double energy = 0.5 * v.squaredNorm();
    CHECK(events.handle(0.3, q, v, {-1, 0}));
    CHECK_NEAR(v[1], e * w, 1e-14 * w);
    CHECK(v[0] == 0.0 && v[2] == 0.0);
    CHECK(0.5 * v.squaredNorm() <= energy * (1.0 + 1e-15));
    CHECK_NEAR(0.5 * v.squaredNorm(), e * e * energy, 1e-13 * energy);
    CHECK(events.impacts == 1 && events.records.size() >= 1);
    const EventRecord& hit = events.records[0];
    CHECK(hit.kind == "impact" && hit.element == "stop" && hit.label == "lower" && hit.t == 0.3);
    CHECK_NEAR(hit.speed_before, -w, 1e-15);
    CHECK_NEAR(hit.speed_after, e * w, 1e-14);
    const ConsistentState restart = events.consistent(0.3, q, v);
    CHECK_NEAR(restart.q[1], -h, 1e-15);
    CHECK_NEAR(restart.v[1], e * w, 1e-14);
  }
}

// --- the active set ----------------------------------------------------------

// A plastic impact (e = 0) ends at rest on the limit: the stop is captured
// (its lower row closed in the run's Data), and its event function is then
// its force, the block's weight m g (the upper limit, open, still its gap).
TEST_CASE(a_plastic_impact_captures_the_stop_and_its_force_is_the_weight) {
  const double h = 0.2;
  const auto model = block_on_a_guide(-h, 1.0, 0.0);
  Data run(*model);
  EventRunner events(*model, run, 1e-10);
  const VecX q = block_at(-h);
  VecX v = block_at(-1.5);
  CHECK(events.handle(0.1, q, v, {-1, 0}));
  CHECK(v.norm() <= 1e-15);
  CHECK(events.impacts == 1 && events.captures == 1 && events.releases == 0);
  CHECK(rows_closed(run) == std::vector<int>({2}));
  CHECK(events.records.size() == 2 && events.records[1].kind == "capture" && events.records[1].label == "lower");
  const ConsistentState rest = events.consistent(0.1, q, v);
  CHECK(rest.v.norm() <= 1e-15 && rest.qdd.norm() <= 1e-12);
  const std::vector<double> g = values_at(events, 0.1, rest.q, rest.v);
  CHECK_NEAR(g[0], 1.0 * kG, 1e-12);  // the force f = -lam of the closed row
  CHECK_NEAR(g[1], 1.0 + h, 1e-15);    // the open upper gap
}

// Held on its limit, the block is pushed up by F = c t: the stop's force is
// m g - c t (its event function, exact at every t), which crosses 0 at
// t_r = m g / c; a step's end past it finds the crossing (missed) and
// handle() releases the stop: its row opens, the release is recorded, and
// the restart leaves the block at rest on the limit, accelerating up at
// (c t - m g) / m. The same integrated: the release at m g / c.
TEST_CASE(a_held_stop_lets_go_where_a_rising_push_outweighs_the_weight) {
  const double c = 2.0, t_r = 1.0 * kG / c;
  const auto model = block_on_a_guide(0.0, NAN, 0.0, c);
  Data run(*model);
  EventRunner events(*model, run, 1e-10);
  VecX q = block_at(0.0), v = block_at(0.0);
  CHECK(events.start(0.0, q, v));  // resting on its limit, pressed: captured at the start
  CHECK(rows_closed(run) == std::vector<int>({2}) && events.captures == 1);
  for (double t : {0.0, 1.0, 4.0, 6.0})
    CHECK_NEAR(values_at(events, t, q, v)[0], 1.0 * kG - c * t, 1e-12);
  CHECK_NEAR(first_root([&](double t) { return values_at(events, t, q, v)[0]; }, 0.0, 10.0), t_r, 1e-13);
  std::vector<int> fired;
  const double t = t_r + 1e-3;
  CHECK(!events.missed(t_r - 1e-3, q.data(), v.data(), fired));
  CHECK(events.missed(t, q.data(), v.data(), fired));
  CHECK(fired == std::vector<int>({-1, 0}));
  CHECK(events.handle(t, q, v, fired));
  CHECK(rows_closed(run).empty() && events.releases == 1);
  CHECK(events.records.back().kind == "release" && events.records.back().label == "lower");
  const ConsistentState off = events.consistent(t, q, v);
  CHECK(off.q[1] == 0.0 && off.v.norm() <= 1e-15);
  CHECK_NEAR(off.qdd[1], c * t - kG, 1e-12);

  SimulationOptions o;
  o.t_end = 6.0, o.rtol = 1e-10, o.atol = 1e-12;
  const Trajectory r = simulate(*model, o);
  CHECK(r.events.size() == 2 && r.events[0].kind == "capture" && r.events[0].t == 0.0);
  if (r.events.size() == 2) {
    CHECK(r.events[1].kind == "release");
    CHECK_NEAR(r.events[1].t, t_r, 1e-8);
  }
}

// --- sticks ------------------------------------------------------------------

// A cube resting on a floor (mu_s = 0.5) sticks at the start: its three
// stick rows close and "stick" is recorded. Pushed along x by F = c t at
// its pressing corners' level, the stuck contact holds c t of friction
// against mu_s N, N = m g: its event function (the friction margin) is
// positive before t_s = mu_s m g / c and negative after (its root at t_s);
// past it, missed() flags it and handle() lets the cube slip: the rows
// open, "slip" is recorded.
TEST_CASE(a_stuck_block_slips_where_the_push_reaches_mu_s_times_its_weight) {
  const double mu = 0.3, mu_s = 0.5, c = 1.0, t_s = mu_s * 1.0 * kG / c;
  const auto model = block_on_a_floor(0.2, 1e8, mu, mu_s, c);
  Data run(*model);
  EventRunner events(*model, run, 1e-10);
  const VecX q = model->initial_q();
  VecX v = VecX::Zero(model->n_coordinates());
  events.start(0.0, q, v);
  CHECK(events.records.size() == 1 && events.records[0].kind == "friction" && events.records[0].label == "stick");
  CHECK(rows_closed(run).size() == 3);
  const int stick = events.size() - 1;  // (the contacts' stick functions come last)
  CHECK(events.directions()[stick] == 0);
  CHECK(values_at(events, 0.5 * t_s, q, v)[size_t(stick)] > 0.0);
  CHECK(values_at(events, 1.5 * t_s, q, v)[size_t(stick)] < 0.0);
  CHECK_NEAR(first_root([&](double t) { return values_at(events, t, q, v)[size_t(stick)]; }, 0.0, 2.0 * t_s), t_s,
             1e-9);
  std::vector<int> fired;
  CHECK(!events.missed(0.99 * t_s, q.data(), v.data(), fired));
  CHECK(events.missed(1.01 * t_s, q.data(), v.data(), fired));
  CHECK(fired[size_t(stick)] != 0);
  CHECK(events.handle(1.01 * t_s, q, v, fired));
  CHECK(rows_closed(run).empty());
  CHECK(events.records.back().kind == "friction" && events.records.back().label == "slip");
}

LAGMB_TEST_MAIN()
