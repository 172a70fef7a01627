"""The Buchner (2002) 2D dam break: the pressure on the far wall, with each wall model.

Set-up as Colagrossi & Landrini (2003) and PySPH's ``db_2d_buchner.py`` use it
(``watersim/data/SOURCES.md``): a water column H = 0.6 m high and 2H long against the back wall
of a tank 5.366 H long (3H high, never reached in the time run); the pressure probe on the far
wall at 0.2 H. The pressure is the Shepard interpolation of the fluid's (the core's pressure
gauge, as DualSPHysics' measuring tool) at the probe moved half a dp off the wall into the
water, sampled every 0.005 sqrt(H/g). The three cases ``buchner2d_dbc``, ``buchner2d_adami``
and ``buchner2d_mdbc`` differ only in the wall model.

Errors, in ``p* = p / (rho0 g H)`` against ``t* = t sqrt(g/H)``:

- ``peak``: the first impact's peak (the largest p* for t* in [2, 3.5]) against the
  digitised data's;
- ``impulse``: the integral of p* over t* from 2 to the run's end (7, or 4.5 with ``quick``)
  against the data's over the same window (the data sorted by t* and integrated by the
  trapezoidal rule: the digitised points scatter, which the integral averages);
- ``noise``: the RMS of the signal's high-pass part, p* minus its centred running mean over
  0.25 t* (a quarter of the rise time of the first impact), over t* from 3 to the end, where
  the data are a slow plateau: the acoustic noise of the wall pressure, which modified DBC is
  meant to remove (English et al. 2022). Not an error against data: smaller is smoother.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..flume_cases import _load_csv
from ..scenes import DamBreak
from ..simulation import Simulation
from .running import _Clock, advance, make_record

BUCHNER_H = 0.6
"""Column height H [m] (Buchner 2002; Colagrossi & Landrini 2003)."""
BUCHNER_TANK = 5.366
"""Tank length over H."""
BUCHNER_PROBE = 0.2
"""Probe height over H, on the far wall (PySPH's ``db_2d_buchner.py``)."""
BUCHNER_FILES: Mapping[str, str] = {
    "pysph": "buchner2002_wall_pressure_pysph.csv",
    "jaxsph": "buchner2002_wall_pressure_jaxsph.csv",
}
"""The two independent digitisations of Buchner's record (``watersim/data/SOURCES.md``); the
first is the primary reference (it covers t* up to 7.4, the second to 4.1)."""
WALL_MODELS: tuple[str, ...] = ("dbc", "adami", "mdbc")
"""The wall models the three cases run, one each."""

PEAK_WINDOW = (2.0, 3.5)
"""t* window of the first impact."""
IMPULSE_FROM = 2.0
"""t* where the impulse starts (before the front arrives at about 2.4)."""
NOISE_FROM = 3.0
"""t* where the noise is measured from (after the first impact)."""
NOISE_WINDOW = 0.25
"""Width of the running mean the high-pass part is taken against [t*]."""
SAMPLE = 0.005
"""Pressure sample interval [t*]."""


def buchner_reference(name: str = "pysph") -> tuple[np.ndarray, np.ndarray]:
    """A digitisation of Buchner's wall pressure: t* and p*, sorted by t*."""
    t, p = _load_csv(BUCHNER_FILES[name])
    order = np.argsort(t, kind="stable")
    return t[order], p[order]


def pressure_impulse(t: np.ndarray, p: np.ndarray, start: float, end: float) -> float:
    """The trapezoidal integral of ``p`` over ``t`` in ``[start, end]`` (``t`` sorted), the
    ends interpolated."""
    inner = (t > start) & (t < end)
    tt = np.concatenate([[start], t[inner], [end]])
    pp = np.concatenate([[np.interp(start, t, p)], p[inner], [np.interp(end, t, p)]])
    return float(np.sum(0.5 * (pp[1:] + pp[:-1]) * np.diff(tt)))


def high_pass_rms(t: np.ndarray, p: np.ndarray, start: float, window: float) -> float:
    """The RMS over ``t >= start`` of ``p`` minus its centred running mean over ``window``
    (``t`` evenly sampled)."""
    dt = float(t[1] - t[0])
    n = max(3, int(round(window / dt)) | 1)  # odd, so that the mean is centred
    mean = np.convolve(p, np.ones(n) / n, mode="same")
    half = n // 2
    sel = (t >= start) & (np.arange(t.size) >= half) & (np.arange(t.size) < t.size - half)
    return float(np.sqrt(np.mean((p[sel] - mean[sel]) ** 2))) if np.any(sel) else math.nan


def buchner_builder(dp: float, boundary: str, until: float) -> DamBreak:
    """The Buchner dam break at ``dp`` with the wall model ``boundary``, to ``until`` [s]."""
    h = BUCHNER_H
    return DamBreak(dim=2, dp=dp, width=2.0 * h, height=h, tank_length=BUCHNER_TANK * h,
                    tank_height=3.0 * h, boundary=boundary, until=until)


def run_buchner(case: Any, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """A ``buchner2d_<model>`` case at ``res`` = H / dp (the runner of :mod:`.cases`)."""
    boundary = case.name.rsplit("_", 1)[1]
    dp = case.dp(res)
    h = BUCHNER_H
    builder = buchner_builder(dp, boundary, 1.0)
    g = builder.g
    t_scale = math.sqrt(h / g)
    end = 4.5 if quick else 7.0
    until = end * t_scale
    builder = buchner_builder(dp, boundary, until)
    scene = builder.to_scene()
    probe = [BUCHNER_TANK * h - 0.5 * dp, BUCHNER_PROBE * h]
    scene["gauges"] = [{"type": "pressure", "name": "buchner", "points": [probe],
                        "interval": SAMPLE * t_scale}]
    clock = _Clock()
    sim = Simulation(scene)
    status, message = advance(sim, until, until / 20.0, progress=progress,
                              label=f"{case.name} {res:g}")
    record = next(r for r in sim.core.gauges() if r["name"] == "buchner")
    rho0 = float(sim.scene["rho0"])
    t = np.asarray(record["t"], dtype=np.float64) / t_scale
    p = np.asarray(record["pressure"], dtype=np.float64).reshape(-1) / (rho0 * g * h)
    t_end = min(end, float(t[-1])) if t.size else 0.0
    errors: dict[str, float | None] = {"peak": None, "impulse": None, "noise": None}
    details: dict[str, Any] = {"boundary": boundary, "probe": probe, "until": until,
                               "t_star": [round(float(v), 4) for v in t],
                               "p_star": [round(float(v), 5) for v in p]}
    if t.size > 10 and t_end > PEAK_WINDOW[1]:
        in_peak = (t >= PEAK_WINDOW[0]) & (t <= PEAK_WINDOW[1])
        peak = float(np.max(p[in_peak]))
        impulse = pressure_impulse(t, p, IMPULSE_FROM, t_end)
        noise = high_pass_rms(t, p, NOISE_FROM, NOISE_WINDOW)
        details.update(peak=peak, t_peak=float(t[in_peak][np.argmax(p[in_peak])]),
                       impulse=impulse, noise=noise, impulse_window=[IMPULSE_FROM, t_end])
        for name in BUCHNER_FILES:
            tr, pr = buchner_reference(name)
            ref_peak = float(np.max(pr[(tr >= PEAK_WINDOW[0]) & (tr <= PEAK_WINDOW[1])]))
            details[f"peak_{name}"] = ref_peak
            details[f"peak_error_{name}"] = abs(peak / ref_peak - 1.0)
            if tr[-1] >= t_end:
                ref_impulse = pressure_impulse(tr, pr, IMPULSE_FROM, t_end)
                details[f"impulse_{name}"] = ref_impulse
                details[f"impulse_error_{name}"] = abs(impulse / ref_impulse - 1.0)
        errors.update(peak=details["peak_error_pysph"],
                      impulse=details.get("impulse_error_pysph"), noise=noise)
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


def plot_buchner(runs: Sequence[Mapping[str, Any]], path: Path) -> None:
    """The wall pressure of each run against t*, over both digitisations of the data."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4))
    for name, marker in zip(BUCHNER_FILES, ("o", "s"), strict=True):
        tr, pr = buchner_reference(name)
        ax.plot(tr, pr, marker, ms=3, mfc="none", color="k", label=f"Buchner (2002), {name}")
    for run in sorted(runs, key=lambda r: r["resolution"]):
        d = run.get("details", {})
        if d.get("t_star"):
            ax.plot(d["t_star"], d["p_star"], lw=0.8,
                    label=f"{d.get('boundary', '')} H/dp = {run['resolution']:g}")
    ax.set_xlabel("t sqrt(g/H)")
    ax.set_ylabel("p / (rho g H)")
    ax.set_xlim(1.5, 7.2)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
