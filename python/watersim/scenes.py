"""Scene builders: dam break and still-water tank, in 2D and 3D.

A builder is a frozen dataclass whose fields are every physical and numerical parameter of the
case. All fields are checked when the builder is created (and again by :meth:`to_scene`), so a bad
value is refused with a :class:`~watersim.SceneError` that names the field and the reason before
anything runs. :meth:`to_scene` gives the scene in the JSON form the core reads and :meth:`build`
gives a ready :class:`~watersim.Simulation`.

Coordinates: the last axis is vertical (z, up); x runs along the tank; in 3D, y runs across it.
The tank is a box with a floor and side walls and an open top; its inner faces are given, so the
wall surfaces sit exactly at x = 0, x = tank length, etc. Particles sit on a lattice at
``(i + 1/2) dp`` from the tank's min corner, so a fluid box ``[0, W]`` holds exactly ``W / dp``
particles across when ``W / dp`` is a whole number.

Numerics: a parameter left ``None`` is not sent, and the core's default applies (the only
defaults, ``crates/sph-core/src/scene/defaults.rs``; :meth:`SceneBuilder.core_value` reads the
value a run uses). The dam break and the tank choose artificial viscosity 0.02
(:data:`watersim.numerics.VERIFICATION`, with the reason); the options and the presets of every
case are in :mod:`watersim.numerics`.
"""

from __future__ import annotations

import dataclasses
import json
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from . import _core
from . import numerics as nm
from ._core import SceneError
from .checks import _choice, _integer, _non_negative, _positive

if TYPE_CHECKING:
    from .simulation import Simulation

__all__ = [
    "DamBreak",
    "SceneBuilder",
    "Tank",
]

def _resolution(name: str, extent: float, dp: float, what: str) -> None:
    """Refuse a dp that leaves fewer than 2 particles across a fluid extent."""
    if extent < 2.0 * dp * (1.0 - 1e-9):
        raise SceneError(
            f"dp: {dp:g} m leaves fewer than 2 particles across the {what} ({name} = {extent:g} m)"
        )


def _at_most(name: str, value: Any, limit: float, why: str) -> None:
    """Refuse a set number above ``limit`` (after the caller's own check of its sign)."""
    if value is not None and value > limit:
        raise SceneError(f"{name}: must be at most {limit:g} ({why}), got {value!r}")


# ------------------------------------------------------------------------------------------------


MAX_USUAL_COEFSOUND = 200.0
"""Above this ``coefsound`` a builder warns: the sound speed sets the time step (CFL), and such
a stiff fluid only multiplies the steps (the stable region measured goes to 80)."""


class StiffFluidWarning(UserWarning):
    """``coefsound`` far above the usual range: legal, but the run takes proportionally more
    steps. Its own class so that a script that means it can silence it alone."""


