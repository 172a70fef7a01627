"""Fixed solid bodies of a scene: one class per shape, each owning its schema, its checks and
its core obstacle (``to_core``).

Every body is one of the core's obstacles (``scene.obstacles``, an arm of ``Obstacle`` in
``crates/sph-core/src/scene/geometry.rs``), a parry shape with a signed distance that the core
samples into wall particles of the scene's wall model, ``layers`` deep inside its surface; fluid
particles inside a body are removed, and fluid that bodies close off from the open top is
refused when the particles are built. Coordinates are scene coordinates: (x, z) in 2D,
(x, y, z) in 3D, z up.

A body may carry a ``name``: a :class:`~watersim.ForceGauge` names the body it measures.
:class:`~watersim.Scene` and its presets (the flume too) take any of them in ``bodies``.
"""

from __future__ import annotations

import math
import typing
from dataclasses import dataclass
from typing import Any, ClassVar

from . import meshbed
from ._core import SceneError
from .checks import _positive
from .flume.checks import _TOL, _finite_tuple, _optional_name, _set

__all__ = ["BODY_TYPES", "Body", "Box", "Capsule", "Cylinder", "HalfSpace", "Mesh", "Polygon",
           "Sphere"]

RESOLVABLE_DP = 2.0
"""A body thinner than this many dp along any axis is not resolved by the particles."""


def _point(name: str, values: Any) -> tuple[float, ...]:
    """A point of 2 (x, z) or 3 (x, y, z) finite coordinates."""
    p = _finite_tuple(name, values, 2)
    if len(p) not in (2, 3):
        raise SceneError(f"{name}: needs 2 (x, z) or 3 (x, y, z) coordinates, got {len(p)}")
    return p


class _Body:
    """What every body tells its scene: its dimension, extent, checks and core obstacle."""

    TAG: ClassVar[str]
    """The body's ``type`` in a scene file and its ``shape`` in the core."""
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {}
    DIMS: ClassVar[tuple[int, ...]] = (2, 3)
    """The scene dimensions the shape exists in."""
    LOW: ClassVar[str]
    """The field a refusal of the body's low end names."""
    HIGH: ClassVar[str]
    """The field a refusal of the body's high end names."""

    name: str | None

    def _check_name(self) -> None:
        _optional_name("body.name", self.name)

    def dim(self) -> int | None:
        """The dimension its coordinates give (None for a shape whose data do not say)."""
        raise NotImplementedError

    def bounds(self) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
        """``(min, max)`` corners [m] of the bounding box; None for a half-space (which the
        tank clips)."""
        raise NotImplementedError

    def x_start(self) -> float | None:
        """Where the body begins along x [m] (None: everywhere, a half-space)."""
        box = self.bounds()
        return None if box is None else box[0][0]

    def thickness(self) -> dict[str, float]:
        """Each field's extent that must resolve into particles [m], by field name."""
        raise NotImplementedError

    def to_core(self) -> dict[str, Any]:
        """The core's obstacle JSON."""
        raise NotImplementedError

    def check_in(self, dim: int, lo: tuple[float, ...], hi: tuple[float, ...], dp: float,
                 label: str, symmetry_y_min: bool = False) -> None:
        """Refuse a body of the wrong dimension, outside the tank ``[lo, hi]`` (it may rise
        above the walls' top ``hi[-1]``: the top is open; and cross the wall y = ``lo[1]``
        where that is a plane of symmetry, ``symmetry_y_min``) or thinner than
        :data:`RESOLVABLE_DP` dp, naming ``label`` (``bodies[i]``) and the field."""
        if dim not in self.DIMS:
            raise SceneError(f"{label}: a {type(self).__name__} exists in "
                             f"{' or '.join(f'{d}D' for d in self.DIMS)} scenes only")
        own = self.dim()
        if own is not None and own != dim:
            raise SceneError(f"{label}.{self.LOW}: a {dim}D scene needs {dim} coordinates, "
                             f"got {own}")
        box = self.bounds()
        if box is not None:
            axes = "xz" if dim == 2 else "xyz"
            for k in range(dim):
                # the top is open: a body may rise above the walls
                high = k < dim - 1 and box[1][k] > hi[k] + _TOL
                crosses = k == 1 and symmetry_y_min and box[1][k] > lo[k] + _TOL
                low = box[0][k] < lo[k] - _TOL and not crosses
                if low or high:
                    hint = (" (it may cross the wall y = 0 when that is a plane of symmetry, "
                            "symmetry_y_min)" if low and k == 1 and dim == 3 else "")
                    raise SceneError(
                        f"{label}.{self.LOW if low else self.HIGH}: the body spans {axes[k]} = "
                        f"[{box[0][k]:.6g}, {box[1][k]:.6g}] m, outside the tank "
                        f"[{lo[k]:g}, {hi[k]:g}] m{hint}")
        for name, size in self.thickness().items():
            if size < RESOLVABLE_DP * dp * (1.0 - 1e-9):
                raise SceneError(f"{label}.{name}: the body is {size:.4g} m thick there, "
                                 f"thinner than {RESOLVABLE_DP:g} dp ({RESOLVABLE_DP * dp:.4g} m); "
                                 "a finer dp or a thicker body resolves it")


