"""The wave analysis of a flume run: wave statistics, envelopes, breaking, run-up, reflection,
and for long regular-wave records the phase-averaged breaking point, the crest velocity on
velocity verticals and the drift of the mean level near the paddle."""

from __future__ import annotations

import functools
import itertools
import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from .. import analysis as an
from .. import wave_theory as wt
from .gauges import ForceGauge, OvertoppingGauge
from .paddles import PaddleLaw
from .waves import IrregularWave, RegularWave

if TYPE_CHECKING:
    from .records import FlumeGauges
    from .scene import FlumeScene


MIN_WINDOW_PERIODS = 3.0
"""Wave periods of steady record that wave statistics, run-up per wave and reflection need at
the least: any window of three periods holds two whole zero-down-crossing waves, whatever the
phase it starts at (fewer periods may hold a single wave, or none)."""

MIN_WAVES = 2
"""Whole waves a gauge's statistics need at the least."""

FORCE_UNIT = "N (N/m in 2D)"

UNITS: dict[str, str] = {
    "x": "m", "y": "m", "still_depth": "m", "still_water_depth": "m", "window": "s",
    "needs_until": "s", "record_end": "s", "H_mean": "m", "H_max": "m", "H_min": "m",
    "H_rms": "m", "H_significant": "m", "H_target": "m", "H_rel_error": "1", "T_mean": "s",
    "crest_mean": "m", "trough_mean": "m", "mean_level": "m", "harmonics": "m", "hm0": "m",
    "tp": "s", "eta_max": "m", "t_max": "s", "maximum": "m", "minimum": "m", "mean": "m",
    "mid_level": "m", "position": "m", "time": "s", "wave_height": "m", "max_height": "m",
    "max_height_position": "m", "iribarren": "1", "slope": "1", "max": "m", "R2": "m",
    "std": "m", "values": "m", "mean_over_H": "1", "std_over_H": "1", "coefficient": "1",
    "incident_amplitude": "m", "reflected_amplitude": "m", "period": "s", "height": "m",
    "wavelength": "m", "ramp_duration": "s", "stroke": "m", "depth": "m",
    "distance_to_shoreline": "m", "profile": "m", "sqrt_gD": "m/s", "crest_velocity": "m/s",
    "trough_velocity": "m/s", "crest_velocity_over_sqrt_gD": "1",
    "trough_velocity_over_sqrt_gD": "1", "crest_velocity_per_wave_mean": "m/s",
    "crest_velocity_per_wave_std": "m/s", "block_starts": "s", "block_means": "m",
    "spread": "m", "drift": "m", "spread_over_H": "1", "drift_over_H": "1",
    "trough_level": "m", "undertow": "m/s", "undertow_over_sqrt_gD": "1",
    "flux_below_trough": "m^2/s", "flux_above_trough": "m^2/s", "mean_u": "m/s", "z": "m",
    "celerity": "m/s", "shallow_water_speed": "m/s", "ratio": "1",
    "Fx_max": FORCE_UNIT, "Fx_min": FORCE_UNIT, "Fz_max": FORCE_UNIT, "Fz_min": FORCE_UNIT,
    "Fx_mean": FORCE_UNIT, "Fz_mean": FORCE_UNIT, "Fx_significant": FORCE_UNIT,
    "impulse": "N s (N s/m in 2D)", "impulse_start": "s", "impulse_end": "s",
    "total": "m^3 (m^3/m in 2D)", "peak_discharge": "m^3/s (m^3/s/m in 2D)",
}
"""The units of analysis.json's quantities, by key wherever it appears ("1": a pure number;
elevations and levels are relative to the still-water level, times from the start of the run)."""


def _f(value: Any) -> float | None:
    """A JSON-ready float (None for NaN/inf/None)."""
    if value is None:
        return None
    v = float(value)
    return v if math.isfinite(v) else None


