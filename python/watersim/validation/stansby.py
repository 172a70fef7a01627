"""Seed 002 (Makris et al., SPHysics on Stansby & Feng 2005's flume) as the ``stansby2d``
validation case: its reference values, its run length and its metrics from analysis.json (the
runner and the registry entry are in :mod:`watersim.validation.cases`)."""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from importlib import resources
from typing import Any

import numpy as np

from .. import wave_theory as wt
from ..flume import FlumeScene
from ..flume_cases import STANSBY_GAUGES, STANSBY_UNDERTOW_GAUGES
from . import metrics as m
from .running import _Clock, flume_run, make_record, numerical_case_scene

__all__ = ["stansby_metrics", "stansby_undertow_table", "stansby_until"]


STANSBY_HEIGHT = 0.105
"""Wave height H [m] of seed 002 Table 1."""
STANSBY_FLAT_GAUGES: tuple[float, ...] = (0.8, 1.1, 1.8)
"""The gauges over the flat floor [m], before the beach's toe at 2.0 m: gauge 1 of seed 002
Table 2 and stansby2d's two extra gauges."""
STANSBY_BREAKING_X: tuple[float, float] = (5.54, 5.74)
"""Seed 002's incipient-breaking region [m]: gauges 8-10 (Table 2, Fig. 3)."""
STANSBY_CELERITY_RATIO: tuple[float, float] = (0.70, 0.80)
"""Seed 002's crest celerity in the surf zone over sqrt(g d): "70~80 %" (text under Fig. 4)."""
STANSBY_UNDERTOW_FILE = "stansby_feng2005_undertow_table3_sphysics.csv"
"""Seed 002 Table 3 (watersim/data, SOURCES.md): its SPHysics depth-averaged undertow."""


def stansby_undertow_table() -> dict[int, float]:
    """Seed 002 Table 3: depth-averaged undertow [m/s, seaward positive] by gauge number (the
    seed's own SPHysics values, not measurements)."""
    text = resources.files("watersim.data").joinpath(STANSBY_UNDERTOW_FILE).read_text("utf-8")
    rows = [line.split(",") for line in text.splitlines()[1:] if line.strip()]
    return {int(gauge): float(value) for gauge, _, value in rows}


def _distance_to_range(value: float, low: float, high: float) -> float:
    """How far ``value`` lies outside ``[low, high]`` (0 inside)."""
    return max(low - value, 0.0, value - high)


def _target_first_harmonic(wave: Mapping[str, Any], depth: float) -> float:
    """The first harmonic of the wave the paddle law aims at [m]: the Fourier (stream-function)
    or cnoidal wave's, H/2 for Biesel's and Madsen's laws."""
    height, period, theory = wave["height"], wave["period"], wave.get("theory")
    if theory in wt.FLUX_THEORIES:
        target = (wt.cnoidal_wave(height, period, depth) if theory == "cnoidal"
                  else wt.stream_function_wave(height, period, depth))
        return float(target.elevation_coefficients[1])
    return 0.5 * height


def _incident_wave(result: Mapping[str, Any]) -> dict[str, Any]:
    """The incident first harmonic over the flat floor (analysis.json ``reflection``: Mansard &
    Funke on three gauges there) against the target's: what the paddle made, apart from the
    partial standing wave the beach's reflection sets up along the flume, which moves the height
    at any one gauge by up to twice the reflection coefficient."""
    reflection, wave = result.get("reflection") or {}, result.get("wave") or {}
    incident = reflection.get("incident_amplitude")
    if incident is None or "height" not in wave or "still_water_depth" not in result:
        return {}
    target = _target_first_harmonic(wave, result["still_water_depth"])
    return {"incident_first_harmonic": incident, "target_first_harmonic": target,
            "incident_first_harmonic_error": incident / target - 1.0,
            "reflection_coefficient": reflection.get("coefficient")}


