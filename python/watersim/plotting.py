"""Figures of a finished ``watersim run`` folder (``watersim plot DIR``), drawn with matplotlib's
Agg backend (no display needed).

What is drawn depends on what the run wrote:

- ``gauges.png``: surface elevation against time at every elevation gauge of ``gauges.csv``,
  ordered along the flume (one panel per gauge up to six, else a waterfall offset by gauge),
  each titled with its position, depth and measured wave height against the target, with its
  analysed (steady) window shaded and the target crest and trough (regular waves: the target
  height, shoaled by linear theory over a beach); and the run-up record;
- ``envelopes.png``: highest, lowest and mean water level along the flume (``analysis.json``
  ``envelopes``, each gauge over its steady part; gauges whose part is too short are marked, not
  drawn) with the bed, and the measured wave height per gauge against the target and linear
  shoaling theory;
- ``runup.png``: the run-up record and the distribution of the run-up of each wave
  (``analysis.json`` ``runup.values``; without them, of the analysed part's samples);
- ``velocity_NAME.png`` per ``velocity_NAME.csv``: a velocity probe's components against time
  at each point; a window's mean over its wet points against time, its field at the last
  sample, and its time-mean velocity over the time-mean vorticity where always wet;
- ``forces.png``: per force gauge of ``gauges.csv`` (``analysis.json`` ``forces``), the
  horizontal and vertical force on its structure against time, with the largest event whose
  impulse is given shaded and the significant force drawn;
- ``front.png``: dam-break surge front of ``front.csv`` against Martin & Moyce (1952) in their
  dimensionless form ``x / a`` against ``t sqrt(2 g / a)`` (a the column width);
- ``snapshot.png``: the particles of the last ``.vtu`` snapshot, fluid coloured by speed.

Units: metres, seconds; elevations relative to the still-water level (SWL).
"""

from __future__ import annotations

import csv
import json
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from .flume.gauges import csv_column
from .numerics import core_default

__all__ = ["PlotError", "plot_run"]

MAX_PANELS = 6
"""Gauges drawn one panel each up to this many; more are drawn as a waterfall."""

BREAKING_RATIO = 0.78
"""McCowan's H/d at breaking: the shoaled theory height is capped there."""

_DEFAULT_GAUGE = re.compile(r"^eta_x(\d+)p(\d+)")
"""A default elevation gauge's column (``eta_x1p250_m``): its x is in the name."""

_LOAD_COLUMN = re.compile(r"_(Pa|N|N_per_m|N_m|N_m_per_m)$")
"""A column of gauges.csv that holds a pressure, force or moment, not an elevation."""


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


def _number(value: Any) -> float | None:
    """A finite float from JSON, or None."""
    if value is None:
        return None
    v = float(value)
    return v if math.isfinite(v) else None


# ------------------------------------------------------------------------------------------------
# what the analysis says about the wave and each gauge