@dataclass(frozen=True, kw_only=True)
class SceneBuilder:
    """Parameters shared by every scene. A numerical or physical parameter left ``None`` takes
    the core's default (``watersim._core.scene_defaults()``); ``dp``, ``until`` and the
    geometry fields set to ``None`` take the builder's default for ``dim`` (``_DIM_DEFAULTS``),
    filled in when the builder is created, as do the case's chosen numerics
    (:mod:`watersim.numerics`).

    Attributes:
        dim: 2 or 3.
        dp: initial particle spacing [m].
        kernel: ``"wendland"`` (Wendland C2) or ``"cubic_spline"``.
        coefh: ``h = coefh * sqrt(dim) * dp`` [-], at least 0.5.
        coefsound: ``c0 = coefsound * sqrt(g * h_swl)`` [-].
        gamma: Tait exponent [-].
        cfl: Courant number of the variable time step [-], at most 1.
        viscosity: :class:`~watersim.numerics.Artificial`,
            :class:`~watersim.numerics.Laminar` or :class:`~watersim.numerics.LaminarSps`
            (or a model's name, ``"laminar"``, with the core's parameters).
        diffusion: density diffusion, :class:`~watersim.numerics.NoDiffusion`,
            :class:`~watersim.numerics.Molteni` or :class:`~watersim.numerics.Fourtakas`
            (or ``"none"``, ``"molteni"``, ``"fourtakas"``).
        integrator: :class:`~watersim.numerics.Symplectic` or
            :class:`~watersim.numerics.Verlet` (or ``"symplectic"``, ``"verlet"``).
        boundary: wall boundary model, :class:`~watersim.numerics.Dbc`,
            :class:`~watersim.numerics.Adami` or :class:`~watersim.numerics.Mdbc` (or
            ``"dbc"``, ``"adami"``, ``"mdbc"``).
        force_precision: arithmetic of the force loop's pair terms, ``"f64"`` or ``"f32"``
            (see :data:`~watersim.numerics.FORCE_PRECISIONS`).
        shifting: particle shifting, a :class:`~watersim.numerics.Shifting` (or its
            coefficient alone); ``None``: no shifting.
        rho0: reference density [kg/m^3].
        gravity: gravitational acceleration [m/s^2], acting along -z.
        h_swl: depth for the speed of sound [m]; ``None``: the highest fluid top above the floor.
        boundary_layers: wall particle layers; ``None``: ``ceil(2h / dp)``, the kernel support.
        until: simulated end time [s] used by ``watersim run``.
        density_band: stability monitor: the run stops (``density_out_of_range``) when a
            density leaves ``rho0 (1 -+ density_band)`` [-], in (0, 1].
        lost_fraction_limit: stability monitor: the run stops (``out_of_domain``) when more than
            this fraction of the fluid particles has left the domain [-], in [0, 1].
        energy_growth_limit: stability monitor of scenes without a paddle: the run stops
            (``energy_growth``) when the fluid's mechanical energy exceeds its initial value by
            more than this fraction of the initial potential energy above the floor [-], in
            (0, 1].
    """

    _DIM_DEFAULTS: ClassVar[Mapping[int, Mapping[str, Any]]] = {}
    THREE_D_ONLY: ClassVar[tuple[str, ...]] = ()
    """Fields that only mean something in 3D (must stay ``None`` in 2D)."""
    CORE_KEYS: ClassVar[tuple[str, ...]] = (
        "kernel", "coefh", "coefsound", "gamma", "cfl", "viscosity", "diffusion", "integrator",
        "boundary", "force_precision", "shifting", "rho0", "gravity", "h_swl", "boundary_layers",
        "density_band", "lost_fraction_limit", "energy_growth_limit",
    )
    """The fields sent to the core under their own name when set (None: not sent)."""

    dim: int = 2
    dp: float | None = None
    kernel: str | None = None
    coefh: float | None = None
    coefsound: float | None = None
    gamma: float | None = None
    cfl: float | None = None
    viscosity: nm.Artificial | nm.Laminar | nm.LaminarSps | str | None = None
    diffusion: nm.NoDiffusion | nm.Molteni | nm.Fourtakas | str | None = None
    integrator: nm.Symplectic | nm.Verlet | str | None = None
    boundary: nm.Dbc | nm.Adami | nm.Mdbc | str | None = None
    force_precision: str | None = None
    shifting: nm.Shifting | float | None = None
    rho0: float | None = None
    gravity: float | None = None
    h_swl: float | None = None
    boundary_layers: int | None = None
    until: float | None = None
    density_band: float | None = None
    lost_fraction_limit: float | None = None
    energy_growth_limit: float | None = None

    _ENERGY_MONITOR: ClassVar[bool] = True
    """Whether the core's energy monitor runs for this scene (it skips scenes with a paddle,
    ``check_energy`` in ``crates/sph-core/src/diagnostics.rs``), so ``energy_growth_limit`` means
    something."""

    def __post_init__(self) -> None:
        if isinstance(self.dim, bool) or self.dim not in (2, 3):
            raise SceneError(f"dim: must be 2 or 3, got {self.dim!r}")
        for key, value in self._DIM_DEFAULTS.get(self.dim, {}).items():
            if getattr(self, key) is None:
                object.__setattr__(self, key, value)
        for name in nm.OPTION_CLASSES:
            object.__setattr__(self, name, nm.option(name, getattr(self, name)))
        self.validate()

    # -- checks ---------------------------------------------------------------------------------

    def validate(self) -> None:
        """Check every field; raise :class:`SceneError` naming the first bad one."""
        if isinstance(self.dim, bool) or self.dim not in (2, 3):
            raise SceneError(f"dim: must be 2 or 3, got {self.dim!r}")
        _positive("dp", self.dp)
        self._validate_numerics()
        self._validate_monitors()
        if self.h_swl is not None:
            _positive("h_swl", self.h_swl)
        if self.boundary_layers is not None:
            _integer("boundary_layers", self.boundary_layers, 1)
        _positive("until", self.until)
        self._validate_geometry()

    def _validate_numerics(self) -> None:
        """The numerical parameters that are set (the options check their own)."""
        for name in ("kernel", "force_precision"):
            if getattr(self, name) is not None:
                _choice(name, getattr(self, name), nm.CHOICES[name])
        if self.coefh is not None and _positive("coefh", self.coefh) < nm.MIN_COEFH:
            raise SceneError(
                f"coefh: must be at least {nm.MIN_COEFH} (h = coefh sqrt(dim) dp), got "
                f"{self.coefh!r}: a smaller h reaches no more than the nearest neighbours, and "
                "the core's cell grid (cells of size h) outgrows memory"
            )
        for name in ("coefsound", "gamma", "cfl", "rho0", "gravity"):
            if getattr(self, name) is not None:
                _positive(name, getattr(self, name))
        if self.coefsound is not None and self.coefsound > MAX_USUAL_COEFSOUND:
            warnings.warn(
                f"coefsound = {self.coefsound:.3g}: far above the 10-80 of docs/stability.md; "
                f"the time step shrinks in proportion, {self.coefsound / 10:.3g} times as many "
                "steps as at coefsound 10", StiffFluidWarning, stacklevel=4)
        _at_most("cfl", self.cfl, 1.0, "a Courant number")
        if self.force_precision == "f32" and isinstance(self.viscosity, nm.LaminarSps):
            raise SceneError(
                "force_precision: f32 pair terms exist in the batched force loop only; the "
                "laminar_sps closure runs the f64 loop, so use f64"
            )
        if isinstance(self.shifting, nm.Shifting):
            self.shifting.check_dim(self.dim)

    def _validate_monitors(self) -> None:
        """The stability monitor thresholds that are set (ranges: docs/stability.md)."""
        if self.density_band is not None:
            _positive("density_band", self.density_band)
            _at_most("density_band", self.density_band, nm.MAX_DENSITY_BAND,
                     "the band rho0 (1 -+ density_band) then reaches zero density")
        if self.lost_fraction_limit is not None:
            _non_negative("lost_fraction_limit", self.lost_fraction_limit)
            _at_most("lost_fraction_limit", self.lost_fraction_limit, 1.0,
                     "a fraction of the fluid")
        if self.energy_growth_limit is None:
            return
        if not self._ENERGY_MONITOR:
            raise SceneError(
                "energy_growth_limit: the core's energy monitor does not run in a scene with "
                "a paddle; leave it unset"
            )
        _positive("energy_growth_limit", self.energy_growth_limit)
        _at_most("energy_growth_limit", self.energy_growth_limit, nm.MAX_ENERGY_GROWTH_LIMIT,
                 "a growth by the whole initial potential energy")

    def _validate_geometry(self) -> None:  # pragma: no cover - overridden
        raise NotImplementedError

    # -- scene ----------------------------------------------------------------------------------

    def core_value(self, name: str) -> Any:
        """The value of a core parameter a run uses: this builder's, else the core's default
        (``core_value("gravity")``, ``core_value("coefh")``)."""
        value = getattr(self, name)
        return nm.core_default(name) if value is None else value

    @property
    def g(self) -> float:
        """Gravitational acceleration a run uses [m/s^2]: ``gravity``, else the core's."""
        return float(self.core_value("gravity"))

    @property
    def smoothing_length(self) -> float:
        """``h = coefh * sqrt(dim) * dp`` [m]."""
        assert self.dp is not None
        return float(self.core_value("coefh")) * math.sqrt(self.dim) * self.dp

    def _physics(self) -> dict[str, Any]:
        """The scene keys that do not describe geometry: those set, in the core's form."""
        physics: dict[str, Any] = {"dim": int(self.dim), "dp": float(self.dp)}  # type: ignore[arg-type]
        for name in self.CORE_KEYS:
            value = getattr(self, name)
            if value is None:
                continue
            if isinstance(value, nm.Option):
                physics[name] = value.to_core()
            elif isinstance(value, str):
                physics[name] = value
            else:
                physics[name] = int(value) if name == "boundary_layers" else float(value)
        return physics

    def to_scene(self) -> dict[str, Any]:
        """The scene as a JSON-ready dict in the core's form (checked first)."""
        self.validate()
        scene = self._physics()
        scene.update(self._geometry())
        return scene

    def _geometry(self) -> dict[str, Any]:  # pragma: no cover - overridden
        raise NotImplementedError

    def resolved_scene(self) -> dict[str, Any]:
        """The scene as the core runs it: :meth:`to_scene` with every default filled in by the
        core (``watersim._core.resolve_scene``)."""
        return json.loads(_core.resolve_scene(json.dumps(self.to_scene())))

    def build(self) -> Simulation:
        """Build the particles: a ready :class:`~watersim.Simulation`."""
        from .simulation import Simulation

        return Simulation(self.to_scene())

    def replace(self, **changes: Any) -> SceneBuilder:
        """A copy with some fields changed (checked again)."""
        return dataclasses.replace(self, **changes)

    @classmethod
    def field_names(cls) -> tuple[str, ...]:
        """Names of the settable fields, in declaration order."""
        return tuple(f.name for f in dataclasses.fields(cls))

    def as_dict(self) -> dict[str, Any]:
        """The builder's fields as a plain dict (an option as its scene-file table)."""
        out = dataclasses.asdict(self)
        for name in nm.OPTION_CLASSES:
            value = getattr(self, name)
            out[name] = value.to_table() if isinstance(value, nm.Option) else value
        return out


