"""Bathymetry from a triangle mesh (STL) in a 3D flume: reading, checks, and the particles the
core samples from it."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from typing import Any

import meshio
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import watersim as ws
from watersim import SceneError
from watersim import scenefile as sf
from watersim.meshbed import profile_along_line, surface_height

ROOT = Path(__file__).resolve().parents[1]

# a small flume: 1.2 m long, 0.2 m wide, 0.15 m deep, dp = 0.05 m (about 6,000 particles)
L, W, D, DP = 1.2, 0.2, 0.15, 0.05
TOE, SLOPE = 0.5, 0.25 / 0.7


def _example_module() -> Any:
    spec = importlib.util.spec_from_file_location("mesh_beach", ROOT / "examples" / "mesh_beach.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["mesh_beach"] = module
    spec.loader.exec_module(module)
    return module


WEDGE_V, WEDGE_T = _example_module().plane_beach_mesh(TOE, SLOPE, L, W)


def _box(x0: float, x1: float, y0: float, y1: float, z0: float, z1: float
         ) -> tuple[np.ndarray, np.ndarray]:
    """A closed, outward-oriented box (the core's own test mesh)."""
    v = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]])
    t = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                  [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
    return v, t


def _write(path: Path, v: np.ndarray, t: np.ndarray, binary: bool = False) -> Path:
    meshio.write_points_cells(path, v, [("triangle", t)], file_format="stl", binary=binary)
    return path


def _flume(beach: Any, **kw: Any) -> ws.Flume:
    return ws.Flume(length=kw.pop("length", L), depth=D, width=kw.pop("width", W), height=0.3,
                    beach=beach, **kw)


def _sim(beach: Any) -> ws.FlumeSimulation:
    return _flume(beach).simulation(ws.RegularWave(height=0.03, period=1.0),
                                    paddle=ws.Piston(order=1), dp=DP, runup=False)


def _sorted_rows(a: np.ndarray) -> np.ndarray:
    return a[np.lexsort(a.T[::-1])]


@pytest.mark.parametrize("binary", [False, True], ids=["ascii", "binary"])
def test_stl_beach_particles_lie_on_the_mesh_surface(tmp_path: Path, binary: bool) -> None:
    path = _write(tmp_path / "wedge.stl", WEDGE_V, WEDGE_T, binary)
    beach = ws.MeshBeach(path=str(path))
    assert beach.faces.shape == (8, 3) and beach.points.shape == (6, 3)
    volume = 0.5 * (L - TOE) ** 2 * SLOPE * W
    assert beach.volume == pytest.approx(volume, rel=1e-6)
    sim = _sim(beach)
    pos, kinds = np.asarray(sim.positions), np.asarray(sim.kinds)
    thickness = sim.params()["boundary_layers"] * DP
    normal = np.array([-SLOPE, 0.0, 1.0]) / np.hypot(1.0, SLOPE)
    height = lambda p: (p - np.array([TOE, 0.0, 0.0])) @ normal  # noqa: E731 - above the slope
    # wall particles inside the tank (not its shell nor the paddle) are the bed's: all of them
    # inside the wedge, within the wall thickness of its sloping face
    inner = (kinds == 1) & np.all((pos > 0.0) & (pos < [L, W, 1.0]), axis=1)
    bed = pos[inner]
    assert bed.shape[0] > 50
    assert np.all(height(bed) < 0.0) and np.all(height(bed) >= -thickness - 1e-9)
    assert np.all(bed[:, 0] > TOE)
    # and they cover the slope: every lattice column over it has its top bed particle within
    # one dp (measured along the normal) under the surface
    for x in np.unique(np.round(bed[:, 0], 9)):
        for y in np.unique(np.round(bed[:, 1], 9)):
            column = bed[(np.abs(bed[:, 0] - x) < 1e-9) & (np.abs(bed[:, 1] - y) < 1e-9)]
            assert column.size and height(column).max() > -DP, (x, y)
    # the water fills every lattice site above the bed (it keeps the geometry's volume)
    assert np.min(height(sim.fluid_positions())) >= -1e-9
    # the mesh of a plane beach gives exactly the particles of that PlaneBeach
    plane = _sim(ws.PlaneBeach(toe=TOE, slope=SLOPE))
    plane_pos = np.asarray(plane.positions).copy()
    assert np.array_equal(_sorted_rows(pos.copy()), _sorted_rows(plane_pos))
    sim.step(3)
    assert sim.steps == 3 and np.all(np.isfinite(sim.positions))


def test_bed_profile_shoreline_and_gauge_depths_come_from_the_mesh() -> None:
    sc = _flume(ws.MeshBeach(vertices=WEDGE_V, triangles=WEDGE_T)).scene(
        ws.RegularWave(height=0.03, period=1.0), dp=DP,
        gauges=[ws.ElevationGauge(0.3), ws.ElevationGauge(0.9, y=0.05)])
    px, pz = sc.bed_profile
    assert px == pytest.approx([TOE, L]) and pz == pytest.approx([0.0, SLOPE * (L - TOE)])
    assert sc.shoreline == pytest.approx(TOE + D / SLOPE)
    assert sc.beach_slope == pytest.approx(SLOPE)
    assert sc.still_depth([0.3, 0.9], [0.1, 0.05]) == pytest.approx([D, D - SLOPE * 0.4])
    # the automatic run-up gauge is laid on the centre line over the slope
    runup = sc.runup_gauge
    assert runup is not None and runup.start is not None and runup.start[1] == pytest.approx(W / 2)
    # a box: the profile jumps at its vertical faces; the bed under a point off it is the floor
    v, t = _box(0.6, 0.9, 0.05, 0.15, 0.0, 0.1)
    box = ws.MeshBeach(vertices=v, triangles=t)
    bx, bz = box.profile(L, 0.3, y=0.1)
    assert bx == pytest.approx([0.6, 0.6, 0.9, 0.9], abs=1e-6) and bz == pytest.approx(
        [0.0, 0.1, 0.1, 0.0])
    assert box.profile(L, 0.3, y=0.18) == ([], [])
    assert box.bed([0.7, 0.7], [0.1, 0.18]) == pytest.approx([0.1, 0.0])
    z = surface_height(box.points, box.faces, [0.75, 2.0], [0.1, 0.1])
    assert z[0] == pytest.approx(0.1) and np.isnan(z[1])
    assert profile_along_line(box.points, box.faces, 0.1, 0.0, L)[0][0] == pytest.approx(0.6)


def test_scene_file_mesh_beach_is_read_next_to_the_file(tmp_path: Path) -> None:
    _write(tmp_path / "wedge.stl", WEDGE_V, WEDGE_T)
    text = f"""
type = "flume"
dp = {DP}
[flume]
length = {L}
depth = {D}
width = {W}
height = 0.3
[flume.beach]
type = "mesh"
path = "wedge.stl"
[wave]
type = "regular"
height = 0.03
period = 1.0
"""
    (tmp_path / "scene.toml").write_text(text)
    scene = sf.load(tmp_path / "scene.toml")
    beach = scene.builder.flume.beach  # type: ignore[attr-defined]
    assert isinstance(beach, ws.MeshBeach) and Path(beach.path).parent == tmp_path
    # written back and read again: the same builder
    assert sf.loads(sf.dumps(scene.builder)).builder == scene.builder
    # --set on the mesh's fields is checked like the file, naming the key
    moved = sf.load(tmp_path / "scene.toml", ["flume.beach.offset=[-0.1, 0.0, 0.0]"])
    assert moved.builder.flume.beach.bounds[0][0] == pytest.approx(TOE - 0.1)  # type: ignore
    with pytest.raises(SceneError, match=r"flume\.beach\.path: the mesh spans x"):
        sf.load(tmp_path / "scene.toml", ["flume.beach.offset=[1.0, 0.0, 0.0]"])
    with pytest.raises(SceneError, match=r"flume\.beach\.scale: must be positive"):
        sf.load(tmp_path / "scene.toml", ["flume.beach.scale=-1"])
    with pytest.raises(SceneError, match=r"flume\.beach\.path: no such file"):
        sf.load(tmp_path / "scene.toml", ["flume.beach.path=other.stl"])


def _flip(t: np.ndarray, rows: slice | list[int]) -> np.ndarray:
    out = t.copy()
    out[rows] = out[rows][:, ::-1]
    return out


@pytest.mark.parametrize(
    ("make", "field", "reason"),
    [
        (lambda p: ws.MeshBeach(path=str(p / "missing.stl")), "beach.path", "no such file"),
        (lambda p: ws.MeshBeach(path=str(p / "junk.stl")), "beach.path", "cannot read"),
        (lambda p: ws.MeshBeach(path=str(p / "quads.vtu")), "beach.path", "quad cells"),
        (lambda p: ws.MeshBeach(), "beach.path", "either a mesh file"),
        (lambda p: ws.MeshBeach(path=str(p / "w.stl"), vertices=WEDGE_V, triangles=WEDGE_T),
         "beach.path", "not both"),
        (lambda p: ws.MeshBeach(vertices=WEDGE_V), "beach.triangles", "go together"),
        (lambda p: ws.MeshBeach(vertices=WEDGE_V[:, :2], triangles=WEDGE_T), "beach.vertices",
         "rows of 3"),
        (lambda p: ws.MeshBeach(vertices=WEDGE_V, triangles=WEDGE_T + 3), "beach.triangles",
         "indices must lie in"),
        (lambda p: ws.MeshBeach(vertices=WEDGE_V, triangles=WEDGE_T[:-1]), "beach.vertices",
         "not a closed surface"),
        (lambda p: ws.MeshBeach(vertices=WEDGE_V, triangles=_flip(WEDGE_T, [0])),
         "beach.vertices", "not oriented consistently"),
        (lambda p: ws.MeshBeach(vertices=WEDGE_V, triangles=_flip(WEDGE_T, slice(None))),
         "beach.vertices", "face inward"),
        (lambda p: ws.MeshBeach(path=str(p / "inward.stl")), "beach.path", "face inward"),
        (lambda p: ws.MeshBeach(vertices=np.vstack([WEDGE_V, WEDGE_V[:1]]),
                                triangles=np.vstack([WEDGE_T, [[0, 6, 1]]])),
         "beach.vertices", "degenerate"),
        (lambda p: ws.MeshBeach(vertices=WEDGE_V, triangles=WEDGE_T, scale=0.0), "beach.scale",
         "must be positive"),
        (lambda p: ws.MeshBeach(vertices=WEDGE_V, triangles=WEDGE_T, offset=(0.0, 1.0)),
         "beach.offset", "3 values"),
        (lambda p: ws.Flume(length=L, depth=D, beach=ws.MeshBeach(path=str(p / "w.stl"))),
         "beach", "needs a 3D flume"),
        (lambda p: _flume(ws.MeshBeach(path=str(p / "w.stl"), offset=(0.2, 0.0, 0.0))),
         "beach.path", "spans x = [0.7, 1.4]"),
        (lambda p: _flume(ws.MeshBeach(path=str(p / "w.stl")), width=0.1), "beach.path",
         "spans y"),
        (lambda p: _flume(ws.MeshBeach(vertices=WEDGE_V, triangles=WEDGE_T,
                                       offset=(0.0, 0.0, -0.01))), "beach.vertices", "spans z"),
        (lambda p: _flume(ws.MeshBeach(
            **dict(zip(("vertices", "triangles"), _box(0.6, 0.9, 0.05, 0.15, 0.0, 0.35),
                       strict=True)))),
         "beach.vertices", "spans z = [0, 0.35]"),
        (lambda p: _flume(ws.MeshBeach(vertices=WEDGE_V, triangles=WEDGE_T,
                                       offset=(-0.48, 0.0, 0.0))).scene(
            ws.RegularWave(height=0.03, period=1.0), dp=DP), "beach", "paddle's reach"),
    ],
)
def test_bad_meshes_are_refused_naming_the_field(tmp_path: Path, make: Any, field: str,
                                                  reason: str) -> None:
    _write(tmp_path / "w.stl", WEDGE_V, WEDGE_T)
    _write(tmp_path / "inward.stl", WEDGE_V, _flip(WEDGE_T, slice(None)))
    (tmp_path / "junk.stl").write_text("solid x\nfacet normal 0 0 1\n this is not an STL\n")
    meshio.write_points_cells(tmp_path / "quads.vtu", WEDGE_V[:4], [("quad", [[0, 1, 2, 3]])])
    with pytest.raises(SceneError) as info:
        make(tmp_path)
    message = str(info.value)
    assert message.startswith(f"{field}: ") and reason in message, message


def _heights_by_testing_every_triangle(points: np.ndarray, triangles: np.ndarray,
                                       x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The oracle: every point against every upward-facing triangle, as surface_height did
    before its grid (the same arithmetic per pair)."""
    v0, v1, v2 = (points[triangles[:, k]] for k in range(3))
    nz = ((v1[:, 0] - v0[:, 0]) * (v2[:, 1] - v0[:, 1])
          - (v1[:, 1] - v0[:, 1]) * (v2[:, 0] - v0[:, 0]))
    scale = float(np.max(np.ptp(points, axis=0))) or 1.0
    up = nz > 1e-12 * scale**2
    a, b, c, det = v0[up], v1[up], v2[up], nz[up]
    px, py, tol = x[:, None], y[:, None], 1e-9 * scale
    w0 = ((b[:, 0] - px) * (c[:, 1] - py) - (b[:, 1] - py) * (c[:, 0] - px)) / det
    w1 = ((c[:, 0] - px) * (a[:, 1] - py) - (c[:, 1] - py) * (a[:, 0] - px)) / det
    w2 = 1.0 - w0 - w1
    lengths = np.sqrt(det)
    inside = (w0 * lengths >= -tol) & (w1 * lengths >= -tol) & (w2 * lengths >= -tol)
    top = np.max(np.where(inside, w0 * a[:, 2] + w1 * b[:, 2] + w2 * c[:, 2], -np.inf), axis=1)
    return np.where(np.isfinite(top), top, np.nan)


@settings(max_examples=25, deadline=None)
@given(nx=st.integers(2, 40), ny=st.integers(2, 12), seed=st.integers(0, 2**32 - 1))
def test_surface_height_matches_testing_every_triangle(nx: int, ny: int, seed: int) -> None:
    """The grid of triangle boxes finds exactly the heights of the brute-force test, at random
    points, on the mesh's vertices and edges, and outside it (a 1M-triangle bed's profile took
    minutes with the brute force: docs/stability.md)."""
    rng = np.random.default_rng(seed)
    length, width = 3.0, 0.5
    x = np.linspace(1.0, length, nx)
    y = np.linspace(0.0, width, ny)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    z = 0.05 + 0.1 * (gx - 1.0) + 0.02 * rng.random(gx.shape)
    top = np.stack([gx, gy, z], -1).reshape(-1, 3)
    bottom = top * np.array([1.0, 1.0, 0.0])
    points = np.concatenate([top, bottom])
    t = np.arange(nx * ny).reshape(nx, ny)
    q = t[:-1, :-1], t[1:, :-1], t[1:, 1:], t[:-1, 1:]
    tris = np.concatenate([np.stack([q[0], q[1], q[2]], -1).reshape(-1, 3),
                           np.stack([q[0], q[2], q[3]], -1).reshape(-1, 3)])
    tris = np.concatenate([tris, tris[:, ::-1] + nx * ny])  # the closed slab's bottom, facing down
    px = np.concatenate([rng.uniform(0.5, length + 0.5, 300), top[:, 0],
                         0.5 * (top[:-1, 0] + top[1:, 0])])
    py = np.concatenate([rng.uniform(-0.1, width + 0.1, 300), top[:, 1],
                         0.5 * (top[:-1, 1] + top[1:, 1])])
    got = surface_height(points, tris, px, py)
    want = _heights_by_testing_every_triangle(points, tris, px, py)
    assert np.array_equal(got, want, equal_nan=True)


@pytest.mark.parametrize("binary", [True, False])
def test_a_mesh_beyond_the_memory_is_refused_before_it_is_read(
        tmp_path: Path, binary: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    """The triangle count comes from the STL's header (binary) or its ``endfacet`` lines
    (ASCII) before meshio reads the file; the limit is the memory over the bytes a triangle
    costs (here made small)."""
    from watersim import meshbed

    path = _write(tmp_path / "bed.stl", WEDGE_V, WEDGE_T, binary=binary)
    assert meshbed.stl_triangle_count(path) == len(WEDGE_T)
    monkeypatch.setattr(meshbed, "max_triangles", lambda: len(WEDGE_T) - 1)

    def never(*_a: Any, **_k: Any) -> None:
        raise AssertionError("meshio read the file")

    monkeypatch.setattr(meshio, "read", never)
    with pytest.raises(SceneError, match=rf"beach.path: .* holds {len(WEDGE_T)} triangles"):
        ws.MeshBeach(path=str(path))
    with pytest.raises(SceneError, match="beach.triangles: .* holds"):
        ws.MeshBeach(vertices=WEDGE_V.tolist(), triangles=WEDGE_T.tolist())
