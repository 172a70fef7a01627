"""``watersim stress``: a matrix of stiff and extreme runs, each recorded as stable or failed.

Groups (``--quick`` runs a reduced, coarser, shorter version of each):

- ``stiffness``: a coarse 2D dam break for ``coefsound`` x CFL (the stable region);
- ``dissipation``: artificial viscosity alpha 0, 0.01, 0.1, with and without density diffusion;
- ``violent``: a tall dam break hitting the far wall, a column dropped into a shallow layer, a
  steep regular wave near the Miche limit, a wave of H/d about 0.7 breaking on a beach, and a
  solitary wave running up a dry slope;
- ``long``: a still tank for 20 s (surface drift, spurious velocities);
- ``resolution``: very coarse (H/dp = 4) and the finest dam break the wall budget allows.

Each run is a :class:`RunSpec` (plain data, so it crosses process boundaries and goes into the
JSON report as is). :func:`run_matrix` runs every spec in a fresh worker process through
:class:`concurrent.futures.ProcessPoolExecutor` (one single-worker pool per run, at most
``jobs`` at a time): a run that crashes its process, or raises anything, is recorded as
``error`` and the sweep goes on. :func:`write_report` writes ``README.md`` (a table per group,
the stable region in numbers) and the coefsound x CFL heat map.

What a record holds (see :func:`execute`): ``status`` (``stable``: reached ``until``;
``failed``: a stability monitor stopped it, with ``kind``, ``step``, ``time``, ``particle``,
``position``, ``message``; ``error``: any other exception or a dead worker; ``timeout``: the
run's wall limit stopped it), the largest density error ``max |rho/rho0 - 1|`` over the fluid
at the samples, the energy drift, wall time, particles and steps.
"""

from __future__ import annotations

import concurrent.futures as cf
import dataclasses
import math
import multiprocessing
import os
import platform
import sys
import time
import traceback
import warnings
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from . import numerics as nm
from ._files import write_text_atomic
from ._jsonio import write_json_atomic
from .errors import CliError
from .runrecord import STRESS_FIELDS, instability_fields, measure, run_record

__all__ = [
    "GROUPS",
    "RunSpec",
    "execute",
    "full_matrix",
    "quick_matrix",
    "run_matrix",
    "stable_region",
    "write_report",
]

GROUPS: tuple[str, ...] = ("stiffness", "dissipation", "violent", "long", "resolution")
"""Run groups, in report order."""

STATUSES: tuple[str, ...] = ("stable", "failed", "error", "timeout")

DENSITY_TARGET = 0.01
"""Density error a weakly-compressible run aims to stay under (1 %: Monaghan 1994's choice of
c0 >= 10 |v|max keeps it there); the report states where each coefsound meets it."""

COST_MARGIN = 2.0
"""Factor on the estimated cost of the finest run: in the quick matrix (H/dp = 60, 2,610
particles) the wall per step during the collapse, next to another run on the second core, was
2.4 times the one timed at rest, while dt stayed within 4 %."""


@dataclass(frozen=True)
class RunSpec:
    """One run of the matrix, as plain data.

    Attributes:
        group: one of :data:`GROUPS`.
        name: unique name within the matrix.
        case: how to build it: ``"dambreak"``, ``"tank"`` (the :class:`~watersim.DamBreak` /
            :class:`~watersim.Tank` builders, 2D, with ``params`` as their fields),
            ``"dropped_column"`` (:func:`dropped_column_scene`), ``"flume"``
            (:func:`flume_scene`) or ``"finest_dambreak"`` (:func:`_execute_finest`).
        params: the builder's parameters (JSON values).
        until: simulated end time [s].
        sample_every: interval of the density / energy samples [s] of simulated time.
        max_wall_s: wall-clock limit of the run [s]; past it the run stops as ``timeout``
            (``finest_dambreak``: the budget it sizes itself to, then stops as ``stable``
            short of ``until``).
    """

    group: str
    name: str
    case: str
    params: dict[str, Any]
    until: float
    sample_every: float
    max_wall_s: float = 600.0

    def as_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)


# ------------------------------------------------------------------------------------------------
# scenes


def dropped_column_scene(params: dict[str, Any]) -> dict[str, Any]:
    """A 2D water column released ``drop`` metres above a shallow layer (the core's scene dict).

    ``params``: ``length``, ``tank_height``, ``layer`` (depth of the layer [m]), ``column_x``
    (left edge), ``column_width``, ``column_height``, ``drop`` (gap between the layer's surface
    and the column's bottom [m]), ``dp`` and any :class:`~watersim.Tank` numerical field. The
    column starts at rest with the hydrostatic density of its own height (the core initialises
    each fluid box from its top) and falls freely onto the layer.
    """
    from .scenes import Tank

    p = dict(params)
    geometry = {k: p.pop(k) for k in ("column_x", "column_width", "column_height", "drop")}
    layer = p.pop("layer")
    tank_height = p.pop("tank_height")
    length = p.pop("length")
    scene = Tank(dim=2, length=length, depth=layer, height=tank_height, until=1.0, **p).to_scene()
    z0 = layer + geometry["drop"]
    x0 = geometry["column_x"]
    top = z0 + geometry["column_height"]
    if top > tank_height or x0 + geometry["column_width"] > length or x0 < 0.0:
        from ._core import SceneError

        raise SceneError("column: the dropped column does not fit in the tank")
    scene["fluid"].append({"min": [x0, z0], "max": [x0 + geometry["column_width"], top]})
    return scene


