"""The time a sweep of runs takes to reach an error target, read off a
work-precision curve (bench/chains_accuracy.py, bench/peers/compare.py)."""

import math


def time_to(rows, target):
    """Seconds to reach `target` error, interpolated log-log between the
    loosest run that reaches it and the run before it; None if none does.
    rows: dicts with status ("ok" or not), error and time, coarse to fine."""
    ok = [r for r in rows if r["status"] == "ok"]
    for k, r in enumerate(ok):
        if r["error"] <= target:
            if k == 0 or ok[k - 1]["error"] <= target or ok[k - 1]["error"] <= r["error"]:
                return r["time"]
            a, b = ok[k - 1], r
            s = (math.log(target) - math.log(a["error"])) / (math.log(b["error"]) - math.log(a["error"]))
            return math.exp(math.log(a["time"]) + s * (math.log(b["time"]) - math.log(a["time"])))
    return None
