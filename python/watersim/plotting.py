"""Figures of a finished ``watersim run`` folder (``watersim plot DIR``), drawn with matplotlib's
Agg backend (no display needed).

What is drawn depends on what the run wrote:

- ``gauges.png``: surface elevation against time at every elevation gauge of ``gauges.csv`` (one
  panel per gauge up to six, else a waterfall offset by gauge), and the run-up record;
- ``envelopes.png``: highest, lowest and mean water level along the flume (``analysis.json``
  ``envelopes``, each gauge over its steady part) with the bed;
- ``runup.png``: the run-up record and the distribution of the run-up of each wave
  (``analysis.json`` ``runup.values``; without them, of the record's samples);
- ``front.png``: dam-break surge front of ``front.csv`` against Martin & Moyce (1952) in their
  dimensionless form ``x / a`` against ``t sqrt(2 g / a)`` (a the column width);
- ``snapshot.png``: the particles of the last ``.vtu`` snapshot, fluid coloured by speed.

Units: metres, seconds; elevations relative to the still-water level.
"""

from __future__ import annotations

import csv
import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["PlotError", "plot_run"]

MAX_PANELS = 6
"""Gauges drawn one panel each up to this many; more are drawn as a waterfall."""


class PlotError(Exception):
    """A run folder that cannot be plotted (missing, or without results)."""


def _pyplot() -> Any:
    """matplotlib.pyplot on the Agg backend (files only, never a window)."""
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    return plt


def _read_json(path: Path) -> dict[str, Any] | None:
    if not path.is_file():
        return None
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise PlotError(f"{path}: cannot read it: {exc}") from None
    return data if isinstance(data, dict) else None


def _read_csv(path: Path) -> tuple[list[str], npt.NDArray[np.float64]]:
    """Header and float rows of a CSV file written by ``watersim run``."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except OSError as exc:
        raise PlotError(f"{path}: cannot read it: {exc}") from None
    if not rows:
        raise PlotError(f"{path}: empty file")
    header, body = rows[0], [r for r in rows[1:] if r]
    try:
        data = np.array([[float(v) for v in r] for r in body], dtype=np.float64)
    except ValueError as exc:
        raise PlotError(f"{path}: not a table of numbers: {exc}") from None
    return header, data.reshape(len(body), len(header))


def _save(fig: Any, path: Path) -> Path:
    fig.savefig(path, dpi=120)
    _pyplot().close(fig)
    return path


# ------------------------------------------------------------------------------------------------


def _plot_gauges(csv_path: Path, runup_name: str | None, out: Path) -> Path | None:
    plt = _pyplot()
    header, data = _read_csv(csv_path)
    if data.shape[0] == 0 or len(header) < 2:
        return None
    t = data[:, 0]
    names = header[1:]
    runup_col = names.index(runup_name) + 1 if runup_name in names else None
    gauges = [(i + 1, n) for i, n in enumerate(names) if i + 1 != runup_col]
    n_panels = (min(len(gauges), MAX_PANELS) if len(gauges) <= MAX_PANELS else 1)
    n_panels += runup_col is not None
    fig, axes = plt.subplots(n_panels, 1, sharex=True, squeeze=False,
                             figsize=(9, 1.2 + 1.6 * max(n_panels, 2)))
    axes = axes[:, 0]
    if len(gauges) <= MAX_PANELS:
        for ax, (col, name) in zip(axes, gauges, strict=False):
            ax.plot(t, data[:, col], lw=0.9)
            ax.set_ylabel("eta [m]")
            ax.set_title(name, fontsize=9, loc="left")
            ax.grid(alpha=0.3)
    elif gauges:
        ax = axes[0]
        spread = np.nanmax(np.abs(data[:, [c for c, _ in gauges]])) if data.size else 1.0
        step = 2.2 * (spread if np.isfinite(spread) and spread > 0 else 1.0)
        for k, (col, name) in enumerate(gauges):
            ax.plot(t, data[:, col] + k * step, lw=0.7)
            ax.text(t[-1], k * step, f" {name}", fontsize=6, va="center")
        ax.set_ylabel(f"eta + offset [m] (gauges {step:.3g} m apart)")
        ax.set_title(f"{len(gauges)} elevation gauges", fontsize=9, loc="left")
    if runup_col is not None:
        ax = axes[-1]
        ax.plot(t, data[:, runup_col], color="tab:red", lw=0.9)
        ax.set_ylabel("run-up [m]")
        ax.set_title(f"{names[runup_col - 1]} (above the still-water level)", fontsize=9,
                     loc="left")
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("t [s]")
    fig.tight_layout()
    return _save(fig, out / "gauges.png")


def _bed_profile(summary: dict[str, Any] | None) -> tuple[np.ndarray, np.ndarray] | None:
    """Bed vertices (x, z - depth) [m] from summary.json's scene, or None for a flat floor."""
    if not summary:
        return None
    scene = summary.get("scene") or {}
    depth = ((summary.get("builder") or {}).get("flume") or {}).get("depth")
    for obs in scene.get("obstacles") or []:
        if obs.get("shape") == "profile" and depth is not None:
            return np.asarray(obs["x"], dtype=float), np.asarray(obs["z"], dtype=float) - depth
    return None


