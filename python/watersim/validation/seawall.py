"""Validation case seawall2d: Hsiao & Lin's (2010) breaking solitary wave overtopping a seawall.

The built-in flume case ``seawall2d`` (:func:`watersim.flume_cases.case_seawall2d`: d = 0.2 m,
H = 0.07 m, a 1:20 slope and a seawall whose crest stands 0.056 m above the still water) against
the laboratory records at seven gauges (``watersim/data/SOURCES.md``): the surface elevation at
WG1, WG3, WG10 and WG22, the inundation depth above the local ground at WG28 (the wall's front
face), WG37 (its back face) and WG40 (behind it). The records' clock starts when the crest
passes WG1; the simulation's is put on it by the time of its own crest at WG1 (a parabola
through the highest sample and its neighbours), so the generated wave's travel to WG1 is not an
error here.

Errors, in units of the wave height H = 0.07 m:

- ``gauge_rms``: the mean over the seven gauges of the RMS difference between the simulated
  and the recorded series at the records' times (within the run);
- ``peak``: the RMS over the seven gauges of the difference of their highest values.

``details`` carries each gauge's RMS and peaks, the crest height at WG1 against H, the volume
that went over the crest per unit width (``crest`` overtopping gauge; the records hold no
measured volume to compare it with) and the series the figure draws.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from .. import analysis as an
from .. import wave_theory as wt
from ..flume import FlumeScene
from ..flume_cases import HSIAO_LIN_GAUGES, HSIAO_LIN_OFFSET, _load_csv
from .case import Case
from .running import _Clock, flume_run, make_record, numerical_case_scene

SEAWALL_DEPTH, SEAWALL_HEIGHT = 0.2, 0.07
"""Still-water depth and solitary wave height of Hsiao & Lin's type-1 wave [m]."""
INUNDATION_GAUGES: tuple[str, ...] = ("WG28", "WG37", "WG40")
"""Gauges whose records are the inundation depth above the local ground (dry at rest)."""
QUICK_SPAN = 6.0
"""How long ``--quick`` runs after the crest passes WG1 [s]: the wave has gone over the wall."""
SERIES_STEP = 0.05
"""Sample interval [s] of the series kept in a run's details for the figure."""


def seawall_reference(name: str) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Gauge ``name``'s record: t [s] from the crest at WG1, and the elevation or (WG28, WG37,
    WG40) the inundation depth [m]."""
    return _load_csv(f"hsiao_lin2010_{name}_basilisk.csv")


def seawall_scene(dp: float, settings: Mapping[str, str] | None = None, quick: bool = False
                  ) -> tuple[FlumeScene, list[str]]:
    """seawall2d at ``dp`` with ``--set``-style numerical ``settings``, run to 12 s after the
    crest reaches WG1 (:data:`QUICK_SPAN` with ``quick``), and the warnings its build gave."""
    span = QUICK_SPAN if quick else 12.0

    def until(s: FlumeScene) -> float:
        assert s.law.duration is not None
        c = float(wt.solitary_celerity(SEAWALL_HEIGHT, SEAWALL_DEPTH, s.g))
        x_wg1 = HSIAO_LIN_GAUGES["WG1"] - HSIAO_LIN_OFFSET
        return 0.5 * s.law.duration + x_wg1 / c + span + 0.2

    return numerical_case_scene("seawall2d", dp, settings, until)


def crest_time(t: npt.NDArray[np.float64], eta: npt.NDArray[np.float64]) -> float:
    """Time of the highest finite sample of ``eta``, refined by the parabola through it and
    its neighbours."""
    finite = np.where(np.isfinite(eta), eta, -np.inf)
    i = int(np.argmax(finite))
    if 0 < i < t.size - 1 and np.all(np.isfinite(eta[i - 1:i + 2])):
        shift = float(an.parabola_peak_shift(eta[i - 1], eta[i], eta[i + 1]))
        return float(t[i] + shift * (t[i + 1] - t[i]))
    return float(t[i])


def gauge_series(eta: npt.NDArray[np.float64], bed: float, depth: float, inundation: bool
                 ) -> npt.NDArray[np.float64]:
    """What the laboratory gauge on ground ``bed`` [m above the floor] records, from the
    simulated elevation above the still water ``eta`` (NaN where dry): the inundation depth
    ``max(0, eta + depth - bed)`` (0 where dry) for an ``inundation`` gauge; else the elevation,
    the ground's level where dry."""
    ground = bed - depth
    level = np.where(np.isfinite(eta), np.maximum(eta, ground), ground)
    return np.maximum(level - ground, 0.0) if inundation else level