def flume_scene(params: dict[str, Any]) -> Any:
    """A 2D :class:`~watersim.FlumeScene` from plain parameters.

    ``params``: ``length``, ``depth``, ``slope`` and ``toe`` (plane beach; omit for a flat flume
    with its default damping zone), ``wave`` (``"regular"`` with ``height``, ``period``,
    ``order``, ``ramp_periods``; or ``"solitary"`` with ``height``), ``gauges`` (x list [m]),
    ``runup`` (bool) and numerical fields (``dp``, ``coefsound``, ...). Wave-validity warnings
    are not errors here: the caller records them.
    """
    from .flume import (
        ElevationGauge,
        Flume,
        FlumeScene,
        Piston,
        PlaneBeach,
        RegularWave,
        SolitaryWave,
    )

    p = dict(params)
    beach = None
    if "slope" in p:
        beach = PlaneBeach(toe=p.pop("toe"), slope=p.pop("slope"))
    flume = Flume(length=p.pop("length"), depth=p.pop("depth"), beach=beach)
    kind = p.pop("wave")
    wave: Any
    if kind == "regular":
        wave = RegularWave(height=p.pop("height"), period=p.pop("period"))
        paddle = Piston(order=p.pop("order", 1), ramp_periods=p.pop("ramp_periods", 2.0))
    elif kind == "solitary":
        wave = SolitaryWave(height=p.pop("height"))
        paddle = Piston(order=1, ramp_periods=0.0)
    else:
        raise ValueError(f"wave: unknown kind {kind!r}")
    gauges = [ElevationGauge(x) for x in p.pop("gauges", [])]
    runup = p.pop("runup", None)
    return FlumeScene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, runup=runup, **p)


def _build(spec: RunSpec) -> tuple[Any, dict[str, Any]]:
    """The simulation of ``spec`` and facts about it (``depth`` for the energy reference...)."""
    from .scenes import DamBreak, Tank
    from .simulation import Simulation

    facts: dict[str, Any] = {"energy_meaningful": True}
    if spec.case == "dambreak":
        builder = DamBreak(dim=2, until=spec.until, **spec.params)
        return builder.build(), facts
    if spec.case == "tank":
        tank = Tank(dim=2, until=spec.until, **spec.params)
        facts["depth"] = tank.depth
        facts["length"] = tank.length
        return tank.build(), facts
    if spec.case == "dropped_column":
        return Simulation(dropped_column_scene(spec.params)), facts
    if spec.case == "flume":
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            setup = flume_scene({**spec.params, "until": spec.until})
            sim = setup.build()
        facts["warnings"] = [str(w.message) for w in caught]
        # the paddle does work on the fluid: its energy balance says nothing about stability
        facts["energy_meaningful"] = False
        return sim, facts
    raise ValueError(f"case: unknown case {spec.case!r}")


# ------------------------------------------------------------------------------------------------
# measures


class _Probe:
    """Samples a run: density error, mechanical energy, (still tank) surface and speed.

    Energy: ``E = m sum(|v|^2 / 2 + g (z - z_floor))`` over the fluid particles still in the
    domain (kind 0; excluded particles are frozen and not counted, as in the core's monitor),
    with m from ``params()["mass"]``. The drift is ``(E_end - E_0) / P_0`` and the growth
    ``max(E - E_0) / P_0``, both relative to the initial potential energy above the floor
    ``P_0``, the reference of the core's energy monitor.
    """

    def __init__(self, sim: Any, facts: dict[str, Any], max_wall_s: float) -> None:
        params = sim.params()
        scene = sim.scene
        self.mass = float(params["mass"])
        self.rho0 = float(params["rho0"])
        self.dp = float(params["dp"])
        self.h = float(params["h"])
        self.g = float(scene.get("gravity", 9.81))
        self.floor = float(scene["tank"]["min"][-1])
        self.facts = facts
        self.max_density_error = 0.0
        self.e0: float | None = None
        self.p0: float | None = None
        self.energy_last: float | None = None
        self.energy_max_growth = -math.inf
        self.samples = 0
        self.dt_min = math.inf
        self.start = time.perf_counter()
        self.max_wall_s = max_wall_s
        self.surface0: float | None = None
        self.surface_last: float | None = None
        self.surface_max_change = 0.0
        self.speed_max = 0.0
        self.speed_last = 0.0

    def __call__(self, sim: Any) -> None:
        kinds = np.asarray(sim.kinds)
        fluid = kinds == 0
        rho = np.asarray(sim.densities)[fluid]
        pos = np.asarray(sim.positions)[fluid]
        vel = np.asarray(sim.velocities)[fluid]
        self.samples += 1
        if sim.steps > 0:
            self.dt_min = min(self.dt_min, float(sim.dt))
        err = np.abs(rho / self.rho0 - 1.0)
        err = err[np.isfinite(err)]  # a failed state may hold NaN: the finite part still counts
        if err.size:
            self.max_density_error = max(self.max_density_error, float(np.max(err)))
        kinetic = 0.5 * float(np.sum(vel * vel))
        potential = self.g * float(np.sum(pos[:, -1] - self.floor))
        energy = self.mass * (kinetic + potential)
        if not math.isfinite(energy):
            return
        if self.e0 is None:
            self.e0, self.p0 = energy, self.mass * potential
        self.energy_last = energy
        assert self.p0 is not None
        if self.p0 > 0.0:
            self.energy_max_growth = max(self.energy_max_growth, (energy - self.e0) / self.p0)
        if "depth" in self.facts:
            self._still_water(pos, vel)
        if time.perf_counter() - self.start > self.max_wall_s:
            raise _WallLimit(f"wall-clock limit of {self.max_wall_s:g} s reached at t = "
                             f"{sim.time:.4g} s")

    def _still_water(self, pos: np.ndarray, vel: np.ndarray) -> None:
        """Mean free-surface level over the middle half of the tank (highest particle per
        column of width dp, plus dp/2) and the largest fluid speed."""
        length = float(self.facts["length"])
        x = pos[:, 0]
        middle = np.abs(x - 0.5 * length) <= 0.25 * length
        if np.any(middle):
            bins = np.floor(x[middle] / self.dp).astype(np.int64)
            z = pos[middle, -1]
            tops = np.full(bins.max() - bins.min() + 1, -np.inf)
            np.maximum.at(tops, bins - bins.min(), z)
            surface = float(np.mean(tops[np.isfinite(tops)])) + 0.5 * self.dp
            if self.surface0 is None:
                self.surface0 = surface
            self.surface_last = surface
            self.surface_max_change = max(self.surface_max_change, abs(surface - self.surface0))
        speed = float(np.max(np.linalg.norm(vel, axis=1))) if len(vel) else 0.0
        self.speed_last = speed
        self.speed_max = max(self.speed_max, speed)

    def results(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "max_density_error": self.max_density_error,
            "samples": self.samples,
            "dt_min": self.dt_min if math.isfinite(self.dt_min) else None,
        }
        if self.facts.get("energy_meaningful") and self.e0 is not None and self.p0:
            assert self.energy_last is not None
            out["energy_drift"] = (self.energy_last - self.e0) / self.p0
            out["energy_growth_max"] = self.energy_max_growth
        else:
            out["energy_drift"] = None
            out["energy_growth_max"] = None
        if "depth" in self.facts and self.surface0 is not None:
            depth = float(self.facts["depth"])
            scale = math.sqrt(self.g * depth)
            assert self.surface_last is not None
            out["still_water"] = {
                "surface_drift_m": self.surface_last - self.surface0,
                "surface_drift_over_dp": (self.surface_last - self.surface0) / self.dp,
                "surface_max_change_m": self.surface_max_change,
                "max_speed_over_sqrt_gd": self.speed_max / scale,
                "final_speed_over_sqrt_gd": self.speed_last / scale,
            }
        return out


