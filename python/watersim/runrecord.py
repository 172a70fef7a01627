"""The record of one run, built one way for ``watersim run`` (summary.json), ``watersim stress``
(its JSON's runs) and ``watersim validate`` (runs.json).

Each command lists the fields of its record (:data:`RUN_FIELDS`, :data:`STRESS_FIELDS`,
:data:`VALIDATION_FIELDS`); :func:`run_record` fills them in that order from the values the
command passes, else from the simulation (:data:`MEASURES`), else from the process (``threads``,
``version``), else None.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import Any

from ._core import InstabilityError
from ._version import __version__

__all__ = [
    "MEASURES",
    "RUN_FIELDS",
    "STRESS_FIELDS",
    "VALIDATION_FIELDS",
    "error_record",
    "instability_fields",
    "measure",
    "rayon_threads",
    "run_record",
    "stop_status",
]

RUN_FIELDS: tuple[str, ...] = (
    "case", "status", "dim", "n_particles", "n_fluid", "n_boundary", "steps", "sim_time",
    "until", "wall_s", "threads", "state_sha256", "memory_bytes", "version",
)
"""The fields of summary.json that every ``watersim run`` case writes (first, in this order)."""

STRESS_FIELDS: tuple[str, ...] = (
    "group", "name", "case", "params", "until", "sample_every", "status", "kind", "step", "time",
    "particle", "position", "message", "max_density_error", "energy_drift", "energy_growth_max",
    "wall_s", "n_particles", "n_fluid", "steps", "sim_time", "dp", "completed", "max_wall_s",
    "notes",
)
"""The fields of a ``watersim stress`` record before its run starts (:mod:`watersim.stress`)."""

VALIDATION_FIELDS: tuple[str, ...] = (
    "case", "resolution", "dp", "n_particles", "steps", "sim_time", "wall_s", "cpu_s", "threads",
    "n_sims", "errors", "status", "message", "details",
)
"""The fields of a ``watersim validate`` run record
(:func:`watersim.validation.running.make_record`)."""

INSTABILITY_FIELDS: tuple[str, ...] = ("kind", "step", "time", "particle", "position")
"""What a stability monitor's :class:`~watersim.InstabilityError` says about where it stopped."""

MEASURES: dict[str, Callable[[Any], Any]] = {
    "dim": lambda sim: int(sim.dim),
    "n_particles": lambda sim: int(sim.n_particles),
    "n_fluid": lambda sim: int(sim.n_fluid),
    "n_boundary": lambda sim: int(sim.n_boundary),
    "steps": lambda sim: int(sim.steps),
    "sim_time": lambda sim: float(sim.time),
    "dp": lambda sim: float(sim.params()["dp"]),
    "c0": lambda sim: float(sim.params()["c0"]),
    "state_sha256": lambda sim: sim.state_sha256(),
    "memory_bytes": lambda sim: sim.memory_bytes(),
}
"""The fields read from a simulation."""


def rayon_threads() -> int:
    """Number of threads rayon uses: ``RAYON_NUM_THREADS`` if set and positive, else the CPUs
    this process may run on."""
    env = os.environ.get("RAYON_NUM_THREADS", "").strip()
    if env:
        try:
            n = int(env)
        except ValueError:
            n = 0
        if n > 0:
            return n
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def measure(sim: Any, names: Sequence[str]) -> dict[str, Any]:
    """The fields ``names`` of :data:`MEASURES` read from ``sim``."""
    return {name: MEASURES[name](sim) for name in names}


def run_record(fields: Sequence[str], sim: Any | None, **values: Any) -> dict[str, Any]:
    """A run's record: each of ``fields`` in order, from ``values`` if given there, else read
    from ``sim`` (:data:`MEASURES`, when there is a simulation), else ``threads``
    (:func:`rayon_threads`) and ``version`` of this process, else None."""
    process: dict[str, Callable[[], Any]] = {"threads": rayon_threads,
                                             "version": lambda: __version__}
    record: dict[str, Any] = {}
    for name in fields:
        if name in values:
            record[name] = values[name]
        elif sim is not None and name in MEASURES:
            record[name] = MEASURES[name](sim)
        elif name in process:
            record[name] = process[name]()
        else:
            record[name] = None
    return record


def instability_fields(exc: BaseException) -> dict[str, Any]:
    """Where a stability monitor stopped the run (:data:`INSTABILITY_FIELDS`; the position as
    a list)."""
    out = {attr: getattr(exc, attr, None) for attr in INSTABILITY_FIELDS}
    if out["position"] is not None:
        out["position"] = list(out["position"])
    return out


def error_record(exc: BaseException) -> dict[str, Any]:
    """What went wrong, as summary.json stores it: type and message, and where a stability
    monitor stopped the run."""
    record: dict[str, Any] = {"type": type(exc).__name__, "message": str(exc)}
    if isinstance(exc, InstabilityError):
        record.update(instability_fields(exc))
    return record


def stop_status(exc: InstabilityError) -> str:
    """The status of a run a stability monitor stopped: the monitor's kind."""
    return str(getattr(exc, "kind", "") or "unstable")
