"""Which numerical choice makes a regular wave lose height along a flat flume? (project issue 3)

Short, cheap runs of one wave (d = 0.3 m, T = 1.2 s, L = 1.77 m, H = 0.1 m, second-order
piston, two-period ramp, coefsound 10) at dp = 0.025 m (H/dp = 4) in a short flume: 2.25 L of
flat floor plus a 1 L damping zone, gauges at 0.5, 1, 1.5 and 2 L, until = ramp + arrival at
2 L + 3 periods. Each variant changes one numerical parameter of the flume defaults (alpha 0.01,
Symplectic, Fourtakas delta 0.1, coefh 1.5, coefsound 10) and records the zero-crossing wave
height over the target at each gauge. About 1-3 minutes per variant on one core.

Run::

    RAYON_NUM_THREADS=1 python3 examples/flume_numerics_study.py \
        --json docs/wave-flume/numerics-study.json            # every variant
    ... examples/flume_numerics_study.py base alpha0 --json out.json   # some of them

The JSON holds one record per variant (settings, particles, steps, wall and CPU time, H / H_target
by gauge position in wavelengths); ``--table`` prints the Markdown table of a JSON file without
running anything. Units: metres, seconds.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from watersim import wave_theory as wt
from watersim.flume import DampingZone, ElevationGauge, Flume, FlumeScene, Piston, RegularWave

DEPTH, PERIOD, HEIGHT = 0.3, 1.2, 0.1
"""The wave [m, s]: flume2d's depth and period with the flume2d validation case's height."""
GAUGES_L = (0.5, 1.0, 1.5, 2.0)
"""Gauge positions [wavelengths from the paddle]."""

VARIANTS: dict[str, dict[str, Any]] = {
    "base": {},
    "alpha0": {"viscosity": {"type": "artificial", "alpha": 0.0}},
    "laminar": {"viscosity": {"type": "laminar", "nu": 1e-6}},
    "nodiff": {"diffusion": "none"},
    "verlet": {"integrator": "verlet"},
    "verlet_alpha0": {"integrator": "verlet", "viscosity": {"type": "artificial", "alpha": 0.0}},
    "verlet_alpha0.003": {"integrator": "verlet",
                          "viscosity": {"type": "artificial", "alpha": 0.003}},
    "verlet_alpha0.003_coefsound20": {"integrator": "verlet", "coefsound": 20.0,
                                      "viscosity": {"type": "artificial", "alpha": 0.003}},
    "verlet_alpha0.003_coefh2": {"integrator": "verlet", "coefh": 2.0,
                                 "viscosity": {"type": "artificial", "alpha": 0.003}},
}
"""Each variant's changes to the flume defaults (FlumeScene fields; an option as its table)."""


def scene(dp: float = 0.025, **numerics: Any) -> tuple[FlumeScene, float]:
    """The study's flume at ``dp`` with ``numerics`` (FlumeScene fields); returns (scene, L)."""
    wl = float(wt.wavelength(PERIOD, DEPTH))
    flume = Flume(length=round(3.25 * wl, 3), depth=DEPTH,
                  damping=DampingZone(length=round(wl, 3)))
    gauges = [ElevationGauge(round(n * wl, 3)) for n in GAUGES_L]
    kwargs: dict[str, Any] = {"coefsound": 10.0, **numerics}
    wave, paddle = RegularWave(height=HEIGHT, period=PERIOD), Piston(order=2, ramp_periods=2.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        probe = FlumeScene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, dp=dp,
                           until=1.0, **kwargs)
    until = probe.law.ramp_duration + probe.arrival_time(GAUGES_L[-1] * wl) + 3.0 * PERIOD
    return FlumeScene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, dp=dp,
                      until=round(until, 2), **kwargs), wl


def run_variant(name: str) -> dict[str, Any]:
    """Run one variant; its record (see the module docstring)."""
    settings = VARIANTS[name]
    sc, wl = scene(**settings)
    sim = sc.build()
    wall0, cpu0 = time.perf_counter(), time.process_time()
    sim.run(until=float(sc.until))  # type: ignore[arg-type]
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    result = sim.analyse()
    return {
        "variant": name, "settings": settings, "dp": sc.dp, "particles": sim.n_particles,
        "steps": sim.steps, "until": sc.until, "wall_s": wall, "cpu_s": cpu,
        "H_over_target": {f"{g['x'] / wl:.2f}": (None if g.get("H_mean") is None
                                                else g["H_mean"] / HEIGHT)
                          for g in result["gauges"]},
    }


def _change(key: str, value: Any) -> str:
    """One setting as the table shows it (``viscosity artificial alpha 0``)."""
    if isinstance(value, dict):
        return " ".join([key, *(f"{v}" if k == "type" else f"{k} {v:g}" for k, v in value.items())])
    return f"{key} {value:g}" if isinstance(value, float) else f"{key} {value}"


def table(records: Sequence[dict[str, Any]]) -> str:
    """Markdown table: one row per variant, H / H_target at each gauge."""
    cols = [f"{n:.2f}" for n in GAUGES_L]
    lines = ["| variant | changes | steps | cpu [s] | "
             + " | ".join(f"{float(c):g} L" for c in cols) + " |",
             "|---|---|---|---|" + "---|" * len(cols)]
    for r in records:
        changes = ", ".join(_change(k, v) for k, v in r["settings"].items()) or "flume defaults"
        hs = " | ".join("-" if r["H_over_target"].get(c) is None
                        else f"{r['H_over_target'][c]:.3f}" for c in cols)
        lines.append(f"| {r['variant']} | {changes} | {r['steps']:,} | {r['cpu_s']:.0f} | {hs} |")
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("variants", nargs="*", help=f"default: all of {', '.join(VARIANTS)}")
    parser.add_argument("--json", type=Path, help="write (or, with --table, read) the records")
    parser.add_argument("--table", action="store_true", help="print the table of --json, no run")
    args = parser.parse_args(argv)
    if args.table:
        if args.json is None:
            print("flume_numerics_study: --table needs --json FILE", file=sys.stderr)
            return 2
        print(table(json.loads(args.json.read_text("utf-8"))))
        return 0
    names = args.variants or list(VARIANTS)
    unknown = [n for n in names if n not in VARIANTS]
    if unknown:
        print(f"flume_numerics_study: unknown variant(s) {', '.join(unknown)}; known: "
              f"{', '.join(VARIANTS)}", file=sys.stderr)
        return 2
    records = []
    for name in names:
        records.append(run_variant(name))
        print(table(records[-1:]).splitlines()[-1], flush=True)
        if args.json is not None:
            args.json.parent.mkdir(parents=True, exist_ok=True)
            args.json.write_text(json.dumps(records, indent=1), "utf-8")
    print(table(records))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
