"""The bed of the flume: plane, profile and mesh beaches, and the damping zone."""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
import numpy.typing as npt

from .. import meshbed
from .._core import SceneError
from ..checks import _non_negative, _positive
from .checks import _TOL, _finite_tuple, _set, _strictly_increasing

if TYPE_CHECKING:
    from .scene import Flume

Profile = tuple[Sequence[float], Sequence[float]]
"""Bed vertices ``(x, z)`` [m]."""


class SteepSlopeWarning(UserWarning):
    """A plane beach steeper than 1:1: more likely a slope written as run over rise (5 for 1:5)
    than a wall meant as a beach."""


class _Bed:
    """What every beach tells the flume (each beach overrides what differs)."""

    TAG: ClassVar[str]
    """The beach's ``type`` in a scene file."""
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {}
    """The allowed values of the beach's string fields."""

    def wall_top(self, height: float) -> float:
        """The tank height ``height`` [m] raised, if need be, to the bed's highest point."""
        return height

    def bed_in(self, flume: Flume, profile: Profile, x: npt.ArrayLike,
               y: npt.ArrayLike | None) -> npt.NDArray[np.float64]:
        """Bed height above the floor at ``x`` [m] (uniform across the flume)."""
        return _bed(*profile, x)

    def iribarren_slope(self, profile: Profile, level: float) -> float | None:
        """tan(beta) for the Iribarren number: the slope of the profile segment crossing
        ``level`` (else the steepest rising segment), None without one."""
        px, pz = profile
        if not px:
            return None
        seg = _shoreline_segment(px, pz, level)
        if seg is not None:
            x0, z0, x1, z1 = seg
            return (z1 - z0) / (x1 - x0)
        slopes = [(pz[i + 1] - pz[i]) / (px[i + 1] - px[i]) for i in range(len(px) - 1)]
        rising = [s for s in slopes if s > 0.0]
        return max(rising) if rising else None

    def rises_within(self, flume: Flume, reach: float, dp: float) -> bool:
        """Whether the bed rises off the floor at x < ``reach`` [m] beyond what the profile
        shows (a mesh's relief off the centre line)."""
        return False

    def to_core(self, profile: Profile | None = None) -> dict[str, Any]:
        """The core's obstacle JSON: the bed ``profile`` (``shape = "profile"``)."""
        assert profile is not None
        px, pz = profile
        return {"shape": "profile", "x": list(px), "z": list(pz)}


@dataclass(frozen=True)
class PlaneBeach(_Bed):
    """A plane (uniform) beach rising from the flume floor at ``toe`` with slope ``slope``.

    The bed is ``z = slope (x - toe)`` for x >= toe, up to the top of the tank walls, and flat at
    that height beyond (if the flume is long enough to get there).

    Attributes:
        toe: x of the toe, where the slope leaves the floor [m] (from the paddle at rest).
        slope: tan(beta), rise over run [-] (1/15 for a 1:15 beach); above 1 (steeper than
            45 degrees) gives a :class:`SteepSlopeWarning`.
    """

    toe: float
    slope: float

    TAG: ClassVar[str] = "plane"

    def __post_init__(self) -> None:
        _set(self, "toe", _non_negative("beach.toe", self.toe))
        slope = _positive("beach.slope", self.slope)
        if slope > 10.0:
            raise SceneError(f"beach.slope: tan(beta) = {slope:g} is steeper than 10; use a wall")
        if slope > 1.0:
            warnings.warn(
                f"beach.slope: tan(beta) = {slope:g} rises {math.degrees(math.atan(slope)):.0f} "
                f"degrees, steeper than 1:1; slope is rise over run, so a 1:{slope:g} beach is "
                f"slope = {1.0 / slope:.6g}", SteepSlopeWarning, stacklevel=3)
        _set(self, "slope", slope)

    def profile(self, length: float, top: float) -> tuple[list[float], list[float]]:
        """Bed vertices ``(x, z)`` [m] of this beach in a flume of ``length`` with walls ``top``
        high."""
        x_top = self.toe + top / self.slope
        if x_top >= length - _TOL:
            return [self.toe, length], [0.0, self.slope * (length - self.toe)]
        return [self.toe, x_top, length], [0.0, top, top]

    def check_in(self, flume: Flume) -> None:
        """Refuse a toe beyond the flume."""
        if self.toe >= flume.length:
            raise SceneError(
                f"beach.toe: the toe at x = {self.toe:g} m lies beyond the flume "
                f"(length = {flume.length:g} m)"
            )

    def iribarren_slope(self, profile: Profile, level: float) -> float:
        return self.slope

    def profile_in(self, flume: Flume, top: float) -> tuple[list[float], list[float]]:
        """Bed vertices ``(x, z)`` [m] in ``flume`` with walls ``top`` [m] high."""
        return self.profile(flume.length, top)


