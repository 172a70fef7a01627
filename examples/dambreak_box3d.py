"""A 3D dam break against a box: water-height gauges in front of and behind it, pressure
sensors on its front face and the force on it.

The geometry is the MARIN experiment (Kleefsman et al. 2005, J. Comput. Phys. 206, 363-393;
SPHERIC benchmark 2): a 3.22 x 1 x 1 m tank, a 1.228 m long column of water 0.55 m deep against
its far wall, a 0.161 x 0.403 x 0.161 m box on the floor 0.67 m from the near wall; water
heights H1-H4 and pressures P1-P4 on the box's face towards the water (its positions; the
experiment's records are not compared here).

    python3 examples/dambreak_box3d.py --dp 0.02 --until 1.0    # writes runs/dambreak_box3d/
"""

from __future__ import annotations

import argparse
from pathlib import Path

import watersim as ws

BOX = ((0.6635, 0.2975, 0.0), (0.8245, 0.7025, 0.161))


def scene(dp: float = 0.02, until: float = 1.0) -> ws.Scene:
    """The scene: every object of it in a few lines."""
    return ws.Scene(
        tank=(3.22, 1.0, 1.0), dp=dp, until=until,
        fluid=[ws.FluidBlock((3.22 - 1.228, 0.0, 0.0), (3.22, 1.0, 0.55))],
        bodies=[ws.Box(*BOX, name="box")],
        gauges=[
            *(ws.ElevationGauge(x, 0.5, name=f"H{i + 1}")
              for i, x in enumerate((2.725, 2.228, 1.732, 0.582))),
            ws.PressureGauge([(0.8245, 0.5, z) for z in (0.021, 0.061, 0.101, 0.141)],
                             on_wall=True, name="P"),
            ws.ForceGauge("box", point=(0.744, 0.5, 0.0)),
        ],
    )


def main(argv: list[str] | None = None) -> ws.SceneSimulation:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dp", type=float, default=0.02)
    parser.add_argument("--until", type=float, default=1.0)
    parser.add_argument("--out", type=Path, default=Path("runs/dambreak_box3d"))
    args = parser.parse_args(argv)
    sim = scene(args.dp, args.until).build()
    sim.run(args.until)
    args.out.mkdir(parents=True, exist_ok=True)
    written = sim.write_gauges_csv(args.out / "gauges.csv")
    print(f"{sim.n_particles} particles, {sim.steps} steps: {written}")
    force = sim.gauges.records["box"]["force"]
    print(f"largest force on the box along x: {abs(force[:, 0]).max():.1f} N")
    return sim


if __name__ == "__main__":
    main()