def _caught(fn: Callable[[], Any], notes: list[str], what: str) -> Any:
    """Call ``fn``; turn warnings and ValueErrors into notes (the analysis never raises)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = fn()
        except ValueError as exc:
            notes.append(f"{what}: {exc}")
            result = None
    for w in caught:
        notes.append(f"{what}: {w.message}")
    return result


def _best_gauge_set(
    x: npt.NDArray[np.float64], k: float, size: int
) -> tuple[tuple[int, ...], float] | None:
    """The ``size`` gauges (indices into x) best conditioned to separate incident and reflected
    waves of wavenumber k: the largest ``(n - |sum exp(2ikx)|) / (n + |...|)``."""
    best: tuple[tuple[int, ...], float] | None = None
    for combo in itertools.islice(itertools.combinations(range(x.size), size), 5000):
        s = abs(np.sum(np.exp(2j * k * x[list(combo)])))
        cond = (size - s) / (size + s)
        if best is None or cond > best[1] + 1e-12:
            best = (combo, float(cond))
    return best


def _overturn_summary(overturns: Sequence[tuple[float, an.Overturn]], checks: int
                      ) -> dict[str, Any]:
    """JSON-ready summary of the overturned surfaces seen in ``checks`` snapshots."""
    out: dict[str, Any] = {"checks": checks, "seen": len(overturns)}
    if overturns:
        t, first = overturns[0]
        out["first"] = {"time": t, "x_min": first.x_min, "x_max": first.x_max,
                        "gap": first.z_gap_top - first.z_gap_bottom}
        out["x_min"] = min(o.x_min for _, o in overturns)
        out["x_max"] = max(o.x_max for _, o in overturns)
        out["columns"] = max(o.n_columns for _, o in overturns)
    return out


@dataclass(frozen=True)
class _Run:
    """What every part of the analysis reads: the set-up, the resampled records, the notes."""

    setup: FlumeScene
    gauges: FlumeGauges
    t_start: float | None
    t: npt.NDArray[np.float64]
    eta: npt.NDArray[np.float64]
    runup: npt.NDArray[np.float64] | None
    notes: list[str]
    regular: bool
    irregular: bool

    @property
    def law(self) -> PaddleLaw:
        return self.setup.law

    @property
    def period(self) -> float | None:
        return self.setup.law.period

    @property
    def depth(self) -> float:
        return self.setup.flume.depth

    @property
    def end(self) -> float:
        return float(self.t[-1]) if self.t.size else 0.0

    def window_start(self, x: float) -> float:
        """Start of the steady part at ``x`` [m]: the ramp, the arrival and one period."""
        if self.t_start is not None:
            return float(self.t_start)
        extra = self.period if self.period is not None else 0.0
        return self.law.ramp_duration + self.setup.arrival_time(x) + extra

    def needed_end(self, start: float) -> float | None:
        """The record end [s] a window from ``start`` [s] needs for periodic waves
        (:data:`MIN_WINDOW_PERIODS` periods), or None for waves without a period."""
        if not (self.regular or self.irregular) or self.period is None:
            return None
        return start + MIN_WINDOW_PERIODS * self.period

    def too_short(self, start: float) -> float | None:
        """The end time [s] a window from ``start`` needs when the record ends before it,
        else None. A run to that end time qualifies: its last sample may fall up to a sample
        interval before it."""
        needed = self.needed_end(start)
        slack = float(self.setup.sample_interval or 0.0) + 1e-9
        if needed is not None and self.end < needed - slack:
            return needed
        return None

    def short_note(self, what: str, start: float, needed: float, why: str) -> str:
        """A note that ``what`` needs the record to ``needed`` [s] (a window from ``start``,
        ``why`` it starts there) and what to run."""
        return (f"{what}: not computed; needs {MIN_WINDOW_PERIODS:g} wave periods of steady "
                f"record from t = {start:.3g} s ({why}) to {needed:.3g} s, but the record ends "
                f"at {self.end:.3g} s: run with until >= {math.ceil(needed * 10) / 10:g} s")


def analyse_flume(
    setup: FlumeScene,
    gauges: FlumeGauges,
    t_start: float | None = None,
    overturns: Sequence[tuple[float, an.Overturn]] = (),
    overturn_checks: int = 0,
) -> dict[str, Any]:
    """Wave analysis of a flume run, as a JSON-ready dict.

    Time windows: each gauge is analysed over its *steady part*, from the wave's arrival
    (:meth:`FlumeScene.arrival_time`) plus the ramp plus one period, to the end of the record
    (``t_start``, if given, overrides the start for every gauge). Records are resampled on a
    uniform grid of ``sample_interval`` and dry samples read the bed level. Periodic waves need
    :data:`MIN_WINDOW_PERIODS` periods of window: where the record is shorter, the part is not
    computed, ``needs_until`` gives the end time it needs and a note says what to run (a part
    of a window is never analysed as a whole one).

    Keys:

    - ``wave``: the wave and paddle (type, period, height, wavelength, stroke, ...); ``dim``.
    - ``gauges``: per elevation gauge: ``name``, ``x`` (``y``), ``still_depth``, ``window``,
      and zero-down-crossing ``H_mean``, ``H_max``, ``H_min``, ``H_rms``, ``T_mean``,
      ``n_waves``, ``crest_mean``, ``trough_mean``, ``mean_level`` (set-up); ``H_target`` and
      ``H_rel_error`` for regular waves at gauges over the flat floor; ``harmonics`` (first three
      harmonic amplitudes [m]) for regular waves; ``hm0``, ``tp`` (spectrum) for irregular waves;
      ``eta_max`` and ``t_max`` for solitary waves and tabulated motions.
    - ``envelopes``: ``name``, ``x``, ``maximum``, ``minimum``, ``mean``, ``mid_level`` per gauge
      sorted by x (seed 001 Fig. 8), each over its steady part (None where it is too short, with
      the end time it needs in ``needs_until``).
    - ``breaking`` (with a beach): ``criterion`` H/d > 0.78 from the gauges' waves, ``position``,
      ``time``, ``wave_height``, ``iribarren`` and ``breaker_type`` from that height, plus
      ``max_height_position`` / ``max_height`` (where the mean wave height peaks among the
      gauges over the slope) and ``iribarren_incident`` / ``breaker_type_incident`` from the
      target height; with ``overturn_checks`` snapshots searched
      (:attr:`FlumeSimulation.overturns`): ``overturn`` (``checks``, ``seen`` = snapshots
      with an overturned surface, the ``first`` one's ``time``, ``x_min``, ``x_max``, ``gap``,
      the ``x_min``/``x_max`` over all, the most ``columns``) and ``breaker_type_observed``:
      ``"plunging"`` when the surface overturned, else None (spilling, or no breaking
      resolved).
      For regular waves ``phase_averaged``: the same criterion met by the phase-averaged wave
      of each gauge's window (``position`` interpolated between gauges, ``wave_height`` and
      ``depth`` there, ``distance_to_shoreline``, ``max_height`` and its position, the
      ``profile`` of phase-averaged heights, ``n_waves``): a height and a place of one wave.
    - ``velocity_verticals`` (regular waves, velocity probes on a vertical): ``crest_velocity``
      and ``trough_velocity`` (phase-averaged highest and lowest u in the water column), against
      ``sqrt_gD``, and the per-wave crest velocity's mean and std; the time-averaged ``mean_u``
      at each point (``z`` above the SWL), the ``trough_level``, the ``undertow`` below it (also
      over ``sqrt_gD``; seed 002 Table 3) and the mass fluxes below and above the trough.
    - ``crest_celerity`` (regular waves with a beach): the phase-averaged crest's speed between
      neighbouring gauges (``x`` midpoints), ``shallow_water_speed`` sqrt(g d) and their
      ``ratio`` (seed 002: 0.7-0.8 in the surf zone).
    - ``mean_level_near_paddle`` (regular waves): the mean level at the gauge nearest the paddle
      in 8 blocks of whole periods, its ``spread`` and ``drift``, also over H.
    - ``runup`` (with a run-up gauge): per wave (regular: ``mean``, ``std``, ``values``,
      ``mean_over_H``) or overall (``max``; ``R2`` for irregular waves).
    - ``reflection`` (regular or irregular waves, 2-3 gauges over the flat floor between the
      paddle and the beach's toe, outside the damping zone, with a usable spacing): ``method``,
      ``gauges``, ``coefficient``, ``incident_amplitude``, ``reflected_amplitude``.
    - ``forces``: per force gauge ``name``, ``structure``, the record's peaks, means, impulse and
      significant force (:func:`watersim.analysis.load_statistics`); ``overtopping``: per
      overtopping gauge ``name``, ``x``, ``total`` crossed volume and ``peak_discharge``.
    - ``notes``: what could not be computed and why.
    - ``units``: the unit of each quantity by key (:data:`UNITS`).
    """
    notes: list[str] = []
    t, eta, runup = gauges.uniform()
    run = _Run(setup, gauges, t_start, t, eta, runup, notes,
               regular=isinstance(setup.wave, RegularWave),
               irregular=isinstance(setup.wave, IrregularWave))
    result: dict[str, Any] = {
        "wave": setup.describe(), "dim": setup.dim,
        "still_water_depth": run.depth,
        "record_end": run.end,
        "gauges": [],
        "notes": notes,
        "units": UNITS,
    }
    waves = [_gauge_waves(run, j) for j in range(len(gauges.names))]
    result["gauges"] = [entry for entry, _ in waves]
    if gauges.names and eta.size:
        result["envelopes"] = _envelopes(run)
        if setup.flume.beach is not None:
            means = [mean for _, mean in waves]
            result["breaking"] = _breaking(run, means, overturns, overturn_checks)
    if runup is not None and t.size:
        result["runup"] = _runup(run, runup)
    if (run.regular or run.irregular) and run.period is not None and gauges.names:
        result["reflection"] = _reflection(run)
    if run.regular:
        if "breaking" in result:
            result["breaking"]["phase_averaged"] = _phase_averaged_breaking(run)
        verticals = _velocity_verticals(run)
        if verticals:
            result["velocity_verticals"] = verticals
        if setup.flume.beach is not None:
            result["crest_celerity"] = _crest_celerity(run)
        result["mean_level_near_paddle"] = _mean_level_near_paddle(run)
    result.update({k: v for k, v in (("forces", _forces(run)),
                                     ("overtopping", _overtopping(run))) if v})
    return result


def _forces(run: _Run) -> list[dict[str, Any]]:
    """Per force gauge with at least two samples: its load statistics (see ``forces``)."""
    gauges: dict[str, Any] = dict(zip(run.setup._gauge_names(), run.setup.gauges, strict=True))
    out: list[dict[str, Any]] = []
    for name, t, force, _ in ForceGauge.records_of(run.gauges):
        if t.size < 2:
            run.notes.append(f"forces: gauge {name!r} has fewer than two samples")
            continue
        stats = an.load_statistics(t, force[:, 0], force[:, -1])
        out.append({"name": name, "structure": gauges[name].structure,
                    **{k: _f(v) for k, v in stats.items()}, "n_waves": stats["n_waves"]})
    return out


def _gauge_waves(run: _Run, j: int) -> tuple[dict[str, Any], float | None]:
    """Gauge ``j``'s waves over its steady part: zero-down-crossing statistics, set-up, and
    the harmonics (regular waves), the spectrum (irregular) or the highest crest (others);
    with the mean wave height [m] (None if not measured)."""
    gauges, t, eta, notes, T = run.gauges, run.t, run.eta, run.notes, run.period
    name = gauges.names[j]
    x = float(gauges.x[j])
    entry: dict[str, Any] = {"name": name, "x": x, "still_depth": float(gauges.still_depth[j])}
    if gauges.y is not None:
        entry["y"] = float(gauges.y[j])
    t0 = run.window_start(x)
    end = run.end
    sel = t >= t0
    entry["window"] = [t0, end]
    series = eta[sel, j] if eta.size else np.zeros(0)
    ts = t[sel]
    entry["n_samples"] = int(ts.size)
    if not (run.regular or run.irregular):
        if eta.size:
            k = int(np.argmax(eta[:, j]))
            entry.update(eta_max=_f(eta[k, j]), t_max=_f(t[k]))
        return entry, None
    needed = run.too_short(t0)
    if needed is not None or ts.size < 4:
        needed = needed if needed is not None else t0 + float(T or 0.0) * MIN_WINDOW_PERIODS
        entry["needs_until"] = needed
        notes.append(run.short_note(f"{name} (x = {x:g} m) wave statistics", t0, needed,
                                    _WHY_GAUGE_WINDOW))
        return entry, None
    zc = _caught(functools.partial(an.zero_crossing_waves, series, ts), notes, name)
    if zc is not None and zc.heights.size < MIN_WAVES:
        notes.append(f"{name} (x = {x:g} m) wave statistics: not computed; the window "
                     f"{t0:.3g}-{end:.3g} s holds {zc.heights.size} whole wave, fewer than "
                     f"{MIN_WAVES}: run longer")
        zc = None
    mean_h = None if zc is None else float(zc.mean_height)
    if zc is not None:
        entry.update(
            H_mean=_f(zc.mean_height),
            H_max=_f(zc.max_height),
            H_min=_f(np.min(zc.heights)),
            H_rms=_f(np.sqrt(np.mean(zc.heights**2))),
            H_significant=_f(zc.significant_height),
            T_mean=_f(zc.mean_period),
            n_waves=int(zc.heights.size),
            crest_mean=_f(np.mean(zc.crest_elevations)),
            trough_mean=_f(np.mean(zc.trough_elevations)),
        )
    entry["mean_level"] = _f(np.mean(series))
    if run.regular and T is not None:
        harm = _caught(functools.partial(an.harmonic_analysis, series, ts, T, 3), notes, name)
        if harm is not None:
            entry["harmonics"] = [_f(a) for a in harm.amplitudes]
        if gauges.still_depth[j] >= run.depth - 1e-9:
            target = run.setup.wave.height  # type: ignore[union-attr]
            entry["H_target"] = target
            if mean_h is not None:
                entry["H_rel_error"] = (mean_h - target) / target
    if run.irregular:
        spec = _caught(functools.partial(an.wave_spectrum, series, ts), notes, name)
        if spec is not None:
            entry.update(hm0=_f(spec.hm0), tp=_f(spec.tp))
    return entry, mean_h


_WHY_GAUGE_WINDOW = "the ramp, the waves' arrival at the gauge and one period"

_ENVELOPE_KEYS = ("maximum", "minimum", "mean", "mid_level")


def _envelopes(run: _Run) -> dict[str, list[Any]]:
    """Highest, lowest, mean and mid water level at each gauge (sorted by x) over its steady
    part; None (and the record end it needs in ``needs_until``) where that part is too short
    (:meth:`_Run.too_short`, or fewer than two samples): a part of a window is no envelope."""
    gauges, t, eta = run.gauges, run.t, run.eta
    env: dict[str, list[Any]] = {"name": [], "x": [], **{k: [] for k in _ENVELOPE_KEYS},
                                 "needs_until": []}
    for j in np.argsort(gauges.x, kind="stable"):
        t0 = run.window_start(float(gauges.x[j]))
        sel = t >= t0
        needed = run.too_short(t0)
        env["name"].append(gauges.names[j])
        env["x"].append(float(gauges.x[j]))
        if needed is not None or np.count_nonzero(sel) < 2:
            for key in _ENVELOPE_KEYS:
                env[key].append(None)
            env["needs_until"].append(needed if needed is not None else t0)
            continue
        e = an.water_level_envelopes(eta[sel, j])
        for key in _ENVELOPE_KEYS:
            env[key].append(_f(getattr(e, key)))
        env["needs_until"].append(None)
    return env


def _breaking(run: _Run, means: Sequence[float | None],
              overturns: Sequence[tuple[float, an.Overturn]], overturn_checks: int
              ) -> dict[str, Any]:
    """Where and how the waves break on the beach: the gauges' H/d criterion, where the mean
    wave height ``means`` peaks, the incident Iribarren number and the overturns seen."""
    setup, gauges, t, eta, notes, T = run.setup, run.gauges, run.t, run.eta, run.notes, run.period
    depth, g, law = run.depth, setup.g, run.law
    slope = setup.beach_slope
    breaking: dict[str, Any] = {}
    sel = t >= (law.ramp_duration if run.t_start is None else run.t_start)
    if np.count_nonzero(sel) >= 4:
        onset = _caught(
            lambda: an.breaking_onset_from_gauges(
                eta[sel], t[sel], gauges.x, gauges.still_depth, slope, T, g
            ),
            notes,
            "breaking",
        )
        if onset is not None:
            breaking.update(
                criterion=onset.criterion,
                position=onset.position,
                time=onset.time,
                gauge=gauges.names[onset.index],
                wave_height=_f(onset.wave_height),
                iribarren=_f(onset.iribarren),
                breaker_type=onset.breaker_type,
            )
        else:
            breaking["criterion"] = f"H/d > {wt.MCCOWAN_BREAKING_RATIO}"
            breaking["position"] = None
            notes.append("breaking: no gauge recorded a wave with H/d > 0.78")
    # where the mean wave height peaks, over the gauges on the slope (all wet ones if none)
    wet = [(j, m) for j, m in enumerate(means)
           if m is not None and 0.0 < gauges.still_depth[j] < depth - 1e-9]
    if not wet:
        wet = [(j, m) for j, m in enumerate(means)
               if m is not None and gauges.still_depth[j] > 0.0]
    if wet:
        j_max, h_max = max(wet, key=lambda item: item[1])
        breaking["max_height_position"] = float(gauges.x[j_max])
        breaking["max_height"] = h_max
    if slope is not None and T is not None and law.design_height is not None:
        l0 = float(wt.deep_water_wavelength(T, g))
        height = (setup.wave.height if run.regular  # type: ignore[union-attr]
                  else law.design_height / 1.8)
        xi = float(wt.iribarren(slope, height, l0))
        breaking["iribarren_incident"] = xi
        breaking["breaker_type_incident"] = str(wt.breaker_type(xi))
    breaking["slope"] = slope
    if overturn_checks:
        breaking["overturn"] = _overturn_summary(overturns, overturn_checks)
        breaking["breaker_type_observed"] = "plunging" if overturns else None
        if not overturns:
            notes.append(f"breaking: no overturned surface (a jet over air) in "
                         f"{overturn_checks} snapshots over the beach")
    return breaking


def _runup(run: _Run, runup: npt.NDArray[np.float64]) -> dict[str, Any]:
    """The run-up after the waves reach the shoreline: its highest value, per wave (regular
    waves) or its 2 % exceedance R2 (irregular)."""
    setup, t, notes, T = run.setup, run.t, run.notes, run.period
    info: dict[str, Any] = {"name": run.gauges.runup_name}
    runup_start = run.law.ramp_duration
    shore = setup.shoreline
    if shore is not None:
        runup_start += setup.arrival_time(shore)
    if run.t_start is not None:
        runup_start = run.t_start
    sel = t >= runup_start
    info["window"] = [runup_start, run.end]
    needed = run.too_short(runup_start)
    if needed is not None:
        info["needs_until"] = needed
        notes.append(run.short_note("runup", runup_start, needed,
                                    "the ramp and the waves' arrival at the shoreline"))
        return info
    if np.count_nonzero(sel) < 2:
        info["needs_until"] = runup_start
        notes.append(f"runup: not computed; the record ends at {run.end:.3g} s, before the "
                     f"waves reach the shoreline (t = {runup_start:.3g} s)")
        return info
    info["max"] = _f(np.max(runup[sel]))
    if run.regular and T is not None:
        height = setup.wave.height  # type: ignore[union-attr]
        per_wave = _caught(lambda: an.runup_per_wave(runup[sel], t[sel], T, 0.0), notes, "runup")
        if per_wave is not None:
            info.update(
                mean=per_wave.mean,
                std=per_wave.std,
                n_waves=int(per_wave.values.size),
                values=[float(v) for v in per_wave.values],
                mean_over_H=per_wave.mean / height,
                std_over_H=per_wave.std / height,
            )
    elif run.irregular:
        info["R2"] = _f(np.percentile(runup[sel], 98.0))
    return info


def _reflection_gauges(
    run: _Run, k: float
) -> tuple[list[int], tuple[tuple[int, ...], float] | None]:
    """The gauges over the flat floor before the beach and the damping zone (one per x, on
    the first gauge's line across), and the best conditioned set of three (or two) of them
    for wavenumber ``k`` with its condition."""
    setup, gauges = run.setup, run.gauges
    zone = setup.damping_zone
    limit = min(zone[0] if zone is not None else setup.flume.length, setup.toe)
    flat = [j for j in range(len(gauges.names))
            if gauges.still_depth[j] >= run.depth - 1e-9 and 0.0 < gauges.x[j] < limit
            and (gauges.y is None or abs(gauges.y[j] - gauges.y[0]) < 1e-12)]
    xs = np.unique(gauges.x[flat]) if flat else np.zeros(0)
    flat = [next(j for j in flat if gauges.x[j] == xv) for xv in xs]
    chosen: tuple[tuple[int, ...], float] | None = None
    if len(flat) >= 3:
        chosen = _best_gauge_set(gauges.x[flat], k, 3)
    if len(flat) >= 2 and (chosen is None or chosen[1] < an._SPACING_CONDITION_LIMIT):
        pair = _best_gauge_set(gauges.x[flat], k, 2)
        if pair is not None and (chosen is None or pair[1] > chosen[1]):
            chosen = pair
    return flat, chosen


def _reflection(run: _Run) -> dict[str, Any] | None:
    """The reflection coefficient from two (Goda & Suzuki 1976) or three (Mansard & Funke
    1980) gauges over the flat floor, or None (with a note) without a usable set."""
    gauges, t, eta, notes, depth, g = (run.gauges, run.t, run.eta, run.notes, run.depth,
                                       run.setup.g)
    T = run.period
    assert T is not None
    knum = 2.0 * math.pi / float(wt.wavelength(T, depth, g))
    flat, chosen = _reflection_gauges(run, knum)
    if chosen is None or chosen[1] < an._SPACING_CONDITION_LIMIT:
        notes.append(
            "reflection: fewer than two gauges over the flat floor with a spacing away from "
            "multiples of half a wavelength"
        )
        return None
    idx = np.asarray([flat[i] for i in chosen[0]], dtype=np.intp)
    t0 = max(run.window_start(float(gauges.x[j])) for j in idx)
    sel = t >= t0
    method = an.mansard_funke if len(idx) == 3 else an.goda_suzuki
    kwargs: dict[str, Any] = (
        {"period": T} if run.regular else {"frequency_band": (0.5 / T, 2.0 / T)}
    )
    needed = run.too_short(t0)
    if needed is not None or np.count_nonzero(sel) < 8:
        needed = needed if needed is not None else t0 + MIN_WINDOW_PERIODS * T
        notes.append(run.short_note(
            f"reflection (gauges {', '.join(gauges.names[int(j)] for j in idx)})", t0, needed,
            "the ramp, the waves' arrival at the farthest of its gauges and one period"))
        return None
    refl = _caught(
        lambda: method(eta[np.ix_(sel, idx)], t[sel], gauges.x[idx], depth, g=g, **kwargs),
        notes,
        "reflection",
    )
    if refl is None:
        return None
    valid = refl.valid
    inc = np.sqrt(np.sum(refl.incident_amplitudes[valid] ** 2))
    ref = np.sqrt(np.sum(refl.reflected_amplitudes[valid] ** 2))
    return {
        "method": refl.method,
        "gauges": [gauges.names[int(j)] for j in idx],
        "coefficient": _f(refl.reflection_coefficient),
        "incident_amplitude": _f(inc),
        "reflected_amplitude": _f(ref),
        "window": [t0, run.end],
    }


# Long records of regular waves (seed 001 averages 128 waves after 128 of spin-up): breaking of
# the phase-averaged wave, crest velocity on verticals, drift of the mean level near the paddle

MEAN_LEVEL_BLOCKS = 8
"""Blocks the mean level near the paddle is averaged over, to see it drift."""

MIN_BLOCK_PERIODS = 2
"""Whole periods a mean-level block needs at the least."""


def _phase_averaged_breaking(run: _Run) -> dict[str, Any] | None:
    """Where the phase-averaged wave first reaches H/d = 0.78 among the wet gauges, and its
    height there (:func:`watersim.analysis.breaking_from_phase_averaged_heights`); each gauge
    averages the whole periods of its own steady window. None (with a note) without two wet
    gauges with a window of :data:`MIN_WINDOW_PERIODS`."""
    gauges, t, eta, T = run.gauges, run.t, run.eta, run.period
    if T is None or not eta.size:
        return None
    xs, heights, depths, waves = [], [], [], []
    for j in np.argsort(gauges.x, kind="stable"):
        x, depth = float(gauges.x[j]), float(gauges.still_depth[j])
        t0 = run.window_start(x)
        sel = t >= t0
        if depth <= 0.0 or run.too_short(t0) is not None or np.count_nonzero(sel) < 4:
            continue
        series = eta[sel, j]
        if not np.all(np.isfinite(series)):
            continue
        pa = an.phase_average(series, t[sel], T)
        xs.append(x)
        heights.append(float(np.ptp(pa.mean)))
        depths.append(depth)
        waves.append(pa.n_waves)
    if len(xs) < 2:
        run.notes.append("breaking.phase_averaged: not computed; fewer than two wet gauges "
                         "with a steady window")
        return None
    # the gauges on the slope (and the last one over the flat floor) when there are two
    on_slope = [i for i, d in enumerate(depths) if d < run.depth - 1e-9]
    if len(on_slope) >= 2:
        keep = list(range(max(0, on_slope[0] - 1), len(xs)))
        xs, heights, depths, waves = ([v[i] for i in keep] for v in (xs, heights, depths, waves))
    out: dict[str, Any] = {
        "criterion": f"H/d >= {wt.MCCOWAN_BREAKING_RATIO} of the phase-averaged wave",
        "n_waves": min(waves),
        "profile": {"x": xs, "height": heights, "still_depth": depths},
    }
    found = an.breaking_from_phase_averaged_heights(xs, heights, depths)
    if found is None:
        run.notes.append("breaking.phase_averaged: the phase-averaged wave stays below "
                         f"H/d = {wt.MCCOWAN_BREAKING_RATIO} at every gauge")
        out["position"] = None
        k = int(np.argmax(heights))
        out.update(max_height=heights[k], max_height_position=xs[k])
        return out
    shore = run.setup.shoreline
    out.update(position=found.position, wave_height=found.wave_height, depth=found.depth,
               max_height=found.max_height, max_height_position=found.max_height_position)
    if shore is not None:
        out["distance_to_shoreline"] = shore - found.position
    return out


WET_KERNEL_SUM = 0.5
"""A probe point is in the water where the fluid's kernel sum (Shepard's denominator) is at
least this: half a kernel of fluid, the level of a free surface."""


def _water_column(kernel_sum: npt.NDArray[np.float64], z: npt.NDArray[np.float64]
                  ) -> npt.NDArray[np.bool_]:
    """Which points of a vertical are in the water at each sample ``(n_samples, n_points)``:
    those with a kernel sum of at least :data:`WET_KERNEL_SUM` and every point below one (the
    water reaches the bed). The kernel sum counts fluid particles only, so next to the bed,
    whose particles fill the other half of the kernel, it is about 0.5 in water: at dp/2 above
    the bed it falls below 0.5 in some samples (measured at seed 002's gauge 8, dp 0.068 m: 96
    of 177), which would put the trough at the bed."""
    wet = np.asarray(kernel_sum) >= WET_KERNEL_SUM
    order = np.argsort(z, kind="stable")[::-1]  # from the top down
    below_wet = np.logical_or.accumulate(wet[:, order], axis=1)
    out = np.empty_like(wet)
    out[:, order] = below_wet
    return out


def _velocity_verticals(run: _Run) -> list[dict[str, Any]]:
    """For each velocity probe laid on a vertical (every point at one x) over wet bed: the crest
    and trough velocities (:func:`watersim.analysis.crest_velocity`) over its steady window, and
    against ``sqrt(g D)``."""
    out: list[dict[str, Any]] = []
    T = run.period
    if T is None:
        return out
    g = run.setup.g
    for name, record in run.gauges.velocity.items():
        points = np.asarray(record.points)
        x = float(points[0, 0])
        if not np.allclose(points[:, 0], x) or points.shape[0] < 2:
            continue
        depth = float(np.asarray(run.setup.still_depth(x)).ravel()[0])
        entry: dict[str, Any] = {"name": name, "x": x, "still_depth": depth}
        out.append(entry)
        t0 = run.window_start(x)
        needed = run.too_short(t0)
        sel = record.t >= t0
        if depth <= 0.0:
            run.notes.append(f"{name}: no crest velocity; the vertical stands on a dry bed")
            continue
        if needed is not None or np.count_nonzero(sel) < 4:
            entry["needs_until"] = needed
            run.notes.append(run.short_note(f"{name} crest velocity", t0, needed or t0,
                                            "the ramp, the waves' arrival and one period"))
            continue
        u = np.asarray(record.velocity)[sel, :, 0]
        wet = _water_column(np.asarray(record.kernel_sum)[sel], points[:, 1])
        cv = _caught(functools.partial(an.crest_velocity, u, wet, record.t[sel], T, depth,
                                       g=g), run.notes, name)
        if cv is None:
            continue
        bed = float(np.asarray(run.setup.bed(x)).ravel()[0])
        # the time mean needs uniform samples: the probe samples at the first step after each
        # sample time, so its times are interpolated onto the nominal interval
        ts = record.t[sel]
        grid = np.arange(ts[0], ts[-1], float(np.median(np.diff(ts))))
        u_grid = np.stack([np.interp(grid, ts, u[:, k]) for k in range(u.shape[1])], axis=1)
        wet_grid = np.stack([np.interp(grid, ts, wet[:, k].astype(float)) >= 0.5
                             for k in range(u.shape[1])], axis=1)
        flow = _caught(functools.partial(an.vertical_mean_flow, u_grid, wet_grid, points[:, 1],
                                         grid, T, bed=bed), run.notes, name)
        if flow is not None:
            entry.update(
                trough_level=_f(flow.trough_level - run.depth),
                undertow=_f(flow.undertow),
                undertow_over_sqrt_gD=_f(flow.undertow / np.sqrt(g * depth)),
                flux_below_trough=_f(flow.flux_below_trough),
                flux_above_trough=_f(flow.flux_above_trough),
                mean_u=[_f(v) for v in flow.mean_u],
                z=[float(v) - run.depth for v in points[:, 1]],
            )
        entry.update(
            window=[t0, float(record.t[-1])],
            n_waves=cv.n_waves,
            sqrt_gD=cv.sqrt_gd,
            crest_velocity=cv.crest,
            trough_velocity=cv.trough,
            crest_velocity_over_sqrt_gD=cv.crest / cv.sqrt_gd,
            trough_velocity_over_sqrt_gD=cv.trough / cv.sqrt_gd,
            crest_velocity_per_wave_mean=float(np.mean(cv.crest_per_wave)),
            crest_velocity_per_wave_std=float(np.std(cv.crest_per_wave)),
        )
    return out


def _crest_celerity(run: _Run) -> dict[str, Any] | None:
    """The phase-averaged crest's speed between neighbouring wet gauges (one per x) against
    ``sqrt(g d)`` (:func:`watersim.analysis.crest_celerity`), over the whole periods after the
    latest of their steady starts; None (with a note) when that window is too short."""
    gauges, t, eta, T = run.gauges, run.t, run.eta, run.period
    if T is None or not eta.size:
        return None
    cols: list[int] = []
    for j in np.argsort(gauges.x, kind="stable"):
        if gauges.still_depth[j] > 0.0 and (not cols or gauges.x[j] > gauges.x[cols[-1]] + 1e-9):
            cols.append(int(j))
    if len(cols) < 2:
        return None
    t0 = max(run.window_start(float(gauges.x[j])) for j in cols)
    needed = run.too_short(t0)
    sel = t >= t0
    if needed is not None or np.count_nonzero(sel) < 4:
        run.notes.append(run.short_note("celerity", t0, needed or t0,
                                        "the ramp, the waves' arrival at the farthest gauge "
                                        "and one period"))
        return None
    found = _caught(functools.partial(an.crest_celerity, eta[np.ix_(sel, cols)], t[sel],
                                      gauges.x[cols], gauges.still_depth[cols], T,
                                      g=run.setup.g), run.notes, "celerity")
    if found is None:
        return None
    return {
        "window": [t0, run.end],
        "x": [float(v) for v in found.x],
        "celerity": [_f(v) for v in found.celerity],
        "shallow_water_speed": [_f(v) for v in found.shallow_water_speed],
        "ratio": [_f(v) for v in found.ratio],
    }


def _mean_level_near_paddle(run: _Run) -> dict[str, Any] | None:
    """The mean water level at the gauge nearest the paddle over the flat floor, in
    :data:`MEAN_LEVEL_BLOCKS` blocks of whole periods of its steady window, and how far it
    wanders against the wave height; None when the steady window holds fewer than
    ``MEAN_LEVEL_BLOCKS * MIN_BLOCK_PERIODS`` periods."""
    gauges, t, eta, T = run.gauges, run.t, run.eta, run.period
    height = run.law.design_height
    flat = [j for j in range(len(gauges.names)) if gauges.still_depth[j] >= run.depth - 1e-9]
    if T is None or not flat or not eta.size or not height:
        return None
    j = min(flat, key=lambda k: gauges.x[k])
    x = float(gauges.x[j])
    t0 = run.window_start(x)
    sel = t >= t0
    periods = int((run.end - t0) // T)
    block = periods // MEAN_LEVEL_BLOCKS
    if block < MIN_BLOCK_PERIODS:
        # a drift is a long run's question: a short run gets None and no note
        return None
    blocks = _caught(functools.partial(an.mean_level_blocks, eta[sel, j], t[sel], T, block),
                     run.notes, "mean_level_near_paddle")
    if blocks is None:
        return None
    return {
        "gauge": gauges.names[j],
        "x": x,
        "block_periods": blocks.block_periods,
        "block_starts": [float(s) for s in blocks.starts],
        "block_means": [_f(m) for m in blocks.means],
        "spread": blocks.spread,
        "drift": blocks.drift,
        "spread_over_H": blocks.spread / height,
        "drift_over_H": blocks.drift / height,
    }


def _overtopping(run: _Run) -> list[dict[str, Any]]:
    """Per overtopping gauge with samples: the total volume over its section and the peak
    discharge (see ``overtopping``)."""
    specs = {s["name"]: s for s in run.setup._gauge_specs()}
    return [{"name": name, "x": specs[name]["x"], "total": _f(volume[-1]),
             "peak_discharge": _f(np.max(discharge))}
            for name, t, volume, discharge in OvertoppingGauge.records_of(run.gauges) if t.size]
