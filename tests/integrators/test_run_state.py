"""A run never changes its Model (issue 10, part 1).

Everything a run records (a contact's impact speed, the rows it drops as
redundant) lives in that run's Data. So a quantity computed from a model is
the same before and after any number of runs, and one model may be run by
several threads at once with exactly the results of one thread.
"""

import threading

import numpy as np

import lagmb as mb

G = 9.81


def bouncing_ball():
    """A ball (r = 0.1 m, 1 kg) above the floor y = 0, Hunt-Crossley contact
    with e = 0.8; its damping divides by the impact speed of the contact in
    progress, which the run records at each onset."""
    m = mb.Model(gravity=(0.0, -G))
    m.add_body("ball", 1.0, 0.004, position=(0.0, 1.0))
    m.add_contact("floor", "ball", center=(0.0, 1.0), radius=0.1, line_body="ground",
                  point=(0.0, 0.0), direction=(1.0, 0.0), stiffness=1e7, restitution=0.8)
    return m


def test_accelerations_do_not_depend_on_the_history_of_the_model():
    """The ball 1 mm into the floor, falling at 1 m/s: the contact force and
    so the acceleration are the same, bit for bit, before and after a run
    that bounced the ball (that run's impact speed, 4.2 m/s, stays with it).
    Before the run state moved to Data the two differed by 1.3e4 m/s^2."""
    m = bouncing_ball()
    q = np.array([0.0, 0.099, 0.0])   # centre 0.099 m above the floor: 1 mm deep
    v = np.array([0.0, -1.0, 0.0])
    before, _ = mb.solve_accelerations(m, q, v)
    r = mb.simulate(m, t_end=0.6, rtol=1e-8, atol=1e-10)
    assert r.stats["events"] >= 1                       # it did touch the floor
    after, _ = mb.solve_accelerations(m, q, v)
    assert np.array_equal(before, after)
    # outside a run no impact is in progress: v_impact is its floor 1e-3 m/s,
    # so the damping term dominates and pushes the ball up hard
    assert before[1] > 1e3


def test_a_second_run_repeats_the_first_bit_for_bit():
    """Two runs of the same model, one after the other, give identical
    trajectories and event records: nothing of the first carries over."""
    m = bouncing_ball()
    options = dict(t_end=1.5, rtol=1e-8, atol=1e-10, n_out=301)
    first, second = mb.simulate(m, **options), mb.simulate(m, **options)
    assert first.stats["events"] >= 3
    assert np.array_equal(first.q, second.q) and np.array_equal(first.lam, second.lam)
    assert np.array_equal(first.a, second.a)


def run_in_threads(function, n):
    results, errors = [None] * n, []

    def work(k):
        try:
            results[k] = function()
        except BaseException as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    return results


def four_bar_with_stop_and_ball():
    """A pendulum hitting a stop and a bouncing ball in one model: events of
    both kinds, contact run state, redundant rows (the pin given twice)."""
    m = bouncing_ball()
    rod = m.add_body("rod", 1.0, 1.0 / 12.0, position=(2.5, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(2.0, 0.0))
    m.add_revolute("pin_again", m.ground, rod, at=(2.0, 0.0))
    m.add_stop("limit", "pin", lower=-1.0, upper=None, restitution=0.9)
    return m


def test_two_threads_running_one_model_get_the_results_of_one_thread():
    """One compiled model simulated by two threads at once (the GIL is
    released during runs) gives each thread the single-threaded result, bit
    for bit: no run writes into the model."""
    import warnings

    m = four_bar_with_stop_and_ball()
    options = dict(t_end=1.0, rtol=1e-8, atol=1e-10, n_out=101)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.RedundantConstraintWarning)
        alone = mb.simulate(m, **options)
        together = run_in_threads(lambda: mb.simulate(m, **options), 2)
    assert alone.stats["events"] >= 3
    for r in together:
        assert np.array_equal(r.q, alone.q)
        assert np.array_equal(r.lam, alone.lam)
        assert r.events == alone.events
