"""Particle snapshots for ParaView: VTK unstructured-grid files (``.vtu``, written with meshio)
and a ``.pvd`` collection that ParaView opens as one time series.

Each snapshot holds every particle as a vertex with the point fields ``velocity`` [m/s],
``density`` [kg/m^3], ``pressure`` [Pa], ``kind`` (0 fluid, 1 fixed wall, 2 moving wall,
3 excluded) and ``id`` (creation order), in particle-id order so that files of one run line up.
2D runs are written in the x-z plane of ParaView's 3D space (coordinates ``(x, 0, z)``), so that
"up" is z in both dimensions.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import numpy.typing as npt

from .simulation import Simulation

__all__ = ["SnapshotWriter", "snapshot_mesh"]


def _to_3d(a: npt.NDArray[np.float64], dim: int) -> npt.NDArray[np.float64]:
    """(N, 2) x-z arrays as (N, 3) with a zero y column; (N, 3) unchanged."""
    if dim == 3:
        return np.ascontiguousarray(a)
    out = np.zeros((a.shape[0], 3))
    out[:, 0] = a[:, 0]
    out[:, 2] = a[:, 1]
    return out


def snapshot_mesh(sim: Simulation) -> meshio.Mesh:
    """The current particle state as a meshio point cloud (one vertex cell per particle)."""
    core = sim.core
    order = np.argsort(np.asarray(core.ids), kind="stable")
    dim = core.dim
    points = _to_3d(np.asarray(core.positions)[order], dim)
    n = points.shape[0]
    point_data = {
        "velocity": _to_3d(np.asarray(core.velocities)[order], dim),
        "density": np.asarray(core.densities)[order].copy(),
        "pressure": np.asarray(core.pressures)[order].copy(),
        "kind": np.asarray(core.kinds)[order].astype(np.int32),
        "id": np.asarray(core.ids)[order].astype(np.int64),
    }
    cells = [("vertex", np.arange(n, dtype=np.int64).reshape(-1, 1))]
    return meshio.Mesh(points, cells, point_data=point_data)


class SnapshotWriter:
    """Writes ``DIR/particles_NNNNN.vtu`` snapshots and keeps ``DIR/particles.pvd`` up to date.

    The ``.pvd`` file is rewritten after every snapshot, so a run that stops early still leaves
    a collection ParaView can open with every snapshot written so far.

    Args:
        directory: output folder (created if missing).
        prefix: file name prefix.
    """

    def __init__(self, directory: str | Path, prefix: str = "particles") -> None:
        self.directory = Path(directory)
        self.directory.mkdir(parents=True, exist_ok=True)
        self.prefix = prefix
        self.entries: list[tuple[float, str]] = []

    @property
    def pvd_path(self) -> Path:
        return self.directory / f"{self.prefix}.pvd"

    def write(self, sim: Simulation) -> Path:
        """Writes one snapshot of ``sim`` at its current time; returns the ``.vtu`` path."""
        name = f"{self.prefix}_{len(self.entries):05d}.vtu"
        path = self.directory / name
        meshio.write(path, snapshot_mesh(sim), binary=True)
        self.entries.append((sim.time, name))
        self._write_pvd()
        return path

    def _write_pvd(self) -> None:
        root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
        collection = ET.SubElement(root, "Collection")
        for t, name in self.entries:
            ET.SubElement(collection, "DataSet", timestep=repr(float(t)), group="", part="0", file=name)
        tmp = self.pvd_path.with_suffix(".pvd.tmp")
        ET.ElementTree(root).write(tmp, xml_declaration=True, encoding="utf-8")
        tmp.replace(self.pvd_path)