@dataclass(frozen=True)
class _Wave:
    """The wave the run made, as analysis.json describes it."""

    kind: str
    period: float | None
    height: float | None
    """Regular waves: the target height H [m] at the paddle depth; irregular: Hm0 (hs)."""
    depth: float | None
    gravity: float

    @classmethod
    def of(cls, analysis: dict[str, Any], summary: dict[str, Any] | None) -> _Wave:
        wave = analysis.get("wave") or {}
        kind = str(wave.get("type") or "")
        height = _number(wave.get("height"))
        if kind == "IrregularWave":
            height = _number(wave.get("hs"))
        builder = (summary or {}).get("builder") or {}
        gravity = _number(builder.get("gravity")) or core_default("gravity")
        return cls(kind, _number(wave.get("period")), height,
                   _number(analysis.get("still_water_depth")), gravity)

    @property
    def regular(self) -> bool:
        return self.kind == "RegularWave" and self.period is not None and bool(self.height)

    def label(self) -> str:
        if self.regular:
            return f"regular wave H = {self.height:.3g} m, T = {self.period:.3g} s"
        if self.kind == "IrregularWave" and self.height and self.period:
            return f"irregular wave Hm0 = {self.height:.3g} m, Tp = {self.period:.3g} s"
        return self.kind.replace("Wave", " wave").lower().strip()

    def theory_height(self, local_depth: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Regular waves: the target height shoaled by linear theory to ``local_depth`` [m]
        (energy flux conserved, ``H = H0 sqrt(cg0 / cg)``), at most McCowan's breaking height
        ``0.78 d``; NaN where dry, and for other waves."""
        d = np.asarray(local_depth, dtype=np.float64)
        out = np.full(d.shape, np.nan)
        if not self.regular or self.depth is None:
            return out
        from . import wave_theory as wt

        assert self.period is not None and self.height is not None
        wet = d > 1e-3 * self.depth
        cg0 = float(wt.group_velocity(self.period, self.depth, self.gravity))
        cg = np.asarray(wt.group_velocity(self.period, np.where(wet, d, self.depth),
                                          self.gravity))
        shoaled = self.height * np.sqrt(cg0 / cg)
        out[wet] = np.minimum(shoaled, BREAKING_RATIO * d)[wet]
        return out


@dataclass(frozen=True)
class _Gauge:
    """An elevation gauge's column of gauges.csv with what analysis.json says about it."""

    column: int
    name: str
    x: float | None
    entry: dict[str, Any]

    @property
    def depth(self) -> float | None:
        return _number(self.entry.get("still_depth"))

    def title(self, wave: _Wave) -> str:
        """Where the gauge is and what it measured, against the target."""
        where = f"x = {self.x:.3f} m" if self.x is not None else self.name
        if self.depth is not None:
            where += f", depth {self.depth:.3g} m" if self.depth > 0 else ", dry at rest"
        e = self.entry
        needs = _number(e.get("needs_until"))
        if needs is not None:
            return f"{where}: too short for statistics (run to t >= {needs:.3g} s)"
        measured = _number(e.get("hm0")) if wave.kind == "IrregularWave" else None
        symbol = "Hm0" if measured is not None else "H"
        measured = measured if measured is not None else _number(e.get("H_mean"))
        if measured is None:
            peak = _number(e.get("eta_max"))
            return where + (f": highest {peak:.3g} m" if peak is not None else "")
        text = f"{where}: {symbol} = {measured:.3g} m"
        target = self.target(wave)
        if target is not None:
            text += f", target {target:.3g} m ({100 * (measured / target - 1):+.0f} %)"
        return text

    def target(self, wave: _Wave) -> float | None:
        """The height this gauge should measure: the target over the flat floor, the shoaled
        theory height over a beach (regular waves), the target Hm0 (irregular)."""
        target = _number(self.entry.get("H_target"))
        if target is not None:
            return target
        if wave.kind == "IrregularWave":
            return wave.height
        if self.depth is not None and self.depth > 0:
            shoaled = float(wave.theory_height(self.depth))
            return shoaled if math.isfinite(shoaled) else None
        return None

    def window(self) -> tuple[float, float] | None:
        w = self.entry.get("window")
        if self.entry.get("needs_until") is not None or not w or None in w or w[0] >= w[1]:
            return None
        return float(w[0]), float(w[1])


def _gauge_columns(header: list[str], analysis: dict[str, Any]) -> tuple[list[_Gauge], int | None]:
    """The elevation gauges of gauges.csv, ordered along the flume, and the run-up column."""
    runup_name = (analysis.get("runup") or {}).get("name")
    runup_col = header.index(csv_column(runup_name, "m")) if runup_name and csv_column(
        runup_name, "m") in header else (header.index("runup_m") if "runup_m" in header else None)
    by_column = {csv_column(str(g.get("name")), "m"): g for g in analysis.get("gauges") or []}
    gauges = []
    for col, column in enumerate(header):
        if col == 0 or col == runup_col or _LOAD_COLUMN.search(column):
            continue
        entry = by_column.get(column, {})
        x = _number(entry.get("x"))
        match = _DEFAULT_GAUGE.match(column)
        if x is None and match:
            x = float(f"{match.group(1)}.{match.group(2)}")
        gauges.append(_Gauge(col, str(entry.get("name") or column), x, entry))
    gauges.sort(key=lambda g: math.inf if g.x is None else g.x)
    return gauges, runup_col


# ------------------------------------------------------------------------------------------------


def _shade(ax: Any, window: tuple[float, float] | None, label: bool) -> None:
    if window is not None:
        ax.axvspan(*window, color="0.92", zorder=0,
                   label="analysed (steady) window" if label else None)


def _plot_gauges(csv_path: Path, analysis: dict[str, Any], summary: dict[str, Any] | None,
                 out: Path) -> Path | None:
    plt = _pyplot()
    header, data = _read_csv(csv_path)
    if data.shape[0] == 0 or len(header) < 2:
        return None
    t = data[:, 0]
    wave = _Wave.of(analysis, summary)
    gauges, runup_col = _gauge_columns(header, analysis)
    n_panels = (len(gauges) if len(gauges) <= MAX_PANELS else 1) + (runup_col is not None)
    fig, axes = plt.subplots(max(n_panels, 1), 1, sharex=True, squeeze=False,
                             figsize=(9, 1.2 + 1.7 * max(n_panels, 2)))
    axes = axes[:, 0]
    if len(gauges) <= MAX_PANELS:
        for k, (ax, g) in enumerate(zip(axes, gauges, strict=False)):
            _shade(ax, g.window(), label=k == 0)
            ax.plot(t, data[:, g.column], lw=0.9, label="measured")
            target = g.target(wave)
            if target is not None and wave.kind == "RegularWave":
                for sign in (1, -1):
                    ax.axhline(sign * target / 2, color="tab:green", lw=0.8, ls="--",
                               label="target crest and trough (+-H/2)" if sign > 0 else None)
            ax.set_ylabel("eta above SWL [m]", fontsize=8)
            ax.set_title(g.title(wave), fontsize=9, loc="left")
            ax.grid(alpha=0.3)
        if gauges:
            axes[0].legend(fontsize=7, loc="upper left", ncols=3)
    elif gauges:
        ax = axes[0]
        spread = np.nanmax(np.abs(data[:, [g.column for g in gauges]])) if data.size else 1.0
        step = 2.2 * (spread if np.isfinite(spread) and spread > 0 else 1.0)
        for k, g in enumerate(gauges):
            ax.plot(t, data[:, g.column] + k * step, lw=0.7)
            label = f" x = {g.x:.2f} m" if g.x is not None else f" {g.name}"
            ax.text(t[-1], k * step, label, fontsize=6, va="center")
        ax.set_ylabel(f"eta above SWL + offset [m] (gauges {step:.3g} m apart)", fontsize=8)
        ax.set_title(f"{len(gauges)} elevation gauges, ordered along the flume from the paddle",
                     fontsize=9, loc="left")
    if runup_col is not None:
        ax = axes[-1]
        window = (analysis.get("runup") or {}).get("window")
        if window and (analysis.get("runup") or {}).get("needs_until") is None:
            _shade(ax, (float(window[0]), float(window[1])), label=True)
        ax.plot(t, data[:, runup_col], color="tab:red", lw=0.9)
        ax.set_ylabel("run-up above SWL [m]", fontsize=8)
        ax.set_title("run-up: the wet tip on the beach, above the still-water level",
                     fontsize=9, loc="left")
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(f"{analysis.get('case') or csv_path.parent.name}: {wave.label()}", fontsize=10)
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


def _flume_length(summary: dict[str, Any] | None) -> float | None:
    return _number((((summary or {}).get("builder") or {}).get("flume") or {}).get("length"))


def _plot_envelopes(analysis: dict[str, Any], summary: dict[str, Any] | None,
                    out: Path) -> Path | None:
    env = analysis.get("envelopes")
    if not env or len(env.get("x") or []) < 2:
        return None
    plt = _pyplot()
    wave = _Wave.of(analysis, summary)
    x = np.asarray(env["x"], dtype=float)

    def col(key: str) -> np.ndarray:
        return np.asarray([np.nan if v is None else v for v in env.get(key) or [None] * x.size],
                          dtype=float)

    fig, (ax, ax_h) = plt.subplots(2, 1, sharex=True, figsize=(9, 7),
                                   gridspec_kw={"height_ratios": [3, 2]})
    ax.plot(x, col("maximum"), "^-", ms=4, label="highest level")
    ax.plot(x, col("minimum"), "v-", ms=4, label="lowest level")
    ax.plot(x, col("mean"), "o-", ms=3, label="mean level (set-up)")
    ax.axhline(0.0, color="k", lw=0.6, ls="--", label="still-water level")
    short = np.asarray([v is not None for v in env.get("needs_until") or [None] * x.size])
    if np.any(short):
        ax.plot(x[short], np.zeros(int(short.sum())), "kx", ms=7,
                label="window too short: no envelope")
    bed = _bed_profile(summary)
    length = _flume_length(summary) or float(x.max())
    xs = np.linspace(0.0, length, 400)
    depth = wave.depth
    local_depth = np.full(xs.shape, np.nan if depth is None else depth)
    if bed is not None:
        bx, bz = bed
        local_depth = np.where((xs >= bx[0]) & (xs <= bx[-1]), -np.interp(xs, bx, bz),
                               local_depth)
        lows = [float(np.nanmin(bz))]
        if np.any(np.isfinite(col("minimum"))):
            lows.append(float(np.nanmin(col("minimum"))))
        lo = min(lows) - 0.05
        ax.fill_between(bx, bz, lo, color="0.75", label="bed")
        ax.set_ylim(bottom=lo)
    theory = wave.theory_height(local_depth)
    if np.any(np.isfinite(theory)):
        label = "linear theory, +-H/2" + (" (shoaling, capped at H = 0.78 d)" if bed is not None
                                           else "")
        ax.plot(xs, theory / 2, color="tab:green", lw=0.9, ls=":", label=label)
        ax.plot(xs, -theory / 2, color="tab:green", lw=0.9, ls=":")
    ax.set_xlim(0.0, length * 1.02)
    ax.set_ylabel("level above still water [m]")
    ax.set_title(f"water-level envelopes over each gauge's analysed window; {wave.label()}",
                 fontsize=10)
    ax.legend(fontsize=7, ncols=2)
    ax.grid(alpha=0.3)
    _plot_heights(ax_h, analysis, wave, xs, theory)
    ax_h.set_xlabel("x [m] (from the paddle at rest)")
    fig.tight_layout()
    return _save(fig, out / "envelopes.png")


def _plot_heights(ax: Any, analysis: dict[str, Any], wave: _Wave, xs: np.ndarray,
                  theory: np.ndarray) -> None:
    """The measured wave height per gauge along the flume, against the target and theory."""
    irregular = wave.kind == "IrregularWave"
    key, symbol = ("hm0", "Hm0") if irregular else ("H_mean", "mean H")
    points = [(float(g["x"]), float(g[key])) for g in analysis.get("gauges") or []
              if _number(g.get(key)) is not None and _number(g.get("x")) is not None]
    if points:
        px, ph = np.asarray(points).T
        ax.plot(px, ph, "o", color="tab:blue", label=f"measured {symbol} (zero-crossing)"
                if not irregular else "measured Hm0 (spectrum)")
    if np.any(np.isfinite(theory)):
        ax.plot(xs, theory, color="tab:green", lw=1.0, label="linear theory (target shoaled)")
    elif wave.height is not None:
        ax.axhline(wave.height, color="tab:green", lw=1.0, ls="--",
                   label=f"target {'Hm0' if irregular else 'H'}")
    short = [float(g["x"]) for g in analysis.get("gauges") or []
             if g.get("needs_until") is not None and _number(g.get("x")) is not None]
    if short:
        ax.plot(short, np.zeros(len(short)), "kx", ms=7, label="window too short: no statistics")
    ax.set_ylabel("wave height [m]")
    drawn = [h for line in ax.get_lines() for h in np.asarray(line.get_ydata(), dtype=float)]
    top = max((h for h in drawn if math.isfinite(h)), default=0.0)
    if top > 0.0:  # the target and theory lines inside the axes, not on their top edge
        ax.set_ylim(0.0, 1.15 * top)
    else:
        ax.set_ylim(bottom=0.0)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)