class _WallLimit(Exception):
    """A run's wall-clock limit was reached (raised from the sampling callback)."""


# ------------------------------------------------------------------------------------------------
# one run (in a worker process)


_BUILT: tuple[str, ...] = ("n_particles", "n_fluid", "dp", "c0")
"""What a record says of the simulation once it is built."""


def _base_record(spec: RunSpec) -> dict[str, Any]:
    """A spec's record before its run: an ``error`` until the run says otherwise."""
    return run_record(STRESS_FIELDS, None, group=spec.group, name=spec.name, case=spec.case,
                      params=dict(spec.params), until=spec.until, sample_every=spec.sample_every,
                      status="error", completed=False, max_wall_s=spec.max_wall_s, notes=[])


def execute(spec: RunSpec | dict[str, Any]) -> dict[str, Any]:
    """Run one spec and return its record (never raises for a failing run).

    ``InstabilityError`` gives ``failed`` with the monitor's fields; any other exception
    (including a Rust panic, pyo3's ``PanicException``, a ``BaseException``) gives ``error``
    with its type and message; the wall limit gives ``timeout``.
    """
    if isinstance(spec, dict):
        spec = RunSpec(**spec)
    # one thread per run unless the caller chose otherwise (before the core's pool starts)
    os.environ.setdefault("RAYON_NUM_THREADS", "1")
    from ._core import InstabilityError

    record = _base_record(spec)
    record["threads"] = int(os.environ["RAYON_NUM_THREADS"])
    start = time.perf_counter()
    sim = None
    probe: _Probe | None = None
    try:
        if spec.case == "finest_dambreak":
            return _execute_finest(spec, record, start)
        sim, facts = _build(spec)
        record["notes"].extend(facts.get("warnings", []))
        record.update(measure(sim, _BUILT))
        probe = _Probe(sim, facts, spec.max_wall_s)
        sim.run(spec.until, callback_every=spec.sample_every, callback=probe)
        record["status"] = "stable"
        record["completed"] = True
    except InstabilityError as exc:
        record.update(status="failed", message=str(exc), **instability_fields(exc))
    except _WallLimit as exc:
        record["status"] = "timeout"
        record["message"] = str(exc)
    except KeyboardInterrupt:
        raise
    except BaseException as exc:  # noqa: BLE001 - a panic or any bug is recorded, not fatal
        record["status"] = "error"
        record["message"] = f"{type(exc).__name__}: {exc}"
        record["notes"].append(traceback.format_exc(limit=3).strip().splitlines()[-1])
    record["wall_s"] = time.perf_counter() - start
    if sim is not None:
        record.update(measure(sim, ("steps", "sim_time")))
        if probe is not None:
            # the state after a failure is the failed one: its densities count too
            if record["status"] != "error":
                try:
                    probe(sim)
                except _WallLimit:
                    pass
            record.update(probe.results())
    return record