@dataclass(frozen=True, kw_only=True)
class DamBreak(SceneBuilder):
    """Collapse of a water column against the back wall of a box tank.

    The column ``[0, width] x [0, height]`` (in 3D ``x [0, tank_width]`` across) stands against
    the back wall x = 0 of a tank ``[0, tank_length] x [0, tank_height]`` and is released at
    t = 0 with hydrostatic density. The defaults (1 m x 2 m column in a 4 m long tank) are the
    Martin & Moyce (1952) n^2 = 2 geometry, as in DualSPHysics' CaseDambreakVal2D; the surge
    front is compared with their measurements by :func:`watersim.measure.front_error`.

    Defaults run to t = 0.7 s, when the front reaches the far wall, past the last measured
    point (t = 0.67 s). In 2D, dp = 0.025 m (40 x 80 fluid particles, about 4300 in all) runs in
    about a minute on two cores; the test suite uses dp = 0.04 m. In 3D the column spans the
    whole tank width (0.5 m), so the flow is the 2D one up to the friction of the side walls;
    its default resolution is coarse (dp = 0.1 m, 1000 fluid and about 12700 wall particles)
    so that it runs in well under a minute.

    Attributes:
        width: column width along x [m] (L1 of Martin & Moyce; ``a`` in their notation).
        height: column height [m].
        tank_length: inner tank length along x [m].
        tank_height: inner height of the tank walls [m].
        tank_width: inner tank width along y [m], 3D only (``None`` in 2D).
    """

    THREE_D_ONLY: ClassVar[tuple[str, ...]] = ("tank_width",)
    _DIM_DEFAULTS: ClassVar[Mapping[int, Mapping[str, Any]]] = {
        2: {"dp": 0.025, "until": 0.7, **nm.VERIFICATION},
        3: {"dp": 0.1, "until": 0.7, "tank_width": 0.5, **nm.VERIFICATION},
    }

    width: float = 1.0
    height: float = 2.0
    tank_length: float = 4.0
    tank_height: float = 2.4
    tank_width: float | None = None

    def _validate_geometry(self) -> None:
        dp = _positive("dp", self.dp)
        width = _positive("width", self.width)
        height = _positive("height", self.height)
        tank_length = _positive("tank_length", self.tank_length)
        tank_height = _positive("tank_height", self.tank_height)
        if width > tank_length:
            raise SceneError(
                f"width: the column ({width:g} m) is wider than the tank length ({tank_length:g} m)"
            )
        if height > tank_height:
            raise SceneError(
                f"height: the column ({height:g} m) is higher than the tank walls "
                f"(tank_height = {tank_height:g} m)"
            )
        _resolution("width", width, dp, "column width")
        _resolution("height", height, dp, "column height")
        if self.dim == 3:
            if self.tank_width is None:
                raise SceneError("tank_width: required in 3D")
            tank_width = _positive("tank_width", self.tank_width)
            _resolution("tank_width", tank_width, dp, "tank width")
        elif self.tank_width is not None:
            raise SceneError("tank_width: only used in 3D (dim = 3); leave it unset in 2D")

    def _geometry(self) -> dict[str, Any]:
        if self.dim == 2:
            tank_max = [float(self.tank_length), float(self.tank_height)]
            fluid_max = [float(self.width), float(self.height)]
        else:
            assert self.tank_width is not None
            tank_max = [float(self.tank_length), float(self.tank_width), float(self.tank_height)]
            fluid_max = [float(self.width), float(self.tank_width), float(self.height)]
        zero = [0.0] * self.dim
        return {
            "tank": {"min": list(zero), "max": tank_max},
            "obstacles": [],
            "fluid": [{"min": list(zero), "max": fluid_max}],
        }


