"""Fully driven mechanisms: kinematic analysis + inverse dynamics vs the DAE.

A model whose every motion is prescribed by drivers (0 degrees of freedom)
needs no integration: lagmb's analysis="auto" solves it from its
constraints (Newton on Phi(q, t) = 0 at each output, then Phi_q v = -Phi_t,
Phi_q a = gamma and M a + Phi_q^T lam = Q). This compares it with
integrating the same model as a DAE (analysis="dynamic", GGL + IDA) at the
same outputs and rtol:

- slider-crank (crank r = 0.1 m, rod l = 0.3 m) driven at 10 rad/s;
- a chain of N rods (L = 1 m) whose every revolute is driven by a harmonic
  relative angle, N = 10, 30, 100.

1 s, 101 outputs, rtol 1e-8 (atol 1e-10) for the dynamic run, and again at
rtol 1e-10 (atol 1e-12), nearer the kinematic analysis' accuracy (positions
to rounding level). Wall time is
the best of --repeat runs (stats["wall_time"]); also the steps, Newton
iterations and factorizations, and the largest differences between the two
analyses in positions (m, rad) and in the driver efforts (relative to the
largest effort). Prints a table and writes bench/results/kinematic.json.

    python bench/performance/kinematic.py [--n 10 30 100] [--repeat 3] [--out FILE]
"""

import argparse
import json
import math
import os
import platform
import sys

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.paths import RESULTS  # noqa: E402

T_END, N_OUT, RTOL, ATOL = 1.0, 101, 1e-8, 1e-10
TIGHT_RTOL, TIGHT_ATOL = 1e-10, 1e-12  # the dynamic run near the kinematic analysis' accuracy


