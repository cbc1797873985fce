"""lagmb on the peer-comparison chain (bench/peers/compare.py drives it).

The chain of bench/chain.py (N rods in Cartesian body coordinates, revolute
joints with Lagrange multipliers); the stiff variant adds
add_rotational_spring_damper between consecutive rods (torque on rod j
-k (phi_j - phi_i - 0) - c (phi_j' - phi_i'), rest angle = the initial
relative angle 0; none at the ground pin). A run is
mb.simulate(model, t_end=1, rtol, atol=1e-2 rtol, n_out=2, method options
from mb.METHODS), timed around the call as in bench/chains_accuracy.py
(the model is compiled beforehand). The tip is the last rod's (x, y).

Self-check against the reference (error must fall with rtol):

    python bench/peers/peer_lagmb.py [--n 8] [--stiff]
"""

import os
import sys
import time

NAME = "lagmb"
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))  # bench/, for chain.py

# rtol levels, half decades 1e-3 .. 1e-11 (bench/chains_accuracy.py uses
# whole decades 1e-4 .. 1e-11; the looser ones place the 1e-6 crossing of
# the explicit method, which is already below 1e-6 at 1e-4)
RTOLS = tuple(10.0 ** (-k / 2) for k in range(6, 23))


def available():
    try:
        import lagmb as mb
    except ImportError as e:
        return False, f"lagmb not importable: {e}"
    return True, (f"lagmb {mb.__version__} ({os.path.dirname(mb.__file__)}, {build_id(mb)}), "
                  f"SUNDIALS {mb.SUNDIALS_VERSION}")


def run_versions(mb, **others):
    """{"lagmb": version, "lagmb_build": build_id, **others}: what a bench's
    JSON records of the code that ran."""
    return {"lagmb": mb.__version__, "lagmb_build": build_id(mb), **others}


def build_id(mb):
    """Which build ran: md5 (12 digits) and time of the compiled core, so that
    results from a rebuilt lagmb can be told apart."""
    import hashlib

    core = getattr(mb, "_core", None)
    path = getattr(core, "__file__", None)
    if not path or not os.path.exists(path):
        return "core build unknown"
    with open(path, "rb") as f:
        digest = hashlib.md5(f.read()).hexdigest()[:12]
    stamp = time.strftime("%Y-%m-%d %H:%M", time.gmtime(os.path.getmtime(path)))
    return f"_core md5 {digest}, {stamp} UTC"


def lagmb_chain(n, k=0.0, c=0.0):
    """bench/chain.py's chain, plus a rotational spring-damper per inner joint."""
    from chain import chain

    m = chain(n)
    if k or c:
        for i in range(1, n):
            m.add_rotational_spring_damper(f"sd{i}", f"rod{i - 1}", f"rod{i}", stiffness=k, damping=c)
    return m


class Engine:
    name = NAME

    def __init__(self, n, k=0.0, c=0.0):
        import lagmb as mb

        self.mb = mb
        self.n = n
        self.model = lagmb_chain(n, k, c)
        self.model.compiled()

    def methods(self, stiff):
        names = ["projection-erk", "ggl"] + (["projection-bdf"] if stiff else [])
        return [{"method": m, "kind": "rtol", "levels": RTOLS} for m in names]

    def run(self, method, rtol):
        mb, n = self.mb, self.n
        t0 = time.perf_counter()
        r = mb.simulate(self.model, t_end=1.0, rtol=rtol, atol=1e-2 * rtol, n_out=2, **mb.METHODS[method])
        wall = time.perf_counter() - t0
        return {"tip": [float(r.q[-1, 3 * n - 3]), float(r.q[-1, 3 * n - 2])], "time": wall,
                "steps": int(r.stats["steps"]), "evals": int(r.stats["residual_evals"])}


if __name__ == "__main__":
    from selfcheck import selfcheck

    selfcheck(sys.modules[__name__])
