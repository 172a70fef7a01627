"""Validation case flume2d-long: the flume2d wave (H = 0.1 m, T = 1.2 s, d = 0.3 m) carried over
ten wavelengths of flat floor, to measure what the numerics take from a wave per wavelength
(issue 30): the height along the flume, its loss per wavelength and at ten wavelengths, the
wavelength against the nonlinear (stream-function) wave of the same height and period, and the
mean water level.

The numerics are the built-in flume2d's (:data:`watersim.numerics.FLUME_CASE` and
:data:`~watersim.numerics.WAVE_CARRYING`) unless ``watersim validate flume2d-long --set
KEY=VALUE`` changes them (the numerical keys of the flume cases: ``shifting.model=delta_plus``,
``viscosity.alpha=0.001``, ``kernel=wendland_c4``, ...): one command measures each option on the
same wave.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import numerics as nm
from .. import wave_theory as wt
from ..flume import DampingZone, ElevationGauge, Flume, FlumeScene, Piston, RegularWave
from ..flume_cases import _Settings
from . import metrics as m
from .running import _Clock, make_record

if TYPE_CHECKING:
    from .case import Case

LONG_FLUME_WAVE: dict[str, float] = {"depth": 0.3, "period": 1.2, "height": 0.1}
"""The wave of flume2d-long: flume2d's validation wave (L = 1.77 m, kd = 1.06, H/L = 0.056)."""

LONG_FLUME_WAVELENGTHS = 10
"""Gauges at 1, 2, ..., this many wavelengths from the paddle's rest position."""

LONG_FLUME_PERIODS = 4.5
"""Simulated periods after the wave's arrival at 10 L (linear group velocity): the flume
analysis takes a gauge's statistics from one period after the arrival and needs three periods of
record from there; half a period more for the front, which arrives later than the linear
estimate."""

LONG_FLUME_DAMPING_L = 1.5
"""Length of the damping zone past the last gauge [wavelengths] (flume2d's, whose reflection
coefficient that case measures); the flume is 10.5 + 1.5 L long."""


def long_flume_scene(dp: float, settings: Mapping[str, str] | None = None
                     ) -> tuple[FlumeScene, list[str]]:
    """The flume2d-long scene at ``dp`` with ``--set``-style numerical ``settings`` applied, and
    the warnings its build gave (as notes).

    Flat flume 12 L long (a 1.5 L damping zone from 10.5 L), second-order piston with a
    two-period ramp, gauges every wavelength from 1 to 10 L, until = ramp + arrival at 10 L +
    :data:`LONG_FLUME_PERIODS` periods.

    Raises:
        FlumeCaseError: a settings key that is not a numerical key of the flume cases.
    """
    d, period, height = (LONG_FLUME_WAVE[k] for k in ("depth", "period", "height"))
    wl = float(wt.wavelength(period, d))
    s = _Settings(dict(settings or {}))
    num = s.numerics(dp=dp, **nm.FLUME_CASE, **nm.WAVE_CARRYING)
    s.only_numerics("flume2d-long")
    damping = LONG_FLUME_WAVELENGTHS + 0.5
    flume = Flume(length=round((damping + LONG_FLUME_DAMPING_L) * wl, 3), depth=d,
                  damping=DampingZone(length=round(LONG_FLUME_DAMPING_L * wl, 3)))
    gauges = [ElevationGauge(round(n * wl, 3)) for n in range(1, LONG_FLUME_WAVELENGTHS + 1)]
    wave = RegularWave(height=height, period=period)
    paddle = Piston(order=2, ramp_periods=2.0)
    kwargs: dict[str, Any] = {"flume": flume, "wave": wave, "paddle": paddle, "gauges": gauges,
                              **num}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # sizing only; the real scene below records them
        probe = FlumeScene(**{**kwargs, "until": 1.0})
    until = (probe.law.ramp_duration + probe.arrival_time(LONG_FLUME_WAVELENGTHS * wl)
             + LONG_FLUME_PERIODS * period)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        scene = FlumeScene(**{**kwargs, "until": round(until, 2)})
    return scene, [f"{w.category.__name__}: {w.message}" for w in caught]


