"""What accuracy costs: work-precision tables and diagrams.

``work_precision(model, t_end)`` runs every method at every tolerance and
measures each run against a reference: a much tighter run of a method of
the other family (CVODE projection for the IDA forms, IDA GGL for the
projection forms), or one you pass. One row per method x tolerance:

    method, formulation, integrator, rtol, atol, reference (which reference
    run, e.g. "projection-bdf rtol 1e-13"), status, message,
    error (max over outputs of max |q - q_ref|, m or rad),
    error_final (the same at t_end), cpu_time (s, process time of the run),
    wall_time (s, the solver's own), steps, residual_evals, jacobian_evals,
    lu_factorizations, augmented_factorizations, error_test_failures,
    convergence_failures, drift_position (max |Phi|, m),
    drift_velocity (max |Phi_q v + Phi_t|), energy_error (max |E - E(t0)|, J)

``WorkPrecision.plot(path)`` draws error against CPU time on log axes, one
line per method, and the position drift along the run for each method at a
middle tolerance.
"""

import json
import time

import numpy as np

from .errors import ModelError, SimulationError
from .simulation import methods, simulate

def _presets():
    """Every variable-step method of lagmb.methods() by its name (a
    work-precision sweep varies the tolerance, which a fixed step ignores),
    and index1 with Baumgarte terms alpha = beta = 10 as its own line."""
    presets = {}
    for m in methods():
        if m["fixed_step"]:
            continue
        presets[m["name"]] = dict(formulation=m["formulation"], integrator=m["integrator"])
        if m["name"] == "index1":
            presets["index1-baumgarte"] = dict(presets["index1"], baumgarte=(10.0, 10.0))
    return presets


#: The methods a work-precision study runs, by name.
METHODS = _presets()

COLUMNS = ["method", "formulation", "integrator", "rtol", "atol", "reference", "status", "message", "error",
           "error_final", "cpu_time", "wall_time", "steps", "residual_evals", "jacobian_evals",
           "lu_factorizations", "augmented_factorizations", "error_test_failures",
           "convergence_failures", "drift_position", "drift_velocity", "energy_error"]

DEFAULT_TOLERANCES = tuple(10.0 ** -k for k in range(3, 12))


def _method(m):
    if isinstance(m, str):
        if m not in METHODS:
            raise ModelError(f"unknown method '{m}' (known: {', '.join(METHODS)})")
        return m, dict(METHODS[m])
    if isinstance(m, dict) and "name" in m:
        opts = {k: v for k, v in m.items() if k != "name"}
        return m["name"], opts
    raise ModelError(f"a method is a name ({', '.join(METHODS)}) or a dict with a 'name', got {m!r}")