def slider_crank(omega=10.0, theta0=math.pi / 3, r=0.1, l=0.3):
    B = r * np.array([math.cos(theta0), math.sin(theta0)])
    C = np.array([r * math.cos(theta0) + math.sqrt(l**2 - (r * math.sin(theta0))**2), 0.0])
    m = mb.Model(gravity=(0.0, -9.81))
    crank = m.add_body("crank", 1.0, r**2 / 12, position=0.5 * B, angle=theta0)
    rod = m.add_body("rod", 2.0, 2 * l**2 / 12, position=0.5 * (B + C),
                     angle=math.atan2(C[1] - B[1], C[0] - B[0]))
    slider = m.add_body("slider", 0.5, 1e-4, position=C)
    m.add_revolute("O", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("B", crank, rod, at=B)
    m.add_revolute("C", rod, slider, at=C)
    m.add_translational("guide", m.ground, slider, at=C, axis=(1.0, 0.0))
    m.drive_joint("motor", "O", mb.Linear(omega, start=theta0))
    return m, ["motor"]


def driven_chain(n):
    """n rods along +x, every revolute driven: relative angle
    0.3 sin(2 t + 0.1 k) about its initial 0."""
    m = mb.Model(gravity=(0.0, -9.81))
    prev = m.ground
    drivers = []
    for k in range(n):
        rod = m.add_body(f"rod{k}", 1.0, 1 / 12, position=(k + 0.5, 0.0))
        m.add_revolute(f"pin{k}", prev, rod, at=(float(k), 0.0))
        m.drive_joint(f"motor{k}", f"pin{k}", mb.Harmonic(0.3, 2.0, phase=0.1 * k))
        drivers.append(f"motor{k}")
        prev = rod
    return m, drivers


def best_of(model, repeat, **kw):
    best = None
    for _ in range(repeat):
        r = mb.simulate(model, t_end=T_END, n_out=N_OUT, **kw)
        if best is None or r.stats["wall_time"] < best.stats["wall_time"]:
            best = r
    return best


def measure(name, build, repeat):
    model, drivers = build()
    kin = best_of(model, repeat)  # auto: inverse dynamics at 0 DOF
    dyn = best_of(model, repeat, analysis="dynamic", rtol=RTOL, atol=ATOL)
    try:
        tight = best_of(model, repeat, analysis="dynamic", rtol=TIGHT_RTOL, atol=TIGHT_ATOL)
    except mb.SimulationError as e:  # IDA may not deliver that tolerance on a long driven chain
        tight = None
        tight_failure = str(e).split(".")[0]
    assert kin.stats["analysis"] == "inverse_dynamics" and kin.stats["steps"] == 0
    effort_k = np.column_stack([kin.effort(d) for d in drivers])
    effort_d = np.column_stack([dyn.effort(d) for d in drivers])
    row = {
        "model": name,
        "coordinates": model.n_coordinates,
        "kinematic": {k: kin.stats[k] for k in ("wall_time", "steps", "kinematic_solves", "newton_iterations",
                                                "lu_factorizations", "augmented_factorizations")},
        "dynamic": {k: dyn.stats[k] for k in ("wall_time", "steps", "residual_evals", "jacobian_evals",
                                              "lu_factorizations", "newton_iterations")},
        "speedup": dyn.stats["wall_time"] / kin.stats["wall_time"],
        "max_position_difference": float(np.max(np.abs(kin.q - dyn.q))),
        "max_effort_difference_relative": float(np.max(np.abs(effort_k - effort_d)) / np.max(np.abs(effort_k))),
        "max_residual_kinematic": float(np.max(kin.residual)),
    }
    if tight is None:
        row["dynamic_tight"] = {"failed": tight_failure}
    else:
        row["dynamic_tight"] = {k: tight.stats[k] for k in ("wall_time", "steps", "lu_factorizations")}
        row["speedup_tight"] = tight.stats["wall_time"] / kin.stats["wall_time"]
        row["max_position_difference_tight"] = float(np.max(np.abs(kin.q - tight.q)))
    return row


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, nargs="+", default=[10, 30, 100])
    p.add_argument("--repeat", type=int, default=3, help="runs per model; the fastest is kept")
    p.add_argument("--out", default=os.path.join(RESULTS, "kinematic.json"))
    args = p.parse_args()

    cases = [("slider_crank", slider_crank)] + [(f"driven_chain_{n}", lambda n=n: driven_chain(n)) for n in args.n]
    rows = []
    head = (f"{'model':>16} {'n':>5} | {'kin ms':>8} {'solves':>6} {'newton':>6} {'LU':>6} | "
            f"{'dyn ms':>8} {'steps':>6} {'LU':>6} | {'speedup':>7} {'|dq|':>8} {'d effort':>8} | "
            f"{'tight ms':>8} {'steps':>6} {'speedup':>7} {'|dq|':>8}")
    print(head)
    print("-" * len(head))
    for name, build in cases:
        r = measure(name, build, args.repeat)
        rows.append(r)
        k, d = r["kinematic"], r["dynamic"]
        print(f"{name:>16} {r['coordinates']:>5} | {1e3 * k['wall_time']:8.2f} {k['kinematic_solves']:6d} "
              f"{k['newton_iterations']:6d} {k['lu_factorizations'] + k['augmented_factorizations']:6d} | {1e3 * d['wall_time']:8.2f} "
              f"{d['steps']:6d} {d['lu_factorizations']:6d} | {r['speedup']:7.1f} "
              f"{r['max_position_difference']:8.1e} {r['max_effort_difference_relative']:8.1e} | "
              + (f"{1e3 * r['dynamic_tight']['wall_time']:8.2f} {r['dynamic_tight']['steps']:6d} "
                 f"{r['speedup_tight']:7.1f} {r['max_position_difference_tight']:8.1e}"
                 if "speedup_tight" in r else "  failed: " + r["dynamic_tight"]["failed"][:40]), flush=True)
    out = {
        "description": "kinematic analysis + inverse dynamics (analysis='auto' at 0 DOF) vs the dynamic DAE run "
                       f"(analysis='dynamic', ggl/IDA, rtol {RTOL}, atol {ATOL}; 'tight': rtol {TIGHT_RTOL}, "
                       f"atol {TIGHT_ATOL}); {T_END} s, {N_OUT} outputs; "
                       "wall time: best of repeat",
        "machine": {"platform": platform.platform(), "python": platform.python_version(),
                    "sundials": mb.SUNDIALS_VERSION},
        "repeat": args.repeat,
        "results": rows,
    }
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as fh:
        json.dump(out, fh, indent=1)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