def seawall_metrics(t: npt.NDArray[np.float64], series: Mapping[str, npt.NDArray[np.float64]],
                    beds: Mapping[str, float], overtopping: npt.NDArray[np.float64] | None = None
                    ) -> tuple[dict[str, float | None], dict[str, Any]]:
    """Errors and details of a run from its gauge times ``t`` [s], each gauge's elevation
    above the still water (NaN when dry) in ``series`` (by name, WG1 ... WG40), the gauges'
    ground heights above the floor ``beds`` and the crest's overtopping volume record."""
    if "WG1" not in series or t.size < 3 or not np.any(np.isfinite(series["WG1"])):
        return {"gauge_rms": None, "peak": None}, {"notes": ["no crest at WG1"]}
    t0 = crest_time(t, series["WG1"])
    rel = t - t0
    h = SEAWALL_HEIGHT
    rms: dict[str, float] = {}
    peaks: dict[str, tuple[float, float]] = {}
    kept: dict[str, list[float]] = {}
    grid = np.arange(math.floor(rel[0] / SERIES_STEP) * SERIES_STEP, rel[-1], SERIES_STEP)
    for name in HSIAO_LIN_GAUGES:
        if name not in series:
            continue
        sim = gauge_series(series[name], beds[name], SEAWALL_DEPTH, name in INUNDATION_GAUGES)
        kept[name] = [round(float(v), 5) for v in np.interp(grid, rel, sim)]
        td, vd = seawall_reference(name)
        inside = (td >= rel[0]) & (td <= rel[-1])
        if np.count_nonzero(inside) < 2:
            continue
        simulated = np.interp(td[inside], rel, sim)
        rms[name] = float(np.sqrt(np.mean((simulated - vd[inside]) ** 2)) / h)
        window = (rel >= td[inside][0]) & (rel <= td[inside][-1])
        peaks[name] = (float(np.max(sim[window])), float(np.max(vd[inside])))
    errors: dict[str, float | None] = {
        "gauge_rms": float(np.mean(list(rms.values()))) if rms else None,
        "peak": (float(np.sqrt(np.mean([((a - b) / h) ** 2 for a, b in peaks.values()])))
                 if peaks else None),
    }
    eta1 = series["WG1"]
    details: dict[str, Any] = {
        "t_crest_wg1": t0,
        "crest_height_wg1": float(np.nanmax(eta1)),
        "crest_height_wg1_error": float(np.nanmax(eta1)) / h - 1.0,
        "rms_over_H": rms,
        "peak_simulated": {k: v[0] for k, v in peaks.items()},
        "peak_recorded": {k: v[1] for k, v in peaks.items()},
        "series_t": [round(float(v), 3) for v in grid],
        "series": kept,
    }
    if overtopping is not None and overtopping.size:
        details["overtopped_volume"] = float(overtopping[-1])
    return errors, details