class WorkPrecision:
    """Rows of a work-precision study; see the module docstring."""

    def __init__(self, rows, reference, reference_info, drifts, middle_tolerance, t_end):
        self.rows = rows
        self.reference = reference  # {"<method> rtol <r>": Result}, or the Result given
        self.reference_info = reference_info  # {"<method> rtol <r>": {"method", "rtol", "atol"}}
        self.drifts = drifts  # method -> (t, |Phi|) of its run at the middle tolerance
        self.middle_tolerance = middle_tolerance
        self.t_end = t_end

    columns = COLUMNS

    def reference_for(self, method):
        """The reference Result the rows of `method` were measured against."""
        rows = self.method_rows(method)
        if not rows:
            raise ModelError(f"no rows for method '{method}'")
        ok = [r for r in rows if r["reference"]]
        if not ok:
            raise ModelError(f"method '{method}' has no successful run")
        return self.reference if ok[0]["reference"] == "given" else self.reference[ok[0]["reference"]]

    def method_rows(self, method):
        return [r for r in self.rows if r["method"] == method]

    @property
    def methods(self):
        return list(dict.fromkeys(r["method"] for r in self.rows))

    def to_dict(self):
        return {"columns": COLUMNS, "rows": self.rows, "t_end": self.t_end,
                "reference": self.reference_info}

    def save(self, path):
        with open(path, "w") as f:
            json.dump(self.to_dict(), f, indent=1, default=float)

    def table(self):
        """The rows as fixed-width text."""
        # Newton: factorizations of the Newton matrix (the implicit methods'
        # LU); KKT: of the augmented system (the explicit and projection
        # methods' accelerations), as `lagmb run` counts them
        head = (f"{'method':<18} {'rtol':>7} {'error':>9} {'cpu (s)':>9} {'steps':>7} "
                f"{'Newton':>6} {'KKT':>6} {'max|Phi|':>9} {'max|Phi_v|':>10} {'|dE|':>9}")
        lines = [head, "-" * len(head)]
        for r in self.rows:
            if r["status"] != "ok":
                lines.append(f"{r['method']:<18} {r['rtol']:>7.0e}   failed: {r['message'][:60]}")
                continue
            lines.append(
                f"{r['method']:<18} {r['rtol']:>7.0e} {r['error']:>9.2e} {r['cpu_time']:>9.4f} "
                f"{r['steps']:>7d} {r['lu_factorizations']:>6d} {r['augmented_factorizations']:>6d} "
                f"{r['drift_position']:>9.1e} {r['drift_velocity']:>10.1e} {r['energy_error']:>9.1e}")
        return "\n".join(lines)

    def cheapest_run(self, error):
        """The row of least CPU time among the successful runs with error <=
        `error` (any method, any tolerance), or None if none reached it."""
        rows = [r for r in self.rows if r["status"] == "ok" and r["error"] <= error]
        return min(rows, key=lambda r: r["cpu_time"]) if rows else None

    def summary(self, errors=None):
        """What the table's numbers mean, in lines of text: the error's
        definition and unit; which reference run each method was measured
        against; and, for each error asked for (default: every decade from
        the largest error down to the smallest reached), the cheapest run
        that reaches it (method, tolerance, CPU time)."""
        lines = ["error: the largest |q - q_ref| over every coordinate and output time (m for positions,",
                 "  rad for angles, Euler parameters dimensionless); |dE|: max |E - E(t0)| (J)"]
        served = {}
        for r in self.rows:
            if r["reference"]:
                served.setdefault(r["reference"], []).append(r["method"])
        for key, names in served.items():
            names = ", ".join(dict.fromkeys(names))
            if key == "given":
                lines.append(f"reference: the Result given, for {names}")
            else:
                ref = self.reference_info[key]
                lines.append(f"reference for {names}: {ref['method']} at rtol {ref['rtol']:.0e}, "
                             f"atol {ref['atol']:.0e}")
        reached = [r["error"] for r in self.rows if r["status"] == "ok" and r["error"] > 0]
        if errors is None and reached:
            top, bottom = np.floor(np.log10(max(reached))), np.ceil(np.log10(min(reached)))
            errors = [10.0 ** k for k in np.arange(top, bottom - 1, -1)]
        for e in errors or ():
            best = self.cheapest_run(e)
            if best is None:
                lines.append(f"error <= {e:.0e}: no run reached it")
            else:
                lines.append(f"error <= {e:.0e}: cheapest {best['method']} at rtol {best['rtol']:.0e} "
                             f"({best['cpu_time']:.2g} s CPU, error {best['error']:.1e})")
        return "\n".join(lines)

    def cheapest(self, error):
        """For each method, the least CPU time of its runs with error <= `error`
        (None if no run reached it)."""
        out = {}
        for m in self.methods:
            times = [r["cpu_time"] for r in self.method_rows(m)
                     if r["status"] == "ok" and r["error"] <= error]
            out[m] = min(times) if times else None
        return out

    def plot(self, path=None, title=None):
        """Error against CPU time (log-log), one line per method, and the
        position drift along each method's middle-tolerance run."""
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        fig = Figure(figsize=(11, 4.6), dpi=110, constrained_layout=True)
        FigureCanvasAgg(fig)
        a1, a2 = fig.subplots(1, 2)
        for k, m in enumerate(self.methods):
            rows = [r for r in self.method_rows(m) if r["status"] == "ok" and r["error"] > 0]
            if not rows:
                continue
            a1.loglog([r["cpu_time"] for r in rows], [r["error"] for r in rows], "o-", ms=4,
                      color=f"C{k}", label=m)
            for r in rows[:1] + rows[-1:]:
                a1.annotate(f"{r['rtol']:.0e}", (r["cpu_time"], r["error"]), fontsize=7,
                            color=f"C{k}", xytext=(3, 3), textcoords="offset points")
            if m in self.drifts:
                t, d = self.drifts[m]
                a2.semilogy(t, np.maximum(d, 1e-17), color=f"C{k}", label=m, lw=1)
        from matplotlib.ticker import NullFormatter

        a1.xaxis.set_minor_formatter(NullFormatter())
        a1.set_xlabel("CPU time (s)")
        a1.set_ylabel("max position error vs reference (m, rad)")
        a1.set_title("work-precision (labels: rtol)")
        a1.grid(True, which="both", alpha=0.3)
        a1.legend(fontsize=8)
        a2.set_xlabel("time t (s)")
        a2.set_ylabel("constraint drift max |Phi| (m)")
        mid = self.middle_tolerance
        a2.set_title(f"drift along the run at rtol {mid:.0e}")
        a2.grid(True, which="both", alpha=0.3)
        if self.drifts:
            a2.legend(fontsize=8)
        if title:
            fig.suptitle(title)
        if path:
            fig.savefig(path)
        return fig


