"""Scene builders: the general scene (a tank, fluid blocks, solid bodies, gauges) and its
presets, the dam break and the still-water tank, in 2D and 3D.

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
import os
import re
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from . import _core
from . import numerics as nm
from ._core import SceneError
from .bodies import BODY_TYPES, Body
from .checks import _choice, _integer, _non_negative, _positive
from .flume.checks import _TOL, _finite_tuple, _models_of, _set
from .flume.gauges import SCENE_GAUGE_TYPES, Gauge, check_gauges, gauge_specs
from .flume.records import FlumeGauges
from .simulation import Simulation

__all__ = [
    "DamBreak",
    "FillTo",
    "FluidBlock",
    "Scene",
    "SceneBuilder",
    "SceneSimulation",
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
        kernel: ``"wendland"`` (Wendland C2), ``"wendland_c4"`` (Wendland C4) or
            ``"cubic_spline"``.
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
        tensile_correction: Monaghan's (2000) tensile correction, a
            :class:`~watersim.numerics.TensileCorrection` (or ``"monaghan"``), with
            ``kernel = "cubic_spline"`` only; ``None``: none.
        riemann: Riemann-solver SPH with the low-dissipation limiter, a
            :class:`~watersim.numerics.RiemannSolver` (or ``"acoustic"``), with laminar
            viscosity and no density diffusion; ``None``: the classic formulation.
        kernel_correction: kernel gradient correction of the pressure term, a
            :class:`~watersim.numerics.KernelCorrection` (or ``{}``); ``None``: none.
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
        "boundary", "force_precision", "shifting", "tensile_correction", "riemann",
        "kernel_correction", "rho0",
        "gravity", "h_swl", "boundary_layers", "density_band", "lost_fraction_limit",
        "energy_growth_limit",
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
    tensile_correction: nm.TensileCorrection | str | None = None
    riemann: nm.RiemannSolver | str | None = None
    kernel_correction: nm.KernelCorrection | None = None
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
        if isinstance(self.tensile_correction, nm.TensileCorrection):
            self.tensile_correction.check_kernel(str(self.core_value("kernel")))
        if isinstance(self.riemann, nm.RiemannSolver):
            def model(name: str, key: str = "model") -> str:
                value = getattr(self, name)
                return str(nm.core_default(f"{name}.{key}") if value is None else value.TAG)
            self.riemann.check_scene(model("viscosity"), model("diffusion"),
                                     model("integrator", "scheme"),
                                     str(self.core_value("force_precision")),
                                     self.tensile_correction is not None)
        if isinstance(self.kernel_correction, nm.KernelCorrection):
            for name, clash in (("force_precision", self.force_precision == "f32"),
                                ("tensile_correction", self.tensile_correction is not None),
                                ("riemann", self.riemann is not None)):
                if clash:
                    raise SceneError(f"{name}: is not combined with the kernel correction "
                                     "(kernel_correction runs the f64 pair-at-a-time loop "
                                     "without either)")

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


@dataclass(frozen=True)
class FluidBlock:
    """Water filling the box ``[min, max]`` (outside the bodies), at rest with hydrostatic
    density from its top.

    Attributes:
        min, max: opposite corners [m], (x, z) or (x, y, z), inside the tank.
    """

    min: tuple[float, ...]
    max: tuple[float, ...]

    TAG: ClassVar[str] = "block"

    def __post_init__(self) -> None:
        lo = _finite_tuple("fluid.min", self.min, 2)
        hi = _finite_tuple("fluid.max", self.max, 2)
        if len(lo) != len(hi) or len(lo) not in (2, 3):
            raise SceneError("fluid.max: min and max need 2 (x, z) or 3 (x, y, z) values each")
        if any(b <= a for a, b in zip(lo, hi, strict=True)):
            raise SceneError(f"fluid.max: must be above min on every axis ({lo} -> {hi})")
        _set(self, "min", lo)
        _set(self, "max", hi)

    def box(self, size: tuple[float, ...]) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """``(min, max)`` of the water in a tank of inner ``size``."""
        return self.min, self.max


@dataclass(frozen=True)
class FillTo:
    """Water over the whole tank floor up to ``level`` (outside the bodies).

    Attributes:
        level: height of the still water above the floor [m].
    """

    level: float

    TAG: ClassVar[str] = "fill"

    def __post_init__(self) -> None:
        _set(self, "level", _positive("fluid.level", self.level))

    def box(self, size: tuple[float, ...]) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return (0.0,) * len(size), (*size[:-1], self.level)


Fluid = FluidBlock | FillTo
"""A block of water of a :class:`Scene`."""


class SceneSimulation(Simulation):
    """A run of a :class:`Scene` (or a preset): a :class:`~watersim.Simulation` with its gauge
    records as NumPy arrays and CSV.

    Args:
        setup: the scene builder.
    """

    def __init__(self, setup: Scene) -> None:
        try:
            super().__init__(setup.to_scene())
        except SceneError as exc:
            # the core names a body by its obstacle index, which is its index in `bodies`
            raise SceneError(re.sub(r"^obstacles\[", "bodies[", str(exc))) from None
        self.setup = setup
        self._gauges_cache: tuple[int, FlumeGauges] | None = None

    def run(  # type: ignore[override]
        self,
        until: float | None = None,
        callback_every: float | None = None,
        callback: Callable[[Simulation], None] | None = None,
        progress: bool = False,
    ) -> None:
        """Advance to ``until`` [s], default the scene's ``until`` (otherwise as
        :meth:`watersim.Simulation.run`)."""
        end = float(self.setup.until if until is None else until)  # type: ignore[arg-type]
        super().run(end, callback_every=callback_every, callback=callback, progress=progress)

    @property
    def gauges(self) -> FlumeGauges:
        """The gauge records so far (:class:`~watersim.FlumeGauges`: ``records[name]`` of the
        pressure, force and overtopping gauges, ``elevation`` of the elevation gauges, which
        in a scene read the water's height above the floor)."""
        if self._gauges_cache is None or self._gauges_cache[0] != self.steps:
            self._gauges_cache = (self.steps, FlumeGauges(self.setup,  # type: ignore[arg-type]
                                                          self._sim.gauges()))
        return self._gauges_cache[1]

    def write_gauges_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write ``gauges.csv`` (see :meth:`~watersim.FlumeGauges.to_csv`)."""
        return self.gauges.to_csv(path)


@dataclass(frozen=True, kw_only=True)
class Scene(SceneBuilder):
    """A general scene: a box tank with an open top, any number of fluid blocks, fixed solid
    bodies and gauges, in 2D or 3D. The dam break and the still tank are presets of it
    (:class:`DamBreak`, :class:`Tank`: their own fields make the tank and the water, and they
    take ``bodies`` and ``gauges`` like any scene). Example: ``examples/dambreak_box3d.py``.

    The tank's inner faces are x = 0 and x = length, y = 0 and y = width (3D), the floor z = 0;
    particles sit on a lattice at ``(i + 1/2) dp``. A body is sampled as wall particles of the
    scene's wall model (``boundary``); fluid inside a body is removed, and fluid that bodies
    close off from the open top is refused when the particles are built (the field is the
    nearest body). Bad input is refused naming the field: a body outside the tank
    (``bodies[i].max``), a mesh that is not closed (``bodies[i].path``), a pressure sensor
    ``on_wall`` farther than dp from every wall (``gauges[i].points[j]``, when built).

    Attributes:
        tank: the tank's inner size [m]: (length, height) in 2D, (length, width, height) in 3D;
            ``dim`` follows it.
        fluid: the water: :class:`FluidBlock` boxes anywhere in the tank, or :class:`FillTo`
            a level over the whole floor; at least one.
        bodies: fixed solid bodies (:mod:`watersim.bodies`: :class:`~watersim.Box`,
            :class:`~watersim.Sphere`, :class:`~watersim.Cylinder`, :class:`~watersim.Capsule`,
            :class:`~watersim.Polygon`, :class:`~watersim.HalfSpace`, :class:`~watersim.Mesh`).
        gauges: gauges of any kind: :class:`~watersim.ElevationGauge` (reads the water's height
            above the floor), :class:`~watersim.VelocityProbe`,
            :class:`~watersim.VelocityWindow`, :class:`~watersim.PressureGauge` (``on_wall``
            for sensors on a wall or body), :class:`~watersim.ForceGauge` (on a named body),
            :class:`~watersim.OvertoppingGauge`.
        sample_interval: the gauges' sampling interval where a gauge gives none [s]; default
            ``until / 200``.
        symmetry_y_min: the side wall y = 0 is a plane of symmetry (3D): the tank is half of
            one mirrored through it. A body may cross that wall (a pile whose axis lies on
            it); the wall's particles inside it are the body's and stand for its mirror half,
            so its force gauge reads half the mirrored tank's force. Give the walls free slip
            (:data:`watersim.numerics.LOW_DISSIPATION`); ``None``: an ordinary wall.
    """

    _DIM_DEFAULTS: ClassVar[Mapping[int, Mapping[str, Any]]] = {
        2: {"until": 1.0, **nm.VERIFICATION},
        3: {"until": 1.0, **nm.VERIFICATION},
    }
    PLACE: ClassVar[str] = "tank"
    """What the gauges' messages call the scene's extent."""
    BODIES: ClassVar[str] = "bodies"
    """The field holding the scene's bodies, for messages."""
    FLUID_CLASSES: ClassVar[tuple[type, ...]] = (FluidBlock, FillTo)
    """What ``fluid`` takes."""
    BODY_CLASSES: ClassVar[tuple[type, ...]] = BODY_TYPES
    """What ``bodies`` takes."""

    dim: int | None = None  # type: ignore[assignment]
    tank: tuple[float, ...] | None = None
    fluid: Sequence[Fluid] = ()
    bodies: Sequence[Body] = ()
    gauges: Sequence[Gauge] = ()
    sample_interval: float | None = None
    symmetry_y_min: bool | None = None

    def __post_init__(self) -> None:
        if self.tank is not None:
            size = _finite_tuple("tank", self.tank, 2)
            if len(size) not in (2, 3):
                raise SceneError(f"tank: needs (length, height) or (length, width, height), got "
                                 f"{len(size)} values")
            _set(self, "tank", size)
            if self.dim is None:
                _set(self, "dim", len(size))
        if self.dim is None:
            _set(self, "dim", 2)
        for field, classes in (("fluid", self.FLUID_CLASSES), ("bodies", self.BODY_CLASSES),
                               ("gauges", SCENE_GAUGE_TYPES)):
            _models_of(self, field, classes)
        names: set[str] = set()
        for i, body in enumerate(self.bodies):
            if body.name is not None:
                if body.name in names:
                    raise SceneError(f"bodies[{i}].name: duplicate body name {body.name!r}")
                names.add(body.name)
        super().__post_init__()

    # -- the geometry a preset replaces ---------------------------------------------------------

    def tank_size(self) -> tuple[float, ...]:
        """The tank's inner size [m] (length, [width,] height)."""
        if self.tank is None:
            raise SceneError("tank: required: (length, height) or (length, width, height)")
        return self.tank

    def fluid_boxes(self) -> list[tuple[tuple[float, ...], tuple[float, ...]]]:
        """The water as boxes ``(min, max)`` [m], in the core's order."""
        size = self.tank_size()
        return [f.box(size) for f in self.fluid]

    # -- checks ---------------------------------------------------------------------------------

    def _validate_geometry(self) -> None:
        dp = _positive("dp", self.dp)
        size = self.tank_size()
        if len(size) != self.dim:
            raise SceneError(f"tank: a {self.dim}D scene needs {self.dim} sizes, got {len(size)}")
        for k, extent in enumerate(size):
            if extent < 2.0 * dp * (1.0 - 1e-9):
                raise SceneError(f"tank: {extent:g} m along axis {k} is less than 2 dp")
        if not self.fluid:
            raise SceneError("fluid: at least one FluidBlock or FillTo is needed")
        self._check_fluid_blocks(size, dp)
        self._validate_contents()

    def _check_fluid_blocks(self, size: tuple[float, ...], dp: float) -> None:
        """Each of ``fluid`` inside the tank ``[0, size]`` and at least dp thick, or SceneError
        naming ``fluid[i]`` and its field."""
        for i, f in enumerate(self.fluid):
            lo, hi = f.box(size)
            label = f"fluid[{i}]"
            if len(lo) != self.dim:
                raise SceneError(f"{label}.min: a {self.dim}D scene needs {self.dim} "
                                 f"coordinates, got {len(lo)}")
            for k in range(self.dim):
                if lo[k] < -_TOL or hi[k] > size[k] + _TOL:
                    field = "level" if isinstance(f, FillTo) else (
                        "min" if lo[k] < -_TOL else "max")
                    raise SceneError(f"{label}.{field}: the water spans [{lo[k]:g}, {hi[k]:g}] m "
                                     f"along axis {k}, outside the tank [0, {size[k]:g}] m")
                if hi[k] - lo[k] < dp * (1.0 - 1e-9):
                    raise SceneError(f"{label}: the water is {hi[k] - lo[k]:g} m thick along "
                                     f"axis {k}, less than dp = {dp:g} m")

    def _validate_contents(self) -> None:
        """The bodies (inside the tank, resolved, uniquely named) and the gauges."""
        dp = float(self.dp)  # type: ignore[arg-type]
        size = self.tank_size()
        symmetry = self._check_symmetry()
        for i, body in enumerate(self.bodies):
            body.check_in(int(self.dim), (0.0,) * len(size), size, dp,  # type: ignore[arg-type]
                          f"bodies[{i}]", symmetry)
        if self.sample_interval is not None:
            _positive("sample_interval", self.sample_interval)
        check_gauges(self, self.gauges)  # type: ignore[arg-type]

    def _check_symmetry(self) -> bool:
        """Whether the wall y = 0 is a plane of symmetry; SceneError naming
        ``symmetry_y_min`` when it is not a bool or the scene not 3D."""
        if self.symmetry_y_min is None:
            return False
        if not isinstance(self.symmetry_y_min, bool):
            raise SceneError(f"symmetry_y_min: must be true or false, got "
                             f"{self.symmetry_y_min!r}")
        if self.symmetry_y_min and self.dim != 3:
            raise SceneError("symmetry_y_min: a side wall y = 0 exists in 3D scenes only")
        return self.symmetry_y_min

    def _symmetry_to_core(self, scene: dict[str, Any]) -> dict[str, Any]:
        """``scene`` (the core's JSON) with ``symmetry_y_min`` where it is set."""
        if self.symmetry_y_min is not None:
            scene["symmetry_y_min"] = self.symmetry_y_min
        return scene

    # -- what the gauges ask of their scene ------------------------------------------------------

    def extent(self, axis: int) -> tuple[float, float]:
        """``(low, high)`` [m] of the tank along horizontal ``axis``."""
        return 0.0, self.tank_size()[axis]

    @property
    def level(self) -> float:
        """The level elevation gauges measure from: the floor (they read the water's height)."""
        return 0.0

    def still_depth(self, x: Any, y: Any = None) -> np.ndarray:
        """Zeros: a scene's elevation gauges read heights above the floor, not zeroed."""
        return np.zeros_like(np.asarray(x, dtype=np.float64))

    def check_point(self, label: str, point: Sequence[float], vertical: bool = True) -> None:
        """A point (x, z) / (x, y, z) inside the tank, or SceneError naming ``label``."""
        size = self.tank_size()
        if len(point) != self.dim:
            raise SceneError(f"{label}: needs {self.dim} coordinates in {self.dim}D, got "
                             f"{len(point)}")
        for k in range(self.dim if vertical else self.dim - 1):  # type: ignore[operator]
            if not -_TOL <= point[k] <= size[k] + _TOL:
                raise SceneError(f"{label}: coordinate {k} = {point[k]:g} m lies outside the "
                                 f"tank [0, {size[k]:g}] m")

    def body_names(self) -> list[str]:
        """The names of the named bodies."""
        return [b.name for b in self.bodies if b.name is not None]

    def obstacle_index(self, name: str) -> int | None:
        """The core's obstacle index of the body named ``name``, None if there is none."""
        for i, b in enumerate(self.bodies):
            if b.name == name:
                return i
        return None

    @property
    def gauge_interval(self) -> float:
        """The gauges' default sampling interval [s]."""
        if self.sample_interval is not None:
            return float(self.sample_interval)
        return float(self.until) / 200.0  # type: ignore[arg-type]

    def _gauge_specs(self) -> list[dict[str, Any]]:
        return gauge_specs(self, self.gauges, self.gauge_interval)  # type: ignore[arg-type]

    # -- scene ----------------------------------------------------------------------------------

    def _geometry(self) -> dict[str, Any]:
        size = [float(v) for v in self.tank_size()]
        scene: dict[str, Any] = {
            "tank": {"min": [0.0] * len(size), "max": size},
            "obstacles": [b.to_core() for b in self.bodies],
            "fluid": [{"min": [float(v) for v in lo], "max": [float(v) for v in hi]}
                      for lo, hi in self.fluid_boxes()],
        }
        if self.gauges:
            scene["gauges"] = self._gauge_specs()
        return self._symmetry_to_core(scene)

    def build(self) -> SceneSimulation:
        """Build the particles: a ready :class:`SceneSimulation`."""
        return SceneSimulation(self)


class _Preset(Scene):
    """A preset of :class:`Scene`: its own fields make the tank and the water."""

    def _refuse_general_geometry(self) -> None:
        for name in ("tank", "fluid"):
            if getattr(self, name) not in (None, ()):
                raise SceneError(f"{name}: a {type(self).__name__} makes its own tank and water "
                                 "from its fields; use watersim.Scene for another geometry")

    def fluid_boxes(self) -> list[tuple[tuple[float, ...], tuple[float, ...]]]:
        return [((0.0,) * self.dim, self._fluid_top())]  # type: ignore[operator]

    def _fluid_top(self) -> tuple[float, ...]:  # pragma: no cover - overridden
        raise NotImplementedError


@dataclass(frozen=True, kw_only=True)
class DamBreak(_Preset):
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

    dim: int = 2
    width: float = 1.0
    height: float = 2.0
    tank_length: float = 4.0
    tank_height: float = 2.4
    tank_width: float | None = None

    def _validate_geometry(self) -> None:
        self._refuse_general_geometry()
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
        self._validate_contents()

    def tank_size(self) -> tuple[float, ...]:
        if self.dim == 2:
            return (float(self.tank_length), float(self.tank_height))
        assert self.tank_width is not None
        return (float(self.tank_length), float(self.tank_width), float(self.tank_height))

    def _fluid_top(self) -> tuple[float, ...]:
        if self.dim == 2:
            return (float(self.width), float(self.height))
        assert self.tank_width is not None
        return (float(self.width), float(self.tank_width), float(self.height))


@dataclass(frozen=True, kw_only=True)
class Tank(_Preset):
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

    dim: int = 2
    length: float | None = None
    depth: float | None = None
    height: float | None = None
    width: float | None = None

    def _validate_geometry(self) -> None:
        self._refuse_general_geometry()
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
        self._validate_contents()

    def tank_size(self) -> tuple[float, ...]:
        assert self.length is not None and self.height is not None
        if self.dim == 2:
            return (float(self.length), float(self.height))
        assert self.width is not None
        return (float(self.length), float(self.width), float(self.height))

    def _fluid_top(self) -> tuple[float, ...]:
        assert self.length is not None and self.depth is not None
        if self.dim == 2:
            return (float(self.length), float(self.depth))
        assert self.width is not None
        return (float(self.length), float(self.width), float(self.depth))
