"""Wall-time loops: a call timed `repeats` times (time.perf_counter around
it), on a shared machine whose noise only ever adds time."""

import time


def wall_times(call, repeats):
    """(the wall seconds of `repeats` calls, the last call's value)."""
    times, value = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        value = call()
        times.append(time.perf_counter() - t0)
    return times, value


def best_of(call, repeats):
    """(fastest wall seconds of `repeats` calls, the last call's value)."""
    times, value = wall_times(call, repeats)
    return min(times, default=float("inf")), value