def run_seawall(case: Any, res: float, quick: bool, progress: bool,
                settings: Mapping[str, str] | None = None) -> dict[str, Any]:
    """seawall2d at ``res`` = H / dp (the runner of :mod:`.cases`)."""
    dp = case.dp(res)
    scene, notes = seawall_scene(dp, settings, quick)
    clock = _Clock()
    sim, status, message, result = flume_run(case, scene, res, progress, f"{case.name} {res:g}")
    gauges = sim.gauges
    names = list(gauges.names)
    series = {n: gauges.elevation[:, j] for j, n in enumerate(names)}
    bx, bz = scene.flume.beach.profile_in(scene.flume, scene.tank_height)  # type: ignore[union-attr]
    beds = {n: float(np.interp(x, bx, bz, left=0.0)) for n, x in zip(names, gauges.x, strict=True)}
    record = gauges.records.get("crest")
    volume = None if record is None else np.asarray(record["volume"], dtype=np.float64)
    errors, details = seawall_metrics(gauges.t, series, beds, volume)
    details.update(until=scene.until, settings=dict(settings or {}), notes=notes,
                   analysis_notes=result.get("notes", []))
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


def plot_seawall(runs: Sequence[Mapping[str, Any]], path: Path) -> None:
    """Each gauge's simulated series of each run over the laboratory record."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(HSIAO_LIN_GAUGES)
    fig, axes = plt.subplots(len(names), 1, figsize=(8, 12), sharex=True)
    for ax, name in zip(axes, names, strict=True):
        td, vd = seawall_reference(name)
        ax.plot(td, vd, "o", ms=2.5, mfc="none", color="k", label="Hsiao & Lin (2010)")
        for run in sorted(runs, key=lambda r: r["resolution"]):
            d = run.get("details", {})
            if name in d.get("series", {}):
                ax.plot(d["series_t"], d["series"][name], lw=0.9,
                        label=f"H/dp = {run['resolution']:g}")
        what = "depth" if name in INUNDATION_GAUGES else "eta"
        x = HSIAO_LIN_GAUGES[name]
        ax.set_ylabel(f"{name} {what} [m]", fontsize=8)
        ax.set_title(f"{name}, x = {x:g} m (Hsiao & Lin's frame)", fontsize=8)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    axes[-1].set_xlabel("t from the crest at WG1 [s]")
    axes[-1].set_xlim(-2.0, 12.0)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


SEAWALL_CASE = Case(
    "seawall2d", "Hsiao & Lin (2010): breaking solitary wave (H/d = 0.35) "
    "overtopping a seawall on a 1:20 slope",
    "Hsiao & Lin (2010) gauge records (Basilisk's copy): elevation at WG1-WG22, "
    "inundation depth at WG28-WG40",
    "wave height / dp", SEAWALL_HEIGHT, (3.0, 5.0, 7.0), (2.0,), "gauge_rms", 0.10,
    "gauge records within 10 % of H (RMS, mean over the seven gauges)", run_seawall,
    "The built-in seawall2d (`watersim/validation/seawall.py`): d = 0.2 m, H = 0.07 m, "
    "Goring's piston 3.9 m before WG1. The records' clock starts when the crest "
    "passes WG1; the simulation's is set on its own crest there. `gauge_rms`: the "
    "mean over the seven gauges of the RMS difference from the record at the "
    "record's times, over H; `peak`: the RMS over the gauges of the difference of "
    "the highest values, over H. WG28, WG37 and WG40 record the inundation depth "
    "above the ground (the seawall's faces and the ground behind it); where a "
    "simulated gauge is dry, its elevation is the ground's. "
    "`details.overtopped_volume`: the volume per unit width that crossed the crest's "
    "landward edge (no measured value in the records). The records of WG3, WG22, WG28, "
    "WG37 and WG40 read 4-5 mm where the water is still or the ground dry (6-7 % of "
    "H, an offset of the gauges or of the digitisation, left in). `--quick` runs 6 s "
    "past WG1.",
    report_details=("crest_height_wg1_error", "overtopped_volume", "t_crest_wg1"),
    depth=SEAWALL_DEPTH, figure=plot_seawall, scene=seawall_scene,
)
"""The ``watersim validate`` entry of seawall2d."""