def nonlinear_wavelength() -> float:
    """Wavelength [m] of the steady (stream-function, zero mass transport) wave of
    :data:`LONG_FLUME_WAVE` (:func:`watersim.wave_theory.stream_function_wave`)."""
    w = LONG_FLUME_WAVE
    return float(wt.stream_function_wave(w["height"], w["period"], w["depth"]).wavelength)


def run_long_flume(case: Case, res: float, quick: bool, progress: bool,
                   settings: Mapping[str, str] | None = None, *,
                   flume_run: Callable[..., Any], phases: Callable[..., dict[str, float]],
                   mean_level_drift: Callable[..., Any]) -> dict[str, Any]:
    """Run flume2d-long at resolution ``res`` (H/dp) and measure it (``quick`` changes
    nothing: every metric needs the wave at 10 L). ``flume_run``, ``phases`` and
    ``mean_level_drift`` are the flume cases' runner and measures (``validation.cases`` binds
    them; taken as arguments so this module does not import the one that imports it)."""
    _flume_run, _phases, _mean_level_drift = flume_run, phases, mean_level_drift

    dp = case.dp(res)
    scene, notes = long_flume_scene(dp, settings)
    clock = _Clock()
    sim, status, message, result = _flume_run(case, scene, res, progress, f"{case.name} {res:g}")
    assert scene.period is not None and scene.wavelength is not None
    wl, height = scene.wavelength, case.length
    resolved = scene.resolved_scene()
    details: dict[str, Any] = {
        "settings": dict(settings or {}), "wavelength_linear": wl, "H_target": height,
        "notes": notes, "analysis_notes": result.get("notes", []),
        "numerics": {k: resolved.get(k) for k in ("kernel", "coefh", "coefsound", "viscosity",
                                                  "diffusion", "integrator", "cfl", "shifting",
                                                  "boundary")},
    }
    gauges = sorted(result["gauges"], key=lambda g: g["x"])
    details["gauges"] = [{k: g.get(k) for k in ("name", "x", "H_mean", "n_waves", "T_mean",
                                                 "mean_level", "harmonics")} for g in gauges]
    errors: dict[str, float | None] = {}
    xs = [g["x"] for g in gauges if g.get("H_mean")]
    hs = [g["H_mean"] for g in gauges if g.get("H_mean")]
    for g in gauges:
        n = round(g["x"] / wl)
        if g.get("H_mean") is not None:
            details[f"H_{n}L"] = g["H_mean"]
    last = f"H_{LONG_FLUME_WAVELENGTHS}L"
    errors[last] = m.relative_error(details[last], height) if last in details else None
    if len(xs) >= 2:
        loss = m.height_loss_per_wavelength(np.array(xs), np.array(hs), wl)
        details["height_loss_per_wavelength"] = loss
        errors["height_loss_per_L"] = abs(loss)
    names = [g["name"] for g in gauges]
    phases = _phases(sim, scene, names)
    px = [g["x"] for g in gauges if g["name"] in phases]
    if len(px) >= 2:
        lw = m.wavelength_from_phases(px, [phases[g["name"]] for g in gauges
                                           if g["name"] in phases], 2 * math.pi / wl)
        ln = nonlinear_wavelength()
        details.update(wavelength_measured=lw, wavelength_nonlinear=ln)
        errors["wavelength_nonlinear"] = m.relative_error(lw, ln)
    drift = _mean_level_drift(sim, scene, names)
    details["mwl"] = drift
    # the mean level over each gauge's steady record against the still water, over H
    means = [v["mean"] for v in drift.values() if v.get("mean") is not None]
    errors["mean_level"] = max(abs(v) for v in means) / height if means else None
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)
