"""The numerical wave flume: a paddle, a beach or a damping zone, gauges, and their analysis.

::

    import watersim as ws

    flume = ws.Flume(length=17.0, depth=0.705, beach=ws.PlaneBeach(toe=4.0, slope=1 / 15))
    sim = flume.simulation(
        wave=ws.RegularWave(period=1.275, height=0.114), paddle=ws.Piston(order=2, ramp_periods=2),
        dp=0.01, gauges=[ws.ElevationGauge(x) for x in (4.0, 12.0, 13.5)], runup=True)
    sim.run(until=30.0)
    eta = sim.gauges.elevation          # (n_samples, n_gauges), metres above still water
    sim.write_gauges_csv("gauges.csv")
    report = sim.analyse()              # wave heights, breaking, run-up, reflection, harmonics

Coordinates (the same in every input and output):

- x runs along the flume from the paddle face at rest (x = 0) to the far wall (x = ``length``);
- z is up from the flume floor (z = 0), so the still-water level (SWL) is z = ``depth``;
- y runs across the flume, from 0 to ``width`` (3D only; the tank's side walls are at y = 0 and
  y = ``width``).

Gauge *positions* are in these coordinates; *elevations* (surface elevation eta, run-up) are
reported relative to the SWL, positive up, in metres.

What is built (the core's scene, see ``crates/sph-core/src/scene.rs``):

- the tank box ``[x_back, length] x [0, height]`` (``x [0, width]`` in 3D), where ``x_back < 0``
  leaves room behind the paddle for its ``boundary_layers`` plate and its largest backward
  excursion. ``x_back`` is a whole number of dp from x = 0, so the particle lattice (particles at
  ``(i + 1/2) dp`` from the tank corner) puts the first fluid column exactly dp/2 in front of
  the paddle face;
- water from the paddle to the far wall up to ``depth`` (minus whatever the beach occupies);
- the beach as a piecewise-linear bed profile (solid below it), a plane beach being the profile
  ``(toe, 0) -> (x_top, height)`` continued flat at the tank top; or, in 3D, a closed triangle
  mesh (:class:`MeshBeach`, from an STL file), passed to the core as a mesh obstacle;
- the paddle: a piston or a flap (hinged at ``hinge_z``), driven by a motion law whose
  coefficients come from :mod:`watersim.wave_theory` (Biesel transfer functions, Madsen's second
  order, spectral synthesis, Goring's solitary wave), or a tabulated displacement;
- an optional velocity damping zone at the far end (on by default in a flume without beach);
- the gauges, all sampled by the core at their own interval.

Wave validity (``wave_theory.check_wave``) is checked when a regular wave is built: a wave
beyond second-order theory or breaking at the paddle gives a
:class:`~watersim.wave_theory.WaveValidityWarning`, not an error. Bad input raises
:class:`~watersim.SceneError` naming the field (``depth``, ``beach.toe``, ``wave.height``,
``paddle.order``, ``gauges[2].x``, ...).
"""

from __future__ import annotations

import csv
import dataclasses
import functools
import itertools
import math
import os
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from . import analysis as an
from . import meshbed
from . import wave_theory as wt
from ._core import SceneError
from .scenes import SceneBuilder, _choice, _integer, _non_negative, _number, _positive
from .simulation import Simulation

__all__ = [
    "SURFACE_METHODS",
    "DampingZone",
    "ElevationGauge",
    "Flap",
    "Flume",
    "FlumeGauges",
    "FlumeScene",
    "FlumeSimulation",
    "IrregularWave",
    "MeshBeach",
    "Piston",
    "PlaneBeach",
    "ProfileBeach",
    "RegularWave",
    "RunupGauge",
    "SolitaryWave",
    "TabulatedMotion",
    "VelocityProbe",
    "VelocityWindow",
    "VelocityRecord",
    "analyse_flume",
    "elevation_gauges_between",
    "flap_height_to_stroke_hinged",
    "lattice_dp",
    "lattice_layers",
]

SURFACE_METHODS: tuple[str, ...] = ("kernel", "particle")
"""Free-surface methods of elevation and run-up gauges (DESIGN.md section 4): ``"kernel"``, the
highest point where the fluid's kernel volume sum fills half the space the walls leave free
(``S_fluid / (1 - S_wall) >= 0.5``: 0.5 away from walls, and right next to a side wall or bed
too); ``"particle"``, the highest fluid particle
near the gauge line (seed 001's method)."""

SPECTRA: dict[str, str] = {
    "jonswap": "jonswap",
    "pm": "pierson-moskowitz",
    "pierson-moskowitz": "pierson-moskowitz",
}
"""Spectrum names accepted by :class:`IrregularWave`, and their :mod:`wave_theory` names."""

RAMPS: tuple[str, ...] = ("linear", "tanh")
"""Start-up ramp shapes of harmonic paddle laws."""

RUNUP_OFFSET_DP = 1.5
"""Distance of the automatic run-up gauge line above the beach surface, in dp (normal to it)."""

_TOL = 1e-9

SOLITARY_MAX_H_OVER_D = 0.83
"""Highest solitary wave, H/d about 0.83 (Longuet-Higgins & Fenton 1974): a taller one does not
exist, and Goring's paddle motion for it is meaningless."""

LATTICE_RTOL = 1e-6
"""Relative tolerance within which ``depth / dp`` (and a 3D flume's ``width / dp``) counts as a
whole number: the core then fills exactly that many layers (see :func:`lattice_layers`)."""

MAX_PARTICLES = 1e10
"""Fluid particle count past which a flume is refused before anything is derived from dp (far
beyond any machine's memory; the core's estimate then refuses what does not fit this one)."""


# ------------------------------------------------------------------------------------------------
# the particle lattice


def lattice_layers(extent: float, dp: float) -> int:
    """Number of fluid layers the core puts in ``[0, extent]`` [m] at spacing ``dp`` [m].

    The core (crates/sph-core/src/geometry.rs, ``sample``) places particles at ``(i + 1/2) dp``
    from the tank's inner corner and keeps those strictly inside a fluid box, so a still-water
    depth (or a 3D flume's width) holds the whole layers whose centres lie below it: about
    ``round(extent / dp)`` (a half rounds down), computed here with the core's own floating-point
    expression. The water it makes is ``lattice_layers(extent, dp) * dp`` deep (wide).
    """
    n = max(math.floor(extent / dp - 0.5) - 1, 0)
    while (n + 0.5) * dp < extent:
        n += 1
    return n


def _whole(extent: float, dp: float) -> bool:
    """Whether ``extent / dp`` is a whole number within :data:`LATTICE_RTOL`."""
    q = extent / dp
    return abs(q - round(q)) <= LATTICE_RTOL * q


def lattice_dp(depth: float, dp: float, width: float | None = None) -> float:
    """The spacing [m] nearest ``dp`` [m] that makes ``depth`` [m] a whole number of layers:
    ``dp`` itself when it already is one, else ``depth / n`` with ``n = round(depth / dp)`` (at
    least 2), so the core fills exactly the depth asked for (:func:`lattice_layers`).

    With a 3D flume's ``width`` [m], the smallest ``n`` from ``round(depth / dp)`` up to twice
    that for which the width is also a whole number of ``depth / n``; when none is, the depth's
    ``n`` (the flume then refuses the width, naming it).
    """
    if _whole(depth, dp) and (width is None or _whole(width, dp)):
        return dp  # already whole: keep it as given (0.025, not 0.3 / 12 = 0.024999...)
    n0 = max(round(depth / dp), 2)
    if width is not None:
        for n in range(n0, 2 * n0 + 1):
            if _whole(width, depth / n):
                return depth / n
    return depth / n0


def _lattice_error(field: str, what: str, extent: float, dp: float, unit: str) -> str:
    """The refusal of an ``extent`` [m] that is not a whole number of dp (see
    :meth:`FlumeScene._check_lattice`)."""
    q = extent / dp
    filled = lattice_layers(extent, dp) * dp
    lo, hi = math.floor(q), math.ceil(q)
    if field == "dp":
        fix = (f"use dp = {extent / lo:.8g} ({lo} {unit}) or {extent / hi:.8g} ({hi} {unit}), "
               f"or a {what.split()[-1]} that is a whole number of dp")
    else:
        fix = (f"use a {field} of {lo * dp:.6g} m ({lo} dp) or {hi * dp:.6g} m ({hi} dp), or a "
               "dp that divides both the depth and the width")
    n = lattice_layers(extent, dp)
    return (f"{field}: the {what} {extent:.6g} m is {q:.6g} dp (dp = {dp:.6g} m); the particle "
            f"lattice fills whole {unit}, so the water would be {filled:.6g} m "
            f"{'deep' if field == 'dp' else 'wide'} ({n} {unit}); {fix}")


# ------------------------------------------------------------------------------------------------
# small checks


def _finite_tuple(name: str, values: Any, min_len: int = 1) -> tuple[float, ...]:
    """``values`` as a tuple of finite floats with at least ``min_len`` entries."""
    if isinstance(values, (str, bytes)):
        raise SceneError(f"{name}: expected a sequence of numbers, got {values!r}")
    try:
        arr = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise SceneError(f"{name}: expected a sequence of numbers, got {values!r}") from None
    if arr.ndim != 1:
        raise SceneError(f"{name}: expected a 1-D sequence of numbers, got shape {arr.shape}")
    if arr.size < min_len:
        raise SceneError(f"{name}: needs at least {min_len} values, got {arr.size}")
    if not np.all(np.isfinite(arr)):
        raise SceneError(f"{name}: values must be finite, got {arr.tolist()}")
    return tuple(float(v) for v in arr)


def _strictly_increasing(name: str, values: Sequence[float]) -> None:
    """SceneError ``name: must increase strictly (v[i] >= v[i + 1])``, ``v`` the last part of
    ``name``, at the first pair that does not increase."""
    symbol = name.rsplit(".", 1)[-1]
    for i in range(len(values) - 1):
        if not values[i + 1] > values[i]:
            raise SceneError(f"{name}: must increase strictly ({symbol}[{i}] >= {symbol}[{i + 1}])")


def _optional_name(name: str, value: Any) -> None:
    if value is not None and (not isinstance(value, str) or not value.strip()):
        raise SceneError(f"{name}: must be a non-empty string, got {value!r}")
    if isinstance(value, str) and ("," in value or "\n" in value):
        raise SceneError(f"{name}: must not contain commas or line breaks, got {value!r}")


def _set(obj: Any, name: str, value: Any) -> None:
    object.__setattr__(obj, name, value)


# ------------------------------------------------------------------------------------------------
# beaches


@dataclass(frozen=True)
class PlaneBeach:
    """A plane (uniform) beach rising from the flume floor at ``toe`` with slope ``slope``.

    The bed is ``z = slope (x - toe)`` for x >= toe, up to the top of the tank walls, and flat at
    that height beyond (if the flume is long enough to get there).

    Attributes:
        toe: x of the toe, where the slope leaves the floor [m] (from the paddle at rest).
        slope: tan(beta), rise over run [-] (1/15 for a 1:15 beach).
    """

    toe: float
    slope: float

    def __post_init__(self) -> None:
        _set(self, "toe", _non_negative("beach.toe", self.toe))
        slope = _positive("beach.slope", self.slope)
        if slope > 10.0:
            raise SceneError(f"beach.slope: tan(beta) = {slope:g} is steeper than 10; use a wall")
        _set(self, "slope", slope)

    def profile(self, length: float, top: float) -> tuple[list[float], list[float]]:
        """Bed vertices ``(x, z)`` [m] of this beach in a flume of ``length`` with walls ``top``
        high."""
        x_top = self.toe + top / self.slope
        if x_top >= length - _TOL:
            return [self.toe, length], [0.0, self.slope * (length - self.toe)]
        return [self.toe, x_top, length], [0.0, top, top]


@dataclass(frozen=True)
class ProfileBeach:
    """A piecewise-linear bed (bar, composite beach, measured bathymetry): solid below the line
    through the vertices ``(x[i], z[i])``; the flume floor (z = 0) outside ``[x[0], x[-1]]``.

    Attributes:
        x: vertex positions along the flume [m], strictly increasing, within the flume.
        z: bed heights above the flume floor [m], >= 0.
    """

    x: tuple[float, ...]
    z: tuple[float, ...]

    def __post_init__(self) -> None:
        x = _finite_tuple("beach.x", self.x, 2)
        z = _finite_tuple("beach.z", self.z, 2)
        if len(x) != len(z):
            raise SceneError(f"beach.z: needs as many values as beach.x ({len(x)}), got {len(z)}")
        _strictly_increasing("beach.x", x)
        if min(z) < 0.0:
            raise SceneError(f"beach.z: bed heights must not be negative, got {min(z):g}")
        if x[0] < 0.0:
            raise SceneError(f"beach.x: the profile starts at x = {x[0]:g} m, behind the paddle")
        _set(self, "x", x)
        _set(self, "z", z)

    def profile(self, length: float, top: float) -> tuple[list[float], list[float]]:
        """Bed vertices ``(x, z)`` [m] (the profile as given)."""
        return list(self.x), list(self.z)


