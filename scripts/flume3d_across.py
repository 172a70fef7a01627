"""flume3d variants with gauges of both surface methods across the width, and their summary.

    # a scene file: flume3d with these --set values, its gauges replaced by kernel and particle
    # gauges at 1/4, 1/2 and 3/4 of the width at 0.5 L and 1 L (gauges do not change the flow)
    python3 scripts/flume3d_across.py write runs/v.toml --set viscosity=artificial --periods 6
    python3 -m watersim run runs/v.toml --out runs/v
    # per gauge: the zero-crossing mean height and the first-harmonic height 2 a1 over the
    # target, and their spread across the width at each x (percent of H)
    python3 scripts/flume3d_across.py summary runs/v [runs/w ...]

``--fractions F1,F2,...``: the gauges' positions across the width (default 0.25,0.5,0.75).
``--periods N``: until = ramp + arrival at 1 L + N periods (the case's own rule, which uses 5).
"""

from __future__ import annotations

import argparse
import collections
import json
import sys
from pathlib import Path

import tomli_w

from watersim import scenefile as sf
from watersim.flume_cases import flume_builder


def write(path: Path, settings: list[str], periods: float, fractions: list[float]) -> None:
    items = dict(s.split("=", 1) for s in settings)
    setup = flume_builder("flume3d", items)
    doc = sf.scene_to_dict(setup)
    wl = float(setup.wavelength or 0.0)
    width = float(setup.flume.width or 0.0)
    x_half, x_one = round(0.5 * wl, 3), round(wl, 3)
    doc["gauges"] = [
        {"type": "elevation", "x": x, "y": round(f * width, 4), "method": m,
         "name": f"{m[0]}_x{x:.3f}_y{f:.2f}"}
        for m in ("particle", "kernel") for x in (x_half, x_one) for f in fractions
    ]
    if "until" not in items:
        period = float(setup.period or 0.0)
        doc["until"] = round(setup.law.ramp_duration + setup.arrival_time(wl) + periods * period, 2)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(tomli_w.dumps(doc))
    print(f"wrote {path}: until {doc['until']} s, width {width} m, dp {setup.dp} m")


def summary(folders: list[Path]) -> None:
    for d in folders:
        a = json.loads((d / "analysis.json").read_text())
        s = json.loads((d / "summary.json").read_text())
        target = a["wave"]["height"]
        print(f"{d}: {s['n_particles']} particles, {s['steps']} steps, wall {s['wall_s']:.0f} s "
              f"({s['threads']} thread(s))")
        groups: dict[tuple[str, float], list[tuple[float, float, float]]] = (
            collections.defaultdict(list))
        for g in a["gauges"]:
            method = g["name"][0] if g["name"][1:2] == "_" else "p"
            h1 = 2.0 * g["harmonics"][0]
            groups[(method, round(g["x"], 3))].append((g.get("y", 0.0), g["H_mean"], h1))
        for (method, x), rows in sorted(groups.items()):
            cells = " ".join(f"y={y:.3f}: zc {100 * (h / target - 1):+.1f} % H1 "
                             f"{100 * (h1 / target - 1):+.1f} %" for y, h, h1 in rows)
            spread = ""
            if len(rows) > 1:
                zc = [r[1] for r in rows]
                h1s = [r[2] for r in rows]
                spread = (f" | spread zc {100 * (max(zc) - min(zc)) / target:.1f} % H1 "
                          f"{100 * (max(h1s) - min(h1s)) / target:.1f} %")
            print(f"  {'kernel' if method == 'k' else 'particle'} x = {x}: {cells}{spread}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    w = sub.add_parser("write")
    w.add_argument("path", type=Path)
    w.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    w.add_argument("--periods", type=float, default=5.0)
    w.add_argument("--fractions", default="0.25,0.5,0.75",
                   help="gauge positions across the width, as fractions of it (comma-separated)")
    s = sub.add_parser("summary")
    s.add_argument("folders", type=Path, nargs="+")
    args = parser.parse_args(argv)
    if args.command == "write":
        write(args.path, args.set, args.periods, [float(f) for f in args.fractions.split(",")])
    else:
        summary(args.folders)
    return 0


if __name__ == "__main__":
    sys.exit(main())
