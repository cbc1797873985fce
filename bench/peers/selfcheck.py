"""Shared `__main__` of the peer_*.py modules: run one engine's sweeps on
one N against the reference and print error and time per level, so that
each engine can be checked on its own (error must fall as the step or
tolerance is refined and reach the targets):

    python bench/peers/peer_mujoco.py --n 8 [--stiff] [--max-run 5]
"""

import argparse
import math

from bench.peers import reference


def selfcheck(module):
    p = argparse.ArgumentParser(description=module.__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, default=8)
    p.add_argument("--stiff", action="store_true")
    p.add_argument("--max-run", type=float, default=5.0, help="stop a sweep after a run this long (s)")
    args = p.parse_args()
    ok, info = module.available()
    print(f"{module.NAME}: {info}")
    if not ok:
        return
    cache = reference.load_cache()
    if args.stiff:
        params, tip = reference.stiff_reference(args.n, cache)
        k, c = params["stiffness"], params["damping"]
    else:
        tip, k, c = reference.nonstiff_reference(args.n, cache), 0.0, 0.0
    reference.save_cache(cache)
    eng = module.Engine(args.n, k, c)
    for m in eng.methods(args.stiff):
        if args.n > m.get("max_n", math.inf):
            print(f"  {m['method']}: skipped above N = {m['max_n']}")
            continue
        for level in m["levels"]:
            try:
                r = eng.run(m["method"], level)
            except Exception as e:  # noqa: BLE001 - report and go on
                print(f"  {m['method']:<24} {m['kind']}={level:<10.3g} failed: {str(e).splitlines()[0][:120]}")
                continue
            err = max(abs(r["tip"][0] - tip[0]), abs(r["tip"][1] - tip[1]))
            print(f"  {m['method']:<24} {m['kind']}={level:<10.3g} error {err:9.2e}  time {r['time']:8.4f} s  "
                  f"steps {r['steps']}", flush=True)
            if err <= 1e-9 or r["time"] > args.max_run:
                break