def _plot_runup(analysis: dict[str, Any], csv_path: Path | None, out: Path) -> Path | None:
    info = analysis.get("runup")
    if not info or csv_path is None:
        return None
    header, data = _read_csv(csv_path)
    column = csv_column(str(info.get("name")), "m")
    if column not in header or data.shape[0] < 2:
        return None
    plt = _pyplot()
    t, r = data[:, 0], data[:, header.index(column)]
    values = info.get("values")
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), gridspec_kw={"width_ratios": [2, 1]})
    ax1.plot(t, r, color="tab:red", lw=0.9)
    window = info.get("window")
    needs = _number(info.get("needs_until"))
    in_window = np.zeros_like(t, dtype=bool)
    if needs is None and window and None not in window and window[0] < window[1]:
        _shade(ax1, (float(window[0]), float(window[1])), label=True)
        ax1.legend(fontsize=8)
        in_window = (t >= window[0]) & (t <= window[1])
    ax1.set_xlabel("t [s]")
    ax1.set_ylabel("run-up above SWL [m]")
    ax1.grid(alpha=0.3)
    if values:
        ax2.hist(values, bins=min(20, max(5, len(values))), color="tab:red", alpha=0.8)
        ax2.set_xlabel("run-up of each wave above SWL [m]")
        title = f"{len(values)} waves"
        if info.get("mean") is not None:
            title += f", mean {info['mean']:.3g} m"
    elif needs is not None:
        ax2.text(0.5, 0.5, f"record too short for run-up\nstatistics: run to t >= {needs:.3g} s",
                 ha="center", va="center", fontsize=9, transform=ax2.transAxes)
        ax2.set_xticks([])
        title = "no analysed window"
    else:
        part = r[in_window]
        ax2.hist(part[np.isfinite(part)], bins=30, color="tab:red", alpha=0.8)
        ax2.set_xlabel("run-up samples above SWL [m]")
        title = "analysed window's samples"
    ax2.set_ylabel("count")
    ax2.set_title(title, fontsize=9)
    fig.tight_layout()
    return _save(fig, out / "runup.png")


