"""How far does WaterSim carry a regular wave, and does second-order generation remove the free
second harmonic? (project issue 3) Figures and tables from ``watersim validate`` run records.

Reads the run records (JSON written by ``watersim validate ... --json FILE``) of the validation
cases ``flume2d`` (a regular wave, H = 0.1 m, T = 1.2 s, d = 0.3 m, gauges at 1, 1.5, 1.6, 1.75,
2 and 3 wavelengths) and ``secondorder2d`` (first- against second-order piston at kd = 0.69),
and writes into ``--out``:

- ``flume2d_height.png``: wave height along the flume over the target, one line per resolution,
  with the +-5 % band of the issue;
- ``secondorder2d.png``: second-harmonic amplitude along the flume over the Stokes bound
  amplitude of each gauge's own first harmonic, first- and second-order piston;
- ``results.md``: the tables (zero-crossing heights and first-harmonic heights 2 a1 at 1, 2,
  3 L, loss per wavelength, wavelength against
  linear and Stokes third-order theory, mean-water-level drift; second-harmonic spreads and
  their ratio) with each run's particles, steps, wall and CPU time;
- ``results.json``: the same numbers.

Run::

    python3 examples/flume_accuracy.py docs/wave-flume/runs-flume2d-res5.json \
        --out docs/wave-flume

Units: metres, seconds; errors are fractions of the target (0.05 = 5 %).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from watersim import wave_theory as wt

Record = Mapping[str, Any]


def load_records(paths: Sequence[Path]) -> list[dict[str, Any]]:
    """Run records from ``watersim validate --json`` files (a list, or ``{"runs": [...]}``)."""
    records: list[dict[str, Any]] = []
    for path in paths:
        data = json.loads(Path(path).read_text("utf-8"))
        runs = data.get("runs", data) if isinstance(data, dict) else data
        if not isinstance(runs, list):
            raise ValueError(f"{path}: expected a list of run records or {{'runs': [...]}}")
        records.extend(r for r in runs if isinstance(r, dict) and "case" in r)
    return records


def _pct(v: float | None, digits: int = 1) -> str:
    return "-" if v is None or not math.isfinite(v) else f"{100.0 * v:+.{digits}f} %"


def flume2d_rows(records: Sequence[Record]) -> list[dict[str, Any]]:
    """One row per finished flume2d run, sorted by resolution: signed errors (fractions)."""
    rows = []
    for r in sorted((r for r in records if r["case"] == "flume2d"),
                    key=lambda r: r["resolution"]):
        d = r.get("details", {})
        target = d.get("H_target")
        wl = d.get("wavelength_linear")
        lw = d.get("wavelength_measured")
        l3 = d.get("wavelength_stokes3")
        mwl = d.get("mwl", {})
        changes = [v.get("change") for v in mwl.values() if v.get("change") is not None]
        means = [v.get("mean") for v in mwl.values() if v.get("mean") is not None]
        rows.append({
            "resolution": r["resolution"], "dp": r["dp"], "status": r["status"],
            "particles": r["n_particles"], "steps": r["steps"], "wall_s": r["wall_s"],
            "cpu_s": r["cpu_s"], "numerics": d.get("numerics"),
            **{f"H_{n}L": (d[f"H_{n}L"] / target - 1.0 if d.get(f"H_{n}L") and target else None)
               for n in (1, 2, 3)},
            **{f"H1_{n}L": _first_harmonic_height(d, n) for n in (1, 2, 3)},
            "loss_per_L": d.get("height_loss_per_wavelength"),
            "wavelength_linear": (lw / wl - 1.0) if lw and wl else None,
            "wavelength_stokes3": (lw / l3 - 1.0) if lw and l3 else None,
            "mwl_change_max_over_H": (max(changes, key=abs) / target
                                      if changes and target else None),
            "mwl_mean_max_over_H": (max(means, key=abs) / target if means and target else None),
        })
    return rows


def _first_harmonic_height(details: Mapping[str, Any], n: int) -> float | None:
    """2 a1 / H_target - 1 at the gauge n wavelengths from the paddle (None if absent)."""
    wl, target = details.get("wavelength_linear"), details.get("H_target")
    if not wl or not target:
        return None
    for g in details.get("gauges", []):
        if abs(g["x"] / wl - n) < 0.01 and g.get("harmonics") and g["harmonics"][0]:
            return float(2.0 * g["harmonics"][0] / target - 1.0)
    return None


def secondorder_rows(records: Sequence[Record]) -> list[dict[str, Any]]:
    """One row per secondorder2d run: local spreads of both pistons and their ratio."""
    rows = []
    for r in sorted((r for r in records if r["case"] == "secondorder2d"),
                    key=lambda r: r["resolution"]):
        e = r.get("errors", {})
        rows.append({
            "resolution": r["resolution"], "dp": r["dp"], "status": r["status"],
            "particles": r["n_particles"], "steps": r["steps"], "wall_s": r["wall_s"],
            "cpu_s": r["cpu_s"],
            "local_spread_order1": e.get("a2_local_spread_order1"),
            "local_spread_order2": e.get("a2_local_spread_order2"),
            "spread_order1": e.get("a2_spread_order1"),
            "spread_order2": e.get("a2_spread_order2"),
            "ratio": e.get("local_spread_ratio"),
        })
    return rows


def markdown(f_rows: Sequence[Mapping[str, Any]], s_rows: Sequence[Mapping[str, Any]]) -> str:
    """The tables of results.md."""
    out = []
    if f_rows:
        out += ["## flume2d: regular wave H = 0.1 m, T = 1.2 s, d = 0.3 m", "",
                "| H/dp | dp [m] | particles | steps | wall [s] | cpu [s] | H at 1 L | H at 2 L "
                "| H at 3 L | 2 a1 at 1 L | 2 a1 at 2 L | 2 a1 at 3 L | loss per L "
                "| wavelength vs linear | vs Stokes 3rd | MWL drift / H | largest mean level / H |",
                "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in f_rows:
            out.append(
                f"| {r['resolution']:g} | {r['dp']:.4g} | {r['particles']:,} | {r['steps']:,} "
                f"| {r['wall_s']:.0f} | {r['cpu_s']:.0f} | {_pct(r['H_1L'])} | {_pct(r['H_2L'])} "
                f"| {_pct(r['H_3L'])} | {_pct(r['H1_1L'])} | {_pct(r['H1_2L'])} "
                f"| {_pct(r['H1_3L'])} | {_pct(r['loss_per_L'])} | {_pct(r['wavelength_linear'])} "
                f"| {_pct(r['wavelength_stokes3'])} | {_pct(r['mwl_change_max_over_H'], 2)} "
                f"| {_pct(r['mwl_mean_max_over_H'], 2)} |")
        out.append("")
    if s_rows:
        out += ["## secondorder2d: first- against second-order piston, kd = 0.69", "",
                "| H/dp | dp [m] | particles | steps (both runs) | wall [s] | cpu [s] "
                "| local spread, order 1 | local spread, order 2 | ratio 2/1 "
                "| spread / target bound, order 1 | order 2 |",
                "|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in s_rows:
            def f(v: float | None) -> str:
                return "-" if v is None else f"{v:.3f}"
            out.append(
                f"| {r['resolution']:g} | {r['dp']:.4g} | {r['particles']:,} | {r['steps']:,} "
                f"| {r['wall_s']:.0f} | {r['cpu_s']:.0f} | {f(r['local_spread_order1'])} "
                f"| {f(r['local_spread_order2'])} | {f(r['ratio'])} | {f(r['spread_order1'])} "
                f"| {f(r['spread_order2'])} |")
        out.append("")
    return "\n".join(out)


def plot(records: Sequence[Record], out: Path) -> list[Path]:
    """The two figures (matplotlib, Agg backend); returns the files written."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    written = []
    flume = sorted((r for r in records if r["case"] == "flume2d" and r["status"] == "ok"),
                   key=lambda r: r["resolution"])
    if flume:
        fig, ax = plt.subplots(figsize=(7, 4))
        ax.axhspan(0.95, 1.05, color="0.9", label="target +- 5 %")
        ax.axhline(1.0, color="k", lw=0.8)
        for r in flume:
            d = r["details"]
            wl, target = d["wavelength_linear"], d["H_target"]
            pts = sorted((g["x"] / wl, g["H_mean"] / target) for g in d.get("gauges", [])
                         if g.get("H_mean") is not None)
            if pts:
                x, h = zip(*pts, strict=True)
                line, = ax.plot(x, h, "o-",
                                label=f"H/dp = {r['resolution']:g} (dp = {r['dp']:.3g} m)")
                first = sorted((g["x"] / wl, 2.0 * g["harmonics"][0] / target)
                               for g in d.get("gauges", [])
                               if g.get("harmonics") and g["harmonics"][0] is not None)
                if first:
                    x1, h1 = zip(*first, strict=True)
                    ax.plot(x1, h1, "x--", color=line.get_color(), lw=0.8,
                            label=f"first harmonic 2 a1, H/dp = {r['resolution']:g}")
        ax.set_xlabel("distance from the paddle x / L")
        ax.set_ylabel("wave height / H_target")
        ax.set_title("flume2d: regular wave H = 0.1 m, T = 1.2 s, d = 0.3 m")
        ax.legend(fontsize=7, loc="lower left")
        ax.grid(alpha=0.3)
        path = out / "flume2d_height.png"
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)
        written.append(path)
    second = [r for r in records if r["case"] == "secondorder2d" and r["status"] == "ok"]
    if second:
        fig, ax = plt.subplots(figsize=(7, 4))
        for r in sorted(second, key=lambda r: r["resolution"]):
            d = r["details"]
            wl = d["wavelength"]
            k = 2.0 * math.pi / wl
            depth = d["wave"]["depth"]
            for order, style in ((1, "s--"), (2, "o-")):
                a1 = np.asarray(d.get(f"a1_order{order}", []), dtype=float)
                a2 = np.asarray(d.get(f"a2_order{order}", []), dtype=float)
                x = np.asarray(d.get(f"x_order{order}", []), dtype=float)
                if a1.size < 2:
                    continue
                bound = np.asarray(wt.stokes2_second_harmonic_amplitude(2.0 * a1, k, depth))
                ax.plot(x / wl, a2 / bound, style,
                        label=f"order {order}, H/dp = {r['resolution']:g}")
        ax.axhline(1.0, color="k", lw=0.8, label="Stokes bound (local first harmonic)")
        ax.set_xlabel("distance from the paddle x / L")
        ax.set_ylabel("a2 / a2,bound(a1 local)")
        ax.set_title("secondorder2d: d = 0.2 m, T = 1.4 s, H = 0.045 m (kd = 0.69)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        path = out / "secondorder2d.png"
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)
        written.append(path)
    return written


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", type=Path, help="watersim validate --json files")
    parser.add_argument("--out", type=Path, required=True, help="directory for figures/tables")
    args = parser.parse_args(argv)
    try:
        records = load_records(args.runs)
    except (OSError, ValueError) as exc:
        print(f"flume_accuracy: {exc}", file=sys.stderr)
        return 2
    f_rows, s_rows = flume2d_rows(records), secondorder_rows(records)
    if not f_rows and not s_rows:
        print("flume_accuracy: no flume2d or secondorder2d runs in the files", file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "results.md").write_text(markdown(f_rows, s_rows), "utf-8")
    (args.out / "results.json").write_text(
        json.dumps({"flume2d": f_rows, "secondorder2d": s_rows}, indent=1), "utf-8")
    for path in plot(records, args.out):
        print(path)
    print(args.out / "results.md")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