@dataclass(frozen=True)
class MeshBeach:
    """Bathymetry from a closed triangle mesh (3D flumes only): an STL file, or NumPy vertices
    and triangles. The solid is the inside of the mesh; the core samples it into wall particles
    (``layers`` deep below its surface) and fills every lattice site above it with water, as
    for the other beaches. Anything the core needs is checked when the beach is made: the
    file is read with meshio, exactly repeated vertices are merged (an STL stores each
    triangle's corners), and the surface must be closed, consistently oriented with its
    triangles facing outward (positive enclosed volume), without degenerate triangles; the
    flume then checks that the mesh lies inside it (x in [0, length], y in [0, width],
    z >= 0, below the walls) and clear of the paddle's stroke.

    The analysis reads the bed under each gauge from the mesh (its highest surface over the
    gauge, 0 where the gauge misses it); the shoreline, toe, beach slope and automatic run-up
    gauge come from the bed profile along the flume's centre line.

    Attributes:
        path: surface mesh file: STL (ASCII or binary) or any triangle mesh meshio reads (OBJ,
            PLY, OFF, ...); in a scene file a relative path is from the scene file's folder.
        vertices: instead of ``path``: the vertices, ``(n, 3)`` rows x, y, z [m] (before
            ``scale`` and ``offset``).
        triangles: with ``vertices``: ``(m, 3)`` vertex indices of each triangle, counter-clockwise
            seen from outside the solid.
        scale: factor applied to the vertices [m per file unit], e.g. 0.001 for a file in mm.
        offset: (x, y, z) added to the scaled vertices [m]: where the mesh's origin goes in
            flume coordinates.
    """

    path: str | None = None
    vertices: tuple[tuple[float, ...], ...] | None = None
    triangles: tuple[tuple[int, ...], ...] | None = None
    scale: float = 1.0
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    points: npt.NDArray[np.float64] = dataclasses.field(
        init=False, repr=False, compare=False)
    """(n, 3) vertices in flume coordinates [m], duplicates merged."""
    faces: npt.NDArray[np.int64] = dataclasses.field(init=False, repr=False, compare=False)
    """(m, 3) triangles indexing :attr:`points`."""
    volume: float = dataclasses.field(init=False, repr=False, compare=False)
    """Volume enclosed by the mesh [m^3]."""

    def __post_init__(self) -> None:
        _set(self, "scale", _positive("beach.scale", self.scale))
        offset = _finite_tuple("beach.offset", self.offset, 3)
        if len(offset) != 3:
            raise SceneError(f"beach.offset: needs 3 values (x, y, z), got {len(offset)}")
        _set(self, "offset", offset)
        if (self.path is None) == (self.vertices is None and self.triangles is None):
            raise SceneError("beach.path: give either a mesh file (path) or vertices and "
                             "triangles, not both nor neither")
        if self.path is not None:
            if not isinstance(self.path, (str, os.PathLike)) or not str(self.path).strip():
                raise SceneError(f"beach.path: expected a file name, got {self.path!r}")
            _set(self, "path", os.fspath(self.path))
            raw, tri = meshbed.read_triangle_mesh(self.path, "beach.path")
        else:
            if self.vertices is None or self.triangles is None:
                missing = "triangles" if self.triangles is None else "vertices"
                raise SceneError(f"beach.{missing}: vertices and triangles go together")
            raw = self._array("beach.vertices", self.vertices, np.float64)
            tri_f = self._array("beach.triangles", self.triangles, np.float64)
            if not np.all(np.isfinite(raw)):
                raise SceneError("beach.vertices: values must be finite")
            if not np.all(tri_f == np.round(tri_f)):
                raise SceneError("beach.triangles: vertex indices must be whole numbers")
            tri = tri_f.astype(np.int64)
            if tri.min() < 0 or tri.max() >= raw.shape[0]:
                raise SceneError(f"beach.triangles: indices must lie in [0, {raw.shape[0] - 1}] "
                                 f"(the vertices), got {int(tri.min())}..{int(tri.max())}")
            # stored as plain tuples: a frozen, comparable builder that a scene file can write
            _set(self, "vertices", tuple(tuple(float(v) for v in row) for row in raw))
            _set(self, "triangles", tuple(tuple(int(i) for i in row) for row in tri))
        pts = raw * self.scale + np.asarray(offset)
        pts, tri = meshbed.merge_duplicate_vertices(pts, tri)
        _set(self, "volume", meshbed.check_closed_mesh(pts, tri, self.source_field))
        pts.setflags(write=False)
        tri.setflags(write=False)
        _set(self, "points", pts)
        _set(self, "faces", tri)

    @staticmethod
    def _array(name: str, values: Any, dtype: type) -> npt.NDArray[Any]:
        try:
            arr: npt.NDArray[Any] = np.asarray(values, dtype=dtype)
        except (TypeError, ValueError):
            raise SceneError(f"{name}: expected rows of 3 numbers") from None
        if arr.ndim != 2 or arr.shape[1] != 3 or arr.shape[0] == 0:
            raise SceneError(f"{name}: expected rows of 3 numbers, got shape {arr.shape}")
        return arr

    @property
    def source_field(self) -> str:
        """The field that gave the mesh (``beach.path`` or ``beach.vertices``), for messages."""
        return "beach.path" if self.path is not None else "beach.vertices"

    @property
    def bounds(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """``(min, max)`` corners of the mesh's bounding box [m], flume coordinates."""
        return self.points.min(axis=0), self.points.max(axis=0)

    def bed(self, x: npt.ArrayLike, y: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Bed height above the floor under ``(x, y)`` [m]: the mesh's highest surface there,
        0 where the vertical line misses the mesh."""
        z = meshbed.surface_height(self.points, self.faces, x, y)
        return np.maximum(np.nan_to_num(z, nan=0.0), 0.0)

    def profile(self, length: float, top: float, y: float | None = None
                ) -> tuple[list[float], list[float]]:
        """Bed vertices ``(x, z)`` [m] along the line ``y`` (the centre line of a flume as wide
        as the mesh when None) from x = 0 to ``length``; ``top`` is not used (the mesh has its
        own height)."""
        lo, hi = self.bounds
        yy = 0.5 * (lo[1] + hi[1]) if y is None else float(y)
        return meshbed.profile_along_line(self.points, self.faces, yy, 0.0, length)

    def to_core(self) -> dict[str, Any]:
        """The core's obstacle JSON (``shape = "mesh"``)."""
        return {"shape": "mesh", "vertices": self.points.tolist(),
                "triangles": self.faces.tolist()}


Beach = PlaneBeach | ProfileBeach | MeshBeach


def _bed(px: Sequence[float], pz: Sequence[float], x: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Bed height [m] at ``x`` for a profile (the floor, 0, outside it or without a profile)."""
    if len(px) == 0:
        return np.zeros_like(np.asarray(x, dtype=np.float64))
    return np.interp(np.asarray(x, dtype=np.float64), px, pz, left=0.0, right=0.0)


def _shoreline_segment(
    px: Sequence[float], pz: Sequence[float], level: float
) -> tuple[float, float, float, float] | None:
    """The last profile segment crossing ``level`` upwards: ``(x0, z0, x1, z1)``, or None."""
    for i in range(len(px) - 2, -1, -1):
        if pz[i] <= level < pz[i + 1]:
            return px[i], pz[i], px[i + 1], pz[i + 1]
    return None


# ------------------------------------------------------------------------------------------------
# damping, flume


@dataclass(frozen=True)
class DampingZone:
    """Velocity damping zone at the far end of the flume (DualSPHysics form): after each step the
    fluid velocity is scaled by ``1 - dt * strength * s^2``, ``s`` rising from 0 at the zone's
    start to 1 at the far wall.

    Attributes:
        length: zone length from the far wall [m]; ``None``: one wavelength of the wave (its
            peak period for irregular waves), or a quarter of the flume when no period is known.
        strength: largest velocity reduction rate [1/s].
    """

    length: float | None = None
    strength: float = 10.0

    def __post_init__(self) -> None:
        if self.length is not None:
            _set(self, "length", _positive("damping.length", self.length))
        _set(self, "strength", _non_negative("damping.strength", self.strength))


@dataclass(frozen=True)
class Flume:
    """A wave flume: its length, still-water depth, beach, and (3D) width.

    Attributes:
        length: from the paddle face at rest (x = 0) to the far wall [m].
        depth: still-water depth over the flat floor [m]; the SWL is z = depth.
        beach: a :class:`PlaneBeach`, a :class:`ProfileBeach`, a :class:`MeshBeach` (3D only),
            or ``None`` (flat floor).
        width: inner width [m] for a 3D flume (side walls at y = 0 and y = width); ``None`` in 2D.
        height: height of the tank walls above the floor [m]; ``None``: chosen from the wave
            (``depth + max(depth / 2, 3 H)``, at least the highest bed point).
        damping: a :class:`DampingZone`; ``True`` for the default zone; ``False`` for none;
            ``None`` (default): a default zone when there is no beach, none with a beach.
    """

    length: float
    depth: float
    beach: Beach | None = None
    width: float | None = None
    height: float | None = None
    damping: DampingZone | bool | None = None

    def __post_init__(self) -> None:
        length = _positive("length", self.length)
        depth = _positive("depth", self.depth)
        _set(self, "length", length)
        _set(self, "depth", depth)
        if self.width is not None:
            _set(self, "width", _positive("width", self.width))
        if self.height is not None:
            height = _positive("height", self.height)
            if height <= depth:
                raise SceneError(
                    f"height: the walls ({height:g} m) must be higher than the water "
                    f"(depth = {depth:g} m)"
                )
            _set(self, "height", height)
        if self.damping is not None and not isinstance(self.damping, (bool, DampingZone)):
            raise SceneError(f"damping: expected a DampingZone, True, False or None, got "
                             f"{self.damping!r}")
        if isinstance(self.damping, DampingZone) and self.damping.length is not None:
            if self.damping.length >= length:
                raise SceneError(
                    f"damping.length: the zone ({self.damping.length:g} m) is as long as the "
                    f"flume (length = {length:g} m)"
                )
        beach = self.beach
        if beach is None:
            return
        if isinstance(beach, PlaneBeach):
            if beach.toe >= length:
                raise SceneError(
                    f"beach.toe: the toe at x = {beach.toe:g} m lies beyond the flume "
                    f"(length = {length:g} m)"
                )
        elif isinstance(beach, ProfileBeach):
            if beach.x[-1] > length + _TOL:
                raise SceneError(
                    f"beach.x: the profile ends at x = {beach.x[-1]:g} m, beyond the flume "
                    f"(length = {length:g} m)"
                )
            if self.height is not None and max(beach.z) > self.height + _TOL:
                raise SceneError(
                    f"beach.z: the bed rises to {max(beach.z):g} m, above the walls "
                    f"(height = {self.height:g} m)"
                )
        elif isinstance(beach, MeshBeach):
            self._check_mesh(beach)
        else:
            raise SceneError(
                f"beach: expected a PlaneBeach, a ProfileBeach, a MeshBeach or None, got {beach!r}"
            )

    def _check_mesh(self, beach: MeshBeach) -> None:
        """A mesh beach needs a 3D flume and must lie inside it (the core would clip what lies
        outside the tank without a word)."""
        field = beach.source_field
        if self.width is None:
            raise SceneError("beach: a MeshBeach (triangle mesh) needs a 3D flume; give the "
                             "flume a width")
        lo, hi = beach.bounds
        tol = 1e-6 * max(self.length, self.width, 1.0)  # float32 STL coordinates
        limits = [("x", 0, 0.0, self.length, f"the flume's length [0, {self.length:g}] m"),
                  ("y", 1, 0.0, self.width, f"the flume's width [0, {self.width:g}] m"),
                  ("z", 2, 0.0, math.inf, "above the floor (z >= 0)")]
        if self.height is not None:
            limits[2] = ("z", 2, 0.0, self.height, f"between the floor and the top of the walls "
                         f"[0, {self.height:g}] m")
        for name, k, a, b, where in limits:
            if lo[k] < a - tol or hi[k] > b + tol:
                raise SceneError(
                    f"{field}: the mesh spans {name} = [{lo[k]:.6g}, {hi[k]:.6g}] m; it must lie "
                    f"within {where} (move it with beach.offset, scale it with beach.scale)"
                )

    @property
    def dim(self) -> int:
        """2 without a width, 3 with one."""
        return 2 if self.width is None else 3

    def damping_enabled(self) -> bool:
        """Whether the flume has a damping zone (default: only without a beach)."""
        if self.damping is None:
            return self.beach is None
        return self.damping is not False

    def scene(self, wave: Wave, **kwargs: Any) -> FlumeScene:
        """The full, checked scene builder of a run in this flume (see :class:`FlumeScene` for
        the keyword arguments: ``paddle``, ``dp``, ``gauges``, ``runup``, ``until``,
        ``sample_interval`` and every numerical parameter of :class:`~watersim.SceneBuilder`)."""
        return FlumeScene(flume=self, wave=wave, **kwargs)

    def simulation(self, wave: Wave, **kwargs: Any) -> FlumeSimulation:
        """Build the particles of a run in this flume: a ready :class:`FlumeSimulation`.

        Same arguments as :meth:`scene`.
        """
        return self.scene(wave, **kwargs).build()


# ------------------------------------------------------------------------------------------------
# waves


@dataclass(frozen=True)
class RegularWave:
    """A regular wave of height ``height`` and period ``period`` (first or second order, as the
    paddle's ``order`` says).

    Attributes:
        height: target wave height H (crest to trough) at the paddle depth [m].
        period: wave period T [s].
        phase: phase delta of the paddle motion ``X = (S/2) sin(omega t + delta) + ...`` [rad].
    """

    height: float
    period: float
    phase: float = 0.0

    def __post_init__(self) -> None:
        _set(self, "height", _positive("wave.height", self.height))
        _set(self, "period", _positive("wave.period", self.period))
        _set(self, "phase", _number("wave.phase", self.phase))


@dataclass(frozen=True)
class IrregularWave:
    """An irregular wave synthesised from a spectrum (seeded, reproducible; see
    :func:`watersim.wave_theory.irregular_paddle_motion`).

    Attributes:
        hs: significant wave height Hm0 [m].
        tp: peak period [s].
        spectrum: ``"jonswap"`` or ``"pm"`` (Pierson-Moskowitz).
        gamma: JONSWAP peak enhancement factor (>= 1).
        seed: seed of the random phases (and amplitudes).
        random_amplitudes: Rayleigh-distributed amplitudes instead of deterministic ones.
        frequency_range: (low, high) component frequencies in units of the peak frequency.
        repeat_period: length of the non-repeating signal [s] (1 / frequency spacing); ``None``:
            256 Tp.
    """

    hs: float
    tp: float
    spectrum: str = "jonswap"
    gamma: float = 3.3
    seed: int = 0
    random_amplitudes: bool = False
    frequency_range: tuple[float, float] = (0.5, 3.0)
    repeat_period: float | None = None

    def __post_init__(self) -> None:
        _set(self, "hs", _positive("wave.hs", self.hs))
        _set(self, "tp", _positive("wave.tp", self.tp))
        _choice("wave.spectrum", self.spectrum, tuple(SPECTRA))
        gamma = _number("wave.gamma", self.gamma)
        if gamma < 1.0:
            raise SceneError(f"wave.gamma: must be >= 1, got {self.gamma!r}")
        _set(self, "gamma", gamma)
        _integer("wave.seed", self.seed, 0)
        if not isinstance(self.random_amplitudes, bool):
            raise SceneError(f"wave.random_amplitudes: expected True or False, got "
                             f"{self.random_amplitudes!r}")
        band = _finite_tuple("wave.frequency_range", self.frequency_range, 2)
        if len(band) != 2 or not 0.0 < band[0] < band[1]:
            raise SceneError(
                f"wave.frequency_range: expected (low, high) with 0 < low < high, got {band}"
            )
        _set(self, "frequency_range", band)
        if self.repeat_period is not None:
            _set(self, "repeat_period", _positive("wave.repeat_period", self.repeat_period))


@dataclass(frozen=True)
class SolitaryWave:
    """A solitary wave made by Goring's (1978) piston motion (a ``table`` law in the core).

    Attributes:
        height: solitary wave height H [m].
        truncation: eta / H where the motion starts and stops (Goring's 3.8 <-> 0.002).
        delay: time at which the paddle starts moving [s].
        samples: number of points of the tabulated motion.
    """

    height: float
    truncation: float = 0.002
    delay: float = 0.0
    samples: int = 1001

    def __post_init__(self) -> None:
        _set(self, "height", _positive("wave.height", self.height))
        trunc = _positive("wave.truncation", self.truncation)
        if trunc >= 1.0:
            raise SceneError(f"wave.truncation: must be < 1, got {self.truncation!r}")
        _set(self, "truncation", trunc)
        _set(self, "delay", _non_negative("wave.delay", self.delay))
        _integer("wave.samples", self.samples, 2)


@dataclass(frozen=True)
class TabulatedMotion:
    """A paddle displacement series (e.g. a measured wave-maker record), linearly interpolated
    by the core and held at its first and last values outside the table.

    For a flap, ``x`` is the displacement at the still-water level.

    Attributes:
        t: times [s], strictly increasing.
        x: displacement of the paddle face from rest [m] (positive towards the far wall).
    """

    t: tuple[float, ...]
    x: tuple[float, ...]

    def __post_init__(self) -> None:
        t = _finite_tuple("wave.t", self.t, 2)
        x = _finite_tuple("wave.x", self.x, 2)
        if len(t) != len(x):
            raise SceneError(f"wave.x: has {len(x)} values but wave.t has {len(t)}")
        _strictly_increasing("wave.t", t)
        _set(self, "t", t)
        _set(self, "x", x)


Wave = RegularWave | IrregularWave | SolitaryWave | TabulatedMotion


# ------------------------------------------------------------------------------------------------
# paddles


@dataclass(frozen=True)
class Piston:
    """A piston wave-maker: the paddle translates along x.

    Attributes:
        order: 1 (Biesel) or 2 (Madsen 1971 second-order correction, regular waves only).
        ramp_periods: start-up ramp length in wave periods (peak periods for irregular waves);
            0 for none. Tabulated and solitary motions have no ramp.
        ramp: ``"linear"`` (``min(1, t / T_r)``) or ``"tanh"`` (``tanh(4 t / T_r)``).
    """

    order: int = 1
    ramp_periods: float = 2.0
    ramp: str = "linear"

    def __post_init__(self) -> None:
        if isinstance(self.order, bool) or self.order not in (1, 2):
            raise SceneError(f"paddle.order: must be 1 or 2, got {self.order!r}")
        _set(self, "ramp_periods", _non_negative("paddle.ramp_periods", self.ramp_periods))
        _choice("paddle.ramp", self.ramp, RAMPS)


@dataclass(frozen=True)
class Flap:
    """A flap wave-maker: the paddle rotates about a horizontal hinge at height ``hinge_z``;
    below the hinge it is a fixed wall. Its displacement X is set at the still-water level
    (``theta = atan(X / (depth - hinge_z))``). First-order generation only.

    Attributes:
        hinge_z: hinge height above the floor [m]; ``None``: on the floor (a bottom-hinged flap).
        ramp_periods: start-up ramp length in wave periods; 0 for none.
        ramp: ``"linear"`` or ``"tanh"``.
    """

    hinge_z: float | None = None
    ramp_periods: float = 2.0
    ramp: str = "linear"

    order: ClassVar[int] = 1

    def __post_init__(self) -> None:
        if self.hinge_z is not None:
            _set(self, "hinge_z", _non_negative("paddle.hinge_z", self.hinge_z))
        _set(self, "ramp_periods", _non_negative("paddle.ramp_periods", self.ramp_periods))
        _choice("paddle.ramp", self.ramp, RAMPS)


Paddle = Piston | Flap


def flap_height_to_stroke_hinged(
    k: npt.ArrayLike, depth: float, hinge_height: float
) -> npt.NDArray[np.float64]:
    """Biesel transfer function H/S of a flap hinged ``hinge_height`` above the bed [-].

    Linear wave-maker theory (Biesel & Suquet 1951; Dean & Dalrymple 1991, ch. 6): for a paddle
    whose horizontal displacement is ``(S/2) f(z)`` (z up from the bed, f = 1 at the surface),
    ``H/S = 4 sinh(kd) / (sinh 2kd + 2kd) * k int_0^d f(z) cosh(kz) dz``. With the flap's
    ``f = (z - l)/(d - l)`` above the hinge l and 0 below, the integral is
    ``[k(d - l) sinh kd - cosh kd + cosh kl] / (k (d - l))``. For l = 0 this is the bottom-hinged
    flap of :func:`watersim.wave_theory.flap_height_to_stroke`, which is used then; f = 1 gives
    the piston.

    Args:
        k: wavenumber [rad/m]; depth: still-water depth d [m]; hinge_height: l, 0 <= l < d [m].
    """
    kk = np.asarray(k, dtype=np.float64)
    if hinge_height == 0.0:
        return np.asarray(wt.flap_height_to_stroke(kk, depth), dtype=np.float64)
    kd = kk * depth
    span = kk * (depth - hinge_height)
    integral = (span * np.sinh(kd) - np.cosh(kd) + np.cosh(kk * hinge_height)) / span
    return np.asarray(4.0 * np.sinh(kd) / (np.sinh(2.0 * kd) + 2.0 * kd) * integral)


# ------------------------------------------------------------------------------------------------
# gauges


@dataclass(frozen=True)
class ElevationGauge:
    """Free-surface elevation on the vertical line through (x[, y]).

    Attributes:
        x: position along the flume [m].
        y: position across (3D only) [m]; ``None``: the flume's centre line.
        method: ``"kernel"`` or ``"particle"`` (see :data:`SURFACE_METHODS`).
        name: column name; default ``eta_x{x:.3f}`` (``_y{y:.3f}`` added in 3D).
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    x: float
    y: float | None = None
    method: str = "kernel"
    name: str | None = None
    interval: float | None = None

    def __post_init__(self) -> None:
        _set(self, "x", _number("gauge.x", self.x))
        if self.y is not None:
            _set(self, "y", _number("gauge.y", self.y))
        _choice("gauge.method", self.method, SURFACE_METHODS)
        _optional_name("gauge.name", self.name)
        if self.interval is not None:
            _set(self, "interval", _positive("gauge.interval", self.interval))


@dataclass(frozen=True)
class VelocityProbe:
    """Fluid velocity (Shepard-interpolated) at fixed points (x, z) or (x, y, z) [m].

    Attributes:
        points: the points, in flume coordinates (z from the floor).
        name: record name; default ``velocity{i}``.
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    points: tuple[tuple[float, ...], ...]
    name: str | None = None
    interval: float | None = None

    def __post_init__(self) -> None:
        try:
            rows = [tuple(p) for p in self.points]
        except TypeError:
            raise SceneError(f"gauge.points: expected a sequence of points, got "
                             f"{self.points!r}") from None
        if not rows:
            raise SceneError("gauge.points: needs at least one point")
        pts = tuple(_finite_tuple(f"gauge.points[{i}]", p, 2) for i, p in enumerate(rows))
        if len({len(p) for p in pts}) != 1 or len(pts[0]) not in (2, 3):
            raise SceneError("gauge.points: every point needs 2 (x, z) or 3 (x, y, z) coordinates")
        _set(self, "points", pts)
        _optional_name("gauge.name", self.name)
        if self.interval is not None:
            _set(self, "interval", _positive("gauge.interval", self.interval))


@dataclass(frozen=True)
class VelocityWindow:
    """PIV-like window: velocity on a regular grid of ``n`` points per axis over ``[min, max]``.

    In 2D ``min``, ``max`` are (x, z) and ``n`` is (nx, nz); in 3D (x, y, z) and (nx, ny, nz)
    (one point along y gives a vertical plane). The record's velocity has shape
    ``(n_samples, *reversed(n), dim)``: z slowest, x fastest.

    Attributes:
        min, max: opposite corners [m], flume coordinates.
        n: points per axis (>= 1).
        name: record name; default ``window{i}``.
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    min: tuple[float, ...]
    max: tuple[float, ...]
    n: tuple[int, ...]
    name: str | None = None
    interval: float | None = None

    def __post_init__(self) -> None:
        lo = _finite_tuple("gauge.min", self.min, 2)
        hi = _finite_tuple("gauge.max", self.max, 2)
        if len(lo) != len(hi) or len(lo) not in (2, 3):
            raise SceneError("gauge.max: min and max need 2 (x, z) or 3 (x, y, z) coordinates")
        if any(b < a for a, b in zip(lo, hi, strict=True)):
            raise SceneError(f"gauge.max: must not be below min on any axis ({lo} -> {hi})")
        counts = tuple(self.n) if not isinstance(self.n, (str, bytes)) else ()
        if len(counts) != len(lo):
            raise SceneError(f"gauge.n: needs {len(lo)} counts, got {self.n!r}")
        for i, c in enumerate(counts):
            _integer(f"gauge.n[{i}]", c, 1)
        _set(self, "min", lo)
        _set(self, "max", hi)
        _set(self, "n", tuple(int(c) for c in counts))
        _optional_name("gauge.name", self.name)
        if self.interval is not None:
            _set(self, "interval", _positive("gauge.interval", self.interval))


@dataclass(frozen=True)
class RunupGauge:
    """Run-up: the highest wet point along a segment laid just above the beach (``end`` uphill);
    records its vertical position.

    Attributes:
        start, end: the segment's ends [m], flume coordinates; ``None`` (both): laid automatically
            along the beach, ``1.5 dp`` above its surface, from below the lowest run-down up to
            the top of the slope.
        method: ``"kernel"`` or ``"particle"``.
        name: record name (default ``"runup"``).
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    start: tuple[float, ...] | None = None
    end: tuple[float, ...] | None = None
    method: str = "kernel"
    name: str = "runup"
    interval: float | None = None

    def __post_init__(self) -> None:
        if (self.start is None) != (self.end is None):
            raise SceneError("runup.end: give both start and end, or neither (automatic)")
        if self.start is not None and self.end is not None:
            a = _finite_tuple("runup.start", self.start, 2)
            b = _finite_tuple("runup.end", self.end, 2)
            if len(a) != len(b) or len(a) not in (2, 3):
                raise SceneError("runup.end: start and end need 2 (x, z) or 3 (x, y, z) values")
            if a == b:
                raise SceneError("runup.end: must differ from start")
            if b[-1] <= a[-1]:
                raise SceneError("runup.end: must be uphill of start (higher z)")
            _set(self, "start", a)
            _set(self, "end", b)
        _choice("runup.method", self.method, SURFACE_METHODS)
        _optional_name("runup.name", self.name)
        if self.interval is not None:
            _set(self, "interval", _positive("runup.interval", self.interval))


Gauge = ElevationGauge | VelocityProbe | VelocityWindow


def elevation_gauges_between(
    x_start: float, x_end: float, spacing: float, method: str = "kernel"
) -> list[ElevationGauge]:
    """Elevation gauges every ``spacing`` metres from ``x_start`` to ``x_end`` (both included
    when they fall on the spacing): a line of gauges for envelopes and breaking position."""
    a = _number("x_start", x_start)
    b = _number("x_end", x_end)
    s = _positive("spacing", spacing)
    if b < a:
        raise SceneError(f"x_end: must not be before x_start ({a:g} -> {b:g})")
    n = math.floor((b - a) / s + 1e-9)
    return [ElevationGauge(round(a + i * s, 9), method=method) for i in range(n + 1)]


# ------------------------------------------------------------------------------------------------
# the scene


@dataclass(frozen=True)
class _Law:
    """A resolved paddle law: the core's JSON and what the analysis needs."""

    law: dict[str, Any]
    backward: float
    forward: float
    ramp_duration: float
    period: float | None
    design_height: float | None
    stroke: float | None = None
    second_order_amplitude: float | None = None
    duration: float | None = None


def _harmonic_law(
    components: list[list[float]], bound: float, paddle: Paddle, period: float, **extra: Any
) -> _Law:
    """The core's ``harmonic`` law, ``X = r(t) sum a sin(omega t + phase)`` over ``components``
    ``[a, omega, phase]`` with the paddle's start-up ramp over ``ramp_periods`` ``period`` [s];
    ``bound`` [m] is the largest excursion either way, ``extra`` the other :class:`_Law` fields."""
    ramp = paddle.ramp_periods * period
    return _Law(
        law={
            "type": "harmonic",
            "components": components,
            "ramp_duration": ramp,
            "ramp_shape": paddle.ramp,
        },
        backward=bound,
        forward=bound,
        ramp_duration=ramp,
        period=period,
        **extra,
    )


@dataclass(frozen=True, kw_only=True)
class FlumeScene(SceneBuilder):
    """Everything about one flume run: the flume, the wave, the paddle, the gauges and every
    numerical parameter (those of :class:`~watersim.SceneBuilder`).

    Build it with :meth:`Flume.scene` (or :meth:`Flume.simulation`, which also builds the
    particles). ``dim`` follows the flume (3 with a width). Defaults filled in when the scene is
    created: ``dp = min(depth / 15, H / 4)`` (H the wave's height, ``1.8 hs`` for irregular
    waves; depth / 15 for a tabulated motion; in 3D at most 8 layers deep), snapped to
    ``depth / round(depth / dp)`` so that the water is a whole number of particle layers deep
    (:func:`lattice_dp`; a given ``dp`` that is not is refused, see :meth:`_check_lattice`),
    ``sample_interval = T / 40`` (at most 0.05 s;
    ``sqrt(depth / g) / 4`` for solitary waves, 0.02 s for a tabulated motion), ``until`` long
    enough for the wave to reach the last gauge (or the shoreline) after the ramp and ten more
    periods there (for irregular waves fifty peak periods, for a solitary wave the time to cross
    the flume and come back, for a tabulated motion the table's end plus one crossing).

    Attributes:
        flume: the :class:`Flume`.
        wave: :class:`RegularWave`, :class:`IrregularWave`, :class:`SolitaryWave` or
            :class:`TabulatedMotion`.
        paddle: :class:`Piston` (default) or :class:`Flap`.
        gauges: :class:`ElevationGauge`, :class:`VelocityProbe` and :class:`VelocityWindow`
            objects.
        runup: ``True`` for an automatic run-up gauge along the beach, a :class:`RunupGauge`,
            ``False`` for none; ``None`` (default): automatic when the beach reaches the SWL.
        sample_interval: default sampling interval of the gauges [s].
        energy_growth_limit: not used: the core's energy monitor skips scenes with a paddle
            (``density_band`` and ``lost_fraction_limit`` do apply); must stay unset.

    Numerical defaults differ from the dam break's in three fields, all for wave propagation:

    - ``coefh = 1.5`` in 2D, 1.2 in 3D (``h = 2.1 dp`` in both; DualSPHysics' 3D wave cases
      use 1.2): at coarse resolution it carries a regular wave much further than
      ``coefh = 1`` (measured here in 2D, d = 0.3 m, T = 1.2 s, H = 0.06 m, dp = 0.02 m,
      H/dp = 3: wave height at one wavelength 92 % of the target against 79 % with
      ``coefh = 1``; ``coefh = 2`` gives the same 92 % at twice the cost). The time step grows
      with h, which pays back most of the extra neighbours in 2D.
    - ``alpha = 0.01``: the artificial viscosity of seed 001 (Roselli et al., Table 2) and of
      DualSPHysics wave cases (Altomare et al. 2017); waves are less damped than with 0.02.
    - ``boundary = "adami"`` (Adami et al. 2012; the dam break keeps DBC): a DBC wall's
      density remembers the water it has seen, so a crest cannot climb a wall that started
      dry and the waterline on a wall is pumped down (docs/wave-flume.md, "Walls that
      remember"). Measured: flume3d's wave at a side wall had 25 % of its height with DBC and
      the same height as on the centre line with Adami's walls; flume2d at H/dp = 5 keeps
      98 % / 95 % / 92 % of the height at 1 / 2 / 3 L instead of 94 % / 91 % / 88 %.
    """

    _DIM_DEFAULTS: ClassVar[Mapping[int, Mapping[str, Any]]] = {
        2: {"coefh": 1.5},
        3: {"coefh": 1.2},
    }
    _ENERGY_MONITOR: ClassVar[bool] = False  # every flume has a paddle

    dim: int | None = None  # type: ignore[assignment]
    coefh: float | None = None  # type: ignore[assignment]
    alpha: float = 0.01
    boundary: str = "adami"
    energy_growth_limit: float | None = None  # type: ignore[assignment]
    flume: Flume
    wave: Wave
    paddle: Paddle = dataclasses.field(default_factory=Piston)
    gauges: Sequence[Gauge] = ()
    runup: bool | RunupGauge | None = None
    sample_interval: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.flume, Flume):
            raise SceneError(f"flume: expected a Flume, got {self.flume!r}")
        if not isinstance(self.wave, (RegularWave, IrregularWave, SolitaryWave, TabulatedMotion)):
            raise SceneError(
                "wave: expected a RegularWave, IrregularWave, SolitaryWave or TabulatedMotion, "
                f"got {self.wave!r}"
            )
        if not isinstance(self.paddle, (Piston, Flap)):
            raise SceneError(f"paddle: expected a Piston or a Flap, got {self.paddle!r}")
        if isinstance(self.gauges, (ElevationGauge, VelocityProbe, VelocityWindow)):
            _set(self, "gauges", (self.gauges,))
        try:
            gauges = tuple(self.gauges)
        except TypeError:
            raise SceneError(
                f"gauges: expected a sequence of gauges, got {self.gauges!r}"
            ) from None
        for i, g in enumerate(gauges):
            if not isinstance(g, (ElevationGauge, VelocityProbe, VelocityWindow)):
                raise SceneError(
                    f"gauges[{i}]: expected an ElevationGauge, VelocityProbe or VelocityWindow, "
                    f"got {g!r}"
                )
        _set(self, "gauges", gauges)
        if self.runup is not None and not isinstance(self.runup, (bool, RunupGauge)):
            raise SceneError(f"runup: expected True, False, None or a RunupGauge, got "
                             f"{self.runup!r}")
        if self.dim is None:
            _set(self, "dim", self.flume.dim)
        elif self.dim != self.flume.dim:
            raise SceneError(
                f"dim: {self.dim!r} does not match the flume ({self.flume.dim}D: width = "
                f"{self.flume.width!r})"
            )
        _positive("gravity", self.gravity)
        if self.dp is not None:
            _positive("dp", self.dp)
        if self.sample_interval is not None:
            _set(self, "sample_interval", _positive("sample_interval", self.sample_interval))
        if self.until is not None:
            _positive("until", self.until)
        self._check_wave_and_paddle()
        if self.dp is None:
            _set(self, "dp", self._default_dp())
        if self.sample_interval is None:
            _set(self, "sample_interval", self._default_sample_interval())
        if self.until is None:
            _set(self, "until", self._default_until())
        super().__post_init__()
        if isinstance(self.wave, RegularWave):
            wt.warn_if_invalid_wave(
                self.wave.height,
                self.wave.period,
                self.flume.depth,
                self.paddle.order,
                "piston" if isinstance(self.paddle, Piston) else "flap",
                self.gravity,
            )

    # -- checks ---------------------------------------------------------------------------------

    def _check_wave_and_paddle(self) -> None:
        """Combinations of wave and paddle the generation theory does not cover."""
        wave, paddle, depth = self.wave, self.paddle, self.flume.depth
        if isinstance(paddle, Flap) and paddle.hinge_z is not None and paddle.hinge_z >= depth:
            raise SceneError(
                f"paddle.hinge_z: the hinge ({paddle.hinge_z:g} m) must be below the still-water "
                f"level (depth = {depth:g} m)"
            )
        if isinstance(paddle, Piston) and paddle.order == 2 and not isinstance(wave, RegularWave):
            raise SceneError(
                "paddle.order: second-order (Madsen 1971) generation is for regular waves only; "
                "use order=1"
            )
        if isinstance(wave, SolitaryWave) and not isinstance(paddle, Piston):
            raise SceneError("paddle: a solitary wave (Goring 1978) needs a Piston")
        if isinstance(wave, SolitaryWave) and wave.height > SOLITARY_MAX_H_OVER_D * depth:
            raise SceneError(
                f"wave.height: H/d = {wave.height / depth:.3g} is above the highest solitary "
                f"wave, H/d = {SOLITARY_MAX_H_OVER_D} (Longuet-Higgins & Fenton 1974)"
            )

    def _validate_geometry(self) -> None:
        flume = self.flume
        dp = _positive("dp", self.dp)
        if flume.dim != self.dim:
            raise SceneError(f"dim: {self.dim!r} does not match the flume ({flume.dim}D)")
        _positive("sample_interval", self.sample_interval)
        if flume.depth < 2.0 * dp * (1.0 - 1e-9):
            raise SceneError(
                f"dp: {dp:g} m leaves fewer than 2 particles across the water depth "
                f"(depth = {flume.depth:g} m)"
            )
        if flume.width is not None and flume.width < 2.0 * dp * (1.0 - 1e-9):
            raise SceneError(
                f"dp: {dp:g} m leaves fewer than 2 particles across the flume width "
                f"(width = {flume.width:g} m)"
            )
        if flume.length < 4.0 * dp:
            raise SceneError(f"dp: {dp:g} m is too coarse for a flume {flume.length:g} m long")
        self._check_lattice()
        across = 1.0 if flume.width is None else flume.width / dp
        n_fluid = flume.length / dp * flume.depth / dp * across
        if not n_fluid <= MAX_PARTICLES:
            raise SceneError(f"dp: {dp:g} m would need about {n_fluid:.3g} fluid particles; "
                             "use a larger dp")
        law = self.law
        if not (math.isfinite(law.forward) and math.isfinite(law.backward)):
            raise SceneError(f"wave: the paddle motion is not finite (excursion {law.forward!r} m)")
        if law.forward + 2.0 * dp >= flume.length:
            raise SceneError(
                f"paddle: its forward excursion ({law.forward:.4g} m, plus 2 dp) reaches the "
                f"far wall (length = {flume.length:g} m); lower the wave height or lengthen "
                "the flume"
            )
        height = self.tank_height
        px, pz = self.bed_profile
        # The bed must be flat where the paddle moves.
        reach = law.forward + 2.0 * dp
        if np.max(_bed(px, pz, np.linspace(0.0, reach, 50))) > 0.0 or self._mesh_in_reach(reach):
            raise SceneError(
                f"beach: the bed rises within the paddle's reach (x < {reach:.3g} m, the forward "
                "stroke plus 2 dp); move the beach away from the paddle"
            )
        if max(pz, default=0.0) > height + _TOL:
            raise SceneError(
                f"beach.z: the bed rises to {max(pz):g} m, above the walls (height = {height:g} m)"
            )
        if self.damping_zone is not None:
            x0, _ = self.damping_zone
            if x0 <= 0.0:
                raise SceneError(
                    f"damping.length: the zone covers the whole flume (it starts at x = {x0:g} m)"
                )
        names: set[str] = set()
        for i, (g, name) in enumerate(zip(self.gauges, self._gauge_names(), strict=True)):
            self._check_gauge(i, g)
            if name in names:
                raise SceneError(f"gauges[{i}].name: duplicate gauge name {name!r}")
            names.add(name)
        runup = self.runup_gauge
        if runup is not None:
            if runup.name in names:
                raise SceneError(f"runup.name: {runup.name!r} is also the name of a gauge")
            assert runup.start is not None and runup.end is not None
            for label, point in (("runup.start", runup.start), ("runup.end", runup.end)):
                self._check_point(label, point)
        elif self.runup is True or isinstance(self.runup, RunupGauge):
            raise SceneError(
                "runup: the bed does not reach the still-water level, so there is no slope to "
                "lay a run-up gauge on; give a RunupGauge(start, end) or runup=False"
            )

    def _check_lattice(self) -> None:
        """The water must be as deep (and, in 3D, as wide) as asked.

        The core fills the fluid box with whole lattice layers (:func:`lattice_layers`): a depth
        of 70.5 dp becomes 70 dp of water, and the paddle law, the wave-theory targets and the
        gauge zeroing, all computed for the depth asked, would then be wrong (measured: kimmoun2d
        at dp 0.05 filled 0.700 m instead of 0.705). Only the still-water depth at the paddle
        matters (the bed is flat there, z = 0; a beach or mesh cutting the water further on does
        not change it). Across a 3D flume the lattice also fills whole columns between the side
        walls at y = 0 and y = width (a width of 12.5 dp holds 12 dp of water beside an empty
        lattice row, 12.6 dp holds 13 dp of water pressed against the wall), so the width must
        be a whole number of dp too.
        """
        flume, dp = self.flume, float(self.dp)  # type: ignore[arg-type]
        if not _whole(flume.depth, dp):
            raise SceneError(_lattice_error("dp", "water depth", flume.depth, dp, "layers"))
        if flume.width is not None and not _whole(flume.width, dp):
            raise SceneError(_lattice_error("width", "flume width", flume.width, dp, "columns"))

    def _mesh_in_reach(self, reach: float) -> bool:
        """Whether a mesh beach rises above the floor at x < ``reach`` anywhere across the
        flume (a vertex there, or the bed under a grid of dp/2 over that strip)."""
        beach = self.flume.beach
        if not isinstance(beach, MeshBeach):
            return False
        assert self.flume.width is not None
        tol = 1e-6 * max(self.flume.length, 1.0)
        pts = beach.points
        if np.any((pts[:, 0] < reach) & (pts[:, 2] > tol)):
            return True
        step = 0.5 * float(self.dp)  # type: ignore[arg-type]
        xs = np.linspace(0.0, reach, max(2, math.ceil(reach / step) + 1))
        ys = np.linspace(0.0, self.flume.width, max(2, math.ceil(self.flume.width / step) + 1))
        gx, gy = np.meshgrid(xs, ys)
        return bool(np.max(beach.bed(gx, gy)) > tol)

    def _check_point(self, label: str, point: Sequence[float], vertical: bool = True) -> None:
        """A point (x, z) / (x, y, z) inside the flume, or SceneError naming ``label``."""
        flume = self.flume
        if len(point) != self.dim:
            raise SceneError(f"{label}: needs {self.dim} coordinates in {self.dim}D, got "
                             f"{len(point)}")
        x = point[0]
        if not -_TOL <= x <= flume.length + _TOL:
            raise SceneError(
                f"{label}: x = {x:g} m lies outside the flume [0, {flume.length:g}] m"
            )
        if self.dim == 3:
            assert flume.width is not None
            y = point[1]
            if not -_TOL <= y <= flume.width + _TOL:
                raise SceneError(
                    f"{label}: y = {y:g} m lies outside the flume width [0, {flume.width:g}] m"
                )
        if vertical:
            z = point[-1]
            if not -_TOL <= z <= self.tank_height + _TOL:
                raise SceneError(
                    f"{label}: z = {z:g} m lies outside the flume height "
                    f"[0, {self.tank_height:g}] m"
                )

    def _check_gauge(self, i: int, g: Gauge) -> None:
        flume = self.flume
        if isinstance(g, ElevationGauge):
            if not -_TOL <= g.x <= flume.length + _TOL:
                raise SceneError(
                    f"gauges[{i}].x: x = {g.x:g} m lies outside the flume [0, {flume.length:g}] m"
                )
            if self.dim == 2 and g.y is not None:
                raise SceneError(f"gauges[{i}].y: only used in 3D; leave it unset in 2D")
            if self.dim == 3 and g.y is not None:
                assert flume.width is not None
                if not -_TOL <= g.y <= flume.width + _TOL:
                    raise SceneError(
                        f"gauges[{i}].y: y = {g.y:g} m lies outside the flume width "
                        f"[0, {flume.width:g}] m"
                    )
        elif isinstance(g, VelocityProbe):
            for j, p in enumerate(g.points):
                self._check_point(f"gauges[{i}].points[{j}]", p)
        else:
            self._check_point(f"gauges[{i}].min", g.min)
            self._check_point(f"gauges[{i}].max", g.max)

    # -- derived quantities ---------------------------------------------------------------------

    @property
    def layers(self) -> int:
        """Wall thickness in particle layers (``boundary_layers`` or ``ceil(2h / dp)``)."""
        if self.boundary_layers is not None:
            return int(self.boundary_layers)
        return math.ceil(2.0 * self.smoothing_length / float(self.dp) - 1e-9)  # type: ignore[arg-type]

    @property
    def period(self) -> float | None:
        """The wave period [s] (peak period for irregular waves; None otherwise)."""
        return self.law.period

    @property
    def design_height(self) -> float | None:
        """Height used to size the flume [m] (H; 1.8 hs for irregular waves; None if unknown)."""
        wave = self.wave
        if isinstance(wave, (RegularWave, SolitaryWave)):
            return wave.height
        if isinstance(wave, IrregularWave):
            return 1.8 * wave.hs
        return None

    @property
    def wavelength(self) -> float | None:
        """Linear wavelength at the paddle depth [m] for the (peak) period, or None."""
        if self.period is None:
            return None
        return float(wt.wavelength(self.period, self.flume.depth, self.gravity))

    @property
    def tank_height(self) -> float:
        """Height of the tank walls [m]: the flume's, or ``depth + max(depth/2, 3 H)`` rounded up
        to a whole dp (and at least the highest point of a profile beach)."""
        flume = self.flume
        if flume.height is not None:
            return flume.height
        h = self.design_height or 0.0
        height = flume.depth + max(0.5 * flume.depth, 3.0 * h)
        if isinstance(flume.beach, ProfileBeach):
            height = max(height, max(flume.beach.z))
        if isinstance(flume.beach, MeshBeach):
            height = max(height, float(flume.beach.bounds[1][2]))
        dp = float(self.dp)  # type: ignore[arg-type]
        return math.ceil(height / dp - 1e-9) * dp

    @functools.cached_property
    def bed_profile(self) -> tuple[list[float], list[float]]:
        """Bed vertices ``(x, z)`` [m] of the beach (empty lists for a flat floor); for a
        :class:`MeshBeach`, along the flume's centre line."""
        beach = self.flume.beach
        if beach is None:
            return [], []
        if isinstance(beach, MeshBeach):
            assert self.flume.width is not None
            return beach.profile(self.flume.length, self.tank_height, y=0.5 * self.flume.width)
        return beach.profile(self.flume.length, self.tank_height)

    def bed(self, x: npt.ArrayLike, y: npt.ArrayLike | None = None) -> npt.NDArray[np.float64]:
        """Bed height above the floor at ``x`` [m] (under ``(x, y)`` for a :class:`MeshBeach`,
        ``y`` defaulting to the centre line; the other beaches are uniform across)."""
        beach = self.flume.beach
        if isinstance(beach, MeshBeach):
            assert self.flume.width is not None
            yy = 0.5 * self.flume.width if y is None else y
            return beach.bed(x, yy)
        px, pz = self.bed_profile
        if not px:
            return np.zeros_like(np.asarray(x, dtype=np.float64))
        return _bed(px, pz, x)

    def still_depth(self, x: npt.ArrayLike, y: npt.ArrayLike | None = None
                    ) -> npt.NDArray[np.float64]:
        """Still-water depth at ``x`` (and ``y``, see :meth:`bed`) [m] (negative where the bed
        is above the SWL)."""
        return self.flume.depth - self.bed(x, y)

    @property
    def beach_slope(self) -> float | None:
        """tan(beta) of the beach for the Iribarren number: the plane beach's slope, or the slope
        of the profile segment crossing the SWL (else the steepest rising segment); None flat."""
        beach = self.flume.beach
        if beach is None:
            return None
        if isinstance(beach, PlaneBeach):
            return beach.slope
        px, pz = (beach.x, beach.z) if isinstance(beach, ProfileBeach) else self.bed_profile
        if not px:
            return None
        seg = _shoreline_segment(px, pz, self.flume.depth)
        if seg is not None:
            x0, z0, x1, z1 = seg
            return (z1 - z0) / (x1 - x0)
        slopes = [(pz[i + 1] - pz[i]) / (px[i + 1] - px[i]) for i in range(len(px) - 1)]
        rising = [s for s in slopes if s > 0.0]
        return max(rising) if rising else None

    @property
    def toe(self) -> float:
        """x where the bed first leaves the floor [m] (the flume length for a flat floor)."""
        px, pz = self.bed_profile
        for i in range(len(px)):
            if pz[i] > 0.0:
                return px[max(i - 1, 0)] if i > 0 else px[0]
        return self.flume.length

    @property
    def shoreline(self) -> float | None:
        """x where the bed crosses the SWL [m] (last upward crossing), or None."""
        px, pz = self.bed_profile
        seg = _shoreline_segment(px, pz, self.flume.depth) if px else None
        if seg is None:
            return None
        x0, z0, x1, z1 = seg
        return x0 + (self.flume.depth - z0) * (x1 - x0) / (z1 - z0)

    @property
    def damping_zone(self) -> tuple[float, float] | None:
        """``(x_start, strength)`` of the damping zone, or None."""
        flume = self.flume
        if not flume.damping_enabled():
            return None
        zone = flume.damping if isinstance(flume.damping, DampingZone) else DampingZone()
        length = zone.length
        if length is None:
            wl = self.wavelength
            if wl is None and isinstance(self.wave, SolitaryWave):
                wl = None
            length = wl if wl is not None else 0.25 * flume.length
        return flume.length - length, zone.strength

    @functools.cached_property
    def law(self) -> _Law:
        """The paddle law (the core's JSON) and its extent."""
        # an absurd wave overflows the theory's formulas: the non-finite excursion that results
        # is refused, naming the wave, by _validate_geometry
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            return self._make_law()

    def _make_law(self) -> _Law:
        wave, paddle, depth, g = self.wave, self.paddle, self.flume.depth, self.gravity
        kind: wt.Paddle = "piston" if isinstance(paddle, Piston) else "flap"
        hinge = (paddle.hinge_z or 0.0) if isinstance(paddle, Flap) else 0.0
        if isinstance(wave, RegularWave):
            try:
                law = wt.regular_paddle_motion(
                    wave.height, wave.period, depth, kind, paddle.order, wave.phase, g
                )
            except ValueError as exc:  # pragma: no cover - inputs are checked above
                raise SceneError(f"wave: {exc}") from None
            stroke = law.stroke
            if kind == "flap" and hinge > 0.0:
                stroke = wave.height / float(flap_height_to_stroke_hinged(law.wavenumber, depth,
                                                                            hinge))
            components = [[0.5 * stroke, law.omega, law.phase]]
            if law.second_order_amplitude != 0.0:
                components.append(
                    [law.second_order_amplitude, 2.0 * law.omega, 2.0 * law.phase]
                )
            return _harmonic_law(
                components, sum(abs(c[0]) for c in components), paddle, wave.period,
                design_height=wave.height, stroke=stroke,
                second_order_amplitude=law.second_order_amplitude,
            )
        if isinstance(wave, IrregularWave):
            try:
                motion = wt.irregular_paddle_motion(
                    wave.hs,
                    wave.tp,
                    depth,
                    SPECTRA[wave.spectrum],  # type: ignore[arg-type]
                    wave.gamma,
                    wave.seed,
                    wave.random_amplitudes,
                    kind,
                    wave.frequency_range,  # type: ignore[arg-type]
                    wave.repeat_period,
                    g,
                )
            except ValueError as exc:
                raise SceneError(f"wave: {exc}") from None
            amplitudes = np.asarray(motion.stroke_amplitudes)
            if kind == "flap" and hinge > 0.0:
                amplitudes = np.asarray(motion.wave_amplitudes) / flap_height_to_stroke_hinged(
                    motion.wavenumbers, depth, hinge
                )
            omegas = 2.0 * np.pi * np.asarray(motion.frequencies)
            components = [
                [float(a), float(w), float(p)]
                for a, w, p in zip(amplitudes, omegas, motion.phases, strict=True)
            ]
            # The core sizes the room behind the paddle with the sum of the amplitudes (a bound
            # of any harmonic law), far above the signal's actual extremes for hundreds of
            # components; the tank must satisfy that bound.
            bound = float(np.sum(np.abs(amplitudes)))
            return _harmonic_law(components, bound, paddle, wave.tp, design_height=1.8 * wave.hs)
        if isinstance(wave, SolitaryWave):
            try:
                duration = float(wt.solitary_piston_duration(wave.height, depth,
                                                             wave.truncation, g))
                t = np.linspace(0.0, duration, wave.samples)
                x, _ = wt.solitary_piston_motion(t, wave.height, depth, wave.truncation, g)
            except ValueError as exc:
                raise SceneError(f"wave: {exc}") from None
            x_arr = np.asarray(x, dtype=np.float64)
            return _Law(
                law={"type": "table", "t": (t + wave.delay).tolist(), "x": x_arr.tolist()},
                backward=0.0,
                forward=float(x_arr.max()),
                ramp_duration=wave.delay,
                period=None,
                design_height=wave.height,
                stroke=float(x_arr[-1]),
                duration=duration,
            )
        assert isinstance(wave, TabulatedMotion)
        xs = np.asarray(wave.x)
        return _Law(
            law={"type": "table", "t": list(wave.t), "x": list(wave.x)},
            backward=max(0.0, float(-xs.min())),
            forward=max(0.0, float(xs.max())),
            ramp_duration=0.0,
            period=None,
            design_height=None,
            duration=wave.t[-1],
        )

    @property
    def back_x(self) -> float:
        """x of the tank's back wall face [m]: a whole number of dp behind the paddle face, far
        enough for the paddle plate and its largest backward excursion (for a flap, the
        excursion of the plate's top, which swings further than the still-water level)."""
        dp = float(self.dp)  # type: ignore[arg-type]
        back = self.law.backward
        if isinstance(self.paddle, Flap):
            hinge = self.paddle.hinge_z or 0.0
            back *= (self.tank_height - hinge) / (self.flume.depth - hinge)
        n = math.ceil((self.layers * dp + back) / dp - 1e-9) + 1
        return round(-n * dp, 12)

    def _default_dp(self) -> float:
        depth = self.flume.depth
        h = self.design_height
        dp = depth / 15.0 if h is None else min(depth / 15.0, h / 4.0)
        if self.flume.dim == 3:
            dp = max(dp, depth / 8.0)
        # a whole number of layers, so the water is as deep (and wide) as asked
        return lattice_dp(depth, dp, self.flume.width)

    def _default_sample_interval(self) -> float:
        wave = self.wave
        if isinstance(wave, RegularWave):
            return min(wave.period / 40.0, 0.05)
        if isinstance(wave, IrregularWave):
            return min(wave.tp / 40.0, 0.05)
        if isinstance(wave, SolitaryWave):
            return min(math.sqrt(self.flume.depth / self.gravity) / 4.0, 0.05)
        return 0.02

    def _far_x(self) -> float:
        """Where the analysis needs waves: the last gauge, or the shoreline, or the flume end."""
        xs = [g.x for g in self.gauges if isinstance(g, ElevationGauge)]
        xs += [p[0] for g in self.gauges if isinstance(g, VelocityProbe) for p in g.points]
        if xs:
            return max(xs)
        shore = self.shoreline
        return shore if shore is not None else 0.75 * self.flume.length

    def _default_until(self) -> float:
        wave = self.wave
        far = self._far_x()
        if isinstance(wave, RegularWave):
            return self.law.ramp_duration + self.arrival_time(far) + 10.0 * wave.period
        if isinstance(wave, IrregularWave):
            return self.law.ramp_duration + self.arrival_time(far) + 50.0 * wave.tp
        if isinstance(wave, SolitaryWave):
            assert self.law.duration is not None
            c = float(wt.solitary_celerity(wave.height, self.flume.depth, self.gravity))
            return wave.delay + self.law.duration + 2.0 * self.flume.length / c
        assert isinstance(wave, TabulatedMotion)
        return wave.t[-1] + self.flume.length / math.sqrt(self.gravity * self.flume.depth)

    def arrival_time(self, x: float) -> float:
        """Time for the wave to travel from the paddle to ``x`` [s] (after the ramp).

        Linear group velocity at the local still-water depth for periodic waves (the front of
        a wave train travels at it), ``sqrt(g (d + H))`` for a solitary wave, ``sqrt(g d)``
        otherwise; integrated along the bed, stopping where the depth falls below 1 % of the
        paddle depth (the shoreline).
        """
        depth, g = self.flume.depth, self.gravity
        xs = np.linspace(0.0, max(float(x), 0.0), 400)
        d_local = np.asarray(self.still_depth(xs))
        wet = d_local > 0.01 * depth
        if not np.any(wet):
            return 0.0
        d_wet = np.where(wet, d_local, 0.01 * depth)
        if self.period is not None:
            speed = np.asarray(wt.group_velocity(self.period, d_wet, g))
        elif isinstance(self.wave, SolitaryWave):
            speed = np.sqrt(g * (d_wet + self.wave.height))
        else:
            speed = np.sqrt(g * d_wet)
        inv = np.where(wet, 1.0 / speed, 0.0)
        if xs.size < 2:
            return 0.0
        return float(np.sum(0.5 * (inv[1:] + inv[:-1]) * np.diff(xs)))

    # -- gauges ---------------------------------------------------------------------------------

    def _gauge_names(self) -> list[str]:
        """Names of :attr:`gauges` (defaults by position or index, deduplicated with ``_2``...)."""
        names: list[str] = []
        taken = {g.name for g in self.gauges if g.name is not None}
        counters = {"velocity": 0, "window": 0}
        for g in self.gauges:
            if g.name is not None:
                names.append(g.name)
                continue
            if isinstance(g, ElevationGauge):
                base = f"eta_x{g.x:.3f}"
                if self.dim == 3:
                    base += f"_y{self._gauge_y(g):.3f}"
            elif isinstance(g, VelocityProbe):
                base = f"velocity{counters['velocity']}"
                counters["velocity"] += 1
            else:
                base = f"window{counters['window']}"
                counters["window"] += 1
            name, k = base, 2
            while name in taken:
                name, k = f"{base}_{k}", k + 1
            taken.add(name)
            names.append(name)
        return names

    def _gauge_y(self, g: ElevationGauge) -> float:
        assert self.flume.width is not None
        return 0.5 * self.flume.width if g.y is None else g.y

    @property
    def runup_gauge(self) -> RunupGauge | None:
        """The run-up gauge with its segment resolved (automatic or given), or None."""
        if self.runup is False:
            return None
        if isinstance(self.runup, RunupGauge) and self.runup.start is not None:
            return self.runup
        spec = self.runup if isinstance(self.runup, RunupGauge) else RunupGauge()
        seg = self._auto_runup_segment()
        if seg is None:
            return None
        start, end = seg
        return dataclasses.replace(spec, start=start, end=end)

    def _auto_runup_segment(self) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
        """A segment ``RUNUP_OFFSET_DP`` dp above the slope crossing the SWL, from well below the
        lowest expected run-down (``max(2 H, 6 dp)`` below the SWL, not below the slope's
        foot) to the top of that slope segment (at most the tank top)."""
        px, pz = self.bed_profile
        if not px:
            return None
        depth = self.flume.depth
        seg = _shoreline_segment(px, pz, depth)
        if seg is None:
            return None
        x0, z0, x1, z1 = seg
        dp = float(self.dp)  # type: ignore[arg-type]
        s = (z1 - z0) / (x1 - x0)
        norm = math.hypot(1.0, s)
        off = RUNUP_OFFSET_DP * dp
        nx, nz = -s / norm * off, 1.0 / norm * off
        drop = max(2.0 * (self.design_height or 0.0), 6.0 * dp)
        z_start = max(z0, depth - drop)
        z_end = min(z1, self.tank_height - nz - 0.5 * dp)
        if z_end <= depth:
            return None

        def at(z: float) -> tuple[float, float]:
            return x0 + (z - z0) / s + nx, z + nz

        (xs, zs), (xe, ze) = at(z_start), at(z_end)
        xe = min(xe, self.flume.length)
        if self.dim == 3:
            assert self.flume.width is not None
            y = 0.5 * self.flume.width
            return (xs, y, zs), (xe, y, ze)
        return (xs, zs), (xe, ze)

    def _gauge_specs(self) -> list[dict[str, Any]]:
        """The gauges in the core's JSON form (runup last)."""
        specs: list[dict[str, Any]] = []
        default = float(self.sample_interval)  # type: ignore[arg-type]
        for g, name in zip(self.gauges, self._gauge_names(), strict=True):
            interval = default if g.interval is None else g.interval
            if isinstance(g, ElevationGauge):
                pos = [g.x, 0.0] if self.dim == 2 else [g.x, self._gauge_y(g), 0.0]
                specs.append({"type": "elevation", "name": name, "position": pos,
                              "method": g.method, "interval": interval})
            elif isinstance(g, VelocityProbe):
                specs.append({"type": "velocity", "name": name,
                              "points": [list(p) for p in g.points], "interval": interval})
            else:
                specs.append({"type": "window", "name": name, "min": list(g.min),
                              "max": list(g.max), "n": list(g.n), "interval": interval})
        runup = self.runup_gauge
        if runup is not None:
            assert runup.start is not None and runup.end is not None
            specs.append({
                "type": "runup",
                "name": runup.name,
                "start": list(runup.start),
                "end": list(runup.end),
                "method": runup.method,
                "interval": default if runup.interval is None else runup.interval,
            })
        return specs

    # -- scene ----------------------------------------------------------------------------------

    def _geometry(self) -> dict[str, Any]:
        flume = self.flume
        height = self.tank_height
        back = self.back_x
        if self.dim == 2:
            tank = {"min": [back, 0.0], "max": [flume.length, height]}
            fluid = {"min": [0.0, 0.0], "max": [flume.length, flume.depth]}
        else:
            assert flume.width is not None
            tank = {"min": [back, 0.0, 0.0], "max": [flume.length, flume.width, height]}
            fluid = {"min": [0.0, 0.0, 0.0], "max": [flume.length, flume.width, flume.depth]}
        obstacles: list[dict[str, Any]] = []
        px, pz = self.bed_profile
        if isinstance(flume.beach, MeshBeach):
            obstacles.append(flume.beach.to_core())
        elif px:
            obstacles.append({"shape": "profile", "x": list(px), "z": list(pz)})
        paddle: dict[str, Any] = {
            "kind": "piston" if isinstance(self.paddle, Piston) else "flap",
            "x": 0.0,
            "hinge_z": None,
            "swl_z": None,
            "law": self.law.law,
        }
        if isinstance(self.paddle, Flap):
            paddle["hinge_z"] = float(self.paddle.hinge_z or 0.0)
            paddle["swl_z"] = float(flume.depth)
        scene: dict[str, Any] = {
            "tank": tank,
            "obstacles": obstacles,
            "fluid": [fluid],
            "paddle": paddle,
            "gauges": self._gauge_specs(),
        }
        zone = self.damping_zone
        if zone is not None:
            scene["damping"] = {"x_start": zone[0], "x_end": flume.length, "strength": zone[1]}
        return scene

    def build(self) -> FlumeSimulation:  # type: ignore[override]
        """Build the particles: a ready :class:`FlumeSimulation`."""
        return FlumeSimulation(self)

    def describe(self) -> dict[str, Any]:
        """What the analysis and reports need to know about the set-up (JSON-ready)."""
        law = self.law
        info: dict[str, Any] = {
            "type": type(self.wave).__name__,
            "paddle": type(self.paddle).__name__.lower(),
            "order": self.paddle.order,
            "period": law.period,
            "height": law.design_height if not isinstance(self.wave, IrregularWave) else None,
            "wavelength": self.wavelength,
            "ramp_duration": law.ramp_duration,
            "stroke": law.stroke,
            "second_order_amplitude": law.second_order_amplitude,
        }
        if isinstance(self.wave, IrregularWave):
            info.update(hs=self.wave.hs, tp=self.wave.tp, spectrum=self.wave.spectrum)
        if isinstance(self.wave, RegularWave) and self.wavelength is not None:
            info["steepness"] = self.wave.height / self.wavelength
            info["ursell"] = float(wt.ursell_number(self.wave.height, self.wave.period,
                                                    self.flume.depth, self.gravity))
            info["kd"] = 2.0 * math.pi / self.wavelength * self.flume.depth
        return info


# ------------------------------------------------------------------------------------------------
# results


@dataclass(frozen=True)
class VelocityRecord:
    """A velocity probe or window record.

    Attributes:
        name: the gauge name.
        t: sample times (n,) [s].
        points: sampled points (p, dim) [m].
        velocity: (n, p, dim) [m/s]; for windows reshaped to ``(n, *reversed(shape), dim)``.
        kernel_sum: (n, p) kernel volume sum (about 1 in the water, 0 outside): mask samples
            with ``kernel_sum < 0.5`` as dry. Windows: ``(n, *reversed(shape))``.
        shape: the window's points per axis (x first), or None for probes.
    """

    name: str
    t: npt.NDArray[np.float64]
    points: npt.NDArray[np.float64]
    velocity: npt.NDArray[np.float64]
    kernel_sum: npt.NDArray[np.float64]
    shape: tuple[int, ...] | None


class FlumeGauges:
    """Gauge records of a flume run as NumPy arrays (a snapshot taken when created).

    Attributes:
        names: elevation gauge names, in scene order.
        x: (g,) gauge positions along the flume [m]; y: (g,) across (3D) or None.
        still_depth: (g,) still-water depth at each gauge [m] (<= 0 on a dry beach).
        t: (n,) sample times of the elevation gauges [s].
        elevation: (n, g) surface elevation above the SWL [m], each gauge zeroed on its
            still-water reading at t = 0 (see :attr:`zero_offsets`); NaN when no water was found.
        elevation_raw: (n, g) the core's surface height minus the depth [m], not zeroed.
        zero_offsets: (g,) the still-water readings subtracted [m] (a fraction of dp).
        runup_t, runup: run-up record [s], [m above the SWL], zeroed on its reading at rest
            (``runup_offset``; ``runup_raw`` is not zeroed); None without a run-up gauge.
        runup_name: the run-up gauge's name, or None.
        velocity: velocity probes by name (:class:`VelocityRecord`).
        windows: velocity windows by name (:class:`VelocityRecord`).
    """

    def __init__(self, setup: FlumeScene, records: list[dict[str, Any]]) -> None:
        depth = setup.flume.depth
        self.setup = setup
        elevation = [r for r in records if r["type"] == "elevation"]
        specs = {s["name"]: s for s in setup._gauge_specs()}
        self.names: tuple[str, ...] = tuple(str(r["name"]) for r in elevation)
        self.x = np.array([specs[n]["position"][0] for n in self.names], dtype=np.float64)
        self.y = (
            np.array([specs[n]["position"][1] for n in self.names], dtype=np.float64)
            if setup.dim == 3 else None
        )
        self.still_depth = np.asarray(setup.still_depth(self.x, self.y), dtype=np.float64)
        if elevation:
            t = np.asarray(elevation[0]["t"], dtype=np.float64)
            cols = []
            for r in elevation:
                tr = np.asarray(r["t"], dtype=np.float64)
                zr = np.asarray(r["z"], dtype=np.float64) - depth
                if tr.shape != t.shape or not np.array_equal(tr, t):
                    zr = np.interp(t, tr, zr) if tr.size else np.full(t.shape, np.nan)
                cols.append(zr)
            self.t = t
            self.elevation_raw = np.stack(cols, axis=1)
        else:
            self.t = np.zeros(0)
            self.elevation_raw = np.zeros((0, 0))
        self.zero_offsets = self._zero_offsets(setup)
        self.elevation = self.elevation_raw - self.zero_offsets
        runup = [r for r in records if r["type"] == "runup"]
        self.runup_offset = 0.0
        if runup:
            self.runup_name: str | None = str(runup[0]["name"])
            self.runup_t: npt.NDArray[np.float64] | None = np.asarray(runup[0]["t"], dtype=float)
            raw = np.asarray(runup[0]["z"], dtype=np.float64) - depth
            if self.runup_t.size and abs(self.runup_t[0]) <= 1e-12 and np.isfinite(raw[0]):
                self.runup_offset = float(raw[0])
            self.runup_raw: npt.NDArray[np.float64] | None = raw
            self.runup: npt.NDArray[np.float64] | None = raw - self.runup_offset
        else:
            self.runup_name, self.runup_t, self.runup, self.runup_raw = None, None, None, None
        self.velocity: dict[str, VelocityRecord] = {}
        self.windows: dict[str, VelocityRecord] = {}
        for r in records:
            if r["type"] not in ("velocity", "window"):
                continue
            vel = np.asarray(r["velocity"], dtype=np.float64)
            ksum = np.asarray(r["kernel_sum"], dtype=np.float64)
            shape = tuple(int(v) for v in r.get("shape") or ()) or None
            if r["type"] == "window" and shape is not None:
                grid = tuple(reversed(shape[: setup.dim]))
                vel = vel.reshape((vel.shape[0], *grid, setup.dim))
                ksum = ksum.reshape((ksum.shape[0], *grid))
            rec = VelocityRecord(
                name=str(r["name"]),
                t=np.asarray(r["t"], dtype=np.float64),
                points=np.asarray(r["points"], dtype=np.float64),
                velocity=vel,
                kernel_sum=ksum,
                shape=shape if r["type"] == "window" else None,
            )
            (self.windows if r["type"] == "window" else self.velocity)[rec.name] = rec

    def _zero_offsets(self, setup: FlumeScene) -> npt.NDArray[np.float64]:
        """Each gauge's still-water reading (t = 0): what it reads above the SWL at rest.

        A surface gauge reads the still water a fraction of dp off the SWL (the kernel method
        finds where the kernel volume sum falls to 0.5, about 0.4 dp above the top particle
        row's nominal surface). Like a laboratory gauge zeroed in still water before the run,
        each gauge's reading at t = 0 is subtracted; gauges too shallow at rest (less than 3 dp
        of water, or dry) take the median offset of the others (0 if none).
        """
        n = len(self.names)
        if n == 0 or self.t.size == 0 or abs(self.t[0]) > 1e-12:
            return np.zeros(n)
        first = self.elevation_raw[0]
        deep = (self.still_depth > 3.0 * float(setup.dp)) & np.isfinite(first)  # type: ignore[arg-type]
        if not np.any(deep):
            return np.zeros(n)
        fallback = float(np.median(first[deep]))
        return np.where(deep, first, fallback)

    @property
    def bed_elevation(self) -> npt.NDArray[np.float64]:
        """(g,) bed level at each gauge relative to the SWL [m] (``-still_depth``)."""
        return -self.still_depth

    @property
    def elevation_filled(self) -> npt.NDArray[np.float64]:
        """:attr:`elevation` with dry samples (NaN) replaced by the bed level: what a gauge
        standing on the beach reads (the convention of envelopes and set-up)."""
        if self.elevation.size == 0:
            return self.elevation.copy()
        bed = np.broadcast_to(self.bed_elevation, self.elevation.shape)
        return np.where(np.isnan(self.elevation), bed, self.elevation)

    def runup_on(self, t: npt.ArrayLike) -> npt.NDArray[np.float64] | None:
        """The run-up record interpolated on times ``t`` [s] (None without run-up gauge)."""
        if self.runup is None or self.runup_t is None:
            return None
        tt = np.asarray(t, dtype=np.float64)
        if self.runup_t.shape == tt.shape and np.array_equal(self.runup_t, tt):
            return self.runup.copy()
        return np.interp(tt, self.runup_t, self.runup) if self.runup_t.size else None

    def uniform(
        self, dt: float | None = None
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64] | None]:
        """``(t, elevation_filled, runup)`` linearly resampled on a uniform time grid.

        The core samples at the first step past each sample time, so recorded times jitter by
        less than one time step; spectral analysis wants them uniform. ``dt`` defaults to the
        scene's ``sample_interval``.
        """
        step = float(self.setup.sample_interval if dt is None else dt)  # type: ignore[arg-type]
        if self.t.size < 2:
            return self.t.copy(), self.elevation_filled, self.runup_on(self.t)
        n = math.floor((self.t[-1] - self.t[0]) / step + 1e-9) + 1
        grid = self.t[0] + step * np.arange(n)
        filled = self.elevation_filled
        eta = np.stack([np.interp(grid, self.t, filled[:, j]) for j in range(filled.shape[1])],
                       axis=1) if filled.shape[1] else np.zeros((n, 0))
        runup = None
        if self.runup is not None and self.runup_t is not None and self.runup_t.size >= 2:
            r = self.runup
            start_level = self._runup_start_level() - self.runup_offset
            r = np.where(np.isnan(r), start_level, r)
            runup = np.interp(grid, self.runup_t, r)
        return grid, eta, runup

    def _runup_start_level(self) -> float:
        gauge = self.setup.runup_gauge
        if gauge is None or gauge.start is None:
            return 0.0
        return float(gauge.start[-1]) - self.setup.flume.depth

    def columns(self) -> list[str]:
        """Column names of :meth:`to_csv`: ``t``, the elevation gauges, the run-up gauge."""
        cols = ["t", *self.names]
        if self.runup_name is not None:
            cols.append(self.runup_name)
        return cols

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write ``t``, one column per elevation gauge (eta above the SWL [m], ``nan`` when dry)
        and the run-up (elevation above the SWL [m]) on the elevation gauges' times.

        Written to a temporary file first and renamed, so a reader never sees half a file.
        """
        out = Path(path)
        tmp = out.with_name(out.name + ".tmp")
        runup = self.runup_on(self.t) if self.t.size else None
        with open(tmp, "w", newline="", encoding="utf-8") as f:
            writer = csv.writer(f)
            writer.writerow(self.columns())
            if self.t.size == 0 and self.runup is not None and self.runup_t is not None:
                for tk, rk in zip(self.runup_t, self.runup, strict=True):
                    writer.writerow([repr(float(tk)), repr(float(rk))])
            for i, tk in enumerate(self.t):
                row = [repr(float(tk))] + [repr(float(v)) for v in self.elevation[i]]
                if runup is not None:
                    row.append(repr(float(runup[i])))
                writer.writerow(row)
        tmp.replace(out)
        return out


class FlumeSimulation(Simulation):
    """A flume run: a :class:`~watersim.Simulation` that knows its flume, with gauges as NumPy,
    CSV output and the wave analysis.

    Args:
        setup: the :class:`FlumeScene`.
    """

    def __init__(self, setup: FlumeScene) -> None:
        super().__init__(setup.to_scene())
        self.setup = setup
        self._gauges_cache: tuple[int, FlumeGauges] | None = None
        self.overturns: list[tuple[float, an.Overturn]] = []
        """Overturned free surfaces seen over the beach, ``(time [s], overturn)``: with a beach,
        :meth:`run` looks for one in every ``sample_interval``
        (:func:`watersim.analysis.overturned_surface`, from the toe to the far wall)."""
        self.overturn_checks = 0
        """Snapshots searched for an overturned surface so far."""
        self._dp = float(self.params()["dp"])

    @property
    def gauges(self) -> FlumeGauges:
        """The gauge records so far (:class:`FlumeGauges`)."""
        if self._gauges_cache is None or self._gauges_cache[0] != self.steps:
            self._gauges_cache = (self.steps, FlumeGauges(self.setup, self._sim.gauges()))
        return self._gauges_cache[1]

    def run(  # type: ignore[override]
        self,
        until: float | None = None,
        progress: bool = False,
        callback_every: float | None = None,
        callback: Callable[[Simulation], None] | None = None,
    ) -> None:
        """Advance to ``until`` [s] (default the scene's ``until``).

        Args:
            until: end time [s].
            progress: show a progress bar on stderr (see :meth:`watersim.Simulation.run`).
            callback_every, callback: as :meth:`watersim.Simulation.run`.

        Raises:
            InstabilityError: a stability monitor stopped the run; the gauge records up to the
                last good step stay readable (:attr:`gauges`).
        """
        end = float(self.setup.until if until is None else until)  # type: ignore[arg-type]
        super().run(end, callback_every=callback_every, callback=callback, progress=progress)

    def _monitors(self) -> list[tuple[float, Callable[[Simulation], Any]]]:
        # a plunging breaker shows as a jet over air; only a beach makes one
        if self.setup.flume.beach is None:
            return []
        return [(float(self.setup.sample_interval),  # type: ignore[arg-type, list-item]
                 FlumeSimulation._watch_overturn)]

    def _watch_overturn(self) -> None:
        """Record an overturned surface over the beach in the current state, if there is one."""
        found = an.overturned_surface(self.fluid_positions(), self._dp,
                                      x_range=(self.setup.toe, self.setup.flume.length))
        self.overturn_checks += 1
        if found is not None:
            self.overturns.append((self.time, found))

    def __repr__(self) -> str:
        setup = self.setup
        flume = setup.flume
        size = f"{flume.length:g} m long, {flume.depth:g} m deep"
        if flume.width is not None:
            size += f", {flume.width:g} m wide"
        n_gauges = len(setup.gauges) + (setup.runup_gauge is not None)
        return (
            f"{super().__repr__()[:-1]}, flume {size}, {type(setup.wave).__name__}, "
            f"{type(setup.paddle).__name__}, {n_gauges} gauges, until={setup.until:g} s)"
        )

    def write_gauges_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write ``gauges.csv`` (see :meth:`FlumeGauges.to_csv`)."""
        return self.gauges.to_csv(path)

    def analyse(self, t_start: float | None = None) -> dict[str, Any]:
        """The wave analysis of the records so far (see :func:`analyse_flume`)."""
        return analyse_flume(self.setup, self.gauges, t_start=t_start,
                             overturns=self.overturns, overturn_checks=self.overturn_checks)


# ------------------------------------------------------------------------------------------------
# analysis


def _f(value: Any) -> float | None:
    """A JSON-ready float (None for NaN/inf/None)."""
    if value is None:
        return None
    v = float(value)
    return v if math.isfinite(v) else None


def _caught(fn: Callable[[], Any], notes: list[str], what: str) -> Any:
    """Call ``fn``; turn warnings and ValueErrors into notes (the analysis never raises)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = fn()
        except ValueError as exc:
            notes.append(f"{what}: {exc}")
            result = None
    for w in caught:
        notes.append(f"{what}: {w.message}")
    return result


def _best_gauge_set(
    x: npt.NDArray[np.float64], k: float, size: int
) -> tuple[tuple[int, ...], float] | None:
    """The ``size`` gauges (indices into x) best conditioned to separate incident and reflected
    waves of wavenumber k: the largest ``(n - |sum exp(2ikx)|) / (n + |...|)``."""
    best: tuple[tuple[int, ...], float] | None = None
    for combo in itertools.islice(itertools.combinations(range(x.size), size), 5000):
        s = abs(np.sum(np.exp(2j * k * x[list(combo)])))
        cond = (size - s) / (size + s)
        if best is None or cond > best[1] + 1e-12:
            best = (combo, float(cond))
    return best


def _overturn_summary(overturns: Sequence[tuple[float, an.Overturn]], checks: int
                      ) -> dict[str, Any]:
    """JSON-ready summary of the overturned surfaces seen in ``checks`` snapshots."""
    out: dict[str, Any] = {"checks": checks, "seen": len(overturns)}
    if overturns:
        t, first = overturns[0]
        out["first"] = {"time": t, "x_min": first.x_min, "x_max": first.x_max,
                        "gap": first.z_gap_top - first.z_gap_bottom}
        out["x_min"] = min(o.x_min for _, o in overturns)
        out["x_max"] = max(o.x_max for _, o in overturns)
        out["columns"] = max(o.n_columns for _, o in overturns)
    return out


def analyse_flume(
    setup: FlumeScene,
    gauges: FlumeGauges,
    t_start: float | None = None,
    overturns: Sequence[tuple[float, an.Overturn]] = (),
    overturn_checks: int = 0,
) -> dict[str, Any]:
    """Wave analysis of a flume run, as a JSON-ready dict.

    Time windows: each gauge is analysed over its *steady part*, from the wave's arrival
    (:meth:`FlumeScene.arrival_time`) plus the ramp plus one period, to the end of the record
    (``t_start``, if given, overrides the start for every gauge). Records are resampled on a
    uniform grid of ``sample_interval`` and dry samples read the bed level.

    Keys:

    - ``wave``: the wave and paddle (type, period, height, wavelength, stroke, ...).
    - ``gauges``: per elevation gauge: ``name``, ``x`` (``y``), ``still_depth``, ``window``,
      and zero-down-crossing ``H_mean``, ``H_max``, ``H_min``, ``H_rms``, ``T_mean``,
      ``n_waves``, ``crest_mean``, ``trough_mean``, ``mean_level`` (set-up); ``H_target`` and
      ``H_rel_error`` for regular waves at gauges over the flat floor; ``harmonics`` (first three
      harmonic amplitudes [m]) for regular waves; ``hm0``, ``tp`` (spectrum) for irregular waves;
      ``eta_max`` and ``t_max`` for solitary waves and tabulated motions.
    - ``envelopes``: ``name``, ``x``, ``maximum``, ``minimum``, ``mean``, ``mid_level`` per gauge
      sorted by x (seed 001 Fig. 8), each over its steady part.
    - ``breaking`` (with a beach): ``criterion`` H/d > 0.78 from the gauges' waves, ``position``,
      ``time``, ``wave_height``, ``iribarren`` and ``breaker_type`` from that height, plus
      ``max_height_position`` / ``max_height`` (where the mean wave height peaks among the
      gauges over the slope) and ``iribarren_incident`` / ``breaker_type_incident`` from the
      target height; with ``overturn_checks`` snapshots searched
      (:attr:`FlumeSimulation.overturns`): ``overturn`` (``checks``, ``seen`` = snapshots
      with an overturned surface, the ``first`` one's ``time``, ``x_min``, ``x_max``, ``gap``,
      the ``x_min``/``x_max`` over all, the most ``columns``) and ``breaker_type_observed``:
      ``"plunging"`` when the surface overturned, else None (spilling, or no breaking
      resolved).
    - ``runup`` (with a run-up gauge): per wave (regular: ``mean``, ``std``, ``values``,
      ``mean_over_H``) or overall (``max``; ``R2`` for irregular waves).
    - ``reflection`` (regular or irregular waves, 2-3 gauges over the flat floor between the
      paddle and the beach's toe, outside the damping zone, with a usable spacing): ``method``,
      ``gauges``, ``coefficient``, ``incident_amplitude``, ``reflected_amplitude``.
    - ``notes``: what could not be computed and why.
    """
    notes: list[str] = []
    wave = setup.wave
    depth = setup.flume.depth
    g = setup.gravity
    law = setup.law
    T = law.period
    t, eta, runup = gauges.uniform()
    end = float(t[-1]) if t.size else 0.0
    result: dict[str, Any] = {
        "wave": setup.describe(),
        "still_water_depth": depth,
        "record_end": end,
        "gauges": [],
        "notes": notes,
    }

    def window_start(x: float) -> float:
        if t_start is not None:
            return float(t_start)
        extra = T if T is not None else 0.0
        return law.ramp_duration + setup.arrival_time(x) + extra

    target = wave.height if isinstance(wave, RegularWave) else None
    per_gauge: list[dict[str, Any]] = []
    means: list[float | None] = []
    for j, name in enumerate(gauges.names):
        x = float(gauges.x[j])
        entry: dict[str, Any] = {"name": name, "x": x, "still_depth": float(gauges.still_depth[j])}
        if gauges.y is not None:
            entry["y"] = float(gauges.y[j])
        t0 = window_start(x)
        sel = t >= t0
        entry["window"] = [t0, end]
        series = eta[sel, j] if eta.size else np.zeros(0)
        ts = t[sel]
        entry["n_samples"] = int(ts.size)
        mean_h: float | None = None
        if isinstance(wave, (SolitaryWave, TabulatedMotion)):
            if eta.size:
                k = int(np.argmax(eta[:, j]))
                entry.update(eta_max=_f(eta[k, j]), t_max=_f(t[k]))
        elif ts.size >= 4 and (T is None or end - t0 >= T):
            zc = _caught(functools.partial(an.zero_crossing_waves, series, ts), notes, name)
            if zc is not None:
                mean_h = float(zc.mean_height)
                entry.update(
                    H_mean=_f(zc.mean_height),
                    H_max=_f(zc.max_height),
                    H_min=_f(np.min(zc.heights)),
                    H_rms=_f(np.sqrt(np.mean(zc.heights**2))),
                    H_significant=_f(zc.significant_height),
                    T_mean=_f(zc.mean_period),
                    n_waves=int(zc.heights.size),
                    crest_mean=_f(np.mean(zc.crest_elevations)),
                    trough_mean=_f(np.mean(zc.trough_elevations)),
                )
            entry["mean_level"] = _f(np.mean(series))
            if isinstance(wave, RegularWave) and T is not None:
                harm = _caught(functools.partial(an.harmonic_analysis, series, ts, T, 3),
                               notes, name)
                if harm is not None:
                    entry["harmonics"] = [_f(a) for a in harm.amplitudes]
                if target is not None and gauges.still_depth[j] >= depth - 1e-9:
                    entry["H_target"] = target
                    if mean_h is not None:
                        entry["H_rel_error"] = (mean_h - target) / target
            if isinstance(wave, IrregularWave):
                spec = _caught(functools.partial(an.wave_spectrum, series, ts), notes, name)
                if spec is not None:
                    entry.update(hm0=_f(spec.hm0), tp=_f(spec.tp))
        else:
            notes.append(
                f"{name}: the steady part starts at t = {t0:.3g} s, after the record's end "
                f"({end:.3g} s); run longer for wave statistics"
            )
        means.append(mean_h)
        per_gauge.append(entry)
    result["gauges"] = per_gauge

    # envelopes over each gauge's steady part
    if gauges.names and eta.size:
        env: dict[str, list[Any]] = {"name": [], "x": [], "maximum": [], "minimum": [],
                                     "mean": [], "mid_level": []}
        for j in np.argsort(gauges.x, kind="stable"):
            sel = t >= window_start(float(gauges.x[j]))
            if np.count_nonzero(sel) < 2:
                sel = np.ones_like(t, dtype=bool)
            e = an.water_level_envelopes(eta[sel, j])
            env["name"].append(gauges.names[j])
            env["x"].append(float(gauges.x[j]))
            env["maximum"].append(_f(e.maximum))
            env["minimum"].append(_f(e.minimum))
            env["mean"].append(_f(e.mean))
            env["mid_level"].append(_f(e.mid_level))
        result["envelopes"] = env

    # breaking
    slope = setup.beach_slope
    if setup.flume.beach is not None and gauges.names and eta.size:
        breaking: dict[str, Any] = {}
        sel = t >= (law.ramp_duration if t_start is None else t_start)
        if np.count_nonzero(sel) >= 4:
            onset = _caught(
                lambda: an.breaking_onset_from_gauges(
                    eta[sel], t[sel], gauges.x, gauges.still_depth, slope, T, g
                ),
                notes,
                "breaking",
            )
            if onset is not None:
                breaking.update(
                    criterion=onset.criterion,
                    position=onset.position,
                    time=onset.time,
                    gauge=gauges.names[onset.index],
                    wave_height=_f(onset.wave_height),
                    iribarren=_f(onset.iribarren),
                    breaker_type=onset.breaker_type,
                )
            else:
                breaking["criterion"] = f"H/d > {wt.MCCOWAN_BREAKING_RATIO}"
                breaking["position"] = None
                notes.append("breaking: no gauge recorded a wave with H/d > 0.78")
        # where the mean wave height peaks, over the gauges on the slope (all wet ones if none)
        wet = [(j, m) for j, m in enumerate(means)
               if m is not None and 0.0 < gauges.still_depth[j] < depth - 1e-9]
        if not wet:
            wet = [(j, m) for j, m in enumerate(means)
                   if m is not None and gauges.still_depth[j] > 0.0]
        if wet:
            j_max, h_max = max(wet, key=lambda item: item[1])
            breaking["max_height_position"] = float(gauges.x[j_max])
            breaking["max_height"] = h_max
        if slope is not None and T is not None and law.design_height is not None:
            l0 = float(wt.deep_water_wavelength(T, g))
            height = wave.height if isinstance(wave, RegularWave) else law.design_height / 1.8
            xi = float(wt.iribarren(slope, height, l0))
            breaking["iribarren_incident"] = xi
            breaking["breaker_type_incident"] = str(wt.breaker_type(xi))
        breaking["slope"] = slope
        if overturn_checks:
            breaking["overturn"] = _overturn_summary(overturns, overturn_checks)
            breaking["breaker_type_observed"] = "plunging" if overturns else None
            if not overturns:
                notes.append(f"breaking: no overturned surface (a jet over air) in "
                             f"{overturn_checks} snapshots over the beach")
        result["breaking"] = breaking

    # run-up
    if runup is not None and t.size:
        info: dict[str, Any] = {"name": gauges.runup_name}
        runup_start = law.ramp_duration
        shore = setup.shoreline
        if shore is not None:
            runup_start += setup.arrival_time(shore)
        if t_start is not None:
            runup_start = t_start
        sel = t >= runup_start
        info["window"] = [runup_start, end]
        if np.count_nonzero(sel) >= 2:
            info["max"] = _f(np.max(runup[sel]))
            if isinstance(wave, RegularWave) and T is not None:
                per_wave = _caught(
                    lambda: an.runup_per_wave(runup[sel], t[sel], T, 0.0), notes, "runup"
                )
                if per_wave is not None:
                    info.update(
                        mean=per_wave.mean,
                        std=per_wave.std,
                        n_waves=int(per_wave.values.size),
                        values=[float(v) for v in per_wave.values],
                        mean_over_H=per_wave.mean / wave.height,
                        std_over_H=per_wave.std / wave.height,
                    )
            elif isinstance(wave, IrregularWave):
                info["R2"] = _f(np.percentile(runup[sel], 98.0))
        else:
            notes.append("runup: the record ends before the waves reach the shoreline")
        result["runup"] = info

    # reflection
    if isinstance(wave, (RegularWave, IrregularWave)) and T is not None and gauges.names:
        zone = setup.damping_zone
        limit = min(zone[0] if zone is not None else setup.flume.length, setup.toe)
        flat = [j for j in range(len(gauges.names))
                if gauges.still_depth[j] >= depth - 1e-9 and 0.0 < gauges.x[j] < limit
                and (gauges.y is None or abs(gauges.y[j] - gauges.y[0]) < 1e-12)]
        knum = 2.0 * math.pi / float(wt.wavelength(T, depth, g))
        xs = np.unique(gauges.x[flat]) if flat else np.zeros(0)
        flat = [next(j for j in flat if gauges.x[j] == xv) for xv in xs]
        chosen: tuple[tuple[int, ...], float] | None = None
        if len(flat) >= 3:
            chosen = _best_gauge_set(gauges.x[flat], knum, 3)
        if len(flat) >= 2 and (chosen is None or chosen[1] < an._SPACING_CONDITION_LIMIT):
            pair = _best_gauge_set(gauges.x[flat], knum, 2)
            if pair is not None and (chosen is None or pair[1] > chosen[1]):
                chosen = pair
        if chosen is None or chosen[1] < an._SPACING_CONDITION_LIMIT:
            result["reflection"] = None
            notes.append(
                "reflection: fewer than two gauges over the flat floor with a spacing away from "
                "multiples of half a wavelength"
            )
        else:
            idx = np.asarray([flat[i] for i in chosen[0]], dtype=np.intp)
            t0 = max(window_start(float(gauges.x[j])) for j in idx)
            sel = t >= t0
            method = an.mansard_funke if len(idx) == 3 else an.goda_suzuki
            kwargs: dict[str, Any] = (
                {"period": T} if isinstance(wave, RegularWave)
                else {"frequency_band": (0.5 / T, 2.0 / T)}
            )
            if np.count_nonzero(sel) >= 8 and t[-1] - t0 >= T:
                refl = _caught(
                    lambda: method(eta[np.ix_(sel, idx)], t[sel], gauges.x[idx], depth, g=g,
                                   **kwargs),
                    notes,
                    "reflection",
                )
            else:
                refl = None
                notes.append("reflection: the record is too short after the waves arrive")
            if refl is not None:
                valid = refl.valid
                inc = np.sqrt(np.sum(refl.incident_amplitudes[valid] ** 2))
                ref = np.sqrt(np.sum(refl.reflected_amplitudes[valid] ** 2))
                result["reflection"] = {
                    "method": refl.method,
                    "gauges": [gauges.names[int(j)] for j in idx],
                    "coefficient": _f(refl.reflection_coefficient),
                    "incident_amplitude": _f(inc),
                    "reflected_amplitude": _f(ref),
                    "window": [t0, end],
                }
            else:
                result["reflection"] = None
    return result

