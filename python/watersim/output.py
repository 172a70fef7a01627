"""Particle snapshots for ParaView: VTK unstructured-grid files (``.vtu``, written with meshio)
and a ``.pvd`` collection that ParaView opens as one time series.

Each snapshot holds every particle as a vertex with the point fields ``velocity`` [m/s],
``vorticity`` [1/s] (of the fluid, :func:`watersim.fields.particle_vorticity`; zero on walls,
NaN for a particle too isolated for a gradient; in 2D the vector ``(0, omega_y, 0)`` across
the x-z plane), ``density`` [kg/m^3], ``pressure`` [Pa], ``kind`` (0 fluid, 1 fixed wall,
2 moving wall, 3 excluded) and ``id`` (creation order), in particle-id order so that files of
one run line up.
2D runs are written in the x-z plane of ParaView's 3D space (coordinates ``(x, 0, z)``), so that
"up" is z in both dimensions.
"""

from __future__ import annotations

import json
import time
import xml.etree.ElementTree as ET
from collections.abc import Callable
from pathlib import Path
from typing import Any, TextIO

import meshio
import numpy as np
import numpy.typing as npt

from ._files import atomic_path, atomic_write, named_errors
from ._jsonio import json_ready
from .fields import particle_vorticity
from .simulation import Simulation

__all__ = ["RunLog", "RunOutputs", "SnapshotWriter", "snapshot_mesh"]


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
        "vorticity": _fluid_vorticity(sim, order),
        "density": np.asarray(core.densities)[order].copy(),
        "pressure": np.asarray(core.pressures)[order].copy(),
        "kind": np.asarray(core.kinds)[order].astype(np.int32),
        "id": np.asarray(core.ids)[order].astype(np.int64),
    }
    cells = [("vertex", np.arange(n, dtype=np.int64).reshape(-1, 1))]
    return meshio.Mesh(points, cells, point_data=point_data)


def _fluid_vorticity(sim: Simulation, order: npt.NDArray[np.intp]) -> npt.NDArray[np.float64]:
    """(N, 3) vorticity of the fluid particles in ``order``, zero for the others."""
    core = sim.core
    params = core.params()
    x = np.asarray(core.positions)[order]
    v = np.asarray(core.velocities)[order]
    rho = np.asarray(core.densities)[order]
    fluid = np.asarray(core.kinds)[order] == 0
    out = np.zeros((x.shape[0], 3))
    if fluid.any():
        omega = particle_vorticity(x[fluid], v[fluid], params["mass"] / rho[fluid],
                                   params["h"], params["kernel"])
        if core.dim == 2:
            out[fluid, 1] = omega
        else:
            out[fluid] = omega
    return out


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

    def continue_from(self, time: float) -> None:
        """Take over the snapshots an earlier run wrote here up to ``time`` [s] (a resumed run):
        later ones, from after its checkpoint, are dropped from the collection and their files
        overwritten as the run writes them again."""
        if not self.pvd_path.is_file():
            return
        root = ET.parse(self.pvd_path).getroot()
        self.entries = [
            (float(d.attrib["timestep"]), d.attrib["file"])
            for d in root.iter("DataSet") if float(d.attrib["timestep"]) <= time
        ]
        self._write_pvd()

    @property
    def pvd_path(self) -> Path:
        return self.directory / f"{self.prefix}.pvd"

    def write(self, sim: Simulation) -> Path:
        """Writes one snapshot of ``sim`` at its current time; returns the ``.vtu`` path."""
        name = f"{self.prefix}_{len(self.entries):05d}.vtu"
        path = self.directory / name
        with atomic_path(path, suffix=".vtu") as tmp:
            meshio.write(tmp, snapshot_mesh(sim), file_format="vtu", binary=True)
        self.entries.append((sim.time, name))
        self._write_pvd()
        return path

    def __call__(self, sim: Simulation) -> None:
        """Writes one snapshot (so a writer can be a :meth:`Simulation.run` callback)."""
        self.write(sim)

    def _write_pvd(self) -> None:
        root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
        collection = ET.SubElement(root, "Collection")
        for t, name in self.entries:
            ET.SubElement(
                collection, "DataSet", timestep=repr(float(t)), group="", part="0", file=name
            )
        with atomic_write(self.pvd_path, "wb") as f:
            ET.ElementTree(root).write(f, xml_declaration=True, encoding="utf-8")


