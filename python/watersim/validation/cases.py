"""The validation cases: each builds its scene from the existing builders at a resolution, runs
it, and measures its errors against a reference.

A case's ``run(resolution, quick=False, progress=False)`` returns a run record (a JSON-ready
dict, see :func:`make_record`). ``resolution`` is a number of particles per characteristic
length of the case (``Case.resolution_meaning``: the column width over dp for dam breaks, the
wave height over dp for waves, the depth over dp for the still tank), so ``dp = length /
resolution`` (for the wave flumes snapped to ``depth / round(depth / dp)``, a whole number of
particle layers: :meth:`Case.dp`). ``quick`` shortens the simulated time where the metric allows
it (tank2d, the dam breaks, standing2d, bar2d, kimmoun2d, stansby2d, absorption2d); flume2d,
secondorder2d and solitary2d keep theirs, already the shortest their metrics need, and run only
at their coarse quick resolution.

References (see ``watersim/data/SOURCES.md``): Martin & Moyce (1952) dam-break front; linear
theory and Stokes third-order dispersion; Beji & Battjes (1993) bar records; Synolakis (1987)
run-up law; seed 001 (Roselli et al.) for Kimmoun & Branger (2007) breaking; for active
absorption (absorption2d), the paddle's own wave measured before the first reflection returns;
seed 002 (Makris et al.) for Stansby & Feng (2005) breaking (:mod:`.stansby`).
"""

from __future__ import annotations

import functools
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .. import analysis as an
from .. import numerics as nm
from .. import wave_theory as wt
from .._core import SceneError
from ..checks import _positive
from ..flume import (
    DampingZone,
    ElevationGauge,
    Flume,
    FlumeScene,
    FlumeSimulation,
    Piston,
    RegularWave,
)
from ..flume_cases import BEJI_BATTJES_FILES, _load_csv
from ..measure import MARTIN_MOYCE_SETS, front_error, front_position, water_column_height
from ..scenes import DamBreak, Tank
from ..simulation import Simulation
from . import metrics as m
from .absorption import (
    ABSORPTION_WAVE,
    _plot_absorption,
    _run_absorption,
)
from .buchner import BUCHNER_H, WALL_MODELS, plot_buchner, run_buchner
from .case import Case
from .cylinder import CYLINDER_CASE
from .longflume import LONG_FLUME_WAVE, long_flume_scene, run_long_flume
from .running import _Clock, _with_until, advance, flume_run, make_record, numerical_case_scene
from .seawall import SEAWALL_CASE
from .solitary import SOLITARY_DEPTH, SOLITARY_HEIGHT, SOLITARY_SLOPE, solitary_scene
from .stansby import STANSBY_HEIGHT, run_stansby, stansby_scene
from .yeh import YEH_CASE

__all__ = ["CASES", "Case", "StandingWaveTank", "make_record", "run_case"]