def _execute_finest(spec: RunSpec, record: dict[str, Any], start: float) -> dict[str, Any]:
    """The finest 2D dam break that fits the wall budget ``spec.max_wall_s``.

    For each candidate ``H/dp`` in ``params["h_over_dp"]`` (coarse to fine) it builds the case,
    times ``params["probe_steps"]`` steps after three warm-up steps, and estimates the cost of the
    run to ``until`` as :data:`COST_MARGIN` x (wall per step) x (until / dt). It picks the
    finest whose estimate fits
    in what is left of the budget, then runs it until ``until`` or the budget, whichever comes
    first (``completed`` says which). The estimates are kept in ``record["sizing"]``.
    """
    from ._core import InstabilityError
    from .scenes import DamBreak

    p = dict(spec.params)
    ratios = p.pop("h_over_dp")
    probe_steps = int(p.pop("probe_steps", 10))
    height = float(p.get("height", 2.0))
    sizing = []
    chosen: float | None = None
    for ratio in ratios:
        dp = height / ratio
        if time.perf_counter() - start > 0.5 * spec.max_wall_s:
            break
        sim = DamBreak(dim=2, dp=dp, until=spec.until, **p).build()
        sim.step(3)
        t0 = time.perf_counter()
        t_sim0 = sim.time
        sim.step(probe_steps)
        per_step = (time.perf_counter() - t0) / probe_steps
        dt = (sim.time - t_sim0) / probe_steps
        estimate = COST_MARGIN * per_step * spec.until / dt
        left = spec.max_wall_s - (time.perf_counter() - start)
        sizing.append({"h_over_dp": ratio, "dp": dp, "n_particles": sim.n_particles,
                       "wall_per_step_s": per_step, "dt_s": dt, "estimated_run_s": estimate})
        if estimate <= left:
            chosen = dp
        else:
            break
    record["sizing"] = sizing
    if chosen is None:
        chosen = height / ratios[0]
        record["notes"].append("no candidate fits the budget: ran the coarsest")
    sim = DamBreak(dim=2, dp=chosen, until=spec.until, **p).build()
    record.update(measure(sim, _BUILT))
    left = spec.max_wall_s - (time.perf_counter() - start)
    probe = _Probe(sim, {"energy_meaningful": True}, max(left, 1.0))
    try:
        sim.run(spec.until, callback_every=spec.sample_every, callback=probe)
        record["status"] = "stable"
        record["completed"] = True
    except _WallLimit:
        record["status"] = "stable"
        record["notes"].append(f"stopped at its wall budget at t = {sim.time:.4g} s")
    except InstabilityError as exc:
        record.update(status="failed", message=str(exc), **instability_fields(exc))
    record["wall_s"] = time.perf_counter() - start
    record.update(measure(sim, ("steps", "sim_time")))
    record.update(probe.results())
    return record


# ------------------------------------------------------------------------------------------------
# matrices


def _dambreak(height_over_dp: float, **extra: Any) -> dict[str, Any]:
    """DamBreak parameters: the Martin & Moyce 1 m x 2 m column in a 4 m tank at H/dp."""
    return {"dp": 2.0 / height_over_dp, **extra}


def full_matrix() -> list[RunSpec]:
    """The full matrix (about 15-20 minutes of one core; see docs/stability.md)."""
    specs: list[RunSpec] = []
    # stiffness: H/dp = 20 (dp = 0.1 m), until the front has hit the far wall (0.7 s). The
    # issue's range is coefsound 10-80 x CFL 0.05-0.5; coefsound 5 and CFL 0.75 and 1 (the
    # largest the scene accepts) are added to find the edge of the stable region.
    for cs in (5, 10, 20, 40, 80):
        for cfl in (0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.75, 1.0):
            specs.append(RunSpec("stiffness", f"cs{cs}_cfl{cfl}", "dambreak",
                                 _dambreak(20, coefsound=float(cs), cfl=cfl), 0.7, 0.005))
    # to 1.5 s: past the impact on the far wall and the plunging of the reflected surge
    specs += _dissipation(20, 1.5)
    specs += [
        # a column 3 m tall (H/dp = 20) in a 4 m tank: the surge hits the far wall at ~0.6 s
        # and runs up it; the walls are 4 m high
        RunSpec("violent", "tall_dambreak", "dambreak",
                {"dp": 0.15, "width": 1.0, "height": 3.0, "tank_length": 4.0,
                 "tank_height": 4.0}, 1.2, 0.005),
        RunSpec("violent", "dropped_column", "dropped_column",
                {"dp": 0.04, "length": 2.0, "tank_height": 2.0, "layer": 0.12,
                 "column_x": 0.8, "column_width": 0.4, "column_height": 0.6, "drop": 0.6},
                1.2, 0.005),
        # d = 0.3 m, T = 1 s (L = 1.37 m): Miche's limit 0.142 L tanh(kd) = 0.171 m; H = 0.9 of it
        RunSpec("violent", "steep_wave_miche0.9", "flume",
                {"wave": "regular", "height": 0.154, "period": 1.0, "order": 2,
                 "ramp_periods": 2.0, "length": 5.5, "depth": 0.3, "dp": 0.025,
                 **nm.FLUME_CASE, "gauges": [1.37, 2.74]}, 6.0, 0.01),
        # d = 0.2 m, T = 2 s, H = 0.14 m (H/d = 0.7, 0.84 of Miche) onto a 1:15 beach
        RunSpec("violent", "beach_wave_Hd0.7", "flume",
                {"wave": "regular", "height": 0.14, "period": 2.0, "order": 1,
                 "ramp_periods": 1.0, "length": 6.0, "depth": 0.2, "toe": 2.0,
                 "slope": 1.0 / 15.0, "dp": 0.02, **nm.FLUME_CASE, "gauges": [1.0, 3.5],
                 "runup": True}, 9.0, 0.01),
        # solitary2d's beach (Synolakis 1:19.85), H/d = 0.3, shortened
        RunSpec("violent", "solitary_runup", "flume",
                {"wave": "solitary", "height": 0.09, "length": 11.0, "depth": 0.3, "toe": 4.0,
                 "slope": 1.0 / 19.85, "dp": 0.03, **nm.FLUME_CASE,
                 "gauges": [2.0, 6.0, 8.0, 9.5], "runup": True}, 8.0, 0.01),
    ]
    specs.append(RunSpec("long", "still_tank_20s", "tank",
                         {"dp": 0.05, "length": 1.0, "depth": 0.5, "height": 0.7}, 20.0, 0.05,
                         max_wall_s=900.0))
    specs += [
        RunSpec("resolution", "coarse_H_dp4", "dambreak", _dambreak(4), 0.7, 0.005),
        RunSpec("resolution", "finest_in_60s", "finest_dambreak",
                {"h_over_dp": [20, 30, 40, 50, 60, 80, 100, 120], "probe_steps": 10}, 0.7,
                0.01, max_wall_s=60.0),
    ]
    return specs


