"""Closed triangle meshes for 3D bathymetry: reading (STL via meshio), checks, bed heights.

The core samples a closed, outward-oriented triangle mesh into wall particles
(``crates/sph-core/src/scene/geometry.rs``, ``Obstacle::Mesh``; parry's pseudo-normal inside
test). It only checks that the triangles index the vertices; a mesh with holes or flipped
triangles would give a wrong inside/outside test, silently. This module checks, in Python and
before anything is built, what the core assumes:

- the surface is closed: every edge borders exactly two triangles;
- the triangles are oriented consistently: the two triangles of an edge run along it in
  opposite directions (so each edge appears once in each direction);
- outward: the enclosed volume, ``sum v0 . (v1 x v2) / 6`` over the triangles (the divergence
  theorem), is positive;
- no degenerate triangle (repeated vertex or zero area).

It also answers the questions the flume's analysis asks of its bed (bed height under a point,
the bed profile along the centre line) by casting vertical rays on the mesh.
"""

from __future__ import annotations

import math
import os
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from ._core import SceneError
from .flume.checks import _finite_tuple

__all__ = [
    "check_closed_mesh",
    "check_triangle_count",
    "enclosed_volume",
    "merge_duplicate_vertices",
    "profile_along_line",
    "read_triangle_mesh",
    "surface_height",
]

_QUERY_BLOCK = 4_000_000
"""Largest block of (point, triangle) pairs of the vectorised ray casting (about 100 MB of
float64 temporaries)."""


