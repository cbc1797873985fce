"""lagmb on the peer-comparison chain (bench/peers/compare.py drives it).

The chain of bench/common/chain.py (N rods in Cartesian body coordinates, revolute
joints with Lagrange multipliers); the stiff variant adds
add_rotational_spring_damper between consecutive rods (torque on rod j
-k (phi_j - phi_i - 0) - c (phi_j' - phi_i'), rest angle = the initial
relative angle 0; none at the ground pin). A run is
mb.simulate(model, t_end=1, rtol, atol=1e-2 rtol, n_out=2, method options
from mb.METHODS), timed around the call as in bench/accuracy/chains_accuracy.py
(the model is compiled beforehand). The tip is the last rod's (x, y).

Self-check against the reference (error must fall with rtol):

    python bench/peers/peer_lagmb.py [--n 8] [--stiff]
"""

import os
import sys
import time

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.chain import stiff_chain  # noqa: E402
from bench.common.record import build_id  # noqa: E402

NAME = "lagmb"

# rtol levels, half decades 1e-3 .. 1e-11 (bench/accuracy/chains_accuracy.py uses
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


class Engine:
    name = NAME

    def __init__(self, n, k=0.0, c=0.0):
        import lagmb as mb

        self.mb = mb
        self.n = n
        self.model = stiff_chain(n, k, c)
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
    from bench.peers.selfcheck import selfcheck

    selfcheck(sys.modules[__name__])