def _dissipation(height_over_dp: float, until: float) -> list[RunSpec]:
    specs = []
    for alpha in (0.0, 0.01, 0.1):
        for diffusion in ("fourtakas", "none"):
            specs.append(RunSpec(
                "dissipation", f"alpha{alpha}_{diffusion}", "dambreak",
                _dambreak(height_over_dp, viscosity={"type": "artificial", "alpha": alpha},
                          diffusion=diffusion),
                until, 0.005))
    return specs


def quick_matrix() -> list[RunSpec]:
    """A reduced matrix: coarser, shorter, fewer points (about 2 minutes on 2 cores)."""
    specs: list[RunSpec] = []
    for cs in (10, 40):
        for cfl in (0.1, 0.3, 0.5, 1.0):
            specs.append(RunSpec("stiffness", f"cs{cs}_cfl{cfl}", "dambreak",
                                 _dambreak(10, coefsound=float(cs), cfl=cfl), 0.6, 0.005))
    specs += [s for s in _dissipation(10, 0.6) if "0.01" not in s.name]
    specs += [
        RunSpec("violent", "tall_dambreak", "dambreak",
                {"dp": 0.3, "width": 1.0, "height": 3.0, "tank_length": 4.0,
                 "tank_height": 4.0}, 1.0, 0.005),
        RunSpec("violent", "dropped_column", "dropped_column",
                {"dp": 0.08, "length": 2.0, "tank_height": 2.0, "layer": 0.24,
                 "column_x": 0.8, "column_width": 0.4, "column_height": 0.6, "drop": 0.6},
                1.0, 0.005),
        RunSpec("violent", "steep_wave_miche0.9", "flume",
                {"wave": "regular", "height": 0.154, "period": 1.0, "order": 2,
                 "ramp_periods": 1.0, "length": 4.0, "depth": 0.3, "dp": 0.05,
                 **nm.FLUME_CASE, "gauges": [1.37]}, 3.0, 0.02),
        RunSpec("violent", "solitary_runup", "flume",
                {"wave": "solitary", "height": 0.09, "length": 11.0, "depth": 0.3, "toe": 4.0,
                 "slope": 1.0 / 19.85, "dp": 0.06, **nm.FLUME_CASE, "gauges": [2.0, 8.0],
                 "runup": True}, 6.0, 0.02),
    ]
    specs.append(RunSpec("long", "still_tank_5s", "tank",
                         {"dp": 0.1, "length": 1.0, "depth": 0.5, "height": 0.7}, 5.0, 0.05))
    specs += [
        RunSpec("resolution", "coarse_H_dp4", "dambreak", _dambreak(4), 0.6, 0.005),
        RunSpec("resolution", "finest_in_15s", "finest_dambreak",
                {"h_over_dp": [10, 20, 30, 40, 60], "probe_steps": 5}, 0.6, 0.01,
                max_wall_s=15.0),
    ]
    return specs


# ------------------------------------------------------------------------------------------------
# the sweep


def _dead_worker_record(spec: RunSpec, exc: BaseException, wall: float) -> dict[str, Any]:
    record = _base_record(spec)
    record["status"] = "error"
    record["message"] = f"worker process died: {type(exc).__name__}: {exc}"
    record["wall_s"] = wall
    return record


def run_matrix(
    specs: Sequence[RunSpec],
    jobs: int = 1,
    progress: bool = True,
    on_record: Callable[[dict[str, Any]], None] | None = None,
) -> list[dict[str, Any]]:
    """Run ``specs``, each in a fresh process, at most ``jobs`` at a time; records in spec order.

    Each run gets its own single-worker :class:`~concurrent.futures.ProcessPoolExecutor`
    (``spawn`` start method: a clean interpreter, no inherited threads): a run that kills its
    process (a segfault, an abort) breaks only its own pool and is recorded as ``error``.
    A worker still busy ``max_wall_s + 120`` s after its start is terminated and recorded as
    ``timeout``. ``on_record`` is called with each record as it arrives (e.g. to save partial
    results).
    """
    from tqdm import tqdm

    if jobs < 1:
        raise ValueError(f"jobs: must be at least 1, got {jobs}")
    names = [s.name for s in specs]
    if len(set(names)) != len(names):
        raise ValueError("specs: run names must be unique")
    context = multiprocessing.get_context("spawn")
    pending = list(enumerate(specs))
    Running = tuple[int, RunSpec, cf.ProcessPoolExecutor, float]  # index, spec, pool, start
    running: dict[cf.Future[dict[str, Any]], Running] = {}
    results: dict[int, dict[str, Any]] = {}
    bar = tqdm(total=len(specs), unit="run", disable=not progress, file=sys.stderr)
    try:
        while pending or running:
            while pending and len(running) < jobs:
                index, spec = pending.pop(0)
                pool = cf.ProcessPoolExecutor(max_workers=1, mp_context=context)
                future = pool.submit(execute, spec.as_dict())
                running[future] = (index, spec, pool, time.perf_counter())
            done, _ = cf.wait(list(running), timeout=5.0, return_when=cf.FIRST_COMPLETED)
            now = time.perf_counter()
            for future in list(running):
                index, spec, pool, started = running[future]
                if future not in done:
                    if now - started > spec.max_wall_s + 120.0:
                        _terminate(pool)
                        record = _base_record(spec)
                        record["status"] = "timeout"
                        record["message"] = f"worker terminated after {now - started:.0f} s"
                        record["wall_s"] = now - started
                        results[index] = record
                        del running[future]
                        bar.update(1)
                        if on_record:
                            on_record(record)
                    continue
                try:
                    record = future.result()
                except BaseException as exc:  # noqa: BLE001 - a dead worker is a result
                    record = _dead_worker_record(spec, exc, now - started)
                pool.shutdown(wait=True)
                results[index] = record
                del running[future]
                bar.set_postfix_str(f"{spec.name}: {record['status']}")
                bar.update(1)
                if on_record:
                    on_record(record)
    finally:
        for _, _, pool, _ in running.values():
            _terminate(pool)
        bar.close()
    return [results[i] for i in range(len(specs))]


