"""dsph-piston2d with f32 or f64 pair terms: the surface at three stations, to compare.

    RAYON_NUM_THREADS=1 python3 scripts/piston_precision.py f32 3.9 OUT_f32.npy
    RAYON_NUM_THREADS=1 python3 scripts/piston_precision.py f64 3.9 OUT_f64.npy
    python3 scripts/piston_precision.py compare OUT_f32.npy OUT_f64.npy

The elevation is the highest fluid particle within dp of each station, every 0.01 s (a coarse
measure, enough to see whether the precision changes the wave: docs/benchmarks.md, "f32
against f64 pair terms").
"""

from __future__ import annotations

import sys
import time

import numpy as np

STATIONS = (0.5, 1.0, 1.5)
"""Stations [m] from the paddle's rest position, on the flat bed before the beach."""


def run(precision: str, until: float, out: str) -> None:
    from watersim import Simulation
    from watersim.bench_cases import dsph_scene

    scene = {**dsph_scene("dsph-piston2d"), "force_precision": precision}
    sim = Simulation(scene)
    dp = scene["dp"]
    rows: list[list[float]] = []

    def sample(s: Simulation) -> None:
        x = s.fluid_positions()
        row = [s.time]
        for station in STATIONS:
            near = np.abs(x[:, 0] - station) < dp
            row.append(float(x[near, 1].max()) if near.any() else float("nan"))
        rows.append(row)

    t0 = time.process_time()
    sim.run(until, callback_every=0.01, callback=sample)
    np.save(out, np.array(rows))
    print(f"{precision}: {sim.steps} steps, {time.process_time() - t0:.0f} s CPU, "
          f"state {sim.state_sha256()[:12]}")


def compare(a_file: str, b_file: str, after: float = 1.3) -> None:
    """Heights (crest to trough after the ramp, ``after`` s) and differences of two records."""
    a, b = np.load(a_file), np.load(b_file)
    n = min(len(a), len(b))
    a, b = a[:n], b[:n]
    late = a[:, 0] > after
    for k, station in enumerate(STATIONS, start=1):
        ea, eb = a[:, k], b[:, k]
        height_a = ea[late].max() - ea[late].min()
        height_b = eb[late].max() - eb[late].min()
        rms = np.sqrt(np.mean((ea - eb) ** 2))
        print(f"x = {station} m: H {1e3 * height_a:.1f} / {1e3 * height_b:.1f} mm, RMS difference "
              f"{1e3 * rms:.2f} mm, mean level {1e3 * ea[late].mean():.1f} / "
              f"{1e3 * eb[late].mean():.1f} mm")


if __name__ == "__main__":
    if sys.argv[1] == "compare":
        compare(sys.argv[2], sys.argv[3])
    else:
        run(sys.argv[1], float(sys.argv[2]), sys.argv[3])