def _plot_forces(analysis: dict[str, Any], csv_path: Path | None, out: Path) -> Path | None:
    forces = analysis.get("forces") or []
    if not forces or csv_path is None:
        return None
    header, data = _read_csv(csv_path)
    if data.shape[0] < 2:
        return None
    plt = _pyplot()
    t = data[:, 0]
    fig, axes = plt.subplots(len(forces), 1, sharex=True, squeeze=False,
                             figsize=(9, 1.2 + 2.4 * len(forces)))
    for ax, info in zip(axes[:, 0], forces, strict=True):
        prefix = csv_column(str(info["name"]))
        for component, colour in (("x", "tab:blue"), ("z", "tab:orange")):
            column = next((c for c in header if c.startswith(f"{prefix}_F{component}_")), None)
            if column is not None:
                unit = column[len(f"{prefix}_F{component}_"):].replace("_per_", "/")
                ax.plot(t, data[:, header.index(column)], color=colour, lw=0.9,
                        label=f"F{component} [{unit}]")
        start, end = _number(info.get("impulse_start")), _number(info.get("impulse_end"))
        if start is not None and end is not None:
            impulse = _number(info.get("impulse")) or 0.0
            ax.axvspan(start, end, color="tab:red", alpha=0.15,
                       label=f"largest event, impulse {impulse:.3g}")
        significant = _number(info.get("Fx_significant"))
        if significant is not None:
            ax.axhline(significant, color="tab:blue", lw=0.8, ls="--",
                       label=f"significant Fx {significant:.3g}")
        ax.set_ylabel("force", fontsize=8)
        ax.set_title(f"{info['name']}: force on structure {info.get('structure')!r}",
                     fontsize=9, loc="left")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper left", ncols=2)
    axes[-1, 0].set_xlabel("t [s]")
    fig.tight_layout()
    return _save(fig, out / "forces.png")