def _terminate(pool: cf.ProcessPoolExecutor) -> None:
    """Stop a pool's worker now (the standard library has no public way before 3.14)."""
    processes = getattr(pool, "_processes", None) or {}
    for process in list(processes.values()):
        process.terminate()
    pool.shutdown(wait=False, cancel_futures=True)


# ------------------------------------------------------------------------------------------------
# report


def stable_region(records: Iterable[dict[str, Any]]) -> dict[float, dict[str, Any]]:
    """For each coefsound of the stiffness group: the CFL values run, those that failed, and the
    largest CFL up to which every run was stable (``None`` if even the smallest failed)."""
    by_cs: dict[float, list[tuple[float, str]]] = {}
    for r in records:
        if r["group"] != "stiffness":
            continue
        cs, cfl = float(r["params"]["coefsound"]), float(r["params"]["cfl"])
        by_cs.setdefault(cs, []).append((cfl, r["status"]))
    errors: dict[tuple[float, float], float | None] = {
        (float(r["params"]["coefsound"]), float(r["params"]["cfl"])): r["max_density_error"]
        for r in records if r["group"] == "stiffness"
    }
    out: dict[float, dict[str, Any]] = {}
    for cs, rows in sorted(by_cs.items()):
        rows.sort()
        limit = None
        for cfl, status in rows:
            if status != "stable":
                break
            limit = cfl
        accurate = [
            c for c, s in rows if s == "stable" and _within(errors[(cs, c)], DENSITY_TARGET)
        ]
        out[cs] = {
            "cfl_run": [c for c, _ in rows],
            "not_stable": [c for c, s in rows if s != "stable"],
            "stable_up_to": limit,
            "density_within_target": accurate,
        }
    return out


def _within(error: float | None, limit: float) -> bool:
    """True when a measured error is known and at most ``limit`` (``None``: not measured)."""
    return error is not None and error <= limit


def _fmt(value: Any, spec: str = ".3g") -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        if not math.isfinite(value):
            return str(value)
        return format(value, spec)
    return str(value)


def _outcome(r: dict[str, Any]) -> str:
    if r["status"] == "failed":
        return f"failed: {r['kind']} at t = {_fmt(r['time'], '.3f')} s (step {r['step']})"
    if r["status"] in ("error", "timeout"):
        return f"{r['status']}: {(r['message'] or '').splitlines()[0][:80]}"
    if not r.get("completed"):
        return f"stable to t = {_fmt(r['sim_time'], '.3f')} s (wall budget)"
    return "stable"


Column = tuple[str, Callable[[dict[str, Any]], str]]
"""A report table column: its header and how to format a record's cell."""


def _table(records: list[dict[str, Any]], columns: list[Column]) -> list[str]:
    lines = ["| " + " | ".join(c for c, _ in columns) + " |",
             "| " + " | ".join("---" for _ in columns) + " |"]
    for r in records:
        lines.append("| " + " | ".join(fn(r) for _, fn in columns) + " |")
    return lines


def _common_columns() -> list[tuple[str, Callable[[dict[str, Any]], str]]]:
    return [
        ("outcome", _outcome),
        ("max abs(rho/rho0 - 1)", lambda r: _fmt(r["max_density_error"])),
        ("energy drift", lambda r: _fmt(r["energy_drift"], "+.3f")),
        ("particles", lambda r: _fmt(r["n_particles"])),
        ("steps", lambda r: _fmt(r["steps"])),
        ("t reached [s]", lambda r: _fmt(r["sim_time"], ".3f")),
        ("wall [s]", lambda r: _fmt(r["wall_s"], ".1f")),
    ]