class RunLog:
    """``log.jsonl``: the run's events, one JSON object per line, flushed as they happen (so a
    crashed or interrupted run keeps its log).

    Each line has ``event`` (``start``, ``sample``, ``snapshot``, ``end``, ...), ``wall_s`` (wall
    seconds since the log was opened) and the event's own fields (``t`` [s], ``steps``, ``dt``
    [s], ...).

    Args:
        path: the file (overwritten, or appended to with ``append``).
        append: add to an existing log (a resumed run).
    """

    def __init__(self, path: str | Path, append: bool = False) -> None:
        self.path = Path(path)
        self._file: TextIO | None = open(self.path, "a" if append else "w", encoding="utf-8")
        self._start = time.perf_counter()

    def write(self, event: str, **fields: Any) -> None:
        """Append one event."""
        if self._file is None:
            raise ValueError(f"{self.path}: the log is closed")
        record = {"event": event, "wall_s": round(time.perf_counter() - self._start, 6), **fields}
        with named_errors(self.path):
            self._file.write(json.dumps(json_ready(record), allow_nan=False) + "\n")
            self._file.flush()

    def sample(self, sim: Simulation, **fields: Any) -> None:
        """A ``sample`` event with the simulation's time, steps and last dt."""
        self.write("sample", t=sim.time, steps=sim.steps, dt=sim.dt, **fields)

    def close(self) -> None:
        if self._file is not None:
            file, self._file = self._file, None
            with named_errors(self.path):
                file.close()


class RunOutputs:
    """The files of one ``watersim run`` besides summary.json: ``log.jsonl`` always, particle
    snapshots (``snapshots/particles_NNNNN.vtu`` + ``snapshots/particles.pvd``) only when
    ``snapshot_every`` is given.

    Args:
        directory: the run's output folder (exists).
        snapshot_every: interval between snapshots [s] of simulated time, or None for none.
        resume_time: a resumed run's start [s]: the log is appended to and the snapshots up to
            that time are kept.
    """

    def __init__(self, directory: str | Path, snapshot_every: float | None,
                 resume_time: float | None = None) -> None:
        self.directory = Path(directory)
        self.snapshot_every = snapshot_every
        self.log = RunLog(self.directory / "log.jsonl", append=resume_time is not None)
        self.snapshots = (
            SnapshotWriter(self.directory / "snapshots") if snapshot_every is not None else None
        )
        if self.snapshots is not None and resume_time is not None:
            self.snapshots.continue_from(resume_time)

    def schedule(self) -> list[tuple[float, Callable[[Simulation], Any]]]:
        """The ``(interval, callback)`` pairs to add to :meth:`Simulation.run_schedule`."""
        if self.snapshots is None or self.snapshot_every is None:
            return []
        return [(self.snapshot_every, self._snapshot)]

    def _snapshot(self, sim: Simulation) -> None:
        assert self.snapshots is not None
        path = self.snapshots.write(sim)
        self.log.write("snapshot", t=sim.time, steps=sim.steps,
                       file=str(path.relative_to(self.directory)))

    def summary(self) -> dict[str, Any]:
        """What summary.json records about these files."""
        info: dict[str, Any] = {"log": "log.jsonl"}
        if self.snapshots is not None:
            info["snapshots"] = {
                "pvd": str(self.snapshots.pvd_path.relative_to(self.directory)),
                "every": self.snapshot_every,
                "count": len(self.snapshots.entries),
                "times": [t for t, _ in self.snapshots.entries],
            }
        return info

    def close(self) -> None:
        self.log.close()