def _mass_transport(result: Mapping[str, Any]) -> dict[str, Any]:
    """What the undertow carries back, on the verticals of Table 3's gauges: in a closed flume
    at steady state the mean volume flux below the trough returns the crests' flux above it
    (Svendsen 1984, Coastal Eng. 8, "Mass flux and undertow in a surf zone"), so
    ``crest_flux_return`` = -(flux below) / (flux above), one at steady state; and the crests'
    flux against the linear wave's ``g H^2 / (8 c)``, ``c = sqrt(g d)``, H the local mean
    zero-crossing height (Svendsen's ``B0 = 1/8`` of a sine; the flatter-crested waves of a
    surf zone have a smaller ``B0``, about half, and add their roller's share):
    ``crest_flux_over_linear``. Means over the verticals, and per gauge. Together they say
    whether an undertow is what the crests' transport asks for."""
    g = 9.81
    heights = {round(float(v["x"]), 6): v.get("H_mean") for v in result.get("gauges", [])}
    ret: dict[str, float] = {}
    lin: dict[str, float] = {}
    for v in result.get("velocity_verticals", []):
        gauge = int(v["name"].removeprefix("u_gauge"))
        above, below = v.get("flux_above_trough"), v.get("flux_below_trough")
        if gauge not in STANSBY_UNDERTOW_GAUGES or not above or below is None:
            continue
        ret[str(gauge)] = -below / above
        height = heights.get(round(float(v["x"]), 6))
        if height and v["still_depth"] > 0.0:
            lin[str(gauge)] = above / (g * height**2 / (8.0 * math.sqrt(g * v["still_depth"])))
    return {"crest_flux_return": float(np.mean(list(ret.values()))) if ret else None,
            "crest_flux_return_by_gauge": ret,
            "crest_flux_over_linear": float(np.mean(list(lin.values()))) if lin else None,
            "crest_flux_over_linear_by_gauge": lin}


def stansby_metrics(result: Mapping[str, Any]) -> tuple[dict[str, float | None],
                                                        dict[str, Any]]:
    """stansby2d's errors and the values behind them, from its analysis.json (``result``);
    the report note of the ``stansby2d`` case defines each."""
    errors: dict[str, float | None] = {}
    details: dict[str, Any] = {}
    # generated height: mean zero-crossing height over the flat floor
    flat = {g["x"]: g.get("H_mean") for g in result.get("gauges", [])
            if any(abs(g["x"] - x) < 1e-6 for x in STANSBY_FLAT_GAUGES)}
    heights = [h for h in flat.values() if h is not None]
    details["H_flat_by_x"] = flat
    details["H_flat"] = float(np.mean(heights)) if heights else None
    errors["H_flat"] = m.relative_error(details["H_flat"], STANSBY_HEIGHT) if heights else None
    details.update(_incident_wave(result))
    # breaking point of the phase-averaged wave against gauges 8-10
    pa = (result.get("breaking") or {}).get("phase_averaged") or {}
    x_b = pa.get("position")
    details.update(breaking_x=x_b, breaking_height=pa.get("wave_height"),
                   breaking_n_waves=pa.get("n_waves"))
    errors["breaking_x_m"] = (_distance_to_range(x_b, *STANSBY_BREAKING_X)
                              if x_b is not None else None)
    # undertow on the verticals at Table 3's gauges (analysis.json: + shoreward)
    table = stansby_undertow_table()
    simulated: dict[int, float] = {}
    crest_u: dict[int, float] = {}
    for v in result.get("velocity_verticals", []):
        gauge = int(v["name"].removeprefix("u_gauge"))
        if gauge not in STANSBY_UNDERTOW_GAUGES:
            continue
        if v.get("undertow") is not None:
            simulated[gauge] = -v["undertow"]
        if v.get("crest_velocity_over_sqrt_gD") is not None:
            crest_u[gauge] = v["crest_velocity_over_sqrt_gD"]
    details.update(_mass_transport(result))
    # the largest phase-averaged u under the crest over sqrt(g d): another reading of the
    # seed's "maximum celerity ... 70~80 %" (which it draws from its velocity field, Fig. 4)
    details["crest_velocity_over_sqrt_gD"] = {str(n): crest_u[n] for n in sorted(crest_u)}
    details["crest_velocity_over_sqrt_gD_max"] = max(crest_u.values()) if crest_u else None
    compared = sorted(simulated)
    details.update(undertow_gauges=compared,
                   undertow_seaward=[simulated[n] for n in compared],
                   undertow_seaward_seed=[table[n] for n in compared])
    if compared:
        sim = np.array([simulated[n] for n in compared])
        ref = np.array([table[n] for n in compared])
        details["undertow_seaward_mean"] = float(np.mean(sim))
        details["undertow_seaward_mean_seed"] = float(np.mean(ref))
        errors["undertow_rms"] = float(np.sqrt(np.mean((sim - ref) ** 2)) / np.mean(ref))
        errors["undertow_mean"] = m.relative_error(float(np.mean(sim)), float(np.mean(ref)))
    else:
        errors["undertow_rms"] = errors["undertow_mean"] = None
    # crest celerity shoreward of gauge 8, each neighbouring pair weighted by its spacing
    cc = result.get("crest_celerity") or {}
    wet = sorted({g["x"] for g in result.get("gauges", []) if g["still_depth"] > 0.0})
    gaps = {round(0.5 * (a + b), 9): b - a for a, b in zip(wet[:-1], wet[1:], strict=True)}
    pairs = [(x, r, gaps.get(round(x, 9))) for x, r in zip(cc.get("x", []), cc.get("ratio", []),
                                                          strict=True)
             if x >= STANSBY_BREAKING_X[0] and r is not None]
    details["celerity_surf_x"] = [x for x, _, _ in pairs]
    details["celerity_surf_ratio"] = [r for _, r, _ in pairs]
    if pairs and all(w is not None for _, _, w in pairs):
        ratio = float(sum(r * w for _, r, w in pairs) / sum(w for _, _, w in pairs))
        details["celerity_ratio_surf"] = ratio
        details["celerity_ratio_surf_median"] = float(np.median([r for _, r, _ in pairs]))
        errors["celerity"] = _distance_to_range(ratio, *STANSBY_CELERITY_RATIO)
    else:
        details["celerity_ratio_surf"] = None
        errors["celerity"] = None
    return errors, details