def heat_map(records: list[dict[str, Any]], path: Path) -> Path | None:
    """coefsound x CFL coloured by outcome, annotated with the max density error [%];
    ``None`` if there are no stiffness runs."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    runs = [r for r in records if r["group"] == "stiffness"]
    if not runs:
        return None
    css = sorted({float(r["params"]["coefsound"]) for r in runs})
    cfls = sorted({float(r["params"]["cfl"]) for r in runs})
    codes = {"stable": 0, "failed": 1, "error": 2, "timeout": 2}
    grid = np.full((len(css), len(cfls)), np.nan)
    fig, ax = plt.subplots(figsize=(1.3 * len(cfls) + 2.5, 0.9 * len(css) + 2.0))
    colours = ListedColormap(["#7fc97f", "#f0027f", "#bbbbbb"])
    for r in runs:
        i = css.index(float(r["params"]["coefsound"]))
        j = cfls.index(float(r["params"]["cfl"]))
        grid[i, j] = codes[r["status"]]
        err = r["max_density_error"]
        label = "-" if err is None else f"{100 * err:.2g} %"
        if r["status"] == "failed":
            label += f"\n{r['kind']}\nt={r['time']:.2f} s"
        ax.text(j, i, label, ha="center", va="center", fontsize=7)
    ax.imshow(np.ma.masked_invalid(grid), cmap=colours, vmin=0, vmax=2, origin="lower",
              aspect="auto")
    ax.set_xticks(range(len(cfls)), [f"{c:g}" for c in cfls])
    ax.set_yticks(range(len(css)), [f"{c:g}" for c in css])
    ax.set_xlabel("CFL number")
    ax.set_ylabel("coefsound (c0 / sqrt(g H))")
    ax.set_title("2D dam break: outcome and max |rho/rho0 - 1|")
    ax.legend(handles=[Patch(color="#7fc97f", label="stable"),
                       Patch(color="#f0027f", label="failed (monitor)"),
                       Patch(color="#bbbbbb", label="error / timeout")],
              loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_report(
    records: list[dict[str, Any]], directory: str | Path, meta: dict[str, Any]
) -> Path:
    """Write ``README.md`` and ``stiffness_heatmap.png`` into ``directory``; returns the README.

    ``meta``: ``command``, ``wall_s`` and anything else to print under "How it was run".
    """
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    png = heat_map(records, out / "stiffness_heatmap.png")
    counts = {s: sum(r["status"] == s for r in records) for s in STATUSES}
    lines = [
        "# Stress matrix: stiff and extreme runs",
        "",
        f"Produced by `{meta.get('command', 'watersim stress')}` (watersim "
        f"{meta.get('version', '?')}); {len(records)} runs: "
        + ", ".join(f"{n} {s}" for s, n in counts.items() if n) + ".",
        "",
        "A run is *stable* when it reached its end time, *failed* when a stability monitor "
        "stopped it (the kind, time and step are given), *error* for any other exception or "
        "a dead worker. The density error is max |rho/rho0 - 1| over the fluid particles at "
        "the samples (every `sample_every` of simulated time, and the final state). The energy "
        "drift is (E_end - E_0) / P_0, E the fluid's kinetic plus potential energy and P_0 its "
        "initial potential energy above the tank floor (negative: dissipated); it is not given "
        "for flume runs, where the paddle works on the fluid.",
        "",
        "## How it was run",
        "",
    ]
    for key, value in meta.items():
        lines.append(f"- {key}: {value}")
    lines.append("")
    for group in GROUPS:
        runs = [r for r in records if r["group"] == group]
        if not runs:
            continue
        lines += [f"## {group}", ""]
        if group == "stiffness":
            lines += _stiffness_section(runs, png)
        elif group == "dissipation":
            cols = [("alpha", lambda r: _fmt(r["params"]["viscosity"]["alpha"])),
                    ("diffusion", lambda r: str(r["params"].get("diffusion")))]
            lines += _table(runs, cols + _common_columns())
        elif group == "long":
            lines += _long_section(runs)
        elif group == "resolution":
            lines += _resolution_section(runs)
        else:
            cols = [("run", lambda r: r["name"]), ("dp [m]", lambda r: _fmt(r["dp"]))]
            lines += _table(runs, cols + _common_columns())
            notes = [(r["name"], n) for r in runs for n in r["notes"]]
            if notes:
                lines += ["", "Warnings raised while building:", ""]
                lines += [f"- {name}: {n}" for name, n in notes]
        lines.append("")
    readme = out / "README.md"
    write_text_atomic(readme, "\n".join(lines).rstrip() + "\n")
    return readme


def _stiffness_section(runs: list[dict[str, Any]], png: Path | None) -> list[str]:
    first = runs[0]
    dp = first["dp"]
    lines = [
        f"2D dam break (1 m x 2 m column, 4 m tank, dp = {_fmt(dp)} m, "
        f"{_fmt(first['n_particles'])} particles) to t = {first['until']:g} s, for each "
        "coefsound (c0 = coefsound sqrt(g H)) and CFL number.",
        "",
        "Stable region:",
        "",
    ]
    for cs, row in stable_region(runs).items():
        if row["stable_up_to"] is None:
            text = f"not stable at any CFL run ({', '.join(f'{c:g}' for c in row['cfl_run'])})"
        else:
            text = f"stable for CFL <= {row['stable_up_to']:g}"
            above = [c for c in row["not_stable"] if c > row["stable_up_to"]]
            if above:
                text += f" (not stable at CFL {', '.join(f'{c:g}' for c in above)})"
        within = row["density_within_target"]
        text += (f"; max density error <= {100 * DENSITY_TARGET:g} % at CFL "
                 f"{', '.join(f'{c:g}' for c in within)}" if within else
                 f"; max density error above {100 * DENSITY_TARGET:g} % at every CFL")
        lines.append(f"- coefsound {cs:g}: {text}")
    lines.append("")
    if png is not None:
        lines += [f"![coefsound x CFL]({png.name})", ""]
    cols = [("coefsound", lambda r: _fmt(r["params"]["coefsound"])),
            ("CFL", lambda r: _fmt(r["params"]["cfl"]))]
    return lines + _table(runs, cols + _common_columns())


def _long_section(runs: list[dict[str, Any]]) -> list[str]:
    def sw(key: str, spec: str) -> Callable[[dict[str, Any]], str]:
        return lambda r: _fmt((r.get("still_water") or {}).get(key), spec)

    cols = [
        ("run", lambda r: r["name"]),
        ("dp [m]", lambda r: _fmt(r["dp"])),
        ("outcome", _outcome),
        ("surface drift [m]", sw("surface_drift_m", "+.2e")),
        ("surface drift / dp", sw("surface_drift_over_dp", "+.3f")),
        ("max spurious speed / sqrt(g d)", sw("max_speed_over_sqrt_gd", ".3g")),
        ("final speed / sqrt(g d)", sw("final_speed_over_sqrt_gd", ".3g")),
        ("max abs(rho/rho0 - 1)", lambda r: _fmt(r["max_density_error"])),
        ("energy drift", lambda r: _fmt(r["energy_drift"], "+.2e")),
        ("steps", lambda r: _fmt(r["steps"])),
        ("wall [s]", lambda r: _fmt(r["wall_s"], ".1f")),
    ]
    return [
        "Still water (2D tank) held for the whole run: the free surface (mean over the middle "
        "half of the tank of the highest particle per dp-wide column, plus dp/2) should not "
        "move and the fluid should stay at rest.",
        "",
        *_table(runs, cols),
    ]


def _resolution_section(runs: list[dict[str, Any]]) -> list[str]:
    cols = [("run", lambda r: r["name"]), ("dp [m]", lambda r: _fmt(r["dp"])),
            ("H/dp", lambda r: _fmt(2.0 / r["dp"] if r["dp"] else None, ".0f"))]
    lines = _table(runs, cols + _common_columns())
    for r in runs:
        if r.get("sizing"):
            lines += ["", f"Sizing of `{r['name']}` (wall budget {r.get('max_wall_s', '?')} s; "
                      "cost of a few steps, then the estimated run to the end time):", "",
                      "| H/dp | dp [m] | particles | wall per step [s] | dt [s] | estimate [s] |",
                      "| --- | --- | --- | --- | --- | --- |"]
            for s in r["sizing"]:
                lines.append(f"| {s['h_over_dp']} | {_fmt(s['dp'])} | {s['n_particles']} | "
                             f"{s['wall_per_step_s']:.3g} | {s['dt_s']:.3g} | "
                             f"{s['estimated_run_s']:.3g} |")
    return lines


def write_json(path: str | Path, records: list[dict[str, Any]], meta: dict[str, Any]) -> Path:
    """``{"meta": ..., "runs": [records]}`` as JSON (non-finite numbers as null)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    write_json_atomic(path, {"meta": meta, "runs": records}, indent=1)
    return path