def run_case(name: str, resolution: float, quick: bool = False, progress: bool = False,
             settings: Mapping[str, str] | None = None) -> dict[str, Any]:
    """Run case ``name`` at ``resolution``: the run record (a module-level function, so that it
    pickles for process pools and Dask workers); :meth:`Case.run` of ``CASES[name]``.

    Raises:
        ValueError: unknown case, a resolution that is not a positive number, or settings for
            a case that takes none.
    """
    if name not in CASES:
        raise ValueError(f"case: unknown validation case {name!r}; known: {', '.join(CASES)}")
    return CASES[name].run(resolution, quick, progress, settings)


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
    sim, status, message, result = flume_run(case, scene, res, progress, f"{case.name} {res:g}")
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
        sim, st, msg, result = flume_run(case, scene, res, progress,
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
    sim, status, message, result = flume_run(case, scene, res, progress, f"{case.name} {res:g}")
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


def _run_solitary(case: Case, res: float, quick: bool, progress: bool,
                  settings: Mapping[str, str] | None = None) -> dict[str, Any]:
    """solitary2d (:func:`solitary_scene`) at resolution ``res`` (H/dp); ``quick`` changes
    nothing (the run is already as short as the run-up allows)."""
    dp = case.dp(res)
    depth, height = SOLITARY_DEPTH, SOLITARY_HEIGHT
    scene, notes = solitary_scene(dp, settings)
    clock = _Clock()
    sim, status, message, result = flume_run(case, scene, res, progress, f"{case.name} {res:g}")
    law = float(wt.synolakis_runup(height, depth, SOLITARY_SLOPE)) * depth
    ru = result.get("runup") or {}
    runup = ru.get("max")
    t, _, r = sim.gauges.uniform()
    t_max = float(t[int(np.nanargmax(r))]) if r is not None and np.any(np.isfinite(r)) else None
    cot = 1.0 / SOLITARY_SLOPE
    details = {"runup_max": runup, "runup_law": law, "runup_method": "wet_front",
               "settings": dict(settings or {}),
               "H_over_d": height / depth,
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


def kimmoun_scene(dp: float, settings: Mapping[str, str] | None = None, quick: bool = False
                  ) -> tuple[FlumeScene, list[str]]:
    """kimmoun2d at ``dp`` with ``--set``-style numerical ``settings`` (``--set
    viscosity.wall_factor=0``, say) and the warnings its build gave; until = ramp + arrival at
    x = 14.155 m + 4 periods (about 20.8 s; ``quick``: 2.2 periods).

    Raises:
        FlumeCaseError: a settings key that is not a numerical key of the flume cases.
    """
    def until(s: FlumeScene) -> float:
        # the analysis reads each gauge from ramp + arrival + one period: this leaves three
        # steady periods (quick: 1.2) at the last breaking gauge, 42 cm before the shoreline
        assert s.period is not None and s.shoreline is not None
        extra = 2.2 if quick else 4.0
        return s.law.ramp_duration + s.arrival_time(s.shoreline - 0.42) + extra * s.period

    return numerical_case_scene("kimmoun2d", dp, settings, until)


def _run_kimmoun(case: Case, res: float, quick: bool, progress: bool,
                 settings: Mapping[str, str] | None = None) -> dict[str, Any]:
    """kimmoun2d (seed 001 flume, H = 0.114 m, T = 1.275 s, 1:15 beach; :func:`kimmoun_scene`).
    Breaking position and H_B: where the phase-averaged wave first reaches H/d = 0.78 among the
    gauges on the slope (every 0.5 m from 8 to 14.5 m) and its height there; crest velocity on
    the vertical 240 cm before the shoreline; run-up: mean per-wave maximum."""
    dp = case.dp(res)
    scene, notes = kimmoun_scene(dp, settings, quick)
    clock = _Clock()
    sim, status, message, result = flume_run(case, scene, res, progress, f"{case.name} {res:g}")
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
               "settings": dict(settings or {}), "notes": notes,
               "analysis_notes": result.get("notes", [])}
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
# Stansby & Feng breaking (seed 002): metrics in validation/stansby.py


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
    "the three gauges over the late window over H, against the level of the same gauges over "
    "the same window in the same flume with the paddle at rest (a seventh simulation; target "
    "<= 0.02): the still water's own level rises by about 0.1 dp as the particles settle "
    "(`mean_level_over_H_still`, zeroed at t = 0: 0.10 H at H/dp 1), more than the limit, "
    "whatever the paddle does; `mean_level_over_H_*` are the levels zeroed at t = 0. "
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
        Case("flume2d-long", "the flume2d wave (H = 0.1 m, T = 1.2 s, d = 0.3 m) over ten "
             "wavelengths of flat floor",
             "target height; stream-function (nonlinear) wavelength; still-water level",
             "wave height / dp", LONG_FLUME_WAVE["height"], (5.0, 10.0), (2.5,), "H_10L", 0.05,
             "wave height at 10 wavelengths within 5 % of the target",
             functools.partial(run_long_flume, flume_run=flume_run, phases=_phases,
                               mean_level_drift=_mean_level_drift),
             "Issue 30's measure of numerical dissipation (`watersim.validation.longflume`): "
             "gauges at 1 to 10 L, a 1.5 L damping zone past 10.5 L, the numerics of flume2d "
             "unless `--set` changes them (`details.settings`, `details.numerics`). "
             "`H_10L`: mean zero-crossing height at 10 L against the target H. "
             "`height_loss_per_L`: fraction of the height lost per wavelength, fitted over the "
             "ten gauges (the issue's targets: at most 0.5 % at H/dp 10, 1 % at H/dp 5). "
             "`wavelength_nonlinear`: wavelength from the first-harmonic phases of the ten "
             "gauges against the stream-function wave of the same H and T (within 1 %). "
             "`mean_level`: the largest mean level of a gauge's steady record over H (within "
             "1 %).",
             report_details=("H_1L", "H_5L", "H_10L", "height_loss_per_wavelength",
                             "wavelength_measured", "wavelength_nonlinear"),
             depth=LONG_FLUME_WAVE["depth"], scene=long_flume_scene),
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
             SOLITARY_HEIGHT, (2.0, 3.5, 5.0), (1.0,), "runup", 0.10,
             "maximum run-up within 10 % of the Synolakis law", _run_solitary,
             "Set up non-breaking for the law: H/d = 0.15 on a 1:3 beach, below the "
             "non-breaking limit H/d < 0.818 (cot beta)^(-10/9) = 0.24 (Synolakis 1987 as "
             "usually quoted). The built-in solitary2d default (H/d = 0.3 on 1:19.85) breaks, "
             "and the law does not apply to it. The run-up is the wet front on the bed "
             "(`RunupGauge(method=\"wet_front\")`: the highest fluid particle with a wall "
             "particle within 1.5 dp), zeroed on its reading at rest; the flume's default "
             "gauge, a line 1.5 dp above the beach, cannot see water thinner than that.",
             report_details=("runup_max", "runup_law", "t_runup_max", "until"),
             depth=SOLITARY_DEPTH, scene=solitary_scene),
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
                             "crest_velocity_over_sqrt_gD", "runup_over_H"), depth=0.705,
             scene=kimmoun_scene),
        Case("stansby2d", "seed 002: regular waves spilling on a 1:20 beach, about 10 periods",
             "seed 002 (Makris et al. on Stansby & Feng 2005): H = 0.105 m, incipient breaking "
             "at gauges 8-10, its SPHysics undertow (Table 3) and crest celerity",
             "wave height / dp", STANSBY_HEIGHT, (2.5, 3.4, 4.5), (2.5,), "H_flat", 0.03,
             "height over the flat floor within 3 % of H = 0.105 m", run_stansby,
             "The built-in stansby2d (stream-function piston law, chosen by the wave's Ursell "
             "number 48; beach toe at 2.0 m, an estimate: the seed does not give it); "
             "resolution 3.4 is the built-in's default dp (0.34 / 11 m). "
             "`H_flat`: the mean of the mean zero-crossing heights at the three gauges over the "
             "flat floor (0.8, 1.1 and 1.8 m) against H = 0.105 m. `breaking_x_m`: distance [m] "
             "from the breaking point of the phase-averaged wave (where its H/d first reaches "
             "0.78, interpolated between gauges; analysis.json `breaking.phase_averaged`) to "
             "the seed's incipient-breaking gauges 8-10, 5.54-5.74 m (0 inside). "
             "`undertow_rms`: the RMS difference between the simulated depth-averaged undertow "
             "(analysis.json `velocity_verticals[].undertow`: the time-mean u from the bed to "
             "the trough level, on 12-point verticals at the gauges) and seed 002 Table 3, over "
             "the mean of Table 3; `undertow_mean`: the relative error of the mean over those "
             "gauges (the seed: \"a seaward mean around 0.02 m/sec\"). Table 3 holds the seed's "
             "own SPHysics values, not measurements. Compared at gauges 8, 10, 11, 12, 15, 17, "
             "18, 19, 21, 23; Table 3's gauges 13 and 14 are left out: Table 2 prints them at "
             "7.2 and 7.6 m, the positions of gauges 23 and 24, out of order between 5.96 and "
             "6.18 m, so where they stood is not known. `celerity`: distance of the crest "
             "celerity over sqrt(g d) in the surf zone to the seed's 0.70-0.80: analysis.json "
             "`crest_celerity.ratio` between neighbouring gauges from gauge 8 (5.54 m) to the "
             "last gauge (7.6 m), averaged with each pair weighted by its spacing (pairs 2 cm "
             "apart time the crest to a fraction of the 0.05 s sample interval); d is the "
             "pair's mean still-water depth, without set-up. "
             "`details.crest_velocity_over_sqrt_gD_max`: the largest phase-averaged velocity "
             "under the crest over sqrt(g d) on those verticals, another reading of the seed's "
             "\"maximum celerity ... 70~80 %\", which it draws from its velocity field. "
             "`details.incident_first_harmonic_error`: the incident first harmonic over the "
             "flat floor (analysis.json `reflection`, Mansard & Funke on 0.8, 1.1 and 1.8 m) "
             "against the target wave's (the Fourier wave's 0.0443 m for the stream-function "
             "law): the generated wave without the partial standing wave of the beach's "
             "reflection, which moves the height at each flat-floor gauge by up to twice "
             "`details.reflection_coefficient` (docs/wave-flume.md). "
             "`details.crest_flux_return`: the share of the crests' mean volume flux (above "
             "the trough) that the undertow carries back (one at steady state in a closed "
             "flume, Svendsen 1984); `details.crest_flux_over_linear`: the crests' flux over "
             "the linear wave's g H^2 / (8 c) with the local H (surf-zone waves about half): "
             "an undertow larger than Table 3's is what the crests' transport asks for when "
             "these are near one and a half.",
             report_details=("H_flat", "incident_first_harmonic_error", "breaking_x",
                             "undertow_seaward_mean", "crest_flux_return",
                             "crest_flux_over_linear",
                             "celerity_ratio_surf", "crest_velocity_over_sqrt_gD_max"),
             depth=0.34, scene=stansby_scene),
        SEAWALL_CASE,
        YEH_CASE,
        CYLINDER_CASE,
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
        *(Case(f"buchner2d_{model}", f"Buchner (2002) dam break, H = 0.6 m: pressure on the far "
             f"wall at 0.2 H, {model} walls",
             "Buchner (2002) wall pressure, two digitisations (PySPH, JAXSPH)", "H / dp",
             BUCHNER_H, (10.0, 20.0, 40.0), (10.0,), "peak", 0.15,
             "first-impact pressure peak within 15 % of Buchner's", run_buchner,
             "Column 2H x H against the back wall of a 5.366 H tank; the probe is the fluid "
             "pressure interpolated half a dp off the far wall at 0.2 H, every 0.005 "
             "sqrt(H/g) (`watersim/validation/buchner.py`). `peak`: the largest p/(rho g H) "
             "for t sqrt(g/H) in [2, 3.5] against the PySPH digitisation's (0.691; JAXSPH's "
             "0.686 in `details`). `impulse`: the integral of p/(rho g H) over t sqrt(g/H) "
             "from 2 to 7 against the data's. `noise`: the RMS of the pressure minus its "
             "running mean over 0.25 t sqrt(g/H), from 3 on (not an error against data: the "
             "acoustic noise of the wall pressure, smaller is smoother).",
             report_details=("peak", "t_peak", "impulse", "noise"), figure=plot_buchner)
          for model in WALL_MODELS),
    )
}
"""The validation cases by name, in report order."""

