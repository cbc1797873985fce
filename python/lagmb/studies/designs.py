"""Designs of experiments (``mb.sweep.monte_carlo``, ``latin_hypercube``,
``sobol``): cases drawn reproducibly from a seed, as a :class:`Design`.
"""

import numbers

import numpy as np

from .._checks import show
from ..errors import ModelError
from .store import MAX_CASES


class Design:
    """Cases made by a design of experiments: ``cases`` (a list of dicts),
    ``kind`` and ``seed``. Pass it as ``mb.sweep(model, design)``."""

    def __init__(self, cases, kind, seed):
        self.cases, self.kind, self.seed = cases, kind, seed

    def __len__(self):
        return len(self.cases)

    def __repr__(self):
        return f"<lagmb.sweep.Design: {self.kind}, {len(self.cases)} cases, seed {self.seed}>"


def _bounds(bounds, who):
    if not isinstance(bounds, dict) or not bounds:
        raise ModelError(f"{who}: give the parameters as a non-empty dict {{name: (low, high)}}, got {bounds!r}")
    names, lows, highs = [], [], []
    for name, pair in bounds.items():
        try:
            low, high = (float(x) for x in pair)
        except (TypeError, ValueError, OverflowError):
            raise ModelError(f"{who}: {name!r} needs (low, high), got {show(pair)}") from None
        if not (np.isfinite(low) and np.isfinite(high) and low < high):
            raise ModelError(f"{who}: {name!r} needs finite low < high, got ({low}, {high})")
        names.append(name), lows.append(low), highs.append(high)
    return names, np.array(lows), np.array(highs)


def _count(n, who):
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 1:
        raise ModelError(f"{who}: n must be a positive integer, got {show(n)}")
    if n > MAX_CASES:
        raise ModelError(f"{who}: n = {show(n)} cases: at most {MAX_CASES:,} in one design (sweep.MAX_CASES)")
    return int(n)


def _seed(seed, who):
    """The seed as numpy takes it: None (fresh entropy) or an integer >= 0
    (a Generator or SeedSequence passes as is)."""
    if seed is None or isinstance(seed, (np.random.Generator, np.random.SeedSequence)):
        return seed
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or seed < 0:
        raise ModelError(f"{who}: seed must be an integer >= 0 (or None), got {show(seed)}")
    return int(seed)


def monte_carlo(distributions, n, seed):
    """n random cases: ``distributions`` maps a parameter to (low, high) (a
    uniform distribution) or to a frozen ``scipy.stats`` distribution
    (anything with ``rvs(size=, random_state=)``); reproducible from
    ``seed`` (numpy's default generator)."""
    who = "sweep.monte_carlo"
    n = _count(n, who)
    if not isinstance(distributions, dict) or not distributions:
        raise ModelError(f"{who}: give the parameters as a non-empty dict {{name: (low, high) or distribution}}")
    rng = np.random.default_rng(_seed(seed, who))
    columns = {}
    for name, d in distributions.items():
        if hasattr(d, "rvs"):
            columns[name] = np.asarray(d.rvs(size=n, random_state=rng), dtype=float)
        else:
            _, low, high = _bounds({name: d}, who)
            columns[name] = rng.uniform(low[0], high[0], size=n)
    return Design([{k: float(v[i]) for k, v in columns.items()} for i in range(n)], "monte_carlo", seed)


def _qmc(kind, bounds, n, seed):
    from scipy.stats import qmc

    who = f"sweep.{kind}"
    n = _count(n, who)
    seed = _seed(seed, who)
    names, low, high = _bounds(bounds, who)
    sampler = (qmc.LatinHypercube(d=len(names), seed=seed) if kind == "latin_hypercube"
               else qmc.Sobol(d=len(names), scramble=True, seed=seed))
    points = qmc.scale(sampler.random(n), low, high)
    return Design([dict(zip(names, map(float, row))) for row in points], kind, seed)


def latin_hypercube(bounds, n, seed):
    """n cases of a Latin hypercube over ``bounds`` ({name: (low, high)}),
    scipy.stats.qmc, reproducible from ``seed``."""
    return _qmc("latin_hypercube", bounds, n, seed)


def sobol(bounds, n, seed):
    """n cases of a scrambled Sobol sequence over ``bounds`` ({name: (low,
    high)}), scipy.stats.qmc, reproducible from ``seed`` (n a power of 2
    keeps its balance)."""
    return _qmc("sobol", bounds, n, seed)

