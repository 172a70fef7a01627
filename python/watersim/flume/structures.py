"""Structures in the flume, a flume's ``bodies``: fixed solid bodies (any body of
:mod:`watersim.bodies`: a box, a cylinder, a convex polygon, a mesh, ...; and the flume's own
:class:`ProfileStructure`, a seawall or breakwater standing on the floor) that a
:class:`~watersim.flume.ForceGauge` measures the load on.

Each structure is one of the core's obstacles (``scene.obstacles``), sampled into wall particles
of the scene's wall model; the flume fills only the lattice sites outside it with water. A
force gauge names its structure; the core takes the obstacle's index (after the beach's).
"""

from __future__ import annotations

import typing
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from .._core import SceneError
from ..bodies import Box, Capsule, Cylinder, Mesh, Polygon, Sphere, _Body
from .checks import _TOL, _finite_tuple, _set, _strictly_increasing

if TYPE_CHECKING:
    from .scene import FlumeScene

__all__ = ["STRUCTURE_TYPES", "BoxStructure", "ProfileStructure", "Structure", "check_structure"]


def BoxStructure(name: str, min: tuple[float, ...], max: tuple[float, ...]) -> Box:  # noqa: N802, A002
    """A named :class:`~watersim.Box` (the flume's earlier name for it)."""
    if name is None:
        raise SceneError("body.name: a structure needs a name")
    return Box(min, max, name=name)


@dataclass(frozen=True)
class ProfileStructure(_Body):
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
    LOW: ClassVar[str] = "x"
    HIGH: ClassVar[str] = "z"

    def __post_init__(self) -> None:
        self._check_name()
        x = _finite_tuple("body.x", self.x, 2)
        z = _finite_tuple("body.z", self.z, 2)
        if len(x) != len(z):
            raise SceneError(f"body.z: needs as many values as body.x ({len(x)}), got {len(z)}")
        _strictly_increasing("body.x", x)
        if min(z) < 0.0:
            raise SceneError(f"body.z: heights must not be negative, got {min(z):g}")
        _set(self, "x", x)
        _set(self, "z", z)

    def dim(self) -> int | None:
        return None

    def bounds(self) -> None:
        return None

    def check_in(self, dim: int, lo: tuple[float, ...], hi: tuple[float, ...], dp: float,
                 label: str, symmetry_y_min: bool = False) -> None:
        super().check_in(dim, lo, hi, dp, label, symmetry_y_min)
        if self.x[0] < lo[0] - _TOL or self.x[-1] > hi[0] + _TOL:
            raise SceneError(f"{label}.x: the structure spans x = [{self.x[0]:.6g}, "
                             f"{self.x[-1]:.6g}] m; it must lie within [{lo[0]:g}, {hi[0]:g}] m")
        if max(self.z) > hi[-1] + _TOL:
            raise SceneError(f"{label}.z: the structure rises to {max(self.z):.6g} m, above the "
                             f"walls ({hi[-1]:g} m)")

    def x_start(self) -> float:
        return self.x[0]

    def thickness(self) -> dict[str, float]:
        return {"x": self.x[-1] - self.x[0], "z": max(self.z)}

    def to_core(self) -> dict[str, Any]:
        return {"shape": "profile", "x": list(self.x), "z": list(self.z)}


Structure = Box | Sphere | Cylinder | Capsule | Polygon | Mesh | ProfileStructure
"""The structures a :class:`~watersim.flume.FlumeScene` takes in its ``bodies``: any
body of :mod:`watersim.bodies` but the half-space (a beach is the flume's ``beach``), or a
:class:`ProfileStructure`."""

STRUCTURE_TYPES: tuple[type[_Body], ...] = typing.get_args(Structure)


def check_structure(structure: _Body, scene: FlumeScene, label: str) -> None:
    """Refuse a structure outside the flume, in the paddle's travel or thinner than
    :data:`watersim.bodies.RESOLVABLE_DP` dp, naming ``label`` (``bodies[i]``) and the field."""
    flume = scene.flume
    lo = (0.0, 0.0, 0.0) if scene.dim == 3 else (0.0, 0.0)
    hi = ((flume.length, flume.width, scene.tank_height) if scene.dim == 3
          else (flume.length, scene.tank_height))
    dp = float(scene.dp)  # type: ignore[arg-type]
    structure.check_in(scene.dim, lo, hi, dp, label,  # type: ignore[arg-type]
                       bool(scene.symmetry_y_min))
    start = structure.x_start()
    reach = scene.law.forward + 2.0 * dp
    if start is not None and start < reach:
        raise SceneError(f"{label}.{structure.LOW}: the structure starts at x = {start:.6g} m, "
                         f"within the paddle's travel (x < {reach:.4g} m, the forward "
                         "stroke plus 2 dp)")
