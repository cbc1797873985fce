"""The time a sweep of runs takes to reach an error target, read off a
work-precision curve (bench/accuracy/chains_accuracy.py, bench/peers/compare.py)."""

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


def decisive(rows, targets, time_key="time"):
    """Indices of the ok rows time_to (and a lower bound) rest on: for each
    target the first row that reaches it and the ok row before; the slowest
    ok row (by time_key) if none does. rows coarse to fine."""
    ok = [i for i, r in enumerate(rows) if r["status"] == "ok"]
    out = set()
    for t in targets:
        hit = [j for j, i in enumerate(ok) if rows[i]["error"] <= t]
        if hit:
            out.add(ok[hit[0]])
            if hit[0] > 0:
                out.add(ok[hit[0] - 1])
        elif ok:
            out.add(max(ok, key=lambda i: rows[i][time_key]))
    return out