_VELOCITY_COLUMN = re.compile(r"^([uvw])_(.+)_m_per_s$")
_COORDINATE = re.compile(r"([xyz])(n?)(\d+)p(\d+)")


def _point_label(label: str) -> str:
    """``x4p000_z0p100`` -> ``x = 4.000, z = 0.100 m``."""
    parts = [f"{a} = {'-' if neg else ''}{i}.{f}" for a, neg, i, f in _COORDINATE.findall(label)]
    return ", ".join(parts) + " m" if parts else label


def _plot_velocity(csv_path: Path, out: Path) -> Path | None:
    """A velocity probe's or window's file: components against time per point (up to
    :data:`MAX_PANELS` points), else the mean over the wet points and the last field."""
    header, data = _read_csv(csv_path)
    if data.shape[0] == 0:
        return None
    t = data[:, 0]
    columns: dict[str, dict[str, int]] = {}
    for col, name in enumerate(header):
        m = _VELOCITY_COLUMN.match(name)
        if m:
            columns.setdefault(m.group(2), {})[m.group(1)] = col
    if not columns:
        return None
    components = sorted({c for point in columns.values() for c in point}, key="uvw".index)
    plt = _pyplot()
    name = csv_path.stem.removeprefix("velocity_")
    names = {"u": "u (along x)", "v": "v (across, y)", "w": "w (vertical, z)"}
    if len(columns) <= MAX_PANELS:
        fig, axes = plt.subplots(len(components), 1, sharex=True, squeeze=False,
                                 figsize=(9, 1.5 + 2.0 * len(components)))
        for ax, c in zip(axes[:, 0], components, strict=True):
            for label, point in columns.items():
                ax.plot(t, data[:, point[c]], lw=0.9, label=_point_label(label))
            ax.set_ylabel(f"{names[c]} [m/s]", fontsize=8)
            ax.grid(alpha=0.3)
        axes[0, 0].legend(fontsize=7)
        axes[-1, 0].set_xlabel("t [s]")
        fig.suptitle(f"velocity probe {name} (gaps: the point is dry)", fontsize=10)
    else:
        fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(15, 4),
                                            gridspec_kw={"width_ratios": [3, 2, 2]})
        for c in components:
            stack = np.stack([data[:, point[c]] for point in columns.values()], axis=1)
            wet = np.isfinite(stack).any(axis=1)
            mean = np.full(t.shape, np.nan)
            mean[wet] = np.nanmean(stack[wet], axis=1)
            ax1.plot(t, mean, lw=0.9, label=names[c])
        ax1.set_xlabel("t [s]")
        ax1.set_ylabel("mean over the wet points [m/s]")
        ax1.legend(fontsize=8)
        ax1.grid(alpha=0.3)
        pts = np.array([[float(v) * (-1 if n else 1) for _, n, v in
                         ((a, n, f"{i}.{f}") for a, n, i, f in _COORDINATE.findall(label))]
                        for label in columns], dtype=float)
        horizontal, vertical = components[0], components[-1]
        u = data[-1, [p[horizontal] for p in columns.values()]]
        w = data[-1, [p[vertical] for p in columns.values()]]
        dry = ~np.isfinite(u)
        ax2.quiver(pts[~dry, 0], pts[~dry, -1], u[~dry], w[~dry], np.hypot(u[~dry], w[~dry]))
        ax2.plot(pts[dry, 0], pts[dry, -1], ".", color="0.7", label="dry")
        ax2.set_xlabel("x [m]")
        ax2.set_ylabel("z [m]")
        ax2.set_title(f"velocity at t = {t[-1]:.3g} s", fontsize=9)
        ax2.set_aspect("equal", adjustable="datalim")
        _plot_mean_vorticity(ax3, fig, pts, np.stack(
            [data[:, [p[c] for p in columns.values()]] for c in (horizontal, vertical)], axis=-1))
        fig.suptitle(f"velocity window {name}: {len(columns)} points", fontsize=10)
    fig.tight_layout()
    return _save(fig, out / f"{csv_path.stem}.png")