def machine_info() -> dict[str, Any]:
    """CPUs, load average and Python, for the report."""
    info: dict[str, Any] = {"python": platform.python_version(), "cpus": os.cpu_count()}
    try:
        info["load_average_1_5_15min"] = [round(x, 2) for x in os.getloadavg()]
    except OSError:  # pragma: no cover - not Unix
        pass
    return info


# ------------------------------------------------------------------------------------------------
# the command


def cmd_stress(args: Any) -> int:
    """``watersim stress``: run the matrix, write the JSON and the report; exit 0 unless a run
    ended in ``error`` or ``timeout`` (unstable runs are results, not errors)."""
    from ._version import __version__

    specs = quick_matrix() if args.quick else full_matrix()
    if args.group:
        unknown = sorted(set(args.group) - set(GROUPS))
        if unknown:
            raise CliError(f"--group: unknown group(s) {', '.join(unknown)}; valid: "
                             f"{', '.join(GROUPS)}")
        specs = [s for s in specs if s.group in args.group]
    if args.jobs < 1:
        raise CliError(f"--jobs: must be at least 1, got {args.jobs}")
    command = "watersim stress" + (" --quick" if args.quick else "")
    command += "".join(f" --group {g}" for g in args.group or [])
    command += f" --jobs {args.jobs}" if args.jobs != 1 else ""
    started = time.strftime("%Y-%m-%d %H:%M:%S %Z")
    meta: dict[str, Any] = {"command": command, "version": __version__, "started": started,
                            "jobs": args.jobs,
                            "threads_per_run": os.environ.get("RAYON_NUM_THREADS", "1"),
                            "machine_at_start": machine_info()}
    t0 = time.perf_counter()
    partial: list[dict[str, Any]] = []

    def save_partial(record: dict[str, Any]) -> None:
        partial.append(record)
        if args.json:
            write_json(args.json, partial, {**meta, "partial": True})

    records = run_matrix(specs, jobs=args.jobs, progress=not args.quiet, on_record=save_partial)
    meta["wall_s"] = round(time.perf_counter() - t0, 1)
    meta["cpu_s_of_runs"] = round(sum(r["wall_s"] or 0.0 for r in records), 1)
    meta["machine_at_end"] = machine_info()
    if args.json:
        write_json(args.json, records, meta)
    if args.report:
        write_report(records, args.report, meta)
    if not args.quiet:
        for r in records:
            print(f"{r['group']:>11} {r['name']:<24} {_outcome(r)}  "
                  f"max|drho|={_fmt(r['max_density_error'])}  wall {_fmt(r['wall_s'], '.1f')} s")
        for cs, row in stable_region(records).items():
            print(f"coefsound {cs:g}: stable for CFL <= {row['stable_up_to']}")
    return 1 if any(r["status"] in ("error", "timeout") for r in records) else 0


def add_parser(sub: Any) -> None:
    """Register ``watersim stress`` on the CLI's sub-parsers."""
    p = sub.add_parser("stress", help="run the matrix of stiff and extreme cases")
    p.add_argument("--quick", action="store_true",
                   help="reduced matrix (about 2 minutes on 2 cores with --jobs 2)")
    p.add_argument("--json", metavar="FILE", help="write the run records as JSON")
    p.add_argument("--report", metavar="DIR", help="write README.md and the heat map into DIR")
    p.add_argument("--jobs", type=int, default=1, metavar="N",
                   help="runs at a time, each in its own process (default 1)")
    p.add_argument("--group", action="append", metavar="GROUP",
                   help=f"only this group (repeatable): {', '.join(GROUPS)}")
    p.add_argument("--quiet", action="store_true", help="no progress bar or summary")
    p.set_defaults(func=cmd_stress)