def read_triangle_mesh(path: str | os.PathLike[str], field: str = "path"
                       ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """The vertices (n, 3) and triangles (m, 3) of a surface mesh file read with meshio.

    STL, ASCII or binary (meshio tells them apart by the file size), or any format meshio reads
    with triangle cells (OBJ, PLY, OFF, VTK, ...). Only triangles are accepted: a file with
    other surface cells (quads, polygons) must be triangulated first.

    Raises:
        SceneError: ``field: reason`` when the file is missing, unreadable or holds no triangles.
    """
    import meshio  # imported here: only meshes need it, and it takes a while to import

    p = Path(path)
    if not p.is_file():
        raise SceneError(f"{field}: no such file {str(p)!r}")
    fmt = "stl" if p.suffix.lower() == ".stl" else None
    if fmt == "stl":
        check_triangle_count(stl_triangle_count(p), field, str(p))
    try:
        with warnings.catch_warnings():
            # meshio first reads an STL's triangle count as binary, which overflows (a
            # RuntimeWarning) on an ASCII file before it falls back to reading it as text
            warnings.simplefilter("ignore", RuntimeWarning)
            mesh = meshio.read(p, file_format=fmt)
    except (Exception, SystemExit) as exc:  # meshio raises ReadError, ValueError, IndexError...
        # on bad files, and calls sys.exit on some malformed .vtu ones
        reason = str(exc) or type(exc).__name__
        raise SceneError(f"{field}: cannot read {str(p)!r} as a triangle mesh: {reason}") from None
    kinds = [block.type for block in mesh.cells]
    others = sorted({k for k in kinds if k not in ("triangle", "vertex", "line")})
    if others:
        raise SceneError(f"{field}: {str(p)!r} holds {', '.join(others)} cells; only triangles "
                         "are accepted (triangulate the surface first)")
    blocks = [np.asarray(b.data, dtype=np.int64) for b in mesh.cells if b.type == "triangle"]
    triangles = np.concatenate(blocks) if blocks else np.zeros((0, 3), dtype=np.int64)
    if triangles.shape[0] == 0:
        raise SceneError(f"{field}: {str(p)!r} holds no triangles")
    check_triangle_count(triangles.shape[0], field, str(p))
    points = np.asarray(mesh.points, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 3:
        raise SceneError(f"{field}: {str(p)!r} has {points.shape[-1]}-D points; a bed mesh "
                         "needs x, y, z")
    return points, triangles


MESH_BYTES_PER_TRIANGLE = 2500
"""Peak memory a mesh beach costs per triangle from its file to the built simulation [bytes]:
meshio's arrays, the merged and checked mesh, its JSON for the core and the core's copy
(measured: see docs/stability.md, "Memory of a run")."""


def max_triangles() -> int:
    """The most triangles a mesh may have: the memory available (80 % of ``MemAvailable``, as
    the core's check) over :data:`MESH_BYTES_PER_TRIANGLE`."""
    from .run_memory import available_memory_bytes

    available = available_memory_bytes({})
    return int(available // MESH_BYTES_PER_TRIANGLE) if math.isfinite(available) else 2**62


def check_triangle_count(count: int, field: str, source: str) -> None:
    """Refuses a mesh of more triangles than :func:`max_triangles`.

    Raises:
        SceneError: ``field: reason`` with the count and the limit.
    """
    limit = max_triangles()
    if count > limit:
        raise SceneError(
            f"{field}: {source!r} holds {count} triangles; a mesh beach needs about "
            f"{MESH_BYTES_PER_TRIANGLE} bytes a triangle to read, check and build, so at most "
            f"{limit} fit in the memory available: simplify (decimate) the mesh")


def stl_triangle_count(path: Path) -> int:
    """The triangles of an STL file, read without loading it: a binary file's header count
    (its size is then 84 + 50 bytes a triangle), else the ``endfacet`` lines of an ASCII one,
    counted in 16 MiB pieces."""
    size = path.stat().st_size
    with open(path, "rb") as f:
        head = f.read(84)
        if len(head) == 84:
            n = int(np.frombuffer(head[80:84], dtype="<u4")[0])
            if size == 84 + 50 * n:
                return n
        f.seek(0)
        count, tail = 0, b""
        while piece := f.read(1 << 24):
            text = tail + piece
            count += text.count(b"endfacet")
            tail = text[-7:]  # a keyword cut between two pieces is counted in the next
        return count


def merge_duplicate_vertices(points: npt.ArrayLike, triangles: npt.ArrayLike
                             ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """The mesh with exactly repeated vertices merged (a "triangle soup", where each triangle
    has its own copies of its corners, becomes an indexed mesh); unused vertices dropped."""
    pts = np.asarray(points, dtype=np.float64)
    tri = np.asarray(triangles, dtype=np.int64)
    used = np.unique(tri)
    unique, inverse = np.unique(pts[used], axis=0, return_inverse=True)
    remap = np.zeros(pts.shape[0], dtype=np.int64)
    remap[used] = np.asarray(inverse).reshape(-1)
    return unique, remap[tri]


def enclosed_volume(points: npt.ArrayLike, triangles: npt.ArrayLike) -> float:
    """Signed volume enclosed by a closed triangle mesh [m^3]: ``sum v0 . (v1 x v2) / 6``
    (divergence theorem); positive when the triangles face outward (counter-clockwise seen
    from outside)."""
    pts = np.asarray(points, dtype=np.float64)
    tri = np.asarray(triangles, dtype=np.int64)
    v0, v1, v2 = pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]]
    return float(np.sum(np.einsum("ij,ij->i", v0, np.cross(v1, v2))) / 6.0)


def _fmt(p: npt.NDArray[np.float64]) -> str:
    return "(" + ", ".join(f"{v:.6g}" for v in p) + ")"


def check_closed_mesh(points: npt.NDArray[np.float64], triangles: npt.NDArray[np.int64],
                      field: str) -> float:
    """Checks that an indexed mesh (duplicate vertices merged) is a closed, consistently and
    outward oriented surface without degenerate triangles; returns its enclosed volume [m^3].

    Raises:
        SceneError: ``field: reason`` naming the first defect and where it is.
    """
    pts, tri = points, triangles
    if tri.ndim != 2 or tri.shape[1] != 3 or tri.shape[0] == 0:
        raise SceneError(f"{field}: needs at least one triangle of 3 vertex indices")
    if pts.ndim != 2 or pts.shape[1] != 3:
        raise SceneError(f"{field}: vertices need 3 coordinates (x, y, z), got shape {pts.shape}")
    if tri.min() < 0 or tri.max() >= pts.shape[0]:
        j = int(np.flatnonzero((tri < 0).any(axis=1) | (tri >= pts.shape[0]).any(axis=1))[0])
        raise SceneError(f"{field}: triangle {j} {tri[j].tolist()} indexes outside the "
                         f"{pts.shape[0]} vertices")
    repeated = (tri[:, 0] == tri[:, 1]) | (tri[:, 1] == tri[:, 2]) | (tri[:, 0] == tri[:, 2])
    v0, v1, v2 = pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]]
    area2 = np.linalg.norm(np.cross(v1 - v0, v2 - v0), axis=1)
    extent = float(np.max(np.ptp(pts, axis=0))) or 1.0
    flat = repeated | (area2 <= 1e-12 * extent**2)
    if np.any(flat):
        j = int(np.flatnonzero(flat)[0])
        raise SceneError(f"{field}: triangle {j} at {_fmt(v0[j])} is degenerate (zero area); "
                         f"{int(flat.sum())} such triangles")
    n = np.int64(pts.shape[0])
    edges = tri[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    keys = edges[:, 0] * n + edges[:, 1]
    unique, first, counts = np.unique(keys, return_index=True, return_counts=True)
    if np.any(counts > 1):
        e = edges[first[np.argmax(counts > 1)]]
        raise SceneError(
            f"{field}: the edge {_fmt(pts[e[0]])} -> {_fmt(pts[e[1]])} is used twice in the same "
            "direction: the triangles are not oriented consistently (a neighbour is flipped) or "
            "more than two triangles share it"
        )
    reverse = edges[:, 1] * n + edges[:, 0]
    open_edges = ~np.isin(reverse, unique)
    if np.any(open_edges):
        e = edges[np.argmax(open_edges)]
        raise SceneError(
            f"{field}: not a closed surface: {int(open_edges.sum())} edges border a single "
            f"triangle (e.g. {_fmt(pts[e[0]])} -> {_fmt(pts[e[1]])}); the solid must be "
            "watertight"
        )
    volume = enclosed_volume(pts, tri)
    if volume <= 0.0:
        raise SceneError(
            f"{field}: the triangles face inward (enclosed volume {volume:.4g} m^3 < 0): "
            "reverse the vertex order of every triangle"
        )
    return volume


@dataclass(frozen=True)
class ClosedMesh:
    """A closed, outward-oriented triangle mesh read from a file or given as arrays, checked
    (:func:`check_closed_mesh`), in scene coordinates (``scale`` and ``offset`` applied,
    duplicate vertices merged): what a mesh beach and a mesh body hold.

    Attributes:
        offset: the offset given, as 3 floats.
        path: the file, or None.
        vertices, triangles: the arrays given, as plain tuples (a frozen, comparable builder
            that a scene file can write), or None with a file.
        points: (n, 3) vertices [m]; faces: (m, 3) triangles; volume: enclosed [m^3].
    """

    offset: tuple[float, float, float]
    path: str | None
    vertices: tuple[tuple[float, ...], ...] | None
    triangles: tuple[tuple[int, ...], ...] | None
    points: npt.NDArray[np.float64]
    faces: npt.NDArray[np.int64]
    volume: float

    @staticmethod
    def load(prefix: str, path: Any, vertices: Any, triangles: Any, scale: float,
             offset: Any) -> ClosedMesh:
        """The mesh of ``path`` or of ``vertices`` and ``triangles``; refusals name
        ``prefix.field`` (``beach.path``, ``body.offset``)."""
        off = _finite_tuple(f"{prefix}.offset", offset, 3)
        if len(off) != 3:
            raise SceneError(f"{prefix}.offset: needs 3 values (x, y, z), got {len(off)}")
        if (path is None) == (vertices is None and triangles is None):
            raise SceneError(f"{prefix}.path: give either a mesh file (path) or vertices and "
                             "triangles, not both nor neither")
        if path is not None:
            if not isinstance(path, (str, os.PathLike)) or not str(path).strip():
                raise SceneError(f"{prefix}.path: expected a file name, got {path!r}")
            path = os.fspath(path)
            raw, tri = read_triangle_mesh(path, f"{prefix}.path")
        else:
            if vertices is None or triangles is None:
                missing = "triangles" if triangles is None else "vertices"
                raise SceneError(f"{prefix}.{missing}: vertices and triangles go together")
            raw = _rows(f"{prefix}.vertices", vertices)
            tri_f = _rows(f"{prefix}.triangles", triangles)
            if not np.all(np.isfinite(raw)):
                raise SceneError(f"{prefix}.vertices: values must be finite")
            if not np.all(tri_f == np.round(tri_f)):
                raise SceneError(f"{prefix}.triangles: vertex indices must be whole numbers")
            tri = tri_f.astype(np.int64)
            check_triangle_count(tri.shape[0], f"{prefix}.triangles", "the triangles given")
            if tri.min() < 0 or tri.max() >= raw.shape[0]:
                raise SceneError(f"{prefix}.triangles: indices must lie in [0, "
                                 f"{raw.shape[0] - 1}] (the vertices), got "
                                 f"{int(tri.min())}..{int(tri.max())}")
            vertices = tuple(tuple(float(v) for v in row) for row in raw)
            triangles = tuple(tuple(int(i) for i in row) for row in tri)
        pts, faces = merge_duplicate_vertices(raw * scale + np.asarray(off), tri)
        source = f"{prefix}.path" if path is not None else f"{prefix}.vertices"
        volume = check_closed_mesh(pts, faces, source)
        pts.setflags(write=False)
        faces.setflags(write=False)
        return ClosedMesh(off, path, vertices, triangles, pts, faces, volume)  # type: ignore[arg-type]


def _rows(name: str, values: Any) -> npt.NDArray[np.float64]:
    """``values`` as rows of 3 numbers, or SceneError naming ``name``."""
    try:
        arr: npt.NDArray[np.float64] = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise SceneError(f"{name}: expected rows of 3 numbers") from None
    if arr.ndim != 2 or arr.shape[1] != 3 or arr.shape[0] == 0:
        raise SceneError(f"{name}: expected rows of 3 numbers, got shape {arr.shape}")
    return arr


def surface_height(points: npt.NDArray[np.float64], triangles: npt.NDArray[np.int64],
                   x: npt.ArrayLike, y: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Highest z where the vertical line through each ``(x, y)`` meets the mesh [m]; NaN where
    it misses the mesh.

    For a closed mesh the highest crossing is on an upward-facing triangle, so only those are
    tested: a point is over a triangle when its barycentric coordinates in the triangle's
    horizontal projection are all >= 0 (edges included), and z there is the barycentric mix.
    Each point is tested only against the triangles whose horizontal bounding box (padded by
    far more than the edge tolerance) holds it, found in a uniform grid of those boxes
    (:class:`_BoxGrid`): the same tests, so the same heights, as testing every triangle, in
    time about proportional to points plus triangles instead of their product.
    """
    xq = np.atleast_1d(np.asarray(x, dtype=np.float64))
    yq = np.atleast_1d(np.asarray(y, dtype=np.float64))
    xq, yq = np.broadcast_arrays(xq, yq)
    shape = xq.shape
    xq, yq = xq.reshape(-1), yq.reshape(-1)
    v0, v1, v2 = points[triangles[:, 0]], points[triangles[:, 1]], points[triangles[:, 2]]
    # twice the signed area of each triangle's horizontal projection (> 0: facing up)
    nz = ((v1[:, 0] - v0[:, 0]) * (v2[:, 1] - v0[:, 1])
          - (v1[:, 1] - v0[:, 1]) * (v2[:, 0] - v0[:, 0]))
    scale = float(np.max(np.ptp(points, axis=0))) or 1.0
    up = nz > 1e-12 * scale**2
    a, b, c, det = v0[up], v1[up], v2[up], nz[up]
    out = np.full(xq.shape, np.nan)
    if a.shape[0] == 0 or xq.size == 0:
        return out.reshape(shape)
    tol = 1e-9 * scale
    grid = _BoxGrid(a, b, c, pad=1e-6 * scale)
    point_ids, tri_ids = grid.candidates(xq, yq)
    if point_ids.size == 0:
        return out.reshape(shape)
    top = np.full(xq.shape, -np.inf)
    for s in range(0, point_ids.size, _QUERY_BLOCK):
        i, t = point_ids[s:s + _QUERY_BLOCK], tri_ids[s:s + _QUERY_BLOCK]
        px, py = xq[i], yq[i]
        ta, tb, tc, tdet = a[t], b[t], c[t], det[t]
        # barycentric weights of the projection (2D cross products over twice the area)
        w0 = ((tb[:, 0] - px) * (tc[:, 1] - py) - (tb[:, 1] - py) * (tc[:, 0] - px)) / tdet
        w1 = ((tc[:, 0] - px) * (ta[:, 1] - py) - (tc[:, 1] - py) * (ta[:, 0] - px)) / tdet
        w2 = 1.0 - w0 - w1
        # a tolerance in length units: points on a shared edge belong to both triangles
        lengths = np.sqrt(tdet)
        inside = (w0 * lengths >= -tol) & (w1 * lengths >= -tol) & (w2 * lengths >= -tol)
        z = w0 * ta[:, 2] + w1 * tb[:, 2] + w2 * tc[:, 2]
        np.maximum.at(top, i, np.where(inside, z, -np.inf))
    hit = np.isfinite(top)
    out[hit] = top[hit]
    return out.reshape(shape)


class _BoxGrid:
    """The horizontal bounding boxes of triangles in a uniform grid of cells: each cell lists
    the triangles whose (padded) box overlaps it, so the triangles over a point are among those
    of its cell. Cells are about the median box size (a triangle then lists itself in up to
    four cells), with at most four cells per triangle overall."""

    def __init__(self, a: npt.NDArray[np.float64], b: npt.NDArray[np.float64],
                 c: npt.NDArray[np.float64], pad: float) -> None:
        lo = np.minimum(np.minimum(a, b), c)[:, :2] - pad
        hi = np.maximum(np.maximum(a, b), c)[:, :2] + pad
        self.origin = lo.min(axis=0)
        span = np.maximum(hi.max(axis=0) - self.origin, pad)
        n_tri = lo.shape[0]
        cell = np.maximum(np.median(hi - lo, axis=0), np.sqrt(span[0] * span[1] / (4.0 * n_tri)))
        self.cell = np.minimum(cell, span)
        self.shape = np.maximum(np.ceil(span / self.cell).astype(np.int64), 1)
        first, last = self._cell_of(lo), self._cell_of(hi)
        across = last - first + 1
        counts = across[:, 0] * across[:, 1]
        tri = np.repeat(np.arange(n_tri), counts)
        k = np.arange(tri.size) - np.repeat(np.cumsum(counts) - counts, counts)
        cx = first[tri, 0] + k % across[tri, 0]
        cy = first[tri, 1] + k // across[tri, 0]
        key = cy * self.shape[0] + cx
        order = np.argsort(key, kind="stable")
        self.triangles = tri[order]
        self.starts = np.searchsorted(key[order], np.arange(self.shape[0] * self.shape[1] + 1))

    def _cell_of(self, xy: npt.NDArray[np.float64]) -> npt.NDArray[np.int64]:
        ij = np.floor((xy - self.origin) / self.cell).astype(np.int64)
        return np.clip(ij, 0, self.shape - 1)

    def candidates(self, x: npt.NDArray[np.float64], y: npt.NDArray[np.float64]
                   ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
        """``(point, triangle)`` index pairs: every triangle listed in each point's cell (none
        for a point outside the grid), grouped by point."""
        xy = np.stack([x, y], axis=1)
        ij = np.floor((xy - self.origin) / self.cell)
        outside = np.any((ij < 0) | (ij >= self.shape), axis=1) | ~np.all(np.isfinite(xy), axis=1)
        ij = np.where(outside[:, None], 0, ij).astype(np.int64)
        key = ij[:, 1] * self.shape[0] + ij[:, 0]
        begin = self.starts[key]
        counts = np.where(outside, 0, self.starts[key + 1] - begin)
        points = np.repeat(np.arange(x.size), counts)
        k = np.arange(points.size) - np.repeat(np.cumsum(counts) - counts, counts)
        return points, self.triangles[begin[points] + k]


def profile_along_line(points: npt.NDArray[np.float64], triangles: npt.NDArray[np.int64],
                       y: float, x_min: float, x_max: float
                       ) -> tuple[list[float], list[float]]:
    """The bed profile ``(x, z)`` along the line ``y`` from ``x_min`` to ``x_max``: the mesh's
    top surface there (0, the flume floor, where the line misses the mesh), as a polyline.

    The top surface along a line is piecewise linear with corners where the line crosses a
    triangle edge, and jumps at vertical faces; it is evaluated at each crossing, or just
    before and after it (1e-9 of the span apart) where it jumps. Collinear
    vertices are dropped; leading and trailing floor stretches keep one point each.
    """
    p, t = points, triangles
    edges = t[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    ya, yb = p[edges[:, 0], 1], p[edges[:, 1], 1]
    xa, xb = p[edges[:, 0], 0], p[edges[:, 1], 0]
    crossing = ((ya - y) * (yb - y) <= 0.0) & (ya != yb)
    frac = (y - ya[crossing]) / (yb[crossing] - ya[crossing])
    xs = xa[crossing] + frac * (xb[crossing] - xa[crossing])
    on_line = p[np.abs(p[:, 1] - y) <= 1e-12 * max(1.0, abs(y)), 0]
    breaks = np.unique(np.concatenate([xs, on_line]))
    span = x_max - x_min
    eps = 1e-9 * span
    breaks = breaks[(breaks > x_min + eps) & (breaks < x_max - eps)]

    def height(xv: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        z = surface_height(p, t, xv, np.full_like(xv, y))
        return np.maximum(np.nan_to_num(z, nan=0.0), 0.0)

    z_at, z_before, z_after = height(breaks), height(breaks - eps), height(breaks + eps)
    jump = np.abs(z_after - z_before) > 1e-6 * span
    xq = np.concatenate([[x_min, x_max], breaks[~jump], breaks[jump] - eps, breaks[jump] + eps])
    zq = np.concatenate([height(np.array([x_min, x_max])), z_at[~jump], z_before[jump],
                         z_after[jump]])
    order = np.argsort(xq, kind="stable")
    xq, zq = xq[order], zq[order]
    keep = np.ones(xq.size, dtype=bool)
    for i in range(1, xq.size - 1):
        # drop a vertex on the straight line between its neighbours
        slope_in = (zq[i] - zq[i - 1]) / (xq[i] - xq[i - 1])
        slope_out = (zq[i + 1] - zq[i]) / (xq[i + 1] - xq[i])
        if abs(slope_in - slope_out) <= 1e-6 * (1.0 + abs(slope_in)):
            keep[i] = False
    xk, zk = xq[keep], zq[keep]
    wet = np.flatnonzero(zk > 0.0)
    if wet.size == 0:
        return [], []
    lo, hi = max(wet[0] - 1, 0), min(wet[-1] + 1, xk.size - 1)
    return [float(v) for v in xk[lo:hi + 1]], [float(v) for v in zk[lo:hi + 1]]
