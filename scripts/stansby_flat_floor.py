"""Seed 002's flume (stansby2d) read closely: the generated wave over the flat floor and the
undertow definitions (issue 31). One run of stansby2d at its default dp with 32 more gauges (kernel
and particle, every 0.1 m from 0.4 to 1.9 m) that do not change the flow:

    python3 scripts/stansby_flat_floor.py --write-scene /tmp/stansby_extra.toml
    RAYON_NUM_THREADS=1 watersim run /tmp/stansby_extra.toml --out runs/stansby-extra
    python3 scripts/stansby_flat_floor.py runs/stansby-extra

Prints (1) the zero-crossing height H(x) at every flat-floor gauge, both methods, over six whole
periods; (2) per harmonic n = 1..3, a least-squares split of the gauges' complex amplitudes into an
incident wave bound to the first harmonic (wavenumber n k, k the stream-function wave's), an
incident free wave (linear k(n omega)) and a reflected free wave, against the target wave's
harmonics; (3) the depth-averaged undertow at seed 002 Table 3's gauges under other definitions
(to a level other than the vertical's trough, over other time windows) beside Table 3.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

from watersim import analysis as an
from watersim import wave_theory as wt
from watersim.validation.stansby import stansby_undertow_table

H, T, D = 0.105, 2.42, 0.34
XS = [round(0.1 * i, 2) for i in range(4, 20)]
METHODS = ("kernel", "particle")
UNTIL = 25.2  # as watersim validate stansby2d: ramp + arrival at 7.6 m + six periods


def write_scene(path: Path) -> None:
    text = subprocess.run([sys.executable, "-m", "watersim", "show-scene", "stansby2d"],
                          check=True, capture_output=True, text=True).stdout
    text = text.replace("until = 24.2", f"until = {UNTIL}")
    for x in XS:
        for method in METHODS:
            text += (f'\n[[gauges]]\ntype = "elevation"\nx = {x}\nmethod = "{method}"\n'
                     f'name = "{method[0]}_x{x:.2f}"\n')
    path.write_text(text, encoding="utf-8")


def _table(path: Path) -> tuple[list[str], np.ndarray]:
    rows = list(csv.reader(path.open()))
    return rows[0], np.array([[float(v) for v in r] for r in rows[1:]])


def flat_floor(run: Path, start: float) -> None:
    head, data = _table(run / "gauges.csv")
    t = data[:, 0]
    sel = (t >= start) & (t < start + 6.0 * T - 1e-9)
    wave = wt.stream_function_wave(H, T, D)
    k1, target = wave.wavenumber, wave.elevation_coefficients
    xs = np.asarray(XS)
    print(f"flat floor, six periods from t = {start:.2f} s; target harmonics "
          + " ".join(f"{e:.5f}" for e in target[1:4]) + " m")
    for method in METHODS:
        heights, amps = [], []
        for x in XS:
            e = data[sel, head.index(f"{method[0]}_x{x:.2f}".replace(".", "p") + "_m")]
            heights.append(an.zero_crossing_waves(e, t[sel]).mean_height)
            amps.append([2.0 * np.mean((e - e.mean()) * np.exp(2j * math.pi * n * t[sel] / T))
                         for n in (1, 2, 3)])
        h, a = np.asarray(heights), np.asarray(amps)
        print(f"[{method}] H(x) " + " ".join(f"{v:.4f}" for v in h)
              + f"; mean {h.mean():.4f} m ({h.mean() / H - 1:+.1%}), {h.min():.4f}-{h.max():.4f}")
        for n in (1, 2, 3):
            kf = float(wt.wavenumber_from_omega(2.0 * math.pi * n / T, D))
            names = ["incident", "incident free", "reflected"] if n > 1 else ["incident",
                                                                               "reflected"]
            waves = [np.exp(1j * n * k1 * xs)] + ([np.exp(1j * kf * xs)] if n > 1 else [])
            basis = np.stack([*waves, np.exp(-1j * kf * xs)], axis=1)
            c, *_ = np.linalg.lstsq(basis, a[:, n - 1], rcond=None)
            misfit = np.linalg.norm(basis @ c - a[:, n - 1]) / np.linalg.norm(a[:, n - 1])
            print(f"  harmonic {n}: " + ", ".join(f"{s} {abs(v):.5f}" for s, v in zip(names, c,
                                                                                      strict=True))
                  + f" m (target {target[n]:.5f}, {abs(c[0]) / target[n] - 1:+.1%}); local "
                  f"{np.abs(a[:, n - 1]).min():.5f}-{np.abs(a[:, n - 1]).max():.5f}; misfit "
                  f"{misfit:.3f}")


def _depth_mean(mean_u: np.ndarray, edges: np.ndarray, top: float) -> float:
    """Seaward depth average of ``mean_u`` (cells between ``edges``) from the bed to ``top``."""
    w = np.clip(np.minimum(edges[1:], top) - edges[:-1], 0.0, None)
    return -float(np.sum(mean_u * w) / (top - edges[0]))


def _undertows(run: Path, v: dict, mean_level: float) -> dict[str, float]:
    """One vertical's undertow under each definition."""
    head, data = _table(run / f"velocity_{v['name']}.csv")
    t = data[:, 0]
    u = data[:, [i for i, c in enumerate(head) if c.startswith("u_")]]
    wet = data[:, [i for i, c in enumerate(head) if c.startswith("kernel_sum_")]] >= 0.5
    z = np.asarray(v["z"])
    edges = np.concatenate([[-v["still_depth"]], 0.5 * (z[1:] + z[:-1]),
                            [1.5 * z[-1] - 0.5 * z[-2]]])
    mean_u = np.asarray(v["mean_u"])
    w0, w1 = v["window"]
    out = {
        "analysis.json (bed to trough, steady periods)": -v["undertow"],
        "bed to z = -0.05 m (seed's trough envelope, d - H/2)": _depth_mean(mean_u, edges, -0.05),
        "bed to the mean level": _depth_mean(mean_u, edges, mean_level),
        "bed to still water": _depth_mean(mean_u, edges, 0.0),
    }
    for name, (t0, t1) in {"steady periods, raw samples": (w0, w0 + (w1 - w0) // T * T),
                           "t = 0-20 s": (0.0, 20.0), f"t = 0-{UNTIL} s": (0.0, UNTIL)}.items():
        s = (t >= t0) & (t < t1)
        window_u = np.mean(np.where(wet[s], u[s], 0.0), axis=0)
        out[f"to trough, {name}"] = _depth_mean(window_u, edges, v["trough_level"])
    out["flux below / above trough"] = -v["flux_below_trough"] / v["flux_above_trough"]
    return out


def undertow(run: Path) -> None:
    result = json.loads((run / "analysis.json").read_text())
    table = stansby_undertow_table()
    levels = {round(g["x"], 3): g.get("mean_level") for g in result["gauges"]
              if g["name"].startswith("eta")}
    rows: dict[str, list[float]] = {}
    for v in result["velocity_verticals"]:
        found = _undertows(run, v, levels[round(v["x"], 3)])
        found["Table 3"] = table[int(v["name"].removeprefix("u_gauge"))]
        for key, value in found.items():
            rows.setdefault(key, []).append(value)
    ref = np.asarray(rows["Table 3"])
    print("undertow, seaward [m/s], gauges "
          + " ".join(v["name"].removeprefix("u_gauge") for v in result["velocity_verticals"]))
    for key, values in rows.items():
        vals = np.asarray(values)
        against = "" if key.startswith(("Table", "flux")) else (
            f" ({vals.mean() / ref.mean() - 1:+.0%} against Table 3)")
        print(f"  {key}: " + " ".join(f"{x:.3f}" for x in vals)
              + f"; mean {vals.mean():.4f}{against}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", nargs="?", type=Path, help="the run directory")
    parser.add_argument("--write-scene", type=Path, help="write the scene file and stop")
    args = parser.parse_args()
    if args.write_scene:
        write_scene(args.write_scene)
        return
    if args.run is None:
        parser.error("give the run directory (or --write-scene FILE)")
    reflection = json.loads((args.run / "analysis.json").read_text())["reflection"]
    flat_floor(args.run, float(reflection["window"][0]))
    undertow(args.run)


if __name__ == "__main__":
    main()
