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

Default numerics, shared by every case, and why:

- ``kernel="wendland"``, ``coefh=1.0``: Wendland C2 with ``h = coefh sqrt(dim) dp`` is the
  DualSPHysics default; it does not suffer the pairing instability of the cubic spline.
- ``coefsound=20``: ``c0 = 20 sqrt(g h_swl)`` keeps density variations near 0.25 % for the
  hydrostatic column (Mach number about 0.05 for the fastest flow), the usual WCSPH choice.
- ``gamma=7``: Tait equation of state for water (Monaghan 1994).
- ``cfl=0.2``: the DualSPHysics default Courant number for the Monaghan & Kos (1999) time step.
- ``viscosity="artificial"``, ``alpha=0.02``: Monaghan (1992) artificial viscosity, in the
  0.01-0.1 range recommended for free-surface flows; a low value, since it also damps the
  physical flow, but above 0.01 for the coarse resolutions the defaults run at. It is not tuned
  to any data set.
- ``diffusion="fourtakas"``, ``delta=0.1``: density diffusion of Fourtakas et al. (2019), which
  removes the hydrostatic part of the density difference (so it does not pull a still tank
  towards uniform density near the free surface). The hydrostatic part is taken in pressure,
  ``(p_b - p_a - rho0 g z_ab) / c0^2``: zero for every pair of still water, where the paper's
  density form (Eq. 13) adds density at depth and still water slowly expands (docs/wave-flume.md,
  "The mean water level"); delta = 0.1 is the standard value
  (Molteni & Colagrossi 2009; Antuono et al. 2010).
- ``integrator="symplectic"``: second-order, time-reversible scheme, the DualSPHysics default.
- ``rho0=1000`` kg/m^3, ``gravity=9.81`` m/s^2.
- Stability monitors (docs/stability.md): ``density_band=0.5``, ``lost_fraction_limit=0.01``,
  ``energy_growth_limit=0.05``, the core's own defaults (``crates/sph-core/src/scene/defaults.rs``):
  loose enough that a healthy run never trips them, tight enough to stop a diverging one
  within a few steps.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from ._core import SceneError

if TYPE_CHECKING:
    from .simulation import Simulation

__all__ = [
    "DIFFUSION_MODELS",
    "INTEGRATORS",
    "BOUNDARY_MODELS",
    "FORCE_PRECISIONS",
    "KERNELS",
    "VISCOSITY_MODELS",
    "DamBreak",
    "SceneBuilder",
    "Tank",
]

KERNELS: tuple[str, ...] = ("wendland", "cubic_spline")
"""Kernel names the core knows."""
VISCOSITY_MODELS: tuple[str, ...] = ("artificial", "laminar", "laminar_sps")
"""Viscosity models the core knows."""
DIFFUSION_MODELS: tuple[str, ...] = ("none", "molteni", "fourtakas")
"""Density diffusion terms the core knows."""
INTEGRATORS: tuple[str, ...] = ("symplectic", "verlet")
"""Time integration schemes the core knows."""
BOUNDARY_MODELS: tuple[str, ...] = ("dbc", "adami")
"""Wall boundary models the core knows: ``"dbc"``, the dynamic boundary condition (Crespo et
al. 2007; wall particles integrate continuity); ``"adami"``, Adami, Hu & Adams (2012; wall
particles take the pressure extrapolated from their fluid neighbours at every step)."""

FORCE_PRECISIONS: tuple[str, ...] = ("f64", "f32")
"""Arithmetic of the force loop's pair terms: ``"f64"``, or ``"f32"`` (eight pairs to an AVX2
register instead of four, as DualSPHysics forms its forces; the state stays f64). Not with
``viscosity="laminar_sps"``, whose loop is f64 only. ``ForcePrecision`` in
``crates/sph-core/src/scene/numerics.rs``; docs/benchmarks.md measures speed and accuracy."""

MAX_DENSITY_BAND = 1.0
"""Largest ``density_band`` accepted: the band ``rho0 (1 -+ density_band)`` then reaches
density 0, and a wider one bounds nothing below."""

MAX_ENERGY_GROWTH_LIMIT = 1.0
"""Largest ``energy_growth_limit`` accepted: an unforced fluid whose mechanical energy grew by its
whole initial potential energy is no solution any more, so a looser monitor would never stop a
run that needs stopping."""

