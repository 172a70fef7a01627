"""Validation: reference cases, their error metrics, resolution sweeps and reports.

- :data:`CASES` (:mod:`.cases`): the registry of reference cases; ``CASES[name].run(resolution)``
  gives a run record (case, resolution, dp, n_particles, steps, sim_time, wall_s, threads,
  errors, status, ...).
- :mod:`.metrics`: the error metrics, pure functions of arrays.
- :mod:`.sweep`: runs cases at several resolutions on local processes or a Dask cluster,
  writing the records to JSON as they come.
- :mod:`.report`: convergence orders, Pareto fronts, the cheapest run meeting a target, and the
  Markdown + PNG report.

``watersim validate`` (:func:`.sweep.cmd_validate`) is the command-line front.
"""

from __future__ import annotations

from . import metrics
from .case import Case
from .cases import CASES, StandingWaveTank, run_case

__all__ = ["CASES", "Case", "StandingWaveTank", "metrics", "run_case"]