def work_precision(model, t_end, methods=None, tolerances=None, reference=None, n_out=101,
                   atol_ratio=1e-2, reference_rtol=None, t0=0.0, max_steps=500_000, progress=None):
    """Run each method at each tolerance and measure it; returns WorkPrecision.

    methods: names from METHODS (default: all) or dicts with a "name" and
    simulate() options. tolerances: rtol values (atol = atol_ratio * rtol),
    default 1e-3 .. 1e-11. reference: a Result at the output times to compare
    with; default: a tight run of the other family of methods, at
    reference_rtol (default: 1e-2 x the tightest tolerance, at least 1e-13;
    atol at least 1e-13): the projection form (CVODE BDF) for the IDA forms,
    GGL (IDA) for the projection forms. A run stopped by max_steps is a failed row. progress(i, n, row)
    is called after each run.
    """
    methods = [_method(m) for m in (methods or list(METHODS))]
    tolerances = sorted((float(t) for t in (tolerances or DEFAULT_TOLERANCES)), reverse=True)
    if not tolerances or min(tolerances) <= 0:
        raise ModelError("tolerances must be positive numbers")
    t_out = np.linspace(t0, t_end, n_out)
    rtol_ref = reference_rtol or max(1e-13, 1e-2 * min(tolerances))
    atol_ref = max(atol_ratio * rtol_ref, 1e-13)  # below that, roundoff in q decides
    references, info = {}, {}

    def reference_for(opts):
        """A tight run of a method of the other family: the CVODE projection
        form checks the IDA forms and GGL checks the projection form. If that
        run fails (tight runs can meet roundoff), the same family at 10x the
        tolerance, then the other family, are tried; each row names the
        reference it was measured against."""
        if given is not None:
            return given.q, "given"
        preferred = "ggl" if opts.get("formulation") == "projection" else "projection-bdf"
        other = "projection-bdf" if preferred == "ggl" else "ggl"
        why = []
        for family, factor in ((preferred, 1.0), (preferred, 10.0), (other, 1.0), (other, 10.0)):
            key = (family, factor)
            if key not in references:
                rtol, atol = factor * rtol_ref, factor * atol_ref
                try:
                    references[key] = simulate(model, t_out=t_out, t0=t0, rtol=rtol, atol=atol,
                                               **METHODS[family])
                    info[f"{family} rtol {rtol:.0e}"] = {"method": family, "rtol": rtol, "atol": atol}
                except SimulationError as e:
                    references[key] = None
                    why.append(f"{family} at rtol {rtol:g}: {e}")
            if references[key] is not None:
                return references[key].q, f"{family} rtol {factor * rtol_ref:.0e}"
        raise SimulationError("no reference run succeeded: " + "; ".join(why))

    given = reference
    if given is not None:
        t_out = given.t
        info = {"given": True}
    rows, drifts = [], {}
    mid = tolerances[len(tolerances) // 2]
    total = len(methods) * len(tolerances)
    for name, opts in methods:
        for rtol in tolerances:
            row = dict.fromkeys(COLUMNS, float("nan"))
            row.update(method=name, formulation=opts.get("formulation"),
                       integrator=opts.get("integrator", "bdf"), rtol=rtol, atol=atol_ratio * rtol,
                       reference="", status="ok", message="")
            c0 = time.process_time()
            try:
                r = simulate(model, t_out=t_out, t0=t0, rtol=rtol, atol=atol_ratio * rtol,
                             max_steps=max_steps, **opts)
            except SimulationError as e:
                row.update(status="failed", message=str(e), cpu_time=time.process_time() - c0)
                rows.append(row)
                if progress:
                    progress(len(rows), total, row)
                continue
            cpu = time.process_time() - c0
            q_ref, row["reference"] = reference_for(opts)
            err = np.abs(r.q - q_ref).max(axis=1)
            s = r.stats
            E = r.energy
            row.update(
                error=float(err.max()), error_final=float(err[-1]), cpu_time=cpu,
                wall_time=s["wall_time"], steps=s["steps"], residual_evals=s["residual_evals"],
                jacobian_evals=s["jacobian_evals"], lu_factorizations=s["lu_factorizations"],
                augmented_factorizations=s["augmented_factorizations"],
                error_test_failures=s["error_test_failures"],
                convergence_failures=s["convergence_failures"],
                drift_position=float(r.residual.max()), drift_velocity=float(r.velocity_residual.max()),
                energy_error=float(np.abs(E - E[0]).max()))
            rows.append(row)
            if rtol == mid:
                drifts[name] = (r.t, r.residual)
            if progress:
                progress(len(rows), total, row)
    runs = {f"{f} rtol {k * rtol_ref:.0e}": r for (f, k), r in references.items() if r is not None}
    return WorkPrecision(rows, given if given is not None else runs, info, drifts, mid, t_end)