def _plot_mean_vorticity(ax: Any, fig: Any, points: npt.NDArray[np.float64],
                         velocity: npt.NDArray[np.float64]) -> None:
    """The window's time-mean velocity (arrows) over its time-mean vorticity ``omega_y``
    (colours) at the points wet in every sample (below the trough), as seed 002 draws them
    (Stansby & Feng 2005, Figs. 6-7); a note where the points are not a 2D grid.
    ``velocity``: (n_samples, n_points, 2) horizontal and vertical components, NaN when dry."""
    from .fields import grid_vorticity

    xs, zs = np.unique(points[:, 0]), np.unique(points[:, -1])
    if points.shape[1] != 2 or xs.size < 2 or zs.size < 2 or xs.size * zs.size != len(points):
        ax.text(0.5, 0.5, "time-mean vorticity: drawn for 2D windows only", ha="center",
                transform=ax.transAxes, fontsize=8)
        ax.set_axis_off()
        return
    grid = np.full((zs.size, xs.size, 2), np.nan)
    always_wet = np.isfinite(velocity).all(axis=(0, 2))
    rows, cols = np.searchsorted(zs, points[:, 1]), np.searchsorted(xs, points[:, 0])
    grid[rows[always_wet], cols[always_wet]] = velocity[:, always_wet].mean(axis=0)
    omega = grid_vorticity(grid, (float(zs[1] - zs[0]), float(xs[1] - xs[0])))
    limit = float(np.nanmax(np.abs(omega))) if np.isfinite(omega).any() else 1.0
    mesh = ax.pcolormesh(xs, zs, omega, cmap="RdBu_r", vmin=-limit, vmax=limit, shading="nearest")
    fig.colorbar(mesh, ax=ax, label="mean vorticity du/dz - dw/dx [1/s]")
    ax.quiver(xs[None, :].repeat(zs.size, 0), zs[:, None].repeat(xs.size, 1),
              grid[..., 0], grid[..., 1])
    ax.set_xlabel("x [m]")
    ax.set_title("time mean where always wet", fontsize=9)
    ax.set_aspect("equal", adjustable="datalim")


