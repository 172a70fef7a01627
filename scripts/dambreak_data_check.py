"""How far the Martin & Moyce (1952) n^2 = 2 data sets agree with each other, and the dambreak2d
runs of a ``watersim validate`` JSON file point by point against them.

    # the spread between the three front digitisations, and the height's reading step
    python3 scripts/dambreak_data_check.py
    # plus, per dambreak2d run of the file: the relative error of the column height at each
    # tabulated time, and the front's and the height's RMS errors
    python3 scripts/dambreak_data_check.py docs/validation/runs.json

Only the times a 0.7 s run of a 1 m wide column reaches are used (tau = t sqrt(2 g / a) <= 3.10
for the front, t sqrt(g / a) <= 2.19 for the height), so the numbers describe the data that the
dambreak2d case compares with.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np

from watersim.measure import MartinMoyce, load_martin_moyce, load_martin_moyce_height

G = 9.81
WIDTH = 1.0
UNTIL = 0.7
"""dambreak2d: column width [m] and simulated time [s]."""


def _spread(ref: MartinMoyce, other: MartinMoyce) -> tuple[np.ndarray, float]:
    """Relative difference of ``other``'s front to ``ref`` (interpolated at ``other``'s times)
    over the compared range, and its RMS."""
    tau_max = UNTIL * math.sqrt(2.0 * G / WIDTH)
    sel = (other.tau > 0.0) & (other.tau <= min(tau_max, ref.tau[-1]))
    x = np.interp(other.tau[sel], ref.tau, ref.delta)
    rel = (other.delta[sel] - x) / x
    return rel, float(np.sqrt(np.mean(rel**2)))


def data_report() -> None:
    """Print the spread between the front sets and the height's reading step."""
    sets = {name: load_martin_moyce(name) for name in ("lethe", "pysph_a2.25in",
                                                         "pysph_a1.125in")}
    print("front: relative difference between the n^2 = 2 digitisations (tau <= 3.10)")
    for a, b in (("lethe", "pysph_a2.25in"), ("lethe", "pysph_a1.125in"),
                 ("pysph_a2.25in", "pysph_a1.125in")):
        rel, rms = _spread(sets[a], sets[b])
        print(f"  {b} against {a}: {np.array2string(100 * rel, precision=1)} %, "
              f"RMS {100 * rms:.1f} %")
    h = load_martin_moyce_height()
    sel = h.tau <= UNTIL * math.sqrt(G / WIDTH)
    # eta sits on steps of 1/18 (1/4 in marks on a 4.5 in column): read to the nearest mark,
    # a value is uncertain by up to half a step, 1/36 of the initial height
    half = (1.0 / 36.0) / h.eta[sel]
    print(f"height: {int(np.count_nonzero(sel))} points up to tau = {h.tau[sel][-1]:.2f}; half a "
          f"1/18 step relative to each: {np.array2string(100 * half, precision=1)} %, "
          f"RMS {100 * float(np.sqrt(np.mean(half**2))):.1f} %")


def runs_report(path: Path) -> None:
    """Print the dambreak2d runs of a validate JSON file point by point."""
    runs = [r for r in json.loads(path.read_text("utf-8")) if r.get("case") == "dambreak2d"
            and "height_h" in (r.get("details") or {})]
    t_ref, h_ref = load_martin_moyce_height().dimensional(WIDTH, G)
    sel = t_ref <= UNTIL
    print(f"column height, data [m] at t = {np.array2string(t_ref[sel], precision=3)} s:")
    print(f"  {np.array2string(h_ref[sel], precision=3)}")
    for r in sorted(runs, key=lambda r: float(r["resolution"])):
        d = r["details"]
        h = np.interp(t_ref[sel], d["front_t"], d["height_h"])
        rel = h / h_ref[sel] - 1.0
        e = r["errors"]
        print(f"resolution {r['resolution']:g}: height error "
              f"{np.array2string(100 * rel, precision=1)} %; height_rms "
              f"{100 * e['height_rms']:.2f} %, front_rms {100 * e['front_rms']:.2f} %, "
              f"front_rms_shifted {100 * e['front_rms_shifted']:.2f} %")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="?", type=Path, help="a watersim validate JSON file")
    args = parser.parse_args()
    data_report()
    if args.runs is not None:
        runs_report(args.runs)


if __name__ == "__main__":
    main()
