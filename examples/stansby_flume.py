"""Seed 002 (Makris et al.; Stansby & Feng 2005): regular waves breaking on a 1:20 beach, with
the elevation at seed 002's gauges and the water-level envelopes with the breaking point. At the
default dp (5,345 particles, 10 periods, about 34,000 steps) the run takes one to two CPU-minutes;
the script prints its estimate before it starts and the speed it measures once it runs.

    RAYON_NUM_THREADS=2 python3 examples/stansby_flume.py --out runs/stansby
    python3 examples/stansby_flume.py --dp 0.01 --periods 20 --out runs/stansby-fine
    python3 examples/stansby_flume.py --out runs/stansby --replot   # figures only

The flume is the built-in case ``stansby2d`` written out with the public API: d = 0.34 m,
11 m long (seed 002 Table 1), plane 1:20 beach from x = 2.0 m (the seed does not give the toe:
an estimate, see ``watersim.flume_cases.case_stansby2d``), H = 0.105 m, T = 2.42 s,
piston with a two-period ramp following the stream-function law (``theory = "auto"`` picks it at
the wave's Ursell number, 48, beyond second-order theory; ``theory="stokes2"`` gives Madsen's
second-order law with a WaveValidityWarning), the gauges of seed 002 Table 2 (the repeated positions 7.2 and 7.6 m
once) plus two over the flat floor; gauges take the highest particle.

Writes to ``--out``: gauges.csv, analysis.json, records.npz, summary.json,
gauges_phase_averaged.png and envelopes.png.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import watersim as ws
from watersim.flume_cases import STANSBY_GAUGES

sys.path.insert(0, str(Path(__file__).resolve().parent))
from flume_example import (  # noqa: E402 - the shared module sits next to this script
    Records,
    parse_args,
    plot_envelopes,
    plot_phase_averaged_gauges,
    run_flume,
)

DEPTH = 0.34
"""Still-water depth [m] (seed 002 Table 1)."""
PERIOD = 2.42
"""Wave period T [s] (seed 002 Table 1)."""
HEIGHT = 0.105
"""Wave height H [m] (seed 002 Table 1)."""
TOE, SLOPE = 2.0, 1.0 / 20.0
"""Beach toe [m] (estimate, see the module docstring) and slope (seed 002 Table 1)."""
FIGURE_GAUGES = {1: "before the slope", 8: "incipient breaking", 10: "incipient breaking",
                 21: "inner surf zone", 23: "inner surf zone"}
"""Seed 002 gauge numbers drawn (Fig. 3 shows 8, 10, 21 and 23), with the seed's region."""


def make(dp: float, periods: float) -> tuple[ws.Flume, dict[str, Any]]:
    """The flume and the arguments of :meth:`watersim.Flume.simulation` at spacing ``dp`` [m]
    for ``periods`` wave periods."""
    flume = ws.Flume(length=11.0, depth=DEPTH, beach=ws.PlaneBeach(toe=TOE, slope=SLOPE))
    xs = sorted({*STANSBY_GAUGES, 0.8, 1.8})
    return flume, {
        "wave": ws.RegularWave(height=HEIGHT, period=PERIOD),
        "paddle": ws.Piston(order=2, ramp_periods=2.0),
        "dp": dp,
        "coefsound": 10.0,
        "gauges": [ws.ElevationGauge(x, method="particle") for x in xs],
        "runup": True,
        "until": round(periods * PERIOD, 3),
    }


def _references(ax1: Any, ax2: Any) -> None:
    lo, hi = STANSBY_GAUGES[7], STANSBY_GAUGES[9]
    for ax in (ax1, ax2):
        ax.axvspan(lo, hi, color="tab:red", alpha=0.12,
                   label=f"seed 002: incipient breaking, gauges 8-10 ({lo}-{hi} m)")
        ax.axvline(TOE + DEPTH / SLOPE, color="0.4", lw=0.8, ls=":", label="shoreline at rest")


def figures(scene: ws.FlumeScene, records: Records, analysis: dict[str, Any],
            out: Path) -> list[Path]:
    """The two figures into ``out``; returns their paths."""
    gauges = [(STANSBY_GAUGES[n - 1], f"gauge {n} (x = {STANSBY_GAUGES[n - 1]} m), seed 002: "
               f"{region}") for n, region in FIGURE_GAUGES.items()]
    return [
        plot_phase_averaged_gauges(records, analysis, PERIOD, gauges,
                                   out / "gauges_phase_averaged.png",
                                   "seed 002 Fig. 3-like: ensemble-averaged elevation"),
        plot_envelopes(scene, analysis, out / "envelopes.png",
                       "seed 002 Fig. 2-like: envelopes, mean level and wave height on the "
                       "1:20 beach", _references),
    ]


def main(argv: Sequence[str] | None = None) -> list[Path]:
    """Run the example (see the module docstring); returns the figures written."""
    args = parse_args(argv, __doc__.splitlines()[0], dp=0.03, periods=10.0, out="runs/stansby",
                      depth=DEPTH)
    return run_flume(args, make, figures)


if __name__ == "__main__":
    main()
