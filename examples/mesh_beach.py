"""A plane 1:15 beach as a closed triangle mesh, written as an STL file for a 3D flume.

    python3 examples/mesh_beach.py                 # writes examples/beach_1in15.stl (ASCII)
    python3 -m watersim run examples/mesh_beach3d.toml --out runs/mesh_beach3d

The beach is a wedge (a triangular prism) across the flume: its bottom face on the floor from
the toe to the far wall, its sloping face rising 1 in 15, a vertical face against the far wall,
and the two side faces on the side walls. Triangles are counter-clockwise seen from outside
(outward normals), as the core needs (``watersim.MeshBeach`` checks it). The same shape could
come from any CAD or bathymetry tool that writes STL.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import meshio
import numpy as np
import numpy.typing as npt

HERE = Path(__file__).resolve().parent

TOE = 1.0
"""x of the toe [m] (the paddle face at rest is x = 0)."""
SLOPE = 1.0 / 15.0
"""Beach slope tan(beta) [-]."""
LENGTH = 4.5
"""Flume length [m]: the wedge ends at the far wall, z = SLOPE (LENGTH - TOE) = 0.233 m high."""
WIDTH = 0.24
"""Flume width [m]: the wedge spans it."""


def plane_beach_mesh(toe: float, slope: float, length: float, width: float
                     ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """Vertices (6, 3) [m] and outward-oriented triangles (8, 3) of a plane beach wedge from
    the toe ``(toe, z = 0)`` to the far wall ``x = length``, across ``[0, width]``."""
    top = slope * (length - toe)
    vertices = np.array([
        [toe, 0.0, 0.0], [length, 0.0, 0.0], [length, 0.0, top],            # side y = 0
        [toe, width, 0.0], [length, width, 0.0], [length, width, top],      # side y = width
    ])
    triangles = np.array([
        [0, 1, 2],              # side y = 0 (normal -y)
        [3, 5, 4],              # side y = width (normal +y)
        [0, 4, 1], [0, 3, 4],   # bottom (normal -z)
        [1, 5, 2], [1, 4, 5],   # far wall face (normal +x)
        [0, 5, 3], [0, 2, 5],   # the slope (normal up and offshore)
    ])
    return vertices, triangles


def write_stl(path: Path, vertices: npt.NDArray[np.float64], triangles: npt.NDArray[np.int64],
              binary: bool = False) -> Path:
    """Write a triangle mesh as STL with meshio (ASCII unless ``binary``)."""
    meshio.write_points_cells(path, vertices, [("triangle", triangles)], file_format="stl",
                              binary=binary)
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=HERE / "beach_1in15.stl")
    parser.add_argument("--binary", action="store_true", help="binary STL (default ASCII)")
    args = parser.parse_args()
    v, t = plane_beach_mesh(TOE, SLOPE, LENGTH, WIDTH)
    print(f"wrote {write_stl(args.out, v, t, args.binary)}: {len(t)} triangles")


if __name__ == "__main__":
    main()
