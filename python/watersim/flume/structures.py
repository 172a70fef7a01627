"""Structures in the flume: fixed solid bodies (a box, a block with a sloping face, a seawall)
that a :class:`~watersim.flume.ForceGauge` measures the load on.

Each structure is one of the core's obstacles (``scene.obstacles``), sampled into wall particles
of the scene's wall model; the flume fills only the lattice sites outside it with water. A
force gauge names its structure; the core takes the obstacle's index (after the beach's).
"""

from __future__ import annotations

import typing
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from .._core import SceneError
from .checks import _TOL, _finite_tuple, _optional_name, _set, _strictly_increasing

if TYPE_CHECKING:
    from .scene import FlumeScene

RESOLVABLE_DP = 2.0
"""A structure thinner than this many dp along any axis is not resolved by the particles."""


class _Structure:
    """What every structure tells the flume: its extent, its checks and its core obstacle."""

    TAG: ClassVar[str]
    """The structure's ``type`` in a scene file."""
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {}

    name: str

    def _check_name(self) -> None:
        _optional_name("structure.name", self.name)
        if self.name is None:
            raise SceneError("structure.name: a structure needs a name")

    def bounds(self, scene: FlumeScene) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """``(min, max)`` corners [m] of the structure's bounding box in flume coordinates."""
        raise NotImplementedError

    def thickness(self) -> dict[str, float]:
        """Each field's extent that must resolve into particles [m], by field name."""
        raise NotImplementedError

    def to_core(self, scene: FlumeScene) -> dict[str, Any]:
        """The core's obstacle JSON."""
        raise NotImplementedError

    def check_in(self, scene: FlumeScene, label: str) -> None:
        """Refuse a structure outside the flume, in the paddle's travel or thinner than
        :data:`RESOLVABLE_DP` dp, naming ``label`` (``structures[i]``) and the field."""
        flume = scene.flume
        low, high = self.extent_fields
        lo, hi = self.bounds(scene)
        if len(lo) != scene.dim:
            raise SceneError(f"{label}.{low}: a {scene.dim}D flume needs {scene.dim} "
                             f"coordinates, got {len(lo)}")
        limits = [("x", 0.0, flume.length, f"within the flume's length [0, {flume.length:g}] m")]
        if scene.dim == 3:
            assert flume.width is not None
            limits.append(("y", 0.0, flume.width,
                           f"within the flume's width [0, {flume.width:g}] m"))
        top = scene.tank_height
        limits.append(("z", 0.0, top, f"between the floor and the top of the walls "
                       f"[0, {top:g}] m"))
        for k, (axis, a, b, where) in enumerate(limits):
            if lo[k] < a - _TOL or hi[k] > b + _TOL:
                field = low if lo[k] < a - _TOL else high
                raise SceneError(f"{label}.{field}: the structure spans {axis} = "
                                 f"[{lo[k]:.6g}, {hi[k]:.6g}] m; it must lie {where}")
        dp = float(scene.dp)  # type: ignore[arg-type]
        reach = scene.law.forward + 2.0 * dp
        if lo[0] < reach:
            raise SceneError(f"{label}.{low}: the structure starts at x = {lo[0]:.6g} m, "
                             f"within the paddle's travel (x < {reach:.4g} m, the forward "
                             "stroke plus 2 dp)")
        for name, size in self.thickness().items():
            if size < RESOLVABLE_DP * dp * (1.0 - 1e-9):
                raise SceneError(f"{label}.{name}: the structure is {size:.4g} m thick there, "
                                 f"thinner than {RESOLVABLE_DP:g} dp ({RESOLVABLE_DP * dp:.4g} m); "
                                 "a finer dp or a thicker structure resolves it")

    @property
    def extent_fields(self) -> tuple[str, str]:
        """The fields that give the structure's low and high ends, for messages."""
        raise NotImplementedError


