"""Parameter studies: ``mb.sweep`` runs a model over a grid, a table or a
design of experiments on any ``concurrent.futures.Executor`` (a Dask
``Client`` included) and returns an ``xarray.Dataset``, optionally kept in
a Zarr store as cases finish so that an interrupted study resumes.

Each task carries the model as its description text (``ModelSpec``'s, the
FMU's), a batch of cases (parameter values and run settings) and the
output functions; a worker builds the model once per process and runs each
case with ``simulate(model, ..., parameters=case)``, exactly as a run alone
would. A case that fails is recorded with its error; the others go on.

A module per job: ``study`` (``sweep``, end to end), ``cases`` (the cases
and their checks; a grid written as text), ``designs`` (Monte Carlo, Latin
hypercube, Sobol), ``outputs`` (the built-in outputs), ``runs`` (a batch
in a worker; the executors), ``dataset`` (the results as xarray),
``made_of`` (what a sweep is made of: its store's fingerprint) and
``store`` (the Zarr store, its batches and lock; resuming).
"""

from .cases import RUN_SETTINGS, grid_from_text
from .dataset import as_grid
from .designs import Design, latin_hypercube, monte_carlo, sobol
from .outputs import EnergyDrift, Final, PeakEffort, PeakReaction, energy_drift, final, peak_effort, peak_reaction
from .store import MAX_CASES, check_store, open_store
from .study import sweep

# what mb.sweep carries as its attributes (mb.sweep.monte_carlo, mb.sweep.MAX_CASES, ...): the
# designs, the built-in outputs and the readers of its results, set here and nowhere else
sweep.final = final
sweep.peak_reaction = peak_reaction
sweep.peak_effort = peak_effort
sweep.energy_drift = energy_drift
sweep.monte_carlo = monte_carlo
sweep.latin_hypercube = latin_hypercube
sweep.sobol = sobol
sweep.as_grid = as_grid
sweep.grid_from_text = grid_from_text
sweep.open_store = open_store
sweep.MAX_CASES = MAX_CASES
sweep.Design = Design

__all__ = ["sweep", "final", "peak_reaction", "peak_effort", "energy_drift", "monte_carlo", "latin_hypercube",
           "sobol", "Design", "as_grid", "grid_from_text", "open_store", "check_store", "MAX_CASES", "RUN_SETTINGS",
           "Final", "PeakReaction", "PeakEffort", "EnergyDrift"]
