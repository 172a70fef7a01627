"""The validation cases: each builds its scene from the existing builders at a resolution, runs
it, and measures its errors against a reference.

A case's ``run(resolution, quick=False, progress=False)`` returns a run record (a JSON-ready
dict, see :func:`make_record`). ``resolution`` is a number of particles per characteristic
length of the case (``Case.resolution_meaning``: the column width over dp for dam breaks, the
wave height over dp for waves, the depth over dp for the still tank), so ``dp = length /
resolution`` (for the wave flumes snapped to ``depth / round(depth / dp)``, a whole number of
particle layers: :meth:`Case.dp`). ``quick`` shortens the simulated time where the metric allows
it (tank2d, the dam breaks, standing2d, bar2d, kimmoun2d, absorption2d); flume2d,
secondorder2d and solitary2d keep theirs, already the shortest their metrics need, and run only
at their coarse quick resolution.

References (see ``watersim/data/SOURCES.md``): Martin & Moyce (1952) dam-break front; linear
theory and Stokes third-order dispersion; Beji & Battjes (1993) bar records; Synolakis (1987)
run-up law; seed 001 (Roselli et al.) for Kimmoun & Branger (2007) breaking; for active
absorption (absorption2d), the paddle's own wave measured before the first reflection returns.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from .. import analysis as an
from .. import numerics as nm
from .. import wave_theory as wt
from .._core import InstabilityError, SceneError
from ..checks import _positive
from ..flume import (
    DampingZone,
    ElevationGauge,
    Flap,
    Flume,
    FlumeScene,
    FlumeSimulation,
    Piston,
    RegularWave,
    SolitaryWave,
    TabulatedMotion,
    lattice_dp,
)
from ..flume_cases import BEJI_BATTJES_FILES, _load_csv, flume_builder
from ..measure import MARTIN_MOYCE_SETS, front_error, front_position, water_column_height
from ..runrecord import VALIDATION_FIELDS, run_record, stop_status
from ..scenes import DamBreak, Tank
from ..simulation import Simulation
from . import metrics as m

__all__ = ["CASES", "Case", "StandingWaveTank", "make_record", "run_case"]


# ------------------------------------------------------------------------------------------------
# running


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


# ------------------------------------------------------------------------------------------------
# Case


@dataclass(frozen=True)
class Case:
    """A validation case.

    Attributes:
        name: the case's name (``watersim validate NAME``).
        description: one line.
        reference: where the reference comes from.
        resolution_meaning: what the resolution counts, e.g. ``"column width / dp"``.
        length: the characteristic length [m]: ``dp = length / resolution`` (snapped for the
            wave flumes, see ``depth``).
        resolutions: the full sweep's resolutions.
        quick_resolutions: the ``--quick`` sweep's resolutions.
        primary: the metric the accuracy target applies to.
        target: the accuracy target of ``primary`` (an error at most this large meets it).
        target_text: the target in words, for the report.
        runner: ``runner(case, resolution, quick, progress) -> record``.
        report_note: what the report should say about the case's metrics.
        report_details: keys of the records' ``details`` the report tabulates.
        depth: a wave flume's still-water depth [m], which dp must divide (:meth:`dp`); ``None``
            for the other cases.
        modules: optional packages (not WaterSim's own dependencies) the case imports, checked
            before a sweep starts.
        figure: ``figure(runs, path)`` draws the case's own measurements from its run records
            into ``path`` (a PNG), shown in the report under the error plots; ``None``: none.
    """

    name: str
    description: str
    reference: str
    resolution_meaning: str
    length: float
    resolutions: tuple[float, ...]
    quick_resolutions: tuple[float, ...]
    primary: str
    target: float
    target_text: str
    runner: Callable[[Case, float, bool, bool], dict[str, Any]]
    report_note: str = ""
    report_details: tuple[str, ...] = ()
    depth: float | None = None
    modules: tuple[str, ...] = ()
    figure: Callable[[Sequence[Mapping[str, Any]], Path], None] | None = None

    def dp(self, resolution: float) -> float:
        """Particle spacing [m] of a resolution: ``length / resolution``, for a wave flume
        snapped to ``depth / round(depth / dp)`` (:func:`~watersim.flume.lattice_dp`): the core
        fills the water with whole particle layers, so only such a dp gives the flume the depth
        its wave theory and paddle law are computed for (the resolution is then nominal, the
        actual ``length / dp`` within half a layer's share of it)."""
        dp = self.length / resolution
        return dp if self.depth is None else lattice_dp(self.depth, dp)

    def run(self, resolution: float, quick: bool = False, progress: bool = False) -> dict[str, Any]:
        """Run the case at ``resolution``; returns the run record (never raises for a failed
        simulation: the record's ``status`` says what happened)."""
        return run_case(self.name, resolution, quick, progress)


def run_case(name: str, resolution: float, quick: bool = False, progress: bool = False
             ) -> dict[str, Any]:
    """Run case ``name`` at ``resolution``: the run record (a module-level function, so that it
    pickles for process pools and Dask workers).

    Raises:
        ValueError: unknown case or a resolution that is not a positive number.
    """
    if name not in CASES:
        raise ValueError(f"case: unknown validation case {name!r}; known: {', '.join(CASES)}")
    case = CASES[name]
    _positive("resolution", resolution)
    clock = _Clock()
    try:
        return case.runner(case, float(resolution), quick, progress)
    except (SceneError, ValueError, RuntimeError, FloatingPointError) as exc:
        # a case that cannot be built or measured at this resolution is a result, not a crash
        return make_record(name, resolution, case.dp(resolution), None, clock.wall(), clock.cpu(),
                           "error", f"{type(exc).__name__}: {exc}", {}, {})


# ------------------------------------------------------------------------------------------------
# still-water tank


def _run_tank(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """Still water, 2D, 1.0 m x 0.5 m deep (the ``Tank`` defaults), run for 1 s (0.5 s quick).
    Pressure interpolated on the vertical line x = l/2 every dp/2 from dp/2 to d - dp/2."""
    dp = case.dp(res)
    until = 0.5 if quick else 1.0
    builder = Tank(dim=2, dp=dp, until=until)
    assert builder.depth is not None and builder.length is not None
    clock = _Clock()
    sim = builder.build()
    status, message = advance(sim, until, until / 20.0, progress=progress,
                              label=f"{case.name} {res:g}")
    depth, g, rho0 = builder.depth, builder.g, builder.core_value("rho0")
    z = np.arange(0.5 * dp, depth - 0.5 * dp + 1e-9, 0.5 * dp)
    pts = np.column_stack([np.full_like(z, 0.5 * builder.length), z])
    p = sim.interpolate(pts)["pressure"]
    rms, worst = m.hydrostatic_pressure_error(z, p, depth, rho0, g)
    v = m.spurious_velocity(sim.fluid_velocities(), depth, g)
    x, top = m.surface_profile(sim.fluid_positions(), dp, 0.0, builder.length)
    details = {"depth": depth, "length": builder.length, "until": until,
               "surface_mean_minus_depth": float(np.mean(top) - depth),
               "pressure_rms_over_rho_g_d": rms, "pressure_max_over_rho_g_d": worst,
               "max_speed_over_sqrt_gd": v}
    errors = {"pressure_rms": rms, "pressure_max": worst, "spurious_velocity": v}
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


# ------------------------------------------------------------------------------------------------
# dam breaks


def _front_errors(t: list[float], x: list[float], width: float, g: float, x_max: float
                  ) -> tuple[dict[str, float | None], dict[str, Any]]:
    """Raw and best-shift front errors against Martin & Moyce (lethe set)."""
    errors: dict[str, float | None] = {}
    details: dict[str, Any] = {"reference": "lethe"}
    try:
        raw = front_error(t, x, width, g, x_max=x_max)
    except ValueError as exc:
        details["note"] = str(exc)
        return {"front_rms": None}, details
    errors["front_rms"] = raw.rms_rel_error
    errors["front_max"] = raw.max_rel_error
    details.update(mean_rel_error=raw.mean_rel_error, mean_lead_s=raw.mean_lead_s,
                   n_points=raw.n_points, t_max_s=raw.t_max_s)
    try:
        shifted = m.front_error_best_shift(t, x, width, g, x_max=x_max)
        errors["front_rms_shifted"] = shifted.rms_rel_error
        details.update(best_shift_s=shifted.shift_s, n_points_shifted=shifted.n_points)
    except ValueError as exc:
        details["note_shifted"] = str(exc)
    return errors, details


def _height_errors(t: list[float], h: list[float], width: float, g: float,
                   front_shift: float | None) -> tuple[dict[str, float | None], dict[str, Any]]:
    """Residual column height against Martin & Moyce (n^2 = 2), unshifted; and, as a labelled
    diagnostic in ``details`` only, after the front's best shift (does one delay explain both?)."""
    try:
        raw = m.column_height_error(t, h, width, g)
    except ValueError as exc:
        return {"height_rms": None}, {"note_height": str(exc)}
    details: dict[str, Any] = {"height_mean_rel_error": raw.mean_rel_error,
                               "height_n_points": raw.n_points, "height_t_max_s": raw.t_max_s}
    if front_shift is not None:
        try:
            details["height_rms_at_front_shift"] = m.column_height_error(
                t, h, width, g, shift=front_shift).rms_rel_error
        except ValueError as exc:
            details["note_height_shifted"] = str(exc)
    return {"height_rms": raw.rms_rel_error, "height_max": raw.max_rel_error}, details


def _run_dambreak(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """Martin & Moyce column (width 1 m, height 2 m). 2D: the ``DamBreak`` defaults (tank 4 m),
    to 0.7 s (0.4 s quick). 3D: a narrow tank (width 0.5 m) 3 m long, to 0.6 s (0.4 s quick).
    Front and (2D) residual column height at the back wall sampled every 0.01 s."""
    dp = case.dp(res)
    dim = 3 if case.name.endswith("3d") else 2
    if dim == 2:
        builder = DamBreak(dim=2, dp=dp, until=0.4 if quick else 0.7)
    else:
        builder = DamBreak(dim=3, dp=dp, tank_length=3.0, tank_width=0.5,
                           until=0.4 if quick else 0.6)
    until = float(builder.until)  # type: ignore[arg-type]
    clock = _Clock()
    sim = builder.build()
    times: list[float] = []
    fronts: list[float] = []
    heights: list[float] = []

    def sample(s: Simulation) -> None:
        pos = s.fluid_positions()
        times.append(s.time)
        fronts.append(front_position(pos, dp))
        if dim == 2:
            heights.append(water_column_height(pos, dp))

    status, message = advance(sim, until, 0.01, sample, progress, f"{case.name} {res:g}")
    errors, details = _front_errors(times, fronts, builder.width, builder.g,
                                    builder.tank_length)
    if dim == 2:
        # dambreak3d keeps its lethe front metrics only (its committed runs predate these)
        # the same front against the two independent PySPH digitisations of the paper's Fig. 3
        for name in MARTIN_MOYCE_SETS:
            if name != "lethe":
                try:
                    details[f"front_rms_{name}"] = front_error(
                        times, fronts, builder.width, builder.g, name,
                        builder.tank_length).rms_rel_error
                except ValueError:
                    details[f"front_rms_{name}"] = None
        h_err, h_details = _height_errors(times, heights, builder.width, builder.g,
                                          details.get("best_shift_s"))
        errors.update(h_err)
        details.update(h_details)
    details.update(until=until, tank_length=builder.tank_length,
                   tank_width=builder.tank_width, front_final=fronts[-1] if fronts else None,
                   front_t=times, front_x=fronts)
    if dim == 2:
        details["height_h"] = heights
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


# ------------------------------------------------------------------------------------------------
# standing wave


@dataclass(frozen=True, kw_only=True)
class StandingWaveTank(Tank):
    """A closed 2D tank whose still water starts with the surface ``d + a cos(pi x / l)``.

    The core fills fluid *boxes*, so the surface is built from one box per lattice column,
    each as high as the cosine at the column's centre rounded to a whole dp (the particles of a
    box then reach exactly its top, which is also the level the core's hydrostatic initial
    density is measured from). The rounding makes a staircase; the amplitude of the first
    mode actually present is measured from the particles (:func:`metrics.surface_profile`).

    Attributes:
        amplitude: a [m], the first mode's amplitude (``eta = a cos(pi x / l)``).
    """

    _DIM_DEFAULTS: ClassVar[Mapping[int, Mapping[str, Any]]] = {
        2: {"dp": 0.025, "until": 3.0, "length": 1.0, "depth": 0.5, "height": 0.8,
            **nm.VERIFICATION},  # a Tank's numerics: this map replaces Tank's own
    }
    amplitude: float = 0.05

    def _validate_geometry(self) -> None:
        if self.dim != 2:
            raise SceneError("dim: the standing-wave tank is 2D only")
        super()._validate_geometry()
        a = _positive("amplitude", self.amplitude)
        assert self.depth is not None and self.height is not None
        if a >= self.depth:
            raise SceneError(f"amplitude: {a:g} m must be smaller than the depth {self.depth:g} m")
        if self.depth + a > self.height:
            raise SceneError(f"amplitude: the crest ({self.depth + a:g} m) is above the walls "
                             f"(height = {self.height:g} m)")

    def _geometry(self) -> dict[str, Any]:
        assert self.length is not None and self.depth is not None and self.dp is not None
        geometry = super()._geometry()
        n = int(math.floor(self.length / self.dp + 1e-9))
        k = math.pi / self.length
        boxes = []
        for i in range(n):
            xc = (i + 0.5) * self.dp
            top = self.dp * round((self.depth + self.amplitude * math.cos(k * xc)) / self.dp)
            # widened by 1e-6 dp on each side: the core refuses a box narrower than dp, which
            # (i + 1) dp - i dp can be in floating point; no other column's centre is inside
            eps = 1e-6 * self.dp
            x0, x1 = max(i * self.dp - eps, 0.0), min((i + 1) * self.dp + eps, self.length)
            boxes.append({"min": [x0, 0.0], "max": [x1, top]})
        geometry["fluid"] = boxes
        return geometry


def _run_standing(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """First sloshing mode of a 1.0 m tank, d = 0.5 m (kd = pi/2), a = 0.05 m (H = 0.1 m);
    2.5 periods (1.5 quick); surface sampled every T/40, mode amplitude fitted by a damped
    cosine."""
    dp = case.dp(res)
    length, depth, a = 1.0, 0.5, 0.5 * case.length
    period = m.standing_wave_period(length, depth)
    until = (1.5 if quick else 2.5) * period
    builder = StandingWaveTank(dp=dp, length=length, depth=depth, amplitude=a, until=until)
    clock = _Clock()
    sim = builder.build()
    times: list[float] = []
    amps: list[float] = []

    def sample(s: Simulation) -> None:
        x, top = m.surface_profile(s.fluid_positions(), dp, 0.0, length)
        times.append(s.time)
        amps.append(m.standing_wave_mode_amplitude(x, top, length))

    status, message = advance(sim, until, period / 40.0, sample, progress,
                              f"{case.name} {res:g}")
    details: dict[str, Any] = {"period_linear": period, "amplitude_design": a,
                               "amplitude_initial": amps[0] if amps else None, "until": until,
                               "t": times, "mode_amplitude": amps}
    errors: dict[str, float | None] = {"period": None, "decay_per_period": None}
    if len(times) >= 8:
        fit = m.damped_oscillation_fit(times, amps, 2.0 * math.pi / period)
        details.update(period_simulated=fit.period, decay_rate=fit.decay,
                       log_decrement=fit.log_decrement, amplitude_fit=fit.amplitude)
        errors["period"] = m.relative_error(fit.period, period)
        errors["decay_per_period"] = abs(1.0 - math.exp(-fit.log_decrement))
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


# ------------------------------------------------------------------------------------------------
# regular waves in a flat flume


def _phases(sim: FlumeSimulation, scene: FlumeScene, names: list[str]) -> dict[str, float]:
    """First-harmonic phase [rad] of each named gauge over its steady part (the window of
    :func:`watersim.flume.analyse_flume`: ramp + arrival + one period, to the end)."""
    t, eta, _ = sim.gauges.uniform()
    period = scene.law.period
    assert period is not None
    out: dict[str, float] = {}
    for j, name in enumerate(sim.gauges.names):
        if name not in names:
            continue
        t0 = scene.law.ramp_duration + scene.arrival_time(float(sim.gauges.x[j])) + period
        sel = t >= t0
        if np.count_nonzero(sel) < 4 or t[-1] - t0 < period:
            continue
        h = an.harmonic_analysis(eta[sel, j], t[sel], period, 1)
        out[name] = float(h.phases[0])
    return out


def _flume_run(case: Case, scene: FlumeScene, res: float, progress: bool, label: str
               ) -> tuple[FlumeSimulation, str, str | None, dict[str, Any]]:
    """Build and run a flume scene; returns the simulation, status, message and analysis."""
    sim = scene.build()
    until = float(scene.until)  # type: ignore[arg-type]
    status, message = advance(sim, until, max(until / 50.0, 1e-3), None, progress, label)
    return sim, status, message, sim.analyse()


FLUME2D_HEIGHT = 0.1
"""Wave height of the flume2d validation case [m]: the built-in flume2d (d = 0.3 m, T = 1.2 s,
L = 1.77 m) with H = 0.1 m (H/L = 0.056, H/d = 0.33, within Stokes' second order), twice the
built-in's 0.05 m so that H/dp = 10 costs dp = 0.01 m (about 30,000 particles), not 0.005 m."""

def _flume2d_items(dp: float, order: int) -> tuple[FlumeScene, list[str]]:
    """flume2d with H = :data:`FLUME2D_HEIGHT` at dp, until = ramp + arrival at 3 L +
    3.5 periods (2.5 periods of steady record at 3 L; the same with ``quick``, which the
    height at 3 L needs)."""
    items = {"dp": repr(dp), "paddle.order": str(order), "wave.height": repr(FLUME2D_HEIGHT)}

    def until(s: FlumeScene) -> float:
        assert s.period is not None and s.wavelength is not None
        return s.law.ramp_duration + s.arrival_time(3.0 * s.wavelength) + 3.5 * s.period

    return _with_until("flume2d", items, until)


def _run_flume2d(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    dp = case.dp(res)
    scene, notes = _flume2d_items(dp, 2)
    clock = _Clock()
    sim, status, message, result = _flume_run(case, scene, res, progress, f"{case.name} {res:g}")
    assert scene.period is not None and scene.wavelength is not None
    wl, period, height = scene.wavelength, scene.period, case.length
    depth = scene.flume.depth
    resolved = scene.resolved_scene()
    by_x = {round(g["x"] / wl, 2): g for g in result["gauges"]}
    errors: dict[str, float | None] = {}
    details: dict[str, Any] = {"wavelength_linear": wl, "H_target": height, "notes": notes,
                               "numerics": {k: resolved[k] for k in (
                                   "coefh", "coefsound", "viscosity", "diffusion",
                                   "integrator", "cfl")},
                               "analysis_notes": result.get("notes", [])}
    # every gauge, sorted by x: the height along the flume (docs/wave-flume.md's figure)
    gauges = sorted(result["gauges"], key=lambda g: g["x"])
    details["gauges"] = [{k: g.get(k) for k in ("name", "x", "H_mean", "H_min", "H_max",
                                                 "n_waves", "T_mean", "mean_level",
                                                 "harmonics", "window")} for g in gauges]
    heights = {}
    for n in (1.0, 2.0, 3.0):
        g = by_x.get(n)
        if g is not None and g.get("H_mean") is not None:
            heights[n] = g["H_mean"]
            details[f"H_{n:g}L"] = g["H_mean"]
    for n in (1.0, 2.0, 3.0):
        errors[f"H_{n:g}L"] = m.relative_error(heights[n], height) if n in heights else None
    if len(heights) >= 2:
        loss = m.height_loss_per_wavelength(np.array(list(heights)) * wl,
                                            np.array(list(heights.values())), wl)
        details["height_loss_per_wavelength"] = loss
        errors["height_loss_per_L"] = abs(loss)
    flat = [g["name"] for g in result["gauges"]]
    phases = _phases(sim, scene, flat)
    xs = [g["x"] for g in result["gauges"] if g["name"] in phases]
    if len(xs) >= 2:
        lw = m.wavelength_from_phases(xs, [phases[n] for n in phases], 2 * math.pi / wl)
        l3 = m.stokes3_wavelength(period, depth, height, scene.g)
        details.update(wavelength_measured=lw, wavelength_stokes3=l3)
        errors["wavelength_linear"] = m.relative_error(lw, wl)
        errors["wavelength_stokes3"] = m.relative_error(lw, l3)
    drift = _mean_level_drift(sim, scene, [by_x[n]["name"] for n in (1.0, 2.0, 3.0)
                                           if n in by_x])
    details["mwl"] = drift
    changes = [abs(c) for v in drift.values() if (c := v.get("change")) is not None]
    errors["mwl_drift"] = max(changes) / height if changes else None
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


def _mean_level_drift(sim: FlumeSimulation, scene: FlumeScene, names: list[str]
                      ) -> dict[str, dict[str, Any]]:
    """Per named gauge: the mean water level [m] over its steady part (the window of
    :func:`watersim.flume.analyse_flume`), its drift over that part (``slope`` [m/s],
    ``change`` [m], :func:`metrics.mean_level_drift`), and the still-water level just before
    the ramp's first wave arrives (``level_before`` [m], mean of the last period before
    arrival: the settling of the fluid on the floor, not the wave), and ``period_means`` [m]:
    the mean level of each whole period of the record from t = 0."""
    t, eta, _ = sim.gauges.uniform()
    period = scene.law.period
    assert period is not None
    out: dict[str, dict[str, Any]] = {}
    for j, name in enumerate(sim.gauges.names):
        if name not in names:
            continue
        x = float(sim.gauges.x[j])
        arrival = scene.arrival_time(x)
        t0 = scene.law.ramp_duration + arrival + period
        sel = t >= t0
        entry: dict[str, Any] = {"x": x, "mean": None, "slope": None, "change": None,
                                          "level_before": None}
        if np.count_nonzero(sel) >= 4:
            entry["mean"] = float(np.mean(eta[sel, j]))
            try:
                slope, change = m.mean_level_drift(eta[sel, j], t[sel], period)
                entry.update(slope=slope, change=change)
            except ValueError:
                pass  # fewer than two periods: no drift measured (None in the record)
        before = (t >= arrival - period) & (t < arrival)
        if arrival > period and np.count_nonzero(before) >= 2:
            entry["level_before"] = float(np.mean(eta[before, j]))
        # the whole record's per-period means from t = 0 (still water, wave front, steady part)
        per = max(1, round(period / float(t[1] - t[0]))) if t.size > 1 else 1
        n = t.size // per
        entry["period_means"] = [float(v) for v in eta[: n * per, j].reshape(n, per).mean(axis=1)]
        out[name] = entry
    return out


SECOND_ORDER_WAVE: dict[str, float] = {"depth": 0.2, "period": 1.4, "height": 0.045}
"""The wave of secondorder2d: d = 0.2 m, T = 1.4 s (L = 1.83 m, kd = 0.69), H = 0.045 m
(H/d = 0.225). At this kd a first-order piston sheds a strong free second harmonic: Madsen's
(1971) second-order stroke correction is 2.0 mm against a 66 mm stroke (at kd = 1.06, the
flume2d wave, it is 0.1 mm against 48 mm). H is the largest for which Stokes' second order is
valid (bound harmonic 5.4 mm, below a quarter of the first, H/8 = 5.6 mm); the free harmonic
beats with the bound one over 2 pi / (k2 - 2 k) = 1.86 L."""

SECOND_ORDER_GAUGES_L: tuple[float, ...] = tuple(0.5 + 0.25 * j for j in range(9))
"""Gauge positions of secondorder2d [wavelengths]: 0.5 to 2.5 L every L/4, more than one beat
length (1.86 L) of a free second harmonic."""


def secondorder_scene(dp: float, order: int, **numerics: Any) -> FlumeScene:
    """The secondorder2d flume at ``dp`` with a piston of ``order`` (1 or 2).

    Flat flume 2.75 L + a 1 L damping zone; gauges every L/4 from 0.5 to 2.5 L; two-period
    ramp; until = ramp + arrival at 2.5 L + 3.5 periods (2.5 periods of steady record at
    2.5 L); the numerics of the built-in flume2d (coefsound 10, alpha
    :data:`~watersim.numerics.FLUME2D_ALPHA`, Verlet). ``numerics``: further
    :class:`~watersim.SceneBuilder` fields.
    """
    d, period, height = (SECOND_ORDER_WAVE[k] for k in ("depth", "period", "height"))
    wl = float(wt.wavelength(period, d))
    flume = Flume(length=round(3.75 * wl, 3), depth=d, damping=DampingZone(length=round(wl, 3)))
    gauges = [ElevationGauge(round(n * wl, 3)) for n in SECOND_ORDER_GAUGES_L]
    kwargs: dict[str, Any] = {**nm.FLUME_CASE, **nm.WAVE_CARRYING, **numerics}
    wave = RegularWave(height=height, period=period)
    paddle = Piston(order=order, ramp_periods=2.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # sizing only; the real scene below warns
        probe = FlumeScene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, dp=dp,
                           until=1.0, **kwargs)
    until = (probe.law.ramp_duration + probe.arrival_time(SECOND_ORDER_GAUGES_L[-1] * wl)
             + 3.5 * period)
    return FlumeScene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, dp=dp,
                      until=round(until, 2), **kwargs)


def _run_secondorder(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """The :data:`SECOND_ORDER_WAVE` flume twice, with a second- and a first-order piston:
    the spread of the second-harmonic amplitude over the nine gauges (0.5 to 2.5 L), against
    the Stokes bound amplitude of the target wave and of each gauge's own first harmonic."""
    dp = case.dp(res)
    clock = _Clock()
    errors: dict[str, float | None] = {}
    details: dict[str, Any] = {"wave": dict(SECOND_ORDER_WAVE)}
    status, message = "ok", None
    n_particles = steps = 0
    sim: FlumeSimulation | None = None
    for order in (2, 1):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            scene = secondorder_scene(dp, order)
        notes = [f"{w.category.__name__}: {w.message}" for w in caught]
        assert scene.wavelength is not None
        sim, st, msg, result = _flume_run(case, scene, res, progress,
                                          f"{case.name} {res:g} order {order}")
        n_particles = max(n_particles, sim.n_particles)
        steps += sim.steps
        if st != "ok" and status == "ok":
            status, message = st, f"order {order}: {msg}"
        k = 2.0 * math.pi / scene.wavelength
        depth = scene.flume.depth
        bound = float(wt.stokes2_second_harmonic_amplitude(SECOND_ORDER_WAVE["height"], k, depth))
        rows = [g for g in result["gauges"] if g.get("harmonics")
                and None not in g["harmonics"][:2]]
        a1 = [g["harmonics"][0] for g in rows]
        a2 = [g["harmonics"][1] for g in rows]
        details[f"x_order{order}"] = [g["x"] for g in rows]
        details[f"a1_order{order}"] = a1
        details[f"a2_order{order}"] = a2
        details[f"H_order{order}"] = [g.get("H_mean") for g in rows]
        details["a2_bound"] = bound
        details["wavelength"] = scene.wavelength
        details[f"stroke_order{order}"] = scene.law.stroke
        details[f"second_order_amplitude_order{order}"] = scene.law.second_order_amplitude
        details[f"until_order{order}"] = scene.until
        details[f"notes_order{order}"] = notes + result.get("notes", [])
        if len(a2) >= 2:
            errors[f"a2_spread_order{order}"] = m.harmonic_spread(a2, bound)
            errors[f"a2_local_spread_order{order}"] = m.harmonic_spread_local_bound(
                a1, a2, k, depth)
            errors[f"a2_mean_order{order}"] = m.relative_error(float(np.mean(a2)), bound)
    s1, s2 = errors.get("a2_local_spread_order1"), errors.get("a2_local_spread_order2")
    if s1 is not None and s2 is not None and s1 > 0.0:
        # the criterion: second-order generation at least halves the spread
        details["local_spread_ratio_2_over_1"] = s2 / s1
        errors["local_spread_ratio"] = s2 / s1
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details, n_sims=2, particles_total=n_particles,
                       steps_total=steps)


# ------------------------------------------------------------------------------------------------
# Beji & Battjes bar


def _measured_bar(period: float) -> dict[float, tuple[list[float], list[float]]]:
    """(amplitudes, phases) of the first three harmonics of each Beji & Battjes record."""
    out = {}
    for x, name in BEJI_BATTJES_FILES.items():
        t, eta = _load_csv(name)
        dt = (t[-1] - t[0]) / (t.size - 1)
        h = an.harmonic_analysis(eta, t[0] + dt * np.arange(t.size), period, 3)
        out[x] = ([float(v) for v in h.amplitudes], [float(v) for v in h.phases])
    return out


def _run_bar(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """bar2d (d = 0.4 m, H = 0.02 m, T = 2.02 s); until = ramp + arrival at x = 17.3 m +
    3 periods (quick: at x = 10.5 m), so the gauges up to 17.3 m (10.5 m) are compared."""
    dp = case.dp(res)

    def until(s: FlumeScene) -> float:
        assert s.period is not None
        return s.law.ramp_duration + s.arrival_time(10.5 if quick else 17.3) + 3.0 * s.period

    scene, notes = _with_until("bar2d", {"dp": repr(dp)}, until)
    clock = _Clock()
    sim, status, message, result = _flume_run(case, scene, res, progress, f"{case.name} {res:g}")
    assert scene.period is not None
    measured = _measured_bar(scene.period)
    names = [g["name"] for g in result["gauges"]]
    phases = {}
    t, eta, _ = sim.gauges.uniform()
    rows_sim, rows_ref, ph_sim, ph_ref, xs = [], [], [], [], []
    for g in result["gauges"]:
        ref = measured.get(round(g["x"], 1))
        if ref is None or not g.get("harmonics") or any(a is None for a in g["harmonics"]):
            continue
        t0 = g["window"][0]
        sel = t >= t0
        h = an.harmonic_analysis(eta[sel, names.index(g["name"])], t[sel], scene.period, 3)
        phases[g["name"]] = [float(v) for v in h.phases]
        rows_sim.append(g["harmonics"])
        rows_ref.append(ref[0])
        ph_sim.append(phases[g["name"]])
        ph_ref.append(ref[1])
        xs.append(g["x"])
    errors: dict[str, float | None] = {}
    details: dict[str, Any] = {"gauges_x": xs, "amplitudes_simulated": rows_sim,
                               "amplitudes_measured": rows_ref, "phases_simulated": ph_sim,
                               "phases_measured": ph_ref, "notes": notes,
                               "analysis_notes": result.get("notes", [])}
    if rows_sim:
        amp = m.harmonic_amplitude_errors(rows_sim, rows_ref, 0.5 * case.length)
        for n in range(3):
            errors[f"harmonic{n + 1}_amplitude"] = float(amp[n])
        if len(xs) >= 2:
            for n in range(3):
                errors[f"harmonic{n + 1}_phase"] = m.relative_phase_error(
                    [p[n] for p in ph_sim], [p[n] for p in ph_ref])
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


# ------------------------------------------------------------------------------------------------
# solitary wave run-up


SOLITARY_SLOPE = 1.0 / 3.0
"""Beach slope of the run-up case: steep enough that H/d = 0.15 does not break."""


def _run_solitary(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """solitary2d set up non-breaking: d = 0.3 m, H/d = 0.15 (H = 0.045 m), a 1:3 beach from
    x = 3 m, flume 4.8 m (walls d + d/2 = 0.45 m high, above the law's run-up of 0.137 m);
    until = half the paddle motion + travel to the shoreline + 1 s, the same with ``quick``."""
    dp = case.dp(res)
    assert case.depth is not None
    depth, height = case.depth, case.length
    items = {"dp": repr(dp), "wave.height": repr(height), "beach.slope": repr(SOLITARY_SLOPE),
             "beach.toe": "3.0", "flume.length": "4.8"}

    def until(s: FlumeScene) -> float:
        assert s.law.duration is not None and s.shoreline is not None
        c = float(wt.solitary_celerity(height, depth, s.g))
        # Goring's motion is symmetric about the crest's release at half its duration; the
        # run-up peaks within about a second of the crest reaching the shoreline
        return 0.5 * s.law.duration + s.shoreline / c + 1.0

    scene, notes = _with_until("solitary2d", items, until)
    clock = _Clock()
    sim, status, message, result = _flume_run(case, scene, res, progress, f"{case.name} {res:g}")
    law = float(wt.synolakis_runup(height, depth, SOLITARY_SLOPE)) * depth
    ru = result.get("runup") or {}
    runup = ru.get("max")
    t, _, r = sim.gauges.uniform()
    t_max = float(t[int(np.nanargmax(r))]) if r is not None and np.any(np.isfinite(r)) else None
    cot = 1.0 / SOLITARY_SLOPE
    details = {"runup_max": runup, "runup_law": law, "H_over_d": height / depth,
               "cot_beta": cot, "runup_ceiling": scene.tank_height - depth,
               "t_runup_max": t_max, "until": scene.until,
               "non_breaking_limit_H_over_d": 0.818 * cot ** (-10.0 / 9.0), "notes": notes,
               "analysis_notes": result.get("notes", [])}
    errors = {"runup": m.relative_error(runup, law) if runup is not None else None}
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


# ------------------------------------------------------------------------------------------------
# Kimmoun & Branger breaking (seed 001)


KIMMOUN_BREAKING_X = 14.575 - 2.48
"""Incipient breaking [m from the paddle]: seed 001 Fig. 5, 248 cm before the shoreline
(x = 14.575 m)."""
KIMMOUN_BREAKER_HEIGHT = 0.14
"""Wave height at breaking H_B [m], seed 001 section 2."""
KIMMOUN_RUNUP_SPH = 0.0753
"""Seed 001's own SPH mean run-up "R/H = 7.53 %" (Fig. 9, Table 3), kept for comparison."""
KIMMOUN_CREST_VELOCITY_X = 14.575 - 2.40
"""Where seed 001 finds the highest velocities under the crest: 240 cm before the shoreline."""
KIMMOUN_CREST_VELOCITY = 1.20
"""Measured crest velocity over sqrt(g D) (seed 001 section 4, c_EXP = 1.20 sqrt(g D))."""
KIMMOUN_CREST_VELOCITY_SPH = 1.05
"""Seed 001's own SPH crest velocity over sqrt(g D), kept for comparison."""


def _run_kimmoun(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """kimmoun2d (seed 001 flume, H = 0.114 m, T = 1.275 s, 1:15 beach), until = ramp + arrival
    at x = 14.155 m + 4 periods (about 20.8 s; quick 2.2 periods).
    Breaking position and H_B: where the phase-averaged wave first reaches H/d = 0.78 among the
    gauges on the slope (every 0.5 m from 8 to 14.5 m) and its height there; crest velocity on
    the vertical 240 cm before the shoreline; run-up: mean per-wave maximum."""
    dp = case.dp(res)

    def until(s: FlumeScene) -> float:
        # the analysis reads each gauge from ramp + arrival + one period: this leaves three
        # steady periods (quick: 1.2) at the last breaking gauge, 42 cm before the shoreline
        assert s.period is not None and s.shoreline is not None
        extra = 2.2 if quick else 4.0
        return s.law.ramp_duration + s.arrival_time(s.shoreline - 0.42) + extra * s.period

    scene, notes = _with_until("kimmoun2d", {"dp": repr(dp)}, until)
    clock = _Clock()
    sim, status, message, result = _flume_run(case, scene, res, progress, f"{case.name} {res:g}")
    br = result.get("breaking") or {}
    ru = result.get("runup") or {}
    # the breaker: where the phase-averaged wave first reaches H/d = 0.78 and its height there
    # (one wave, the averaged one; analysis.json's breaking.phase_averaged)
    pa = br.get("phase_averaged") or {}
    x_b, h_b = pa.get("position"), pa.get("wave_height")
    # the largest mean wave height among the gauges on the slope, the earlier definition
    depth = scene.flume.depth
    on_slope = [g for g in result["gauges"]
                if 0.0 < g["still_depth"] < depth - 1e-9 and g.get("H_mean") is not None]
    top = max(on_slope, key=lambda g: g["H_mean"]) if on_slope else None
    # the crest velocity on the vertical 240 cm before the shoreline, against sqrt(g D)
    vertical = next((v for v in result.get("velocity_verticals", [])
                     if abs(v["x"] - KIMMOUN_CREST_VELOCITY_X) < 1e-3), {})
    u_crest = vertical.get("crest_velocity_over_sqrt_gD")
    # the seed's comparison values (section 2, Table 3): xi = 0.31, H = 0.11 m, L0 = 2.54 m
    xi = 0.31
    formulas = {"hunt": float(wt.hunt_runup(xi)), "schuttrumpf": float(wt.schuttrumpf_runup(xi)),
                "chue": float(wt.chue_runup(0.11, 2.54, 1.0 / 15.0))}
    r_over_h = ru.get("mean_over_H")
    details = {"breaking_x": x_b, "breaking_x_reference": KIMMOUN_BREAKING_X,
               "breaker_height": h_b, "breaker_height_reference": KIMMOUN_BREAKER_HEIGHT,
               "breaking_n_waves": pa.get("n_waves"),
               "max_mean_height_x": top["x"] if top is not None else None,
               "max_mean_height": top["H_mean"] if top is not None else None,
               "breaking_onset_mccowan_x": br.get("position"),
               "crest_velocity_over_sqrt_gD": u_crest,
               "crest_velocity_over_sqrt_gD_experiment": KIMMOUN_CREST_VELOCITY,
               "crest_velocity_over_sqrt_gD_seed_sph": KIMMOUN_CREST_VELOCITY_SPH,
               "trough_velocity_over_sqrt_gD": vertical.get("trough_velocity_over_sqrt_gD"),
               "runup_over_H": r_over_h,
               "runup_over_H_formulas": formulas, "runup_over_H_seed_sph": KIMMOUN_RUNUP_SPH,
               "notes": notes, "analysis_notes": result.get("notes", [])}
    errors = {
        "breaking_x_m": abs(x_b - KIMMOUN_BREAKING_X) if x_b is not None else None,
        "breaker_height": m.relative_error(h_b, KIMMOUN_BREAKER_HEIGHT) if h_b else None,
        "crest_velocity": (m.relative_error(u_crest, KIMMOUN_CREST_VELOCITY)
                           if u_crest is not None else None),
        "runup_vs_schuttrumpf": (m.relative_error(r_over_h, formulas["schuttrumpf"])
                                 if r_over_h is not None else None),
    }
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


# ------------------------------------------------------------------------------------------------
# active absorption at the paddle


ABSORPTION_WAVE: dict[str, float] = {"depth": 0.4, "kd": 1.0, "height": 0.04}
"""The regular wave of absorption2d: d = 0.4 m, kd = 1 (T = 1.454 s, L = 2.51 m), H/d = 0.1."""

ABSORPTION_FLUME_WAVELENGTHS = 3.0
"""Length of the absorption2d flume [wavelengths]: a whole number of wavelengths is a natural
mode of the closed tank (an antinode at the paddle and at the wall), so without absorption the
re-reflected wave adds up in phase: the strongest build-up a closed tank gives, and the hardest
test for the absorber."""

ABSORPTION_PERIODS = (60, 20)
"""Simulated periods of absorption2d: (full, quick)."""

ABSORPTION_WINDOW_PERIODS = 5
"""Length of each window of the reflection analysis [periods]; the last two make the late
window."""

SOLITARY_CLOSED_FLUME: dict[str, float] = {"depth": 0.2, "height": 0.04, "length": 2.0}
"""The solitary wave of absorption2d (and of tests/test_absorption.py): H/d = 0.2 sent toward
the wall of a 2 m flume."""


def absorption_period(depth: float = ABSORPTION_WAVE["depth"], kd: float = ABSORPTION_WAVE["kd"],
                      g: float = 9.81) -> float:
    """The period [s] of the wave with ``k d = kd`` at ``depth`` (linear dispersion)."""
    k = kd / depth
    return 2.0 * math.pi / math.sqrt(g * k * math.tanh(kd))


def absorption_scene(paddle: Piston | Flap, dp: float, periods: float, still: bool = False
                     ) -> FlumeScene:
    """The absorption2d flume: :data:`ABSORPTION_WAVE` from ``paddle`` toward the vertical far
    wall :data:`ABSORPTION_FLUME_WAVELENGTHS` wavelengths away (a whole number of dp; no beach,
    no damping zone), three gauges near the paddle at 1.5 d, 1.5 d + L/10 and 1.5 d + L/4
    (Mansard & Funke's spacing), run for ``periods`` periods with flume2d's numerics.
    ``still``: the same flume with the paddle at rest (the still water's own settling)."""
    depth, height = ABSORPTION_WAVE["depth"], ABSORPTION_WAVE["height"]
    period = absorption_period()
    wl = float(wt.wavelength(period, depth))
    flume = Flume(length=dp * round(ABSORPTION_FLUME_WAVELENGTHS * wl / dp), depth=depth,
                  damping=False)
    first = 1.5 * depth  # beyond the paddle's evanescent near field (about one depth)
    gauges = [ElevationGauge(round(first + f * wl, 3), name=f"g{i + 1}")
              for i, f in enumerate((0.0, 0.1, 0.25))]
    wave = (TabulatedMotion(t=(0.0, 1.0), x=(0.0, 0.0)) if still
            else RegularWave(height=height, period=period))
    return flume.scene(wave, paddle=paddle, dp=dp,
                       gauges=gauges, until=round(periods * period, 3),
                       sample_interval=period / 40.0, **{**nm.FLUME_CASE, **nm.WAVE_CARRYING})


def _separated(t: np.ndarray, eta: np.ndarray, x: np.ndarray, depth: float, period: float,
               start: float, end: float) -> dict[str, Any]:
    """Incident and reflected first harmonics over the whole periods of [start, end]
    (Mansard & Funke, three gauges): complex incident amplitude at x = 0 and the mean level
    of the gauges."""
    sel = (t >= start) & (t < end)
    r = an.mansard_funke(eta[sel], t[sel], x, depth, period=period)
    a_i, a_r = float(r.incident_amplitudes[0]), float(r.reflected_amplitudes[0])
    return {"start": start, "end": end, "a_incident": a_i, "a_reflected": a_r,
            "incident": a_i * complex(math.cos(r.incident_phases[0]),
                                      math.sin(r.incident_phases[0])),
            "mean_level": float(np.mean(eta[sel]))}


def absorption_measure(sim: FlumeSimulation, scene: FlumeScene) -> dict[str, Any]:
    """What absorption2d measures in one run, from the three gauges near the paddle.

    ``early``: the incident wave before any reflection reaches the gauges (from the ramp's end
    plus the arrival at the farthest gauge plus one period, to the arrival there of the wall's
    reflection, at the group velocity): the paddle's own wave. ``windows``: consecutive
    windows of :data:`ABSORPTION_WINDOW_PERIODS` periods from the end of ``early`` to the end
    of the run; ``late``: the last two. ``rereflected``: ``|A_I(late) - A_I(early)| /
    |A_I(early)|`` with A_I the complex incident amplitude: whatever the paddle sends into the
    flume on top of its own wave, i.e. the re-reflected wave's share of the incident height,
    whatever its phase. ``incident_growth``: ``|A_I(late)| / |A_I(early)| - 1``.
    ``mean_level_over_H``: the gauges' mean level over ``late`` (zeroed at t = 0) over H.
    """
    t, eta, _ = sim.gauges.uniform()
    x = np.asarray(sim.gauges.x, dtype=float)
    period = scene.period
    assert period is not None
    depth, height = scene.flume.depth, ABSORPTION_WAVE["height"]
    cg = float(wt.group_velocity(period, depth, scene.g))
    start = scene.law.ramp_duration + x[-1] / cg + period
    wall_return = (2.0 * scene.flume.length - x[-1]) / cg
    early = _separated(t, eta, x, depth, period, start,
                       start + period * math.floor((wall_return - start) / period))
    span = ABSORPTION_WINDOW_PERIODS * period
    n = math.floor((float(t[-1]) - early["end"]) / span + 1e-6)
    windows = [_separated(t, eta, x, depth, period, early["end"] + i * span,
                          early["end"] + (i + 1) * span + 1e-9) for i in range(n)]
    late = _separated(t, eta, x, depth, period, windows[-2]["start"], windows[-1]["end"])
    a0 = early["incident"]
    return {
        "early": {k: v for k, v in early.items() if k != "incident"},
        "late": {k: v for k, v in late.items() if k != "incident"},
        "windows": [{k: v for k, v in w.items() if k != "incident"} for w in windows],
        "rereflected": abs(late["incident"] - a0) / abs(a0),
        "rereflected_windows": [abs(w["incident"] - a0) / abs(a0) for w in windows],
        "incident_growth": abs(late["incident"]) / abs(a0) - 1.0,
        "incident_over_target": late["a_incident"] / (0.5 * height),
        "mean_level_over_H": late["mean_level"] / height,
    }


def solitary_closed_flume(absorption: bool, dp: float) -> tuple[FlumeScene, float, float]:
    """:data:`SOLITARY_CLOSED_FLUME`'s solitary wave sent toward the vertical far wall, two
    gauges (0.3 m and mid-flume). Returns ``(scene, back, until)``: the time the reflected wave
    is back at the paddle, and that plus one crossing of the flume."""
    depth, height, length = (SOLITARY_CLOSED_FLUME[k] for k in ("depth", "height", "length"))
    flume = Flume(length=length, depth=depth, damping=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # sizing only
        probe = flume.scene(SolitaryWave(height=height), paddle=Piston(absorption=absorption),
                            dp=dp)
    c = float(wt.solitary_celerity(height, depth))
    assert probe.law.duration is not None
    back = probe.law.duration + 2.0 * length / c
    until = back + length / c
    scene = flume.scene(SolitaryWave(height=height), paddle=Piston(absorption=absorption), dp=dp,
                        until=round(until, 3), sample_interval=0.02, **nm.FLUME_CASE,
                        gauges=[ElevationGauge(0.3, name="near"),
                                ElevationGauge(0.5 * length, name="middle")])
    return scene, back, until


def solitary_residual(sim: FlumeSimulation, back: float) -> float:
    """The largest |elevation| [m] at the gauges from 0.3 s after the reflected solitary wave
    is back at the paddle: what the paddle left in the tank."""
    late = sim.gauges.t > back + 0.3
    return float(np.nanmax(np.abs(sim.gauges.elevation[late])))


def _plot_absorption(runs: Sequence[Mapping[str, Any]], path: Path) -> None:
    """The finest finished run of absorption2d: the incident amplitude near the paddle (over
    the paddle's own wave) and the mean level (over H) per window, against time in periods,
    for the piston and the flap with absorption on and off."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    done = [r for r in runs if r.get("status") == "ok" and "piston_on" in (r.get("details") or {})]
    if not done:
        return
    run = min(done, key=lambda r: float(r["dp"]))
    details = run["details"]
    period = float(details["period"])
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for i, label in enumerate(("piston_on", "piston_off", "flap_on", "flap_off")):
        measured = details.get(label)
        if measured is None:
            continue
        windows = [measured["early"], *measured["windows"]]
        t = [0.5 * (w["start"] + w["end"]) / period for w in windows]
        style = {"color": f"C{i // 2}", "ls": "-" if label.endswith("on") else "--",
                 "marker": "o", "label": label.replace("_", ", absorption ")}
        a0 = measured["early"]["a_incident"]
        ax1.plot(t, [w["a_incident"] / a0 for w in windows], **style)
        ax2.plot(t, [w["mean_level"] / ABSORPTION_WAVE["height"] for w in windows], **style)
    still = details.get("mean_level_over_H_still")
    if still is not None:
        ax2.axhline(still, color="0.4", lw=1, label="still water, late window")
    ax1.axhspan(0.9, 1.1, color="0.85", label="+-10 % of the paddle's own wave")
    ax2.axhspan(-0.02, 0.02, color="0.85", label="+-2 % of H")
    ax1.set_ylabel("incident amplitude / paddle's own wave [-]")
    ax2.set_ylabel("mean level / H [-]")
    for ax in (ax1, ax2):
        ax.set_xlabel("t / T (window centres)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, framealpha=0.5)
    fig.suptitle(f"absorption2d at H/dp {float(run['resolution']):g} (dp {float(run['dp']):.4g} "
                 "m): three gauges near the paddle", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _run_absorption(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """absorption2d: :func:`absorption_scene` with a piston and a flap, each with absorption on
    and off, for 60 periods (20 quick), measured by :func:`absorption_measure`; and the
    solitary wave of :func:`solitary_closed_flume`, with and without absorption, at the same
    H/dp (its dp snapped to whole layers of its depth)."""
    dp = case.dp(res)
    periods = ABSORPTION_PERIODS[1 if quick else 0]
    clock = _Clock()
    errors: dict[str, float | None] = {}
    details: dict[str, Any] = {"wave": dict(ABSORPTION_WAVE), "period": absorption_period(),
                               "periods": periods}
    status, message = "ok", None
    n_particles = steps = 0
    sim: FlumeSimulation | None = None
    runs = [(kind, on) for kind in ("piston", "flap") for on in (True, False)]
    for kind, on in runs:
        paddle = Piston(absorption=on) if kind == "piston" else Flap(absorption=on)
        label = f"{kind}_{'on' if on else 'off'}"
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            scene = absorption_scene(paddle, dp, periods)
        sim = scene.build()
        st, msg = advance(sim, float(scene.until), 1.0, None, progress,  # type: ignore[arg-type]
                          f"{case.name} {res:g} {label}")
        n_particles = max(n_particles, sim.n_particles)
        steps += sim.steps
        if st != "ok":
            status, message = (st, f"{label}: {msg}") if status == "ok" else (status, message)
            continue
        measured = absorption_measure(sim, scene)
        measured["notes"] = [f"{w.category.__name__}: {w.message}" for w in caught]
        details[label] = measured
        details["flume_length"] = scene.flume.length
        details["gauges_x"] = [float(v) for v in sim.gauges.x]
        for key in ("rereflected", "incident_growth", "mean_level_over_H"):
            details[f"{key}_{label}"] = measured[key]
        if on:
            errors[f"rereflected_{kind}"] = measured["rereflected"]
            errors[f"mean_level_{kind}"] = abs(measured["mean_level_over_H"])
    # the still water's own level at the gauges over the late window: the settling of the
    # particles on the floor, which every run's mean level carries whatever the paddle does
    still = absorption_scene(Piston(absorption=False), dp, periods, still=True)
    sim_still = still.build()
    st, msg = advance(sim_still, float(still.until), 1.0, None, progress,  # type: ignore[arg-type]
                      f"{case.name} {res:g} still water")
    steps += sim_still.steps
    late = details.get("piston_on", {}).get("late")
    if st != "ok":
        status, message = (st, f"still water: {msg}") if status == "ok" else (status, message)
    elif late is not None:
        t, eta, _ = sim_still.gauges.uniform()
        sel = (t >= late["start"]) & (t < late["end"])
        details["mean_level_over_H_still"] = float(np.mean(eta[sel])) / ABSORPTION_WAVE["height"]
    on_errors = [errors.get(f"rereflected_{k}") for k in ("piston", "flap")]
    errors["rereflected"] = (max(on_errors) if None not in on_errors  # type: ignore[type-var]
                             else None)
    sol_dp = lattice_dp(SOLITARY_CLOSED_FLUME["depth"], SOLITARY_CLOSED_FLUME["height"] / res)
    details["solitary_dp"] = sol_dp
    for on in (True, False):
        scene, back, until = solitary_closed_flume(on, sol_dp)
        sol = scene.build()
        st, msg = advance(sol, until, 0.1, None, progress, f"{case.name} {res:g} solitary")
        steps += sol.steps
        if st != "ok":
            status, message = (st, f"solitary: {msg}") if status == "ok" else (status, message)
            continue
        residual = solitary_residual(sol, back) / SOLITARY_CLOSED_FLUME["height"]
        details[f"solitary_residual_{'on' if on else 'off'}"] = residual
        if on:
            errors["solitary_residual"] = residual
    errors = {"rereflected": errors.pop("rereflected"), **errors}
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details, n_sims=len(runs) + 3, particles_total=n_particles,
                       steps_total=steps)


# ------------------------------------------------------------------------------------------------
# registry


_DAMBREAK_NOTE = (
    "`front_rms` and `front_max` compare the simulated front with the data as they are, "
    "without any shift (`watersim.measure.front_error`). The experiment's gate opened in a "
    "finite time, so an instantly released column leads the data; at coarse dp numerical "
    "dissipation slows the front and cancels part of that lead, so the raw error need not fall "
    "with dp. `front_rms_shifted` is a different, labelled metric: the RMS error left after "
    "removing the best constant time shift of the simulation "
    "(`metrics.front_error_best_shift`; the shift is in runs.json, `details.best_shift_s`); "
    "it measures the shape of the front curve."
)

_DAMBREAK2D_NOTE = _DAMBREAK_NOTE + (
    " `details.front_rms_pysph_a2.25in` and `details.front_rms_pysph_a1.125in` in runs.json "
    "compare the same front with PySPH's two digitisations of the paper's Fig. 3 (a = 2.25 in "
    "and 1.125 in). `height_rms` and `height_max` compare "
    "the residual column height at the back wall (`watersim.measure.water_column_height`) "
    "with the paper's n^2 = 2 table (`watersim.measure.load_martin_moyce_height`), unshifted "
    "(`metrics.column_height_error`), at the 9 tabulated times up to 0.7 s; "
    "`details.height_rms_at_front_shift` is the same after the front's best shift, a check of "
    "whether one start-up delay explains both."
)

_ABSORPTION_NOTE = (
    "Each run is seven simulations (wall time is their sum): a piston and a bottom-hinged flap, "
    "each with active absorption on and off, make the regular wave `ABSORPTION_WAVE` (d = "
    "0.4 m, kd = 1, T = 1.454 s, H = 0.04 m) in a flume closed by a vertical wall three "
    "wavelengths away (a natural mode of the closed tank, so without absorption the "
    "re-reflections add up in phase), no beach, no damping, for 60 periods (20 with "
    "`--quick`); and a solitary wave (d = 0.2 m, H = 0.04 m) is sent against the wall of a 2 m "
    "flume with and without absorption. Three gauges near the paddle (1.5 d, + L/10, + L/4) "
    "separate the incident and reflected first harmonics (`analysis.mansard_funke`; "
    "`cases.absorption_measure`). `rereflected_*` = |A_I(late) - A_I(early)| / |A_I(early)|, "
    "A_I the complex incident amplitude over the late window (the last two whole 5-period "
    "windows counted on from the early one: periods 47-57 of 60, 7-17 of 20 quick) and "
    "before the wall's "
    "reflection reaches the gauges (early, the paddle's own wave): the share of the incident "
    "height that is not the paddle's own wave, i.e. the re-reflected wave, whatever its "
    "phase; `rereflected` is the larger of piston and flap. `mean_level_*`: |mean level| of "
    "the three gauges over the late window over H, zeroed on still water at t = 0 (target "
    "<= 0.02); `mean_level_over_H_still` is the same in the same flume with the paddle at rest "
    "(a seventh simulation): the particles' own settling, part of every run's level. "
    "`solitary_residual`: the largest |elevation| at the two gauges from 0.3 s after "
    "the reflected solitary wave is back at the paddle, over H (target <= 0.05). The same "
    "measures without absorption (the build-up) are in `details` (`*_off`), as are the "
    "5-period windows (`details.<paddle>_<on|off>.windows`)."
)

CASES: dict[str, Case] = {
    c.name: c
    for c in (
        Case("tank2d", "still water, 2D tank 1.0 m x 0.5 m deep, 1 s",
             "hydrostatics p = rho0 g (d - z); fluid at rest", "depth / dp", 0.5,
             (10.0, 20.0, 30.0), (10.0,), "pressure_rms", 0.01,
             "RMS pressure error <= 1 % of rho0 g d", _run_tank,
             report_details=("surface_mean_minus_depth",)),
        Case("dambreak2d", "2D dam break, 1 m x 2 m column (n^2 = 2), to 0.7 s",
             "Martin & Moyce (1952) surge front (lethe set) and residual column height (their "
             "n^2 = 2 table)", "column width / dp", 1.0,
             (10.0, 20.0, 40.0), (8.0,), "front_rms", 0.10,
             "RMS relative front error <= 10 %", _run_dambreak, _DAMBREAK2D_NOTE,
             report_details=("mean_lead_s", "best_shift_s", "front_rms_pysph_a2.25in",
                             "front_rms_pysph_a1.125in", "height_mean_rel_error",
                             "height_rms_at_front_shift")),
        Case("dambreak3d", "3D dam break, narrow tank (0.5 m wide, 3 m long), to 0.6 s",
             "Martin & Moyce (1952) surge front (lethe set)", "column width / dp", 1.0,
             (6.0, 8.0, 12.0), (6.0,), "front_rms", 0.15,
             "RMS relative front error <= 15 %", _run_dambreak, _DAMBREAK_NOTE,
             report_details=("mean_lead_s", "best_shift_s", "n_points", "front_final")),
        Case("standing2d", "first sloshing mode, 1.0 m tank, d = 0.5 m, a = 0.05 m",
             "linear theory omega^2 = g k tanh(k d)", "wave height 2a / dp", 0.1,
             (2.0, 3.0, 4.5), (2.0,), "period", 0.02,
             "period within 2 % of linear theory", _run_standing,
             "The initial surface is a staircase of whole dp (the core fills fluid boxes; see "
             "`StandingWaveTank`), so the initial first-mode amplitude differs from a = 0.05 m "
             "(`details.amplitude_initial`). `decay_per_period` is the fraction of the "
             "amplitude lost per period; inviscid linear theory has none (the physical viscous "
             "decay of this tank is far below 1 % per period).",
             report_details=("period_linear", "period_simulated", "amplitude_initial",
                             "decay_rate"),
             modules=("scipy",)),  # the damped-oscillation fit (metrics.damped_oscillation_fit)
        Case("flume2d", "flat flume, regular wave H = 0.1 m, T = 1.2 s, d = 0.3 m",
             "target height; linear and Stokes third-order wavelength", "wave height / dp",
             FLUME2D_HEIGHT, (2.5, 5.0, 10.0), (2.0,), "H_3L", 0.05,
             "wave height at 3 wavelengths within 5 % of the target", _run_flume2d,
             "The built-in flume2d with H = 0.1 m (`FLUME2D_HEIGHT`; H/L = 0.056): resolution 10 "
             "is dp = 0.01 m, about 30,000 particles. "
             "`H_1L`, `H_2L`, `H_3L`: mean zero-crossing height at 1, 2 and 3 wavelengths "
             "against the target H. `height_loss_per_L`: fraction of the height lost per "
             "wavelength, fitted over the gauges at 1, 2 and 3 L. `wavelength_*`: wavelength "
             "from the first-harmonic phases of the six flat-floor gauges against linear and "
             "Stokes third-order dispersion (for this steepness Stokes' third order is 4.2 % "
             "longer than linear). `mwl_drift`: the largest change of the mean water level "
             "(per-period means, least-squares trend) over the steady record at 1, 2 or 3 L, "
             "over H.",
             report_details=("H_1L", "H_2L", "H_3L", "wavelength_measured",
                             "wavelength_linear", "wavelength_stokes3"),
             depth=0.3),
        Case("secondorder2d", "first- against second-order piston, d = 0.2 m, T = 1.4 s, "
             "H = 0.045 m (kd = 0.69)",
             "Stokes second-order bound harmonic (constant along the flume)", "wave height / dp",
             SECOND_ORDER_WAVE["height"], (2.0, 3.0), (1.5,), "local_spread_ratio", 0.5,
             "second-order generation at least halves the spread of the second harmonic",
             _run_secondorder,
             "Each run is two simulations (second- and first-order piston; wall time is their "
             "sum) of the wave `SECOND_ORDER_WAVE` (kd = 0.69, where Madsen's second-order "
             "stroke correction is 2.0 mm against a 66 mm stroke), nine gauges from 0.5 to "
             "2.5 L, more than one beat length (1.86 L) of a free second harmonic. "
             "`a2_spread_orderN`: (max - min) of the second-harmonic amplitude over the gauges, "
             "over the Stokes bound amplitude of the target wave. `a2_local_spread_orderN`: "
             "(max - min) / mean of the second harmonic over the bound amplitude of each "
             "gauge's own first harmonic, so the wave's loss of height along the flume (its "
             "bound harmonic falls as H^2) is not counted as spread. `local_spread_ratio`: "
             "order-2 over order-1 local spread (the target: at most 0.5, the spread halved). "
             "`a2_mean_orderN`: mean second harmonic against the target's bound amplitude.",
             report_details=("a2_bound", "local_spread_ratio_2_over_1"),
             depth=SECOND_ORDER_WAVE["depth"]),
        Case("bar2d", "Beji & Battjes (1993) submerged bar, H = 0.02 m, T = 2.02 s",
             "Beji & Battjes (1993) gauge records (waves2Foam)", "wave height / dp", 0.02,
             (0.25, 0.33, 0.4), (0.25,), "harmonic1_amplitude", 0.10,
             "first-harmonic amplitude RMS error <= 10 % of H/2", _run_bar,
             "Resolutions below one particle per wave height: the 2 cm wave is numerically "
             "damped at every affordable dp (bar2d's own docstring asks for H/dp >= 5, a run "
             "of hours on this machine). Amplitude errors are RMS over the gauges up to 17.3 m, "
             "over H/2 = 0.01 m; phase errors [rad] are between gauges (the experiment's clock "
             "offset removed).", depth=0.4),
        Case("solitary2d", "non-breaking solitary wave, H/d = 0.15, 1:3 beach",
             "Synolakis (1987) R/d = 2.831 sqrt(cot beta) (H/d)^(5/4)", "wave height / dp",
             0.045, (1.0, 1.5, 2.0), (1.0,), "runup", 0.10,
             "maximum run-up within 10 % of the Synolakis law", _run_solitary,
             "Set up non-breaking for the law: H/d = 0.15 on a 1:3 beach, below the "
             "non-breaking limit H/d < 0.818 (cot beta)^(-10/9) = 0.24 (Synolakis 1987 as "
             "usually quoted). The built-in solitary2d default (H/d = 0.3 on 1:19.85) breaks, "
             "and the law does not apply to it. The run-up is read by the flume's automatic "
             "run-up gauge, a line 1.5 dp above the beach (`RunupGauge`): water thinner than "
             "that (3.4-6.8 cm at these dp, against a law run-up of 13.7 cm) is not seen.",
             report_details=("runup_max", "runup_law", "t_runup_max", "until"), depth=0.3),
        Case("kimmoun2d", "seed 001: regular waves plunging on a 1:15 beach, about 16 periods",
             "seed 001 (Kimmoun & Branger 2007): x_b, H_B = 0.14 m; Schuttrumpf run-up",
             "wave height / dp", 0.114, (1.2, 1.7, 2.3), (1.2,), "breaker_height", 0.10,
             "breaker height within 10 % of H_B = 0.14 m", _run_kimmoun,
             "`breaking_x_m`: distance [m] between the breaking point of the phase-averaged "
             "wave (where its H/d first reaches 0.78, interpolated between the gauges 0.5 m "
             "apart; analysis.json `breaking.phase_averaged`) and the seed's incipient "
             "breaking, 248 cm before the shoreline (x = 12.095 m). `breaker_height`: the "
             "phase-averaged wave's height at that point against H_B = 0.14 m (runs before "
             "2026-12-05 took the largest mean height among the gauges instead, now "
             "`details.max_mean_height`). `crest_velocity`: the phase-averaged crest velocity "
             "over sqrt(g D) on the vertical 240 cm before the shoreline against the measured "
             "1.20 (the seed's SPH: 1.05). `runup_vs_schuttrumpf`: mean run-up R/H against "
             "Schuttrumpf's R/H = 2.25 tanh(xi/2) with the seed's xi = 0.31 (the seed finds its "
             "SPH closest to that formula; the other formulas and the seed's own SPH value are "
             "in runs.json).",
             report_details=("breaking_x", "breaker_height", "max_mean_height",
                             "crest_velocity_over_sqrt_gD", "runup_over_H"), depth=0.705),
        Case("absorption2d", "active absorption: regular wave (kd = 1, H/d = 0.1) against a "
             "vertical wall for 60 periods, piston and flap, absorption on and off; a solitary "
             "wave against the wall",
             "the paddle's own wave (incident wave before the first reflection returns); still "
             "water", "wave height / dp", ABSORPTION_WAVE["height"], (1.0, 1.5), (1.0,),
             "rereflected", 0.10,
             "re-reflected wave at most 10 % of the incident height (piston and flap)",
             _run_absorption, _ABSORPTION_NOTE,
             report_details=("rereflected_piston_off", "rereflected_flap_off",
                             "incident_growth_piston_on", "incident_growth_flap_on",
                             "incident_growth_piston_off", "incident_growth_flap_off",
                             "mean_level_over_H_piston_off", "mean_level_over_H_flap_off",
                             "mean_level_over_H_still", "solitary_residual_off"),
             depth=ABSORPTION_WAVE["depth"], figure=_plot_absorption),
    )
}
"""The validation cases by name, in report order."""