@dataclass(frozen=True)
class BoxStructure(_Structure):
    """An axis-aligned solid box: a block, a caisson, a deck, a column of square section.

    Attributes:
        name: the structure's name, which a :class:`ForceGauge` gives as its ``structure``.
        min, max: opposite corners [m], (x, z) in a 2D flume, (x, y, z) in 3D (flume
            coordinates: x from the paddle at rest, z from the floor). It may float (a
            submerged or emerging box) or stand on the floor.
    """

    name: str
    min: tuple[float, ...]
    max: tuple[float, ...]

    TAG: ClassVar[str] = "box"

    def __post_init__(self) -> None:
        self._check_name()
        lo = _finite_tuple("structure.min", self.min, 2)
        hi = _finite_tuple("structure.max", self.max, 2)
        if len(lo) != len(hi) or len(lo) not in (2, 3):
            raise SceneError("structure.max: min and max need 2 (x, z) or 3 (x, y, z) values")
        if any(b <= a for a, b in zip(lo, hi, strict=True)):
            raise SceneError(f"structure.max: must be above min on every axis ({lo} -> {hi})")
        _set(self, "min", lo)
        _set(self, "max", hi)

    @property
    def extent_fields(self) -> tuple[str, str]:
        return ("min", "max")

    def bounds(self, scene: FlumeScene) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return self.min, self.max

    def thickness(self) -> dict[str, float]:
        return {f"max[{k}]": hi - lo for k, (lo, hi) in enumerate(zip(self.min, self.max,
                                                                      strict=True))}

    def to_core(self, scene: FlumeScene) -> dict[str, Any]:
        return {"shape": "box", "min": list(self.min), "max": list(self.max)}


@dataclass(frozen=True)
class ProfileStructure(_Structure):
    """A structure standing on the floor, solid below the line through ``(x[i], z[i])`` and
    across the whole width in 3D: a seawall, a breakwater, a dike, any convex polygon whose
    base is the floor (its lowest vertices at z = 0 close it). The core samples it as a bed
    profile, so its top line must be a function of x (no overhang).

    Attributes:
        name: the structure's name, which a :class:`ForceGauge` gives as its ``structure``.
        x: vertex positions along the flume [m], strictly increasing.
        z: heights of the top line above the floor [m], >= 0 (0 at both ends for a structure
            with faces on both sides).
    """

    name: str
    x: tuple[float, ...]
    z: tuple[float, ...]

    TAG: ClassVar[str] = "profile_structure"

    def __post_init__(self) -> None:
        self._check_name()
        x = _finite_tuple("structure.x", self.x, 2)
        z = _finite_tuple("structure.z", self.z, 2)
        if len(x) != len(z):
            raise SceneError(f"structure.z: needs as many values as structure.x ({len(x)}), "
                             f"got {len(z)}")
        _strictly_increasing("structure.x", x)
        if min(z) < 0.0:
            raise SceneError(f"structure.z: heights must not be negative, got {min(z):g}")
        _set(self, "x", x)
        _set(self, "z", z)

    @property
    def extent_fields(self) -> tuple[str, str]:
        return ("x", "z")

    def bounds(self, scene: FlumeScene) -> tuple[tuple[float, ...], tuple[float, ...]]:
        if scene.dim == 3:
            assert scene.flume.width is not None
            return (self.x[0], 0.0, 0.0), (self.x[-1], scene.flume.width, max(self.z))
        return (self.x[0], 0.0), (self.x[-1], max(self.z))

    def thickness(self) -> dict[str, float]:
        return {"x": self.x[-1] - self.x[0], "z": max(self.z)}

    def to_core(self, scene: FlumeScene) -> dict[str, Any]:
        return {"shape": "profile", "x": list(self.x), "z": list(self.z)}


Structure = BoxStructure | ProfileStructure
"""The structures a :class:`~watersim.flume.FlumeScene` takes in its ``structures``."""

STRUCTURE_TYPES: tuple[type[_Structure], ...] = typing.get_args(Structure)