@dataclass(frozen=True)
class Box(_Body):
    """An axis-aligned solid box: a block, a caisson, a deck, a column of square section.

    Attributes:
        min, max: opposite corners [m], (x, z) in 2D, (x, y, z) in 3D. It may float (a
            submerged or emerging box) or stand on the floor.
        name: the body's name, which a :class:`~watersim.ForceGauge` gives as its body.
    """

    min: tuple[float, ...]
    max: tuple[float, ...]
    name: str | None = None

    TAG: ClassVar[str] = "box"
    LOW: ClassVar[str] = "min"
    HIGH: ClassVar[str] = "max"

    def __post_init__(self) -> None:
        self._check_name()
        lo, hi = _point("body.min", self.min), _point("body.max", self.max)
        if len(lo) != len(hi):
            raise SceneError("body.max: min and max need 2 (x, z) or 3 (x, y, z) values each")
        if any(b <= a for a, b in zip(lo, hi, strict=True)):
            raise SceneError(f"body.max: must be above min on every axis ({lo} -> {hi})")
        _set(self, "min", lo)
        _set(self, "max", hi)

    def dim(self) -> int | None:
        return len(self.min)

    def bounds(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return self.min, self.max

    def thickness(self) -> dict[str, float]:
        return {f"max[{k}]": hi - lo for k, (lo, hi) in enumerate(zip(self.min, self.max,
                                                                      strict=True))}

    def to_core(self) -> dict[str, Any]:
        return {"shape": "box", "min": list(self.min), "max": list(self.max)}


@dataclass(frozen=True)
class Sphere(_Body):
    """A ball; in 2D a disc, the section of a horizontal cylinder spanning the width.

    Attributes:
        centre: (x, z) or (x, y, z) [m].
        radius: [m].
        name: the body's name.
    """

    centre: tuple[float, ...]
    radius: float
    name: str | None = None

    TAG: ClassVar[str] = "sphere"
    LOW: ClassVar[str] = "centre"
    HIGH: ClassVar[str] = "centre"

    def __post_init__(self) -> None:
        self._check_name()
        _set(self, "centre", _point("body.centre", self.centre))
        _set(self, "radius", _positive("body.radius", self.radius))

    def dim(self) -> int | None:
        return len(self.centre)

    def bounds(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return (tuple(c - self.radius for c in self.centre),
                tuple(c + self.radius for c in self.centre))

    def thickness(self) -> dict[str, float]:
        return {"radius": 2.0 * self.radius}

    @property
    def volume(self) -> float:
        """Volume [m^3] (3D) or area [m^2] (2D: per unit width)."""
        r = self.radius
        return math.pi * r * r if len(self.centre) == 2 else 4.0 / 3.0 * math.pi * r**3

    def to_core(self) -> dict[str, Any]:
        return {"shape": "sphere", "centre": list(self.centre), "radius": self.radius}


@dataclass(frozen=True)
class _Segment(_Body):
    """A body around the segment ``a b`` with ``radius``."""

    a: tuple[float, ...]
    b: tuple[float, ...]
    radius: float
    name: str | None = None

    LOW: ClassVar[str] = "a"
    HIGH: ClassVar[str] = "b"

    def __post_init__(self) -> None:
        self._check_name()
        a, b = _point("body.a", self.a), _point("body.b", self.b)
        if len(a) != len(b):
            raise SceneError("body.b: a and b need the same number of coordinates")
        _set(self, "a", a)
        _set(self, "b", b)
        _set(self, "radius", _positive("body.radius", self.radius))

    def dim(self) -> int | None:
        return len(self.a)

    @property
    def length(self) -> float:
        """Length of the axis ``a b`` [m]."""
        return math.dist(self.a, self.b)

    def thickness(self) -> dict[str, float]:
        return {"radius": 2.0 * self.radius}

    def to_core(self) -> dict[str, Any]:
        return {"shape": self.TAG, "a": list(self.a), "b": list(self.b), "radius": self.radius}


@dataclass(frozen=True)
class Cylinder(_Segment):
    """A circular cylinder (3D): a pile, a column; its axis from the centre of one end, ``a``,
    to the other's, ``b`` (any direction).

    Attributes:
        a, b: (x, y, z) of the ends' centres [m], different.
        radius: [m].
        name: the body's name.
    """

    TAG: ClassVar[str] = "cylinder"
    DIMS: ClassVar[tuple[int, ...]] = (3,)

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.a == self.b:
            raise SceneError("body.b: the axis' ends a and b must differ")

    def bounds(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        # each end is a disc of `radius` normal to the axis n: along axis k it reaches
        # radius sqrt(1 - n_k^2) past the end's centre
        n = [(q - p) / self.length for p, q in zip(self.a, self.b, strict=True)]
        reach = [self.radius * math.sqrt(max(0.0, 1.0 - c * c)) for c in n]
        return (tuple(min(p, q) - r for p, q, r in zip(self.a, self.b, reach, strict=True)),
                tuple(max(p, q) + r for p, q, r in zip(self.a, self.b, reach, strict=True)))

    def thickness(self) -> dict[str, float]:
        return {"radius": 2.0 * self.radius, "b": self.length}

    @property
    def volume(self) -> float:
        """Volume [m^3]."""
        return math.pi * self.radius**2 * self.length


@dataclass(frozen=True)
class Capsule(_Segment):
    """The points within ``radius`` of the segment ``a b``: a pipe with round ends, a rounded
    beam (2D: a stadium).

    Attributes:
        a, b: the segment's ends [m] (equal: a sphere).
        radius: [m].
        name: the body's name.
    """

    TAG: ClassVar[str] = "capsule"

    def bounds(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return (tuple(min(p, q) - self.radius for p, q in zip(self.a, self.b, strict=True)),
                tuple(max(p, q) + self.radius for p, q in zip(self.a, self.b, strict=True)))

    @property
    def volume(self) -> float:
        """Volume [m^3] (3D) or area [m^2] (2D)."""
        r = self.radius
        if len(self.a) == 2:
            return math.pi * r * r + 2.0 * r * self.length
        return 4.0 / 3.0 * math.pi * r**3 + math.pi * r * r * self.length


@dataclass(frozen=True)
class Polygon(_Body):
    """A convex polygon (2D): a caisson's section, a trapezoidal breakwater, a block with a
    sloping face. For a concave outline, put several convex ones side by side.

    Attributes:
        vertices: (x, z) of its corners [m], at least 3, in either order around it.
        name: the body's name.
    """

    vertices: tuple[tuple[float, ...], ...]
    name: str | None = None

    TAG: ClassVar[str] = "polygon"
    DIMS: ClassVar[tuple[int, ...]] = (2,)
    LOW: ClassVar[str] = "vertices"
    HIGH: ClassVar[str] = "vertices"

    def __post_init__(self) -> None:
        self._check_name()
        try:
            rows = [tuple(v) for v in self.vertices]
        except TypeError:
            raise SceneError(f"body.vertices: expected a sequence of (x, z) points, got "
                             f"{self.vertices!r}") from None
        pts = tuple(_finite_tuple(f"body.vertices[{i}]", v, 2) for i, v in enumerate(rows))
        if len(pts) < 3 or any(len(p) != 2 for p in pts):
            raise SceneError("body.vertices: needs at least 3 points of 2 coordinates (x, z)")
        if len(set(pts)) != len(pts):
            raise SceneError("body.vertices: a vertex is repeated")
        # convex: every turn around the centroid has one sign, and it encloses an area
        cx = sum(p[0] for p in pts) / len(pts)
        cz = sum(p[1] for p in pts) / len(pts)
        ring = sorted(pts, key=lambda p: math.atan2(p[1] - cz, p[0] - cx))
        turns = [(b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
                 for a, b, c in zip(ring, ring[1:] + ring[:1], ring[2:] + ring[:2], strict=True)]
        scale = max(max(p[0] for p in pts) - min(p[0] for p in pts),
                    max(p[1] for p in pts) - min(p[1] for p in pts)) ** 2
        if min(turns) <= 1e-12 * scale:
            raise SceneError("body.vertices: the polygon is not convex (or has three vertices "
                             "on a line); split it into convex polygons")
        _set(self, "vertices", pts)

    def dim(self) -> int | None:
        return 2

    def bounds(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        xs = [p[0] for p in self.vertices]
        zs = [p[1] for p in self.vertices]
        return (min(xs), min(zs)), (max(xs), max(zs))

    def thickness(self) -> dict[str, float]:
        lo, hi = self.bounds()
        return {"vertices": min(hi[0] - lo[0], hi[1] - lo[1])}

    @property
    def volume(self) -> float:
        """Area [m^2] (per unit width)."""
        cx = sum(p[0] for p in self.vertices) / len(self.vertices)
        cz = sum(p[1] for p in self.vertices) / len(self.vertices)
        ring = sorted(self.vertices, key=lambda p: math.atan2(p[1] - cz, p[0] - cx))
        return 0.5 * abs(sum(a[0] * b[1] - b[0] * a[1]
                             for a, b in zip(ring, ring[1:] + ring[:1], strict=True)))

    def to_core(self) -> dict[str, Any]:
        return {"shape": "polygon", "vertices": [list(p) for p in self.vertices]}


@dataclass(frozen=True)
class HalfSpace(_Body):
    """Everything on one side of a plane (a line in 2D), clipped to the tank: a sloping
    bed, a plane beach.

    Attributes:
        point: a point of the plane [m].
        normal: the plane's normal, pointing out of the solid into the water (not necessarily
            of unit length).
        name: the body's name.
    """

    point: tuple[float, ...]
    normal: tuple[float, ...]
    name: str | None = None

    TAG: ClassVar[str] = "half_space"
    LOW: ClassVar[str] = "point"
    HIGH: ClassVar[str] = "point"

    def __post_init__(self) -> None:
        self._check_name()
        p, n = _point("body.point", self.point), _point("body.normal", self.normal)
        if len(p) != len(n):
            raise SceneError("body.normal: point and normal need the same number of values")
        if math.hypot(*n) < 1e-12:
            raise SceneError("body.normal: must not be the zero vector")
        _set(self, "point", p)
        _set(self, "normal", n)

    def dim(self) -> int | None:
        return len(self.point)

    def bounds(self) -> None:
        return None

    def thickness(self) -> dict[str, float]:
        return {}

    def to_core(self) -> dict[str, Any]:
        return {"shape": "plane", "point": list(self.point), "normal": list(self.normal)}


@dataclass(frozen=True)
class Mesh(_Body):
    """A closed triangle mesh (3D): any structure from an STL file (ASCII or binary, or any
    triangle mesh meshio reads) or from NumPy vertices and triangles. Checked when made: the
    file readable, exactly repeated vertices merged (an STL stores each triangle's corners),
    the surface closed and consistently oriented with its triangles facing outward (positive
    enclosed volume), no degenerate triangle.

    Attributes:
        path: the mesh file; in a scene file a relative path is from the scene file's folder.
        vertices: instead of ``path``: ``(n, 3)`` rows x, y, z (before ``scale`` and
            ``offset``).
        triangles: with ``vertices``: ``(m, 3)`` vertex indices, counter-clockwise seen from
            outside.
        scale: factor applied to the vertices [m per file unit], e.g. 0.001 for millimetres.
        offset: (x, y, z) added to the scaled vertices [m].
        name: the body's name.
    """

    path: str | None = None
    vertices: tuple[tuple[float, ...], ...] | None = None
    triangles: tuple[tuple[int, ...], ...] | None = None
    scale: float = 1.0
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    name: str | None = None

    TAG: ClassVar[str] = "mesh"
    DIMS: ClassVar[tuple[int, ...]] = (3,)
    LOW: ClassVar[str] = "offset"
    HIGH: ClassVar[str] = "offset"

    def __post_init__(self) -> None:
        self._check_name()
        _set(self, "scale", _positive("body.scale", self.scale))
        mesh = meshbed.ClosedMesh.load("body", self.path, self.vertices, self.triangles,
                                       self.scale, self.offset)
        for name in ("offset", "path", "vertices", "triangles"):
            _set(self, name, getattr(mesh, name))
        object.__setattr__(self, "_mesh", mesh)

    def dim(self) -> int | None:
        return 3

    @property
    def volume(self) -> float:
        """Volume enclosed [m^3]."""
        return float(self._mesh.volume)  # type: ignore[attr-defined]

    def bounds(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        pts = self._mesh.points  # type: ignore[attr-defined]
        return tuple(pts.min(axis=0).tolist()), tuple(pts.max(axis=0).tolist())

    def thickness(self) -> dict[str, float]:
        lo, hi = self.bounds()
        return {"scale": min(b - a for a, b in zip(lo, hi, strict=True))}

    def to_core(self) -> dict[str, Any]:
        mesh = self._mesh  # type: ignore[attr-defined]
        return {"shape": "mesh", "vertices": mesh.points.tolist(),
                "triangles": mesh.faces.tolist()}


Body = Box | Sphere | Cylinder | Capsule | Polygon | HalfSpace | Mesh
"""The bodies a :class:`~watersim.Scene` takes in its ``bodies``."""

BODY_TYPES: tuple[type[_Body], ...] = typing.get_args(Body)