@dataclass(frozen=True, kw_only=True)
class Tank(SceneBuilder):
    """Still water of depth ``depth`` filling a box tank: the hydrostatic verification case.

    The water should stay at rest, its surface at ``depth`` and its pressure hydrostatic,
    ``p = rho0 g (depth - z)``. Defaults depend on ``dim`` so that each runs 2 s of simulated
    time in well under a minute on two cores: 2D 1.0 m long, 0.5 m deep, dp = 0.025 m; 3D
    0.6 m x 0.3 m, 0.3 m deep, dp = 0.05 m.

    Attributes:
        length: inner tank length along x [m].
        depth: still-water depth [m].
        height: inner height of the tank walls [m] (at least the depth).
        width: inner tank width along y [m], 3D only.
    """

    THREE_D_ONLY: ClassVar[tuple[str, ...]] = ("width",)
    _DIM_DEFAULTS: ClassVar[Mapping[int, Mapping[str, Any]]] = {
        2: {"dp": 0.025, "until": 2.0, "length": 1.0, "depth": 0.5, "height": 0.7,
            **nm.VERIFICATION},
        3: {"dp": 0.05, "until": 2.0, "length": 0.6, "depth": 0.3, "height": 0.4, "width": 0.3,
            **nm.VERIFICATION},
    }

    length: float | None = None
    depth: float | None = None
    height: float | None = None
    width: float | None = None

    def _validate_geometry(self) -> None:
        dp = _positive("dp", self.dp)
        length = _positive("length", self.length)
        depth = _positive("depth", self.depth)
        height = _positive("height", self.height)
        if depth > height:
            raise SceneError(
                f"depth: the water ({depth:g} m) is deeper than the tank walls are high "
                f"(height = {height:g} m)"
            )
        _resolution("length", length, dp, "tank length")
        _resolution("depth", depth, dp, "water depth")
        if self.dim == 3:
            if self.width is None:
                raise SceneError("width: required in 3D")
            width = _positive("width", self.width)
            _resolution("width", width, dp, "tank width")
        elif self.width is not None:
            raise SceneError("width: only used in 3D (dim = 3); leave it unset in 2D")

    def _geometry(self) -> dict[str, Any]:
        assert self.length is not None and self.depth is not None and self.height is not None
        if self.dim == 2:
            tank_max = [float(self.length), float(self.height)]
            fluid_max = [float(self.length), float(self.depth)]
        else:
            assert self.width is not None
            tank_max = [float(self.length), float(self.width), float(self.height)]
            fluid_max = [float(self.length), float(self.width), float(self.depth)]
        zero = [0.0] * self.dim
        return {
            "tank": {"min": list(zero), "max": tank_max},
            "obstacles": [],
            "fluid": [{"min": list(zero), "max": fluid_max}],
        }