def _plot_front(csv_path: Path, summary: dict[str, Any] | None, out: Path) -> Path | None:
    from .measure import MARTIN_MOYCE_DESCRIPTIONS, load_martin_moyce

    header, data = _read_csv(csv_path)
    if data.shape[0] == 0 or "x_front_m" not in header:
        return None
    builder = (summary or {}).get("builder") or {}
    width, g = builder.get("width"), builder.get("gravity") or core_default("gravity")
    if not width:
        raise PlotError(f"{csv_path.parent / 'summary.json'}: needs the column width "
                        "(builder.width) to scale front.csv")
    plt = _pyplot()
    t = data[:, header.index("t_s")]
    x = data[:, header.index("x_front_m")]
    scale = math.sqrt(2.0 * g / width)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(t * scale, x / width, "-", lw=1.5, label="WaterSim front")
    ratio = builder.get("height", 0.0) / width
    if abs(ratio - 2.0) <= 0.01:
        ref = load_martin_moyce("lethe")
        ax.plot(ref.tau, ref.delta, "ko", ms=4, mfc="none",
                label=f"Martin & Moyce (1952), n² = 2: {MARTIN_MOYCE_DESCRIPTIONS['lethe']}")
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
    velocity_csvs = sorted(run.glob("velocity_*.csv"))
    vtu = _last_snapshot(run, summary)
    if (gauges_csv is None and front_csv is None and vtu is None and not analysis
            and not velocity_csvs):
        raise PlotError(
            f"{run}: no run results to plot (expected gauges.csv, velocity_*.csv, front.csv, "
            "analysis.json or snapshots/*.vtu written by `watersim run`)"
        )
    figs = Path(out) if out is not None else run / "plots"
    figs.mkdir(parents=True, exist_ok=True)
    written: list[Path | None] = []
    if gauges_csv is not None:
        written.append(_plot_gauges(gauges_csv, analysis, summary, figs))
    if analysis:
        written.append(_plot_envelopes(analysis, summary, figs))
        written.append(_plot_runup(analysis, gauges_csv, figs))
        written.append(_plot_forces(analysis, gauges_csv, figs))
    written += [_plot_velocity(path, figs) for path in velocity_csvs]
    if front_csv is not None:
        written.append(_plot_front(front_csv, summary, figs))
    if vtu is not None:
        written.append(_plot_snapshot(vtu, figs))
    done = [p for p in written if p is not None]
    if not done:
        raise PlotError(f"{run}: the result files hold no samples yet to plot")
    return done