MIN_COEFH = 0.5
"""Smallest ``coefh`` accepted. The core sizes its cell grid by h and does not bound the cell
count, so a tiny coefh makes it panic or abort on allocation (a core gap, see
docs/stability.md); DualSPHysics' cases use 0.75-2."""


# ------------------------------------------------------------------------------------------------
# Field checks. Each raises SceneError("field: reason").


def _number(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SceneError(f"{name}: expected a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise SceneError(f"{name}: must be a finite number, got {value!r}")
    return v


def _positive(name: str, value: Any) -> float:
    v = _number(name, value)
    if v <= 0.0:
        raise SceneError(f"{name}: must be positive, got {value!r}")
    return v


def _non_negative(name: str, value: Any) -> float:
    v = _number(name, value)
    if v < 0.0:
        raise SceneError(f"{name}: must not be negative, got {value!r}")
    return v


def _integer(name: str, value: Any, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise SceneError(f"{name}: expected an integer, got {value!r}")
    if value < minimum:
        raise SceneError(f"{name}: must be at least {minimum}, got {value!r}")
    return value


def _choice(name: str, value: Any, allowed: tuple[str, ...]) -> str:
    if not isinstance(value, str) or value not in allowed:
        options = ", ".join(repr(a) for a in allowed)
        raise SceneError(f"{name}: unknown value {value!r}; allowed: {options}")
    return value


def _resolution(name: str, extent: float, dp: float, what: str) -> None:
    """Refuse a dp that leaves fewer than 2 particles across a fluid extent."""
    if extent < 2.0 * dp * (1.0 - 1e-9):
        raise SceneError(
            f"dp: {dp:g} m leaves fewer than 2 particles across the {what} ({name} = {extent:g} m)"
        )


# ------------------------------------------------------------------------------------------------


@dataclass(frozen=True, kw_only=True)
class SceneBuilder:
    """Parameters shared by every scene (see the module docstring for the defaults).

    Fields set to ``None`` take a default that depends on ``dim`` (``_DIM_DEFAULTS``), filled in
    when the builder is created.

    Attributes:
        dim: 2 or 3.
        dp: initial particle spacing [m].
        kernel: ``"wendland"`` (Wendland C2) or ``"cubic_spline"``.
        coefh: ``h = coefh * sqrt(dim) * dp`` [-].
        coefsound: ``c0 = coefsound * sqrt(g * h_swl)`` [-].
        gamma: Tait exponent [-].
        cfl: Courant number of the variable time step [-].
        viscosity: ``"artificial"``, ``"laminar"`` or ``"laminar_sps"``.
        alpha: artificial viscosity coefficient [-] (``viscosity="artificial"``).
        nu: kinematic viscosity [m^2/s] (laminar models).
        cs: Smagorinsky constant [-] (``"laminar_sps"``).
        ci: Blin constant [-] (``"laminar_sps"``).
        diffusion: density diffusion ``"none"``, ``"molteni"`` or ``"fourtakas"``.
        delta: density diffusion coefficient [-].
        integrator: ``"symplectic"`` or ``"verlet"``.
        euler_every: Verlet: one Euler step every this many steps.
        boundary: wall boundary model, ``"dbc"`` or ``"adami"`` (see :data:`BOUNDARY_MODELS`
            and ``Boundary`` in ``crates/sph-core/src/scene/numerics.rs``).
        force_precision: arithmetic of the force loop's pair terms, ``"f64"`` or ``"f32"``
            (see :data:`FORCE_PRECISIONS`).
        shifting: particle shifting's coefficient ``A`` [-] (Lind et al. 2012 with Skillen et
            al. 2013's ``D = A h |u| dt``; 2 is DualSPHysics' value, 1-6 the proposed range);
            ``None``: no shifting. See ``Shifting`` in ``crates/sph-core/src/scene/numerics.rs``.
        shifting_threshold: particle divergence at and below which a particle counts as on
            the free surface and is not shifted [-], in (0, dim); ``None``: 1.5 in 2D, 2.75
            in 3D. Only with ``shifting``.
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

    dim: int = 2
    dp: float | None = None
    kernel: str = "wendland"
    coefh: float = 1.0
    coefsound: float = 20.0
    gamma: float = 7.0
    cfl: float = 0.2
    viscosity: str = "artificial"
    alpha: float = 0.02
    nu: float = 1.0e-6
    cs: float = 0.12
    ci: float = 0.0066
    diffusion: str = "fourtakas"
    delta: float = 0.1
    integrator: str = "symplectic"
    euler_every: int = 40
    boundary: str = "dbc"
    force_precision: str = "f64"
    shifting: float | None = None
    shifting_threshold: float | None = None
    rho0: float = 1000.0
    gravity: float = 9.81
    h_swl: float | None = None
    boundary_layers: int | None = None
    until: float | None = None
    density_band: float = 0.5
    lost_fraction_limit: float = 0.01
    energy_growth_limit: float = 0.05

    _ENERGY_MONITOR: ClassVar[bool] = True
    """Whether the core's energy monitor runs for this scene (it skips scenes with a paddle,
    ``check_energy`` in ``crates/sph-core/src/simulation.rs``), so ``energy_growth_limit`` means
    something."""

    def __post_init__(self) -> None:
        if isinstance(self.dim, bool) or self.dim not in (2, 3):
            raise SceneError(f"dim: must be 2 or 3, got {self.dim!r}")
        for key, value in self._DIM_DEFAULTS.get(self.dim, {}).items():
            if getattr(self, key) is None:
                object.__setattr__(self, key, value)
        self.validate()

    # -- checks ---------------------------------------------------------------------------------

    def validate(self) -> None:
        """Check every field; raise :class:`SceneError` naming the first bad one."""
        if isinstance(self.dim, bool) or self.dim not in (2, 3):
            raise SceneError(f"dim: must be 2 or 3, got {self.dim!r}")
        _positive("dp", self.dp)
        _choice("kernel", self.kernel, KERNELS)
        if _positive("coefh", self.coefh) < MIN_COEFH:
            raise SceneError(
                f"coefh: must be at least {MIN_COEFH} (h = coefh sqrt(dim) dp), got "
                f"{self.coefh!r}: a smaller h reaches no more than the nearest neighbours, and "
                "the core's cell grid (cells of size h) outgrows memory"
            )
        _positive("coefsound", self.coefsound)
        _positive("gamma", self.gamma)
        cfl = _positive("cfl", self.cfl)
        if cfl > 1.0:
            raise SceneError(f"cfl: must be at most 1, got {self.cfl!r}")
        _choice("viscosity", self.viscosity, VISCOSITY_MODELS)
        _non_negative("alpha", self.alpha)
        _non_negative("nu", self.nu)
        _non_negative("cs", self.cs)
        _non_negative("ci", self.ci)
        _choice("diffusion", self.diffusion, DIFFUSION_MODELS)
        _non_negative("delta", self.delta)
        _choice("integrator", self.integrator, INTEGRATORS)
        _integer("euler_every", self.euler_every, 1)
        _choice("boundary", self.boundary, BOUNDARY_MODELS)
        _choice("force_precision", self.force_precision, FORCE_PRECISIONS)
        if self.force_precision == "f32" and self.viscosity == "laminar_sps":
            raise SceneError(
                "force_precision: f32 pair terms exist in the batched force loop only; the "
                "laminar_sps closure runs the f64 loop, so use f64"
            )
        if self.shifting is not None:
            _positive("shifting", self.shifting)
        if self.shifting_threshold is not None:
            if self.shifting is None:
                raise SceneError(
                    "shifting_threshold: only means something with particle shifting on; set "
                    "shifting (its coefficient, e.g. 2) or leave the threshold unset"
                )
            if not 0.0 < _positive("shifting_threshold", self.shifting_threshold) < self.dim:
                raise SceneError(
                    f"shifting_threshold: must lie strictly between 0 and dim = {self.dim} (the "
                    f"particle divergence inside the water), got {self.shifting_threshold!r}"
                )
        _positive("rho0", self.rho0)
        _positive("gravity", self.gravity)
        if self.h_swl is not None:
            _positive("h_swl", self.h_swl)
        if self.boundary_layers is not None:
            _integer("boundary_layers", self.boundary_layers, 1)
        _positive("until", self.until)
        self._validate_monitors()
        self._validate_geometry()

    def _validate_monitors(self) -> None:
        """The stability monitor thresholds (ranges: docs/stability.md, the constants above)."""
        if _positive("density_band", self.density_band) > MAX_DENSITY_BAND:
            raise SceneError(
                f"density_band: must be at most {MAX_DENSITY_BAND:g} (the band rho0 (1 -+ "
                f"density_band) then reaches zero density), got {self.density_band!r}"
            )
        if _non_negative("lost_fraction_limit", self.lost_fraction_limit) > 1.0:
            raise SceneError(
                f"lost_fraction_limit: must be at most 1 (a fraction of the fluid), got "
                f"{self.lost_fraction_limit!r}"
            )
        if not self._ENERGY_MONITOR:
            if self.energy_growth_limit is not None:
                raise SceneError(
                    "energy_growth_limit: the core's energy monitor does not run in a scene with "
                    "a paddle; leave it unset"
                )
        elif _positive("energy_growth_limit", self.energy_growth_limit) > MAX_ENERGY_GROWTH_LIMIT:
            raise SceneError(
                f"energy_growth_limit: must be at most {MAX_ENERGY_GROWTH_LIMIT:g} (a growth by "
                f"the whole initial potential energy), got {self.energy_growth_limit!r}"
            )

    def _validate_geometry(self) -> None:  # pragma: no cover - overridden
        raise NotImplementedError

    # -- scene ----------------------------------------------------------------------------------

    @property
    def smoothing_length(self) -> float:
        """``h = coefh * sqrt(dim) * dp`` [m]."""
        assert self.dp is not None
        return self.coefh * math.sqrt(self.dim) * self.dp

    def _physics(self) -> dict[str, Any]:
        """The scene keys that do not describe geometry."""
        if self.viscosity == "artificial":
            viscosity: dict[str, Any] = {"model": "artificial", "alpha": float(self.alpha)}
        elif self.viscosity == "laminar":
            viscosity = {"model": "laminar", "nu": float(self.nu)}
        else:
            viscosity = {
                "model": "laminar_sps",
                "nu": float(self.nu),
                "cs": float(self.cs),
                "ci": float(self.ci),
            }
        diffusion: dict[str, Any] = {"model": self.diffusion}
        if self.diffusion != "none":
            diffusion["delta"] = float(self.delta)
        integrator: dict[str, Any] = {"scheme": self.integrator}
        if self.integrator == "verlet":
            integrator["euler_every"] = int(self.euler_every)
        physics: dict[str, Any] = {
            "dim": int(self.dim),
            "dp": float(self.dp),  # type: ignore[arg-type]
            "gravity": float(self.gravity),
            "rho0": float(self.rho0),
            "kernel": self.kernel,
            "coefh": float(self.coefh),
            "coefsound": float(self.coefsound),
            "gamma": float(self.gamma),
            "h_swl": None if self.h_swl is None else float(self.h_swl),
            "cfl": float(self.cfl),
            "viscosity": viscosity,
            "diffusion": diffusion,
            "integrator": integrator,
            "boundary": {"model": self.boundary},
            "force_precision": self.force_precision,
            "shifting": None if self.shifting is None else {
                "coefficient": float(self.shifting),
                "surface_threshold": (None if self.shifting_threshold is None
                                      else float(self.shifting_threshold)),
            },
            "density_band": float(self.density_band),
            "lost_fraction_limit": float(self.lost_fraction_limit),
        }
        if self._ENERGY_MONITOR:
            physics["energy_growth_limit"] = float(self.energy_growth_limit)
        return physics

    def to_scene(self) -> dict[str, Any]:
        """The scene as a JSON-ready dict in the core's form (checked first)."""
        self.validate()
        scene = self._physics()
        scene.update(self._geometry())
        scene["boundary_layers"] = self.boundary_layers
        return scene

    def _geometry(self) -> dict[str, Any]:  # pragma: no cover - overridden
        raise NotImplementedError

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
        """The builder's fields as a plain dict."""
        return dataclasses.asdict(self)


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
        2: {"dp": 0.025, "until": 0.7},
        3: {"dp": 0.1, "until": 0.7, "tank_width": 0.5},
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
        2: {"dp": 0.025, "until": 2.0, "length": 1.0, "depth": 0.5, "height": 0.7},
        3: {"dp": 0.05, "until": 2.0, "length": 0.6, "depth": 0.3, "height": 0.4, "width": 0.3},
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