@dataclass(frozen=True)
class ProfileBeach(_Bed):
    """A piecewise-linear bed (bar, composite beach, measured bathymetry): solid below the line
    through the vertices ``(x[i], z[i])``; the flume floor (z = 0) outside ``[x[0], x[-1]]``.

    Attributes:
        x: vertex positions along the flume [m], strictly increasing, within the flume.
        z: bed heights above the flume floor [m], >= 0.
    """

    x: tuple[float, ...]
    z: tuple[float, ...]

    TAG: ClassVar[str] = "profile"

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

    def check_in(self, flume: Flume) -> None:
        """Refuse a profile beyond the flume or above its walls."""
        if self.x[-1] > flume.length + _TOL:
            raise SceneError(
                f"beach.x: the profile ends at x = {self.x[-1]:g} m, beyond the flume "
                f"(length = {flume.length:g} m)"
            )
        if flume.height is not None and max(self.z) > flume.height + _TOL:
            raise SceneError(
                f"beach.z: the bed rises to {max(self.z):g} m, above the walls "
                f"(height = {flume.height:g} m)"
            )

    def wall_top(self, height: float) -> float:
        return max(height, max(self.z))

    def profile_in(self, flume: Flume, top: float) -> tuple[list[float], list[float]]:
        """Bed vertices ``(x, z)`` [m] in ``flume`` with walls ``top`` [m] high."""
        return self.profile(flume.length, top)


@dataclass(frozen=True)
class MeshBeach(_Bed):
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

    TAG: ClassVar[str] = "mesh"

    def __post_init__(self) -> None:
        _set(self, "scale", _positive("beach.scale", self.scale))
        mesh = meshbed.ClosedMesh.load("beach", self.path, self.vertices, self.triangles,
                                       self.scale, self.offset)
        for name in ("offset", "path", "vertices", "triangles", "points", "faces", "volume"):
            _set(self, name, getattr(mesh, name))

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

    def to_core(self, profile: Profile | None = None) -> dict[str, Any]:
        """The core's obstacle JSON (``shape = "mesh"``; the profile is not needed)."""
        return {"shape": "mesh", "vertices": self.points.tolist(),
                "triangles": self.faces.tolist()}

    def check_in(self, flume: Flume) -> None:
        """A mesh beach needs a 3D flume and must lie inside it (the core would clip what lies
        outside the tank without a word)."""
        field = self.source_field
        if flume.width is None:
            raise SceneError("beach: a MeshBeach (triangle mesh) needs a 3D flume; give the "
                             "flume a width")
        lo, hi = self.bounds
        tol = 1e-6 * max(flume.length, flume.width, 1.0)  # float32 STL coordinates
        limits = [("x", 0, 0.0, flume.length, f"the flume's length [0, {flume.length:g}] m"),
                  ("y", 1, 0.0, flume.width, f"the flume's width [0, {flume.width:g}] m"),
                  ("z", 2, 0.0, math.inf, "above the floor (z >= 0)")]
        if flume.height is not None:
            limits[2] = ("z", 2, 0.0, flume.height, f"between the floor and the top of the "
                         f"walls [0, {flume.height:g}] m")
        for name, k, a, b, where in limits:
            if lo[k] < a - tol or hi[k] > b + tol:
                raise SceneError(
                    f"{field}: the mesh spans {name} = [{lo[k]:.6g}, {hi[k]:.6g}] m; it must "
                    f"lie within {where} (move it with beach.offset, scale it with beach.scale)"
                )

    def profile_in(self, flume: Flume, top: float) -> tuple[list[float], list[float]]:
        """Along the flume's centre line."""
        assert flume.width is not None
        return self.profile(flume.length, top, y=0.5 * flume.width)

    def wall_top(self, height: float) -> float:
        return max(height, float(self.bounds[1][2]))

    def bed_in(self, flume: Flume, profile: Profile, x: npt.ArrayLike,
               y: npt.ArrayLike | None) -> npt.NDArray[np.float64]:
        """Under ``(x, y)``, ``y`` defaulting to the centre line."""
        assert flume.width is not None
        return self.bed(x, 0.5 * flume.width if y is None else y)

    def rises_within(self, flume: Flume, reach: float, dp: float) -> bool:
        """A vertex at x < ``reach`` above the floor, or the bed under a grid of dp/2 over that
        strip, anywhere across the flume."""
        assert flume.width is not None
        tol = 1e-6 * max(flume.length, 1.0)
        pts = self.points
        if np.any((pts[:, 0] < reach) & (pts[:, 2] > tol)):
            return True
        step = 0.5 * dp
        xs = np.linspace(0.0, reach, max(2, math.ceil(reach / step) + 1))
        ys = np.linspace(0.0, flume.width, max(2, math.ceil(flume.width / step) + 1))
        gx, gy = np.meshgrid(xs, ys)
        return bool(np.max(self.bed(gx, gy)) > tol)


Beach = PlaneBeach | ProfileBeach | MeshBeach

BEACH_TYPES: tuple[type, ...] = (PlaneBeach, ProfileBeach, MeshBeach)
"""The beach classes a :class:`Flume` takes."""


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

