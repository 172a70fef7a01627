"""Shared plumbing of the flume examples (``kimmoun_flume.py``, ``stansby_flume.py``).

Command line, running a :class:`watersim.FlumeSimulation` and writing its results, the gauge
records in a small ``records.npz`` (so the figures can be redrawn with ``--replot`` without
running again; ``--from-run DIR`` draws a ``watersim run`` folder of the same case instead), and
the figures both examples draw: phase-averaged gauges and water-level
envelopes with the wave height along the flume.

Units: metres, seconds; elevations above the still-water level (SWL).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

import watersim as ws
from watersim import analysis as an
from watersim import rundir
from watersim.cost import SpeedMeter
from watersim.cost import estimate as estimate_cost
from watersim.flume import lattice_dp, lattice_layers

FloatArray = npt.NDArray[np.float64]

__all__ = ["Records", "parse_args", "pyplot", "run_flume", "save"]


# ------------------------------------------------------------------------------------------------
# command line


def parse_args(
    argv: Sequence[str] | None, description: str, dp: float, periods: float, out: str,
    depth: float | None = None,
) -> argparse.Namespace:
    """``--dp`` [m], ``--periods`` (simulated time in wave periods), ``--out DIR``,
    ``--replot``; bad values exit with code 2 and a message naming the option.

    With the flume's still-water ``depth`` [m], the default ``dp`` is snapped to
    ``depth / round(depth / dp)`` (:func:`watersim.flume.lattice_dp`: the core fills the water
    with whole particle layers) and a ``--dp`` that is not a whole fraction of the depth is
    refused with two that are."""
    if depth is not None:
        dp = lattice_dp(depth, dp)
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--dp", type=float, default=dp,
                   help=f"particle spacing [m] (default {dp:.6g}: coarse; the run prints its cost first"
                        + ("" if depth is None else f"; must divide the depth {depth:g} m")
                        + ")")
    p.add_argument("--periods", type=float, default=periods,
                   help=f"simulated time in wave periods (default {periods:g})")
    p.add_argument("--out", default=out, help=f"output folder (default {out})")
    p.add_argument("--replot", action="store_true",
                   help="redraw the figures from OUT/records.npz and OUT/analysis.json "
                        "without running")
    p.add_argument("--from-run", metavar="DIR", default=None,
                   help="analyse and draw a `watersim run` of the same case (its last "
                        "checkpoint), e.g. the built-in case run for 350 s, into --out")
    p.add_argument("--t-start", type=float, default=None, metavar="T",
                   help="with --from-run: start every gauge's analysis window at T [s] "
                        "(e.g. the last 128 waves of a 350 s run: 350 - 128 T)")
    args = p.parse_args(argv)
    if args.t_start is not None and args.from_run is None:
        p.error("--t-start: only with --from-run")
    if args.from_run is not None and args.replot:
        p.error("--from-run: draws from the run folder; leave out --replot")
    if not (np.isfinite(args.dp) and args.dp > 0):
        p.error(f"--dp: must be a positive number of metres, got {args.dp!r}")
    if depth is not None and lattice_dp(depth, args.dp) != args.dp:
        n = depth / args.dp
        lo, hi = max(math.floor(n), 2), max(math.ceil(n), 3)
        p.error(f"--dp: the depth {depth:g} m is {n:.4g} dp; the particle lattice fills whole "
                f"layers, so the water would be {lattice_layers(depth, args.dp) * args.dp:.4g} m "
                f"deep; use --dp {depth / lo:.8g} ({lo} layers) or {depth / hi:.8g} ({hi} layers)")
    if not (np.isfinite(args.periods) and args.periods > 0):
        p.error(f"--periods: must be a positive number, got {args.periods!r}")
    return args


# ------------------------------------------------------------------------------------------------
# records


@dataclass
class Records:
    """What the figures need from a run, on the uniform time grid of the analysis.

    Attributes:
        t: (n,) times [s].
        eta: (n, g) elevation above the SWL [m], dry samples at the bed level
            (:meth:`watersim.FlumeGauges.uniform`).
        names, x, still_depth: (g,) gauge names, positions [m] and still-water depths [m].
        runup: (n,) run-up above the SWL [m], or None.
        probes: velocity probes by name: ``(t (m,), points (p, 2), u (m, p, 2), kernel_sum
            (m, p))``; u is NaN where the kernel sum is below 0.5 (dry).
    """

    t: FloatArray
    eta: FloatArray
    names: list[str]
    x: FloatArray
    still_depth: FloatArray
    runup: FloatArray | None
    probes: dict[str, tuple[FloatArray, FloatArray, FloatArray, FloatArray]]

    @classmethod
    def from_gauges(cls, gauges: ws.FlumeGauges) -> Records:
        t, eta, runup = gauges.uniform()
        probes = {}
        for name, rec in gauges.velocity.items():
            u = np.where((rec.kernel_sum >= 0.5)[..., None], rec.velocity, np.nan)
            probes[name] = (rec.t, rec.points, u, rec.kernel_sum)
        return cls(t, eta, list(gauges.names), gauges.x.copy(), gauges.still_depth.copy(),
                   runup, probes)

    def save(self, path: Path) -> Path:
        arrays: dict[str, Any] = {"t": self.t, "eta": self.eta, "names": np.array(self.names),
                                  "x": self.x, "still_depth": self.still_depth,
                                  "probe_names": np.array(list(self.probes), dtype=str)}
        if self.runup is not None:
            arrays["runup"] = self.runup
        for i, (pt, pts, u, ks) in enumerate(self.probes.values()):
            arrays.update({f"probe{i}_t": pt, f"probe{i}_points": pts, f"probe{i}_u": u,
                           f"probe{i}_ksum": ks})
        np.savez_compressed(path, **arrays)
        return path

    @classmethod
    def load(cls, path: Path) -> Records:
        with np.load(path) as d:
            probes = {
                str(n): (d[f"probe{i}_t"], d[f"probe{i}_points"], d[f"probe{i}_u"],
                         d[f"probe{i}_ksum"])
                for i, n in enumerate(d["probe_names"])
            }
            return cls(d["t"], d["eta"], [str(n) for n in d["names"]], d["x"], d["still_depth"],
                       d["runup"] if "runup" in d else None, probes)

    def column(self, x: float) -> int:
        """Index of the gauge at ``x`` [m] (within 1 mm); KeyError if there is none."""
        hits = np.flatnonzero(np.abs(self.x - x) < 1e-3)
        if hits.size == 0:
            raise KeyError(f"no gauge at x = {x:g} m")
        return int(hits[0])


# ------------------------------------------------------------------------------------------------
# running


def run_flume(
    args: argparse.Namespace,
    make: Callable[[float, float], tuple[ws.Flume, dict[str, Any]]],
    figures: Callable[[ws.FlumeScene, Records, dict[str, Any], Path], list[Path]],
) -> list[Path]:
    """Run (or with ``--replot`` reload) the flume ``make(dp, periods)`` gives, write
    gauges.csv, analysis.json, records.npz and summary.json to ``args.out``, draw the figures.

    ``make`` returns the flume and the keyword arguments of :meth:`watersim.Flume.simulation`.
    Returns the figure files written.
    """
    out = Path(args.out)
    flume, kwargs = make(args.dp, args.periods)
    if args.from_run is not None:
        scene, records, analysis = _from_run(Path(args.from_run), args.t_start, out)
    elif args.replot:
        scene = flume.scene(**kwargs)
        try:
            records = Records.load(out / "records.npz")
            analysis = json.loads((out / "analysis.json").read_text(encoding="utf-8"))
        except (OSError, ValueError, KeyError) as exc:
            raise SystemExit(f"--replot: cannot read the results in {out}: {exc}") from None
    else:
        out.mkdir(parents=True, exist_ok=True)
        try:
            with rundir.RunFolder(out, claim=False):  # one run at a time writes into out
                scene, records, analysis = _run(flume, kwargs, out)
        except rundir.RunDirError as exc:
            raise SystemExit(f"--out: {exc}") from None
    written = figures(scene, records, analysis, out)
    for path in written:
        print(path)
    return written


def _run(flume: ws.Flume, kwargs: dict[str, Any], out: Path
         ) -> tuple[ws.FlumeScene, Records, dict[str, Any]]:
    """Run the flume into ``out`` (held): gauges.csv as it goes, then analysis.json,
    records.npz and summary.json."""
    sim = flume.simulation(**kwargs)
    scene = sim.setup
    # a run killed before its end leaves this, not the summary of an earlier run
    (out / "summary.json").write_text(json.dumps({"status": "running"}), encoding="utf-8")
    print(f"{sim!r}", file=sys.stderr)
    threads = int(os.environ.get("RAYON_NUM_THREADS") or os.cpu_count() or 1)
    print(estimate_cost(sim, float(scene.until), threads).line(), file=sys.stderr)
    meter = SpeedMeter(sim, float(scene.until), lambda line: print(line, file=sys.stderr))

    def keep(s: ws.Simulation) -> None:
        s.write_gauges_csv(out / "gauges.csv")  # a stopped run keeps its records so far
        meter(s)

    start = time.perf_counter()
    sim.run(scene.until, progress=True, callback_every=float(scene.until) / 50.0,
            callback=keep)
    wall = time.perf_counter() - start
    sim.write_gauges_csv(out / "gauges.csv")
    analysis = sim.analyse()
    (out / "analysis.json").write_text(json.dumps(analysis, indent=1), encoding="utf-8")
    records = Records.from_gauges(sim.gauges)
    records.save(out / "records.npz")
    summary = {
        "status": "ok", "dp": scene.dp, "until": scene.until, "n_particles": sim.n_particles,
        "n_fluid": sim.n_fluid, "steps": sim.steps, "wall_s": wall,
        "threads": os.environ.get("RAYON_NUM_THREADS"),
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=1), encoding="utf-8")
    print(f"{sim.n_particles} particles ({sim.n_fluid} fluid), {sim.steps} steps, "
          f"{wall:.0f} s wall", file=sys.stderr)
    return scene, records, analysis


def _from_run(run: Path, t_start: float | None, out: Path
              ) -> tuple[ws.FlumeScene, Records, dict[str, Any]]:
    """The scene, records and analysis of the ``watersim run`` folder ``run`` (its last
    checkpoint), the analysis windows starting at ``t_start`` if given; writes analysis.json
    and records.npz to ``out``."""
    try:
        sim = rundir.reopen(run).sim
    except (OSError, rundir.RunDirError) as exc:
        raise SystemExit(f"--from-run: cannot reopen {run}: {exc}") from None
    out.mkdir(parents=True, exist_ok=True)
    analysis = sim.analyse(t_start=t_start)
    (out / "analysis.json").write_text(json.dumps(analysis, indent=1), encoding="utf-8")
    records = Records.from_gauges(sim.gauges)
    records.save(out / "records.npz")
    print(f"{run}: t = {sim.time:.2f} s, {sim.steps} steps, {sim.n_particles} particles",
          file=sys.stderr)
    return sim.setup, records, analysis


# ------------------------------------------------------------------------------------------------
# drawing


def pyplot() -> Any:
    """matplotlib.pyplot on the Agg backend (files only)."""
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    return plt


def save(fig: Any, path: Path) -> Path:
    """Write ``fig`` to ``path`` (PNG, 110 dpi) and close it."""
    fig.savefig(path, dpi=110)
    pyplot().close(fig)
    return path


def steady_start(analysis: dict[str, Any], name: str, default: float) -> float:
    """Start [s] of the steady part of gauge ``name`` in analysis.json (after the ramp, the
    wave's arrival and one period), ``default`` if it is not there."""
    for g in analysis.get("gauges", []):
        if g.get("name") == name and g.get("window"):
            return float(g["window"][0])
    return default


def phase_averaged(
    records: Records, cols: Sequence[int], t0: float, period: float
) -> an.PhaseAverage | None:
    """Phase average (seed 001 Eq. 18) of the gauge columns ``cols`` over every whole period
    after ``t0`` [s] (phase 0 at the paddle's start); None if the record holds no whole period
    after ``t0``."""
    sel = records.t >= t0
    if np.count_nonzero(sel) < 4:
        return None
    try:
        idx = np.asarray(cols, dtype=np.intp)
        return an.phase_average(records.eta[np.ix_(sel, idx)], records.t[sel], period)
    except ValueError:
        return None


def note(ax: Any, text: str) -> None:
    """A grey note in the axes' top-left corner (what is missing, or a reference's source)."""
    ax.text(0.01, 0.97, text, transform=ax.transAxes, fontsize=7, va="top", color="0.3",
            wrap=True)


def plot_phase_averaged_gauges(
    records: Records, analysis: dict[str, Any], period: float,
    gauges: Sequence[tuple[float, str]], path: Path, title: str,
    annotations: dict[float, str] | None = None,
) -> Path:
    """One panel per gauge ``(x, label)``: the last whole waves of the record (thin) and their
    phase average (thick, with +- one standard deviation) over two periods."""
    plt = pyplot()
    fig, axes = plt.subplots(len(gauges), 1, figsize=(8, 1.2 + 2.0 * len(gauges)),
                             squeeze=False, sharex=True)
    for ax, (x, label) in zip(axes[:, 0], gauges, strict=True):
        ax.set_title(label, fontsize=9, loc="left")
        ax.set_ylabel("eta [m]")
        ax.grid(alpha=0.3)
        ax.axhline(0.0, color="k", lw=0.5)
        j = records.column(x)
        t0 = steady_start(analysis, records.names[j], 0.0)
        pa = phase_averaged(records, [j], t0, period)
        if pa is None:
            note(ax, f"no whole wave after the steady start t = {t0:.1f} s: run longer")
            continue
        tau = np.concatenate([pa.times, pa.times + period]) / period
        mean = np.tile(pa.mean[:, 0], 2)
        std = np.tile(pa.std[:, 0], 2)
        for k in range(pa.n_waves):
            s = pa.first_wave_start + k * period
            sel = (records.t >= s) & (records.t <= s + 2.0 * period)
            ax.plot((records.t[sel] - s) / period, records.eta[sel, j], color="0.7", lw=0.6)
        ax.fill_between(tau, mean - std, mean + std, color="tab:blue", alpha=0.2)
        ax.plot(tau, mean, color="tab:blue", lw=1.8,
                label=f"phase average over {pa.n_waves} waves (+- 1 std)")
        if annotations and x in annotations:
            note(ax, annotations[x])
        if np.ptp(pa.mean[:, 0]) == 0.0 and np.all(pa.std == 0.0):
            ax.text(0.5, 0.5, f"dry all along: reads the bed level (still depth "
                    f"{100 * records.still_depth[j]:.1f} cm)", transform=ax.transAxes,
                    ha="center", fontsize=8, color="tab:red")
        ax.legend(fontsize=7, loc="lower right")
    axes[-1, 0].set_xlabel("(t - start of the wave) / T [-]  (phase 0: paddle start)")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return save(fig, path)


def plot_envelopes(
    scene: ws.FlumeScene, analysis: dict[str, Any], path: Path, title: str,
    references: Callable[[Any, Any], None] | None = None,
) -> Path:
    """(a) highest, lowest, mean and mid water level along the flume (analysis.json
    ``envelopes``, each gauge over its steady part) with the bed and the breaking position;
    (b) the mean zero-crossing wave height at each gauge against the target.

    ``references(ax_levels, ax_height)`` draws the seed's values on the two panels.
    """
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    env = analysis.get("envelopes") or {}
    x_bed, z_bed = scene.bed_profile
    depth = scene.flume.depth
    lo = -0.25 * depth
    ax1.fill_between(x_bed, np.asarray(z_bed) - depth, lo - 1.0, color="0.8", label="bed")
    if env.get("x"):
        x = np.asarray(env["x"], dtype=float)

        def col(key: str) -> FloatArray:
            return np.asarray([np.nan if v is None else v for v in env[key]], dtype=float)

        ax1.plot(x, col("maximum"), "^-", ms=4, color="tab:blue", label="highest level (crests)")
        ax1.plot(x, col("minimum"), "v-", ms=4, color="tab:green", label="lowest level (troughs)")
        ax1.plot(x, col("mid_level"), "o-", ms=3, color="tab:orange",
                 label="(highest + lowest) / 2")
        ax1.plot(x, col("mean"), ":", color="tab:orange", label="time-mean level (set-up)")
        if np.any(np.isfinite(col("minimum"))):  # None where a gauge's window is too short
            lo = min(lo, float(np.nanmin(col("minimum"))) - 0.03)
    else:
        note(ax1, "no envelopes in analysis.json (record too short)")
    ax1.axhline(0.0, color="k", lw=0.6, ls="--")
    br = analysis.get("breaking") or {}
    for ax in (ax1, ax2):
        if br.get("position") is not None:
            ax.axvline(br["position"], color="tab:red", lw=1.2,
                       label=f"breaking here: H/d > 0.78 at x = {br['position']:.2f} m")
        if br.get("max_height_position") is not None:
            xm = br["max_height_position"]
            ax.axvline(xm, color="tab:red", lw=1.0, ls=":",
                       label=f"highest wave over the slope: x = {xm:.2f} m")
    if br.get("position") is None:
        note(ax1, "no wave reached H/d > 0.78 at a gauge: no breaking found")
    hs = [(g["x"], g["H_mean"]) for g in analysis.get("gauges", []) if g.get("H_mean")]
    if hs:
        hx, hh = np.asarray(sorted(hs)).T
        ax2.plot(hx, hh, "o-", ms=4, color="tab:blue", label="mean wave height here")
    else:
        note(ax2, "no wave heights in analysis.json (record too short)")
    target = getattr(scene.wave, "height", None)
    if target is not None:
        ax2.axhline(target, color="k", lw=0.8, ls="--", label=f"target H = {target:g} m")
    # the depth-limited height 0.78 d (McCowan) over the slope
    xs = np.linspace(float(x_bed[0]), float(x_bed[-1]), 400)
    d = np.asarray(scene.still_depth(xs))
    ax2.plot(xs[d > 0], 0.78 * d[d > 0], color="0.5", lw=0.8, label="0.78 d (depth limit)")
    if references is not None:
        references(ax1, ax2)
    ax1.set_ylim(lo, None)
    ax1.set_ylabel("level above SWL [m]")
    ax1.legend(fontsize=6, loc="best", ncols=2)
    ax1.grid(alpha=0.3)
    ax1.set_title(title, fontsize=10)
    ax2.set_ylim(0.0, 2.2 * target if target is not None else None)
    ax2.set_ylabel("wave height H [m]")
    ax2.set_xlabel("x [m] from the paddle")
    ax2.legend(fontsize=6, loc="upper right", ncols=2)
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    return save(fig, path)
