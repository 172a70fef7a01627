"""VTK snapshots read back with meshio: fields, counts, the .pvd collection."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import pytest

import watersim
from watersim.output import SnapshotWriter


@pytest.mark.parametrize("dim", [2, 3])
def test_snapshots_round_trip_through_meshio(tmp_path: Path, dim: int) -> None:
    extra = {"tank_width": 0.45} if dim == 3 else {}
    sim = watersim.DamBreak(
        dim=dim, dp=0.1 if dim == 2 else 0.15, width=0.6, height=0.9, tank_length=1.8,
        tank_height=1.2, **extra,
    ).build()
    writer = SnapshotWriter(tmp_path)
    writer.write(sim)
    sim.step(5)
    path = writer.write(sim)
    mesh = meshio.read(path)
    n = sim.n_particles
    assert mesh.points.shape == (n, 3)
    shapes = {"velocity": (n, 3), "vorticity": (n, 3), "density": (n,), "pressure": (n,),
              "kind": (n,), "id": (n,)}
    for field, shape in shapes.items():
        assert mesh.point_data[field].shape == shape, field
    order = np.argsort(np.asarray(sim.core.ids))
    assert np.array_equal(mesh.point_data["id"], np.asarray(sim.core.ids)[order])
    assert np.allclose(mesh.point_data["density"], np.asarray(sim.core.densities)[order])
    assert (mesh.point_data["kind"] == 0).sum() == sim.n_fluid
    up = np.asarray(sim.core.positions)[order][:, -1]
    assert np.allclose(mesh.points[:, 2], up), "z is up in both dimensions"
    if dim == 2:
        assert np.all(mesh.points[:, 1] == 0.0)
    pvd = ET.parse(writer.pvd_path).getroot()
    sets = pvd.find("Collection").findall("DataSet")
    assert [d.get("file") for d in sets] == ["particles_00000.vtu", "particles_00001.vtu"]
    assert float(sets[0].get("timestep")) == 0.0
    assert float(sets[1].get("timestep")) == pytest.approx(sim.time)
