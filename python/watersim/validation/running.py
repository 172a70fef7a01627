"""Running a validation case: the progress bar over simulated time, the run to the end or to a
monitor's stop, the run record, the clocks, and the flume cases built quietly (their warnings
kept as notes)."""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Mapping
from typing import Any

from .._core import InstabilityError
from ..flume import (
    FlumeScene,
    FlumeSimulation,
)
from ..flume_cases import _Settings, flume_builder
from ..runrecord import VALIDATION_FIELDS, run_record, stop_status
from ..simulation import Simulation


class _Progress:
    """A tqdm bar over simulated time, with dt and particle-steps per second, fed by the
    callback of :meth:`watersim.Simulation.run`."""

    def __init__(self, sim: Simulation, until: float, label: str, enabled: bool) -> None:
        self.sim = sim
        self.bar: Any = None
        if enabled:
            from tqdm import tqdm  # type: ignore[import-untyped]

            self.bar = tqdm(total=round(until, 6), desc=label, unit="s(sim)", leave=False,
                            dynamic_ncols=True, bar_format="{l_bar}{bar}| {n:.3f}/{total:.3f} s "
                            "[{elapsed}<{remaining}{postfix}]")
        self.wall0 = time.perf_counter()
        self.steps0 = sim.steps

    def update(self) -> None:
        if self.bar is None:
            return
        wall = time.perf_counter() - self.wall0
        rate = self.sim.n_particles * (self.sim.steps - self.steps0) / wall if wall > 0 else 0.0
        self.bar.n = round(self.sim.time, 6)
        self.bar.set_postfix_str(f"t={self.sim.time:.3f} s, dt={self.sim.dt:.2e} s, "
                                 f"{rate:.3g} particle-steps/s", refresh=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def advance(
    sim: Simulation,
    until: float,
    every: float,
    on_sample: Callable[[Simulation], None] | None = None,
    progress: bool = False,
    label: str = "",
) -> tuple[str, str | None]:
    """Run ``sim`` to ``until`` [s], calling ``on_sample`` every ``every`` [s] of simulated time.

    Returns:
        (status, message): ``("ok", None)``, ``(kind, message)`` when a stability monitor
        stopped the run (the samples so far are kept), or ``("error", message)``.
    """
    bar = _Progress(sim, until, label, progress)

    def callback(s: Simulation) -> None:
        if on_sample is not None:
            on_sample(s)
        bar.update()

    try:
        sim.run(until, callback_every=every, callback=callback)
    except InstabilityError as exc:
        return stop_status(exc), str(exc)
    except RuntimeError as exc:
        return "error", f"{type(exc).__name__}: {exc}"
    finally:
        bar.close()
    return "ok", None


def make_record(
    case: str,
    resolution: float,
    dp: float,
    sim: Simulation | None,
    wall_s: float,
    cpu_s: float,
    status: str,
    message: str | None,
    errors: Mapping[str, float | None],
    details: Mapping[str, Any],
    n_sims: int = 1,
    particles_total: int | None = None,
    steps_total: int | None = None,
) -> dict[str, Any]:
    """One run's record: the fields ``watersim validate`` writes for every run.

    ``errors`` maps metric names to non-negative errors (smaller is better; None when a metric
    could not be computed); ``details`` holds the measured values behind them.
    """
    clean: dict[str, float | None] = {}
    for key, value in errors.items():
        v = None if value is None else float(value)
        clean[key] = v if v is not None and math.isfinite(v) else None
    given: dict[str, Any] = {}
    if particles_total is not None:
        given["n_particles"] = int(particles_total)
    if steps_total is not None:
        given["steps"] = int(steps_total)
    if sim is None:  # a case that could not be built
        given = {"n_particles": 0, "steps": 0, "sim_time": 0.0, **given}
    return run_record(VALIDATION_FIELDS, sim, case=case, resolution=float(resolution),
                      dp=float(dp), wall_s=float(wall_s), cpu_s=float(cpu_s), n_sims=n_sims,
                      errors=clean, status=status, message=message, details=dict(details),
                      **given)


class _Clock:
    """Wall and process CPU time since creation [s]."""

    def __init__(self) -> None:
        self.wall0 = time.perf_counter()
        self.cpu0 = time.process_time()

    def wall(self) -> float:
        return time.perf_counter() - self.wall0

    def cpu(self) -> float:
        return time.process_time() - self.cpu0


def _quiet_flume(case: str, items: Mapping[str, str]) -> tuple[FlumeScene, list[str]]:
    """A flume case's scene with ``--set``-style items, its warnings returned as notes."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        scene = flume_builder(case, dict(items))
    return scene, [f"{w.category.__name__}: {w.message}" for w in caught]


def _with_until(case: str, items: dict[str, str], until: Callable[[FlumeScene], float]
                ) -> tuple[FlumeScene, list[str]]:
    """The scene built twice: once to compute ``until`` from it, once with that ``until``."""
    probe, _ = _quiet_flume(case, items)
    return _quiet_flume(case, {**items, "until": repr(round(until(probe), 3))})


def numerical_case_scene(case: str, dp: float, settings: Mapping[str, str] | None,
                         until: Callable[[FlumeScene], float],
                         fixed: Mapping[str, str] | None = None) -> tuple[FlumeScene, list[str]]:
    """A flume case's scene for a validation case that takes numerical ``--set`` items only:
    ``settings`` checked (any other key refused, ``dp`` and ``until`` included, before anything
    runs), then the case built at ``dp`` with them and the case's ``fixed`` items, until
    ``until(scene)``; its warnings as notes.

    Raises:
        FlumeCaseError: a settings key that is not a numerical key of the flume cases.
    """
    probe = _Settings(dict(settings or {}))
    probe.numerics(dp=dp)
    probe.only_numerics(case)
    return _with_until(case, {**(settings or {}), **(fixed or {}), "dp": repr(dp)}, until)


def flume_run(case: Any, scene: FlumeScene, res: float, progress: bool, label: str
              ) -> tuple[FlumeSimulation, str, str | None, dict[str, Any]]:
    """Build and run a flume scene; returns the simulation, status, message and analysis."""
    sim = scene.build()
    until = float(scene.until)  # type: ignore[arg-type]
    status, message = advance(sim, until, max(until / 50.0, 1e-3), None, progress, label)
    return sim, status, message, sim.analyse()