def _plot_envelopes(analysis: dict[str, Any], summary: dict[str, Any] | None,
                    out: Path) -> Path | None:
    env = analysis.get("envelopes")
    if not env or len(env.get("x") or []) < 2:
        return None
    plt = _pyplot()
    x = np.asarray(env["x"], dtype=float)

    def col(key: str) -> np.ndarray:
        return np.asarray([np.nan if v is None else v for v in env[key]], dtype=float)

    fig, ax = plt.subplots(figsize=(9, 4))
    ax.plot(x, col("maximum"), "^-", ms=3, label="highest level")
    ax.plot(x, col("minimum"), "v-", ms=3, label="lowest level")
    ax.plot(x, col("mean"), "o-", ms=3, label="mean level (set-up)")
    ax.axhline(0.0, color="k", lw=0.6, ls="--", label="still-water level")
    bed = _bed_profile(summary)
    if bed is not None:
        bx, bz = bed
        lo = min(float(np.nanmin(bz)), float(np.nanmin(col("minimum")))) - 0.05
        ax.fill_between(bx, bz, lo, color="0.75", label="bed")
        ax.set_xlim(0.0, max(float(x.max()), float(bx.max())) * 1.02)
        ax.set_ylim(bottom=lo)
    ax.set_xlabel("x [m] (from the paddle)")
    ax.set_ylabel("level above still water [m]")
    ax.set_title("water-level envelopes", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return _save(fig, out / "envelopes.png")


def _plot_runup(analysis: dict[str, Any], csv_path: Path | None, out: Path) -> Path | None:
    info = analysis.get("runup")
    if not info or csv_path is None:
        return None
    header, data = _read_csv(csv_path)
    name = info.get("name")
    if name not in header or data.shape[0] < 2:
        return None
    plt = _pyplot()
    t, r = data[:, 0], data[:, header.index(name)]
    values = info.get("values")
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), gridspec_kw={"width_ratios": [2, 1]})
    ax1.plot(t, r, color="tab:red", lw=0.9)
    window = info.get("window")
    in_window = np.zeros_like(t, dtype=bool)
    if window and window[0] is not None and window[1] is not None and window[0] < window[1]:
        ax1.axvspan(window[0], window[1], color="0.9", zorder=0, label="analysed part")
        ax1.legend(fontsize=8)
        in_window = (t >= window[0]) & (t <= window[1])
    ax1.set_xlabel("t [s]")
    ax1.set_ylabel("run-up above still water [m]")
    ax1.grid(alpha=0.3)
    if values:
        ax2.hist(values, bins=min(20, max(5, len(values))), color="tab:red", alpha=0.8)
        ax2.set_xlabel("run-up of each wave [m]")
        title = f"{len(values)} waves"
        if info.get("mean") is not None:
            title += f", mean {info['mean']:.3g} m"
    else:
        part = r[in_window] if np.count_nonzero(in_window) >= 2 else r
        finite = part[np.isfinite(part)]
        ax2.hist(finite, bins=30, color="tab:red", alpha=0.8)
        ax2.set_xlabel("run-up samples [m]")
        title = "analysed part's samples" if part is not r else "all samples (run too short)"
    ax2.set_ylabel("count")
    ax2.set_title(title, fontsize=9)
    fig.tight_layout()
    return _save(fig, out / "runup.png")


def _plot_front(csv_path: Path, summary: dict[str, Any] | None, out: Path) -> Path | None:
    from .measure import load_martin_moyce

    header, data = _read_csv(csv_path)
    if data.shape[0] == 0 or "x_front" not in header:
        return None
    builder = (summary or {}).get("builder") or {}
    width, g = builder.get("width"), builder.get("gravity", 9.81)
    if not width:
        raise PlotError(f"{csv_path.parent / 'summary.json'}: needs the column width "
                        "(builder.width) to scale front.csv")
    plt = _pyplot()
    t = data[:, header.index("t")]
    x = data[:, header.index("x_front")]
    scale = math.sqrt(2.0 * g / width)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(t * scale, x / width, "-", lw=1.5, label="WaterSim front")
    ratio = builder.get("height", 0.0) / width
    if abs(ratio - 2.0) <= 0.01:
        ref = load_martin_moyce("lethe")
        ax.plot(ref.tau, ref.delta, "ko", ms=4, mfc="none", label="Martin & Moyce (1952), n² = 2")
    else:
        ax.set_title(f"column height / width = {ratio:.3g}: no Martin & Moyce n² = 2 data",
                     fontsize=9)
    ax.set_xlabel("t sqrt(2g/a) [-]")
    ax.set_ylabel("x_front / a [-]")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return _save(fig, out / "front.png")