STANSBY_STEADY_PERIODS = {False: 5.0, True: 3.2}
"""Steady periods of record at the last gauge (7.6 m) of stansby2d, full and quick runs: the
phase averages' waves (quick: just above the analysis's three-period minimum)."""


def stansby_until(scene: FlumeScene, quick: bool) -> float:
    """stansby2d's run length [s]: ramp + arrival at the last gauge + one period (where the
    analysis starts each gauge's window) + :data:`STANSBY_STEADY_PERIODS`."""
    assert scene.period is not None
    return (scene.law.ramp_duration + scene.arrival_time(max(STANSBY_GAUGES))
            + (1.0 + STANSBY_STEADY_PERIODS[quick]) * scene.period)


def stansby_scene(dp: float, settings: Mapping[str, str] | None = None, quick: bool = False
                  ) -> tuple[FlumeScene, list[str]]:
    """stansby2d at ``dp`` with ``--set``-style numerical ``settings``, until
    :func:`stansby_until` (about 25.2 s; ``quick`` 20.8 s), and the warnings its build gave."""
    return numerical_case_scene("stansby2d", dp, settings,
                                functools.partial(stansby_until, quick=quick))


def run_stansby(case: Any, res: float, quick: bool, progress: bool,
                settings: Mapping[str, str] | None = None) -> dict[str, Any]:
    """stansby2d (seed 002 flume, H = 0.105 m, T = 2.42 s, 1:20 beach from 2.0 m;
    :func:`stansby_scene`); metrics by :func:`stansby_metrics` (the runner of :mod:`.cases`)."""
    dp = case.dp(res)
    scene, notes = stansby_scene(dp, settings, quick)
    clock = _Clock()
    sim, status, message, result = flume_run(case, scene, res, progress, f"{case.name} {res:g}")
    errors, details = stansby_metrics(result)
    details.update(until=scene.until, settings=dict(settings or {}), notes=notes,
                   analysis_notes=result.get("notes", []))
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)