def _last_snapshot(run: Path, summary: dict[str, Any] | None) -> Path | None:
    pvd = ((summary or {}).get("snapshots") or {}).get("pvd")
    folder = (run / pvd).parent if pvd else run / "snapshots"
    files = sorted(folder.glob("*.vtu")) if folder.is_dir() else []
    if not files:
        files = sorted(run.glob("*.vtu"))
    return files[-1] if files else None


def _snapshot_time(vtu: Path) -> float | None:
    """The time [s] of a snapshot, from the .pvd collection next to it (None if not listed)."""
    import xml.etree.ElementTree as ET

    for pvd in vtu.parent.glob("*.pvd"):
        try:
            root = ET.parse(pvd).getroot()
        except (ET.ParseError, OSError):
            continue
        for ds in root.iter("DataSet"):
            if ds.get("file") == vtu.name and ds.get("timestep") is not None:
                return float(ds.get("timestep", "nan"))
    return None


def _plot_snapshot(vtu: Path, out: Path) -> Path:
    import meshio

    try:
        mesh = meshio.read(vtu)
    except Exception as exc:  # noqa: BLE001 - meshio raises many kinds on a bad file
        raise PlotError(f"{vtu}: cannot read it: {exc}") from None
    plt = _pyplot()
    t = _snapshot_time(vtu)
    pts = np.asarray(mesh.points)
    kind = np.asarray(mesh.point_data.get("kind", np.zeros(len(pts))))
    vel = np.asarray(mesh.point_data.get("velocity", np.zeros_like(pts)))
    speed = np.linalg.norm(vel, axis=1)
    fluid = kind == 0
    span = float(np.ptp(pts[:, 0])) or 1.0
    height = float(np.ptp(pts[:, 2])) or 1.0
    # a long flume drawn to scale is a thin line: stretch z up to a quarter of the width
    stretch = max(1.0, 0.25 * span / height)
    fig, ax = plt.subplots(figsize=(10, max(2.5, min(8.0, 8.5 * stretch * height / span + 1.5))))
    size = max(0.5, 4000.0 / max(len(pts), 1))
    ax.scatter(pts[~fluid, 0], pts[~fluid, 2], s=size, c="0.6", marker="s", lw=0)
    sc = ax.scatter(pts[fluid, 0], pts[fluid, 2], s=size, c=speed[fluid], cmap="viridis", lw=0)
    fig.colorbar(sc, ax=ax, label="|v| [m/s]", shrink=0.8)
    ax.set_aspect(stretch)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    title = f"{vtu.name}"
    if t is not None:
        title += f", t = {t:.4g} s"
    title += f": {int(fluid.sum())} fluid particles, {int((~fluid).sum())} wall"
    if np.ptp(pts[:, 1]) > 0:
        title += " (3D, projected on x-z)"
    if stretch > 1.0:
        title += f"; z stretched x{stretch:.2g}"
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    return _save(fig, out / "snapshot.png")


def plot_run(directory: str | os.PathLike[str], out: str | os.PathLike[str] | None = None
             ) -> list[Path]:
    """Draw the figures a run folder allows; returns the PNG files written.

    Args:
        directory: a ``watersim run`` output folder.
        out: where the PNGs go (default ``directory/plots``, created).

    Raises:
        PlotError: ``directory`` is missing or holds nothing to plot.
    """
    run = Path(directory)
    if not run.is_dir():
        raise PlotError(f"{run}: no such run folder")
    summary = _read_json(run / "summary.json")
    analysis = _read_json(run / "analysis.json") or {}
    gauges_csv = run / "gauges.csv" if (run / "gauges.csv").is_file() else None
    front_csv = run / "front.csv" if (run / "front.csv").is_file() else None
    vtu = _last_snapshot(run, summary)
    if gauges_csv is None and front_csv is None and vtu is None and not analysis:
        raise PlotError(
            f"{run}: no run results to plot (expected gauges.csv, front.csv, analysis.json or "
            "snapshots/*.vtu written by `watersim run`)"
        )
    figs = Path(out) if out is not None else run / "plots"
    figs.mkdir(parents=True, exist_ok=True)
    written: list[Path | None] = []
    runup_name = (analysis.get("runup") or {}).get("name")
    if gauges_csv is not None:
        written.append(_plot_gauges(gauges_csv, runup_name, figs))
    if analysis:
        written.append(_plot_envelopes(analysis, summary, figs))
        written.append(_plot_runup(analysis, gauges_csv, figs))
    if front_csv is not None:
        written.append(_plot_front(front_csv, summary, figs))
    if vtu is not None:
        written.append(_plot_snapshot(vtu, figs))
    done = [p for p in written if p is not None]
    if not done:
        raise PlotError(f"{run}: the result files hold no samples yet to plot")
    return done
