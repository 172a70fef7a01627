"""The numerical options of a scene, one class per model, and the presets of the built-in cases.

Each class mirrors one model of the core's options (``crates/sph-core/src/scene/numerics.rs``):
it owns its parameters, their checks and its core form. Python keeps no default of its own for a
core parameter: a parameter left ``None`` is absent from the scene the core reads, and the
core's default applies (:func:`core_default`, read from ``watersim._core.scene_defaults()``;
``Defaults`` in ``crates/sph-core/src/scene/defaults.rs``).

A builder's option field (``viscosity``, ``diffusion``, ``integrator``, ``boundary``,
``shifting``, ``tensile_correction``, ``riemann``, ``kernel_correction``) takes the option object
(``Laminar(nu=2e-6)``), its model's name (``"laminar"``: that model with the core's
parameters) or its scene-file table (``{"type": "laminar", "nu": 2e-6}``); a shifting
coefficient alone may be given as a number,
and an option that is off by default (``shifting``, ``tensile_correction``, ``riemann``) may be
given by its law's name (``"monaghan"``, ``"acoustic"``).
``--set viscosity.alpha=0.03`` changes one parameter (:func:`from_settings`).

The presets at the end are the numerics the built-in cases choose on purpose, with the reasons;
they are the only numbers for core parameters on the Python side.
"""

from __future__ import annotations

import dataclasses
import functools
import typing
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

from . import _core
from ._core import SceneError
from .checks import _choice, _integer, _non_negative, _positive
from .errors import did_you_mean
from .overrides import Override, OverrideError

__all__ = [
    "BOUNDARIES",
    "BOUNDARY_MODELS",
    "CHOICES",
    "FORCE_PRECISIONS",
    "KERNELS",
    "MAX_DENSITY_BAND",
    "MAX_ENERGY_GROWTH_LIMIT",
    "MIN_COEFH",
    "DIFFUSIONS",
    "FLUME",
    "FLUME2D_ALPHA",
    "FLUME_CASE",
    "INTEGRATORS",
    "SLIP_MODES",
    "OPTION_CLASSES",
    "SETTABLE_PARAMETERS",
    "TAGS",
    "VERIFICATION",
    "VISCOSITIES",
    "WAVE_CARRYING",
    "WATER",
    "Adami",
    "Artificial",
    "Dbc",
    "Fourtakas",
    "KernelCorrection",
    "Laminar",
    "LaminarSps",
    "Mdbc",
    "Molteni",
    "NoDiffusion",
    "Option",
    "RiemannSolver",
    "Shifting",
    "Symplectic",
    "TensileCorrection",
    "Verlet",
    "ViscosityOption",
    "core_default",
    "from_settings",
    "option",
    "option_keys",
]


@functools.cache
def _defaults() -> dict[str, Any]:
    return _core.scene_defaults()


def core_default(key: str) -> Any:
    """The core's default of a scene key, by its dotted path (``"gravity"``,
    ``"viscosity.alpha"``, ``"viscosity.model"``)."""
    node: Any = _defaults()
    for part in key.split("."):
        node = node[part]
    return node


# ------------------------------------------------------------------------------------------------
# options named by a word, and ranges

KERNELS: tuple[str, ...] = ("wendland", "wendland_c4", "cubic_spline")
"""Kernel names the core knows (``KernelKind`` in ``crates/sph-core/src/kernel.rs``):
``"wendland"`` (Wendland C2, free of the cubic spline's pairing instability), ``"wendland_c4"``
(smoother, two multiplications more per pair) and ``"cubic_spline"``."""

FORCE_PRECISIONS: tuple[str, ...] = ("f64", "f32")
"""Arithmetic of the force loop's pair terms: ``"f64"``, or ``"f32"`` (eight pairs to an AVX2
register instead of four, as DualSPHysics forms its forces; the state stays f64). Not with
:class:`LaminarSps`, whose loop is f64 only. ``ForcePrecision`` in
``crates/sph-core/src/scene/numerics.rs``; docs/benchmarks.md measures speed and accuracy."""

CHOICES: dict[str, tuple[str, ...]] = {
    "kernel": KERNELS,
    "force_precision": FORCE_PRECISIONS,
}
"""The options given by a word, and the words allowed."""

MIN_COEFH = 0.5
"""Smallest ``coefh`` accepted (the core's ``MIN_COEFH``): a smaller h reaches no more than the
nearest neighbours, and the neighbour grid (cells of side h) outgrows memory; DualSPHysics'
cases use 0.75-2."""

MAX_DENSITY_BAND = 1.0
"""Largest ``density_band`` accepted (the core's ``MAX_DENSITY_BAND``): the band
``rho0 (1 -+ density_band)`` then reaches density 0, and a wider one bounds nothing below."""

MAX_ENERGY_GROWTH_LIMIT = 1.0
"""Largest ``energy_growth_limit`` accepted (the core's ``MAX_ENERGY_GROWTH_LIMIT``): an
unforced fluid whose mechanical energy grew by its whole initial potential energy is no solution
any more, so a looser monitor would never stop a run that needs stopping."""


# ------------------------------------------------------------------------------------------------
# the options


@dataclass(frozen=True, kw_only=True)
class Option:
    """A numerical option of a scene: every parameter optional (``None``: the core's default)."""

    FIELD: ClassVar[str]
    """The scene key (and builder field) the option sits under."""
    TAG: ClassVar[str] = ""
    """The model's name (its ``type`` in a scene file); empty for an option of one model."""
    TAG_KEY: ClassVar[str] = "model"
    """The key naming the model in the core's scene."""
    POSITIVE: ClassVar[tuple[str, ...]] = ()
    """Parameters that must be > 0 (the others must be >= 0)."""

    def __post_init__(self) -> None:
        self.check()

    def check(self) -> None:
        """Refuse a parameter out of range, naming it by its dotted path."""
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is None:
                continue
            key = f"{self.FIELD}.{f.name}"
            if f.name in self.POSITIVE:
                _positive(key, value)
            else:
                _non_negative(key, value)

    def to_core(self) -> dict[str, Any]:
        """The option in the core's form: its model and the parameters that are set."""
        out: dict[str, Any] = {self.TAG_KEY: self.TAG} if self.TAG else {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if isinstance(value, str):
                out[f.name] = value
            elif value is not None:
                out[f.name] = int(value) if str(f.type).startswith("int") else float(value)
        return out

    def to_table(self) -> dict[str, Any]:
        """The option as a scene-file table (``type``, then the parameters that are set)."""
        out: dict[str, Any] = {"type": self.TAG} if self.TAG else {}
        out.update({f.name: getattr(self, f.name) for f in dataclasses.fields(self)
                    if getattr(self, f.name) is not None})
        return out


@dataclass(frozen=True, kw_only=True)
class ViscosityOption(Option):
    """What every viscosity model takes.

    Attributes:
        wall_factor: factor on the viscous term of fluid-wall pairs (DualSPHysics'
            ``ViscoBoundFactor``): 1 (the core's default) treats a wall particle as fluid, 0
            makes the walls free slip for the viscosity while their pressure still keeps the
            fluid out (Adami et al. 2012's free-slip walls); docs/physics-options.md, "Free-slip
            walls", measures what it does to a wave and to run-up.
    """

    FIELD: ClassVar[str] = "viscosity"

    wall_factor: float | None = None


@dataclass(frozen=True, kw_only=True)
class Artificial(ViscosityOption):
    """Monaghan (1992) artificial viscosity.

    Attributes:
        alpha: coefficient [-].
    """

    TAG: ClassVar[str] = "artificial"

    alpha: float | None = None


@dataclass(frozen=True, kw_only=True)
class Laminar(ViscosityOption):
    """Lo & Shao (2002) laminar viscosity.

    Attributes:
        nu: kinematic viscosity [m^2/s].
    """

    TAG: ClassVar[str] = "laminar"

    nu: float | None = None


@dataclass(frozen=True, kw_only=True)
class LaminarSps(ViscosityOption):
    """Laminar viscosity plus the SPS Smagorinsky closure (Dalrymple & Rogers 2006); its force
    loop is f64 only.

    Attributes:
        nu: kinematic viscosity [m^2/s].
        cs: Smagorinsky constant [-].
        ci: Blin constant [-].
    """

    TAG: ClassVar[str] = "laminar_sps"

    nu: float | None = None
    cs: float | None = None
    ci: float | None = None


@dataclass(frozen=True, kw_only=True)
class NoDiffusion(Option):
    """No density diffusion term."""

    FIELD: ClassVar[str] = "diffusion"
    TAG: ClassVar[str] = "none"


@dataclass(frozen=True, kw_only=True)
class Molteni(Option):
    """Molteni & Colagrossi (2009) density diffusion.

    Attributes:
        delta: coefficient [-].
    """

    FIELD: ClassVar[str] = "diffusion"
    TAG: ClassVar[str] = "molteni"

    delta: float | None = None


@dataclass(frozen=True, kw_only=True)
class Fourtakas(Option):
    """Fourtakas et al. (2019) density diffusion: the hydrostatic part of the density difference
    is removed, taken in pressure, ``(p_b - p_a - rho0 g z_ab) / c0^2``, zero for every pair of
    still water, where the paper's density form (Eq. 13) adds density at depth and still water
    slowly expands (docs/wave-flume.md, "The mean water level").

    Attributes:
        delta: coefficient [-].
    """

    FIELD: ClassVar[str] = "diffusion"
    TAG: ClassVar[str] = "fourtakas"

    delta: float | None = None


@dataclass(frozen=True, kw_only=True)
class Symplectic(Option):
    """The second-order, time-reversible symplectic scheme (two force evaluations a step)."""

    FIELD: ClassVar[str] = "integrator"
    TAG: ClassVar[str] = "symplectic"
    TAG_KEY: ClassVar[str] = "scheme"


@dataclass(frozen=True, kw_only=True)
class Verlet(Option):
    """The Verlet scheme (one force evaluation a step), with an Euler step now and then.

    Attributes:
        euler_every: one Euler step every this many steps.
    """

    FIELD: ClassVar[str] = "integrator"
    TAG: ClassVar[str] = "verlet"
    TAG_KEY: ClassVar[str] = "scheme"

    euler_every: int | None = None

    def check(self) -> None:
        if self.euler_every is not None:
            _integer("integrator.euler_every", self.euler_every, 1)


@dataclass(frozen=True, kw_only=True)
class Shifting(Option):
    """Particle shifting (``Shifting`` in ``crates/sph-core/src/scene/numerics.rs``): Fickian
    shifting (``model="lind"``: Lind et al. 2012 with Skillen et al. 2013's ``D = A h |u| dt``,
    a free-surface ramp on the particle divergence) or the delta-plus-SPH shifting
    (``model="delta_plus"``: Sun et al. 2017, ``dr = -A h U_max dt sum [1 + R (W/W(dp))^4]
    grad W V``, no shift on the free surface found from the renormalisation matrix, only
    along the surface within a kernel support of it, none towards a wall). ``delta_plus``
    lowers a flume's mean level (by 0.15-0.24 H in ``flume2d-long`` at H/dp 5, where
    particles pass through the bed after 17 s, docs/physics-options.md): not for flumes yet.

    Attributes:
        model: ``"lind"`` or ``"delta_plus"``.
        coefficient: ``A`` [-] (``lind``: 1-6 the proposed range; ``delta_plus``: Sun et al.'s
            ``CFL Ma (2h)^2`` is ``A = 4``).
        surface_threshold: ``lind`` only: particle divergence at and below which a particle
            counts as on the free surface and is not shifted [-], in (0, dim); ``None``: the
            core's, by dimension (DualSPHysics' thresholds).
    """

    FIELD: ClassVar[str] = "shifting"
    POSITIVE: ClassVar[tuple[str, ...]] = ("coefficient", "surface_threshold")
    MODELS: ClassVar[tuple[str, ...]] = ("lind", "delta_plus")

    model: str | None = None
    coefficient: float | None = None
    surface_threshold: float | None = None

    def check(self) -> None:
        if self.model is not None and self.model not in self.MODELS:
            hint = did_you_mean(self.model, self.MODELS) if isinstance(self.model, str) else ""
            raise SceneError(f"shifting.model: unknown value {self.model!r}{hint}; allowed: "
                             f"{', '.join(repr(m) for m in self.MODELS)}")
        if self.model == "delta_plus" and self.surface_threshold is not None:
            raise SceneError("shifting.surface_threshold: belongs to model 'lind'; "
                             "'delta_plus' finds the free surface from the renormalisation "
                             "matrix")
        for name in ("coefficient", "surface_threshold"):
            value = getattr(self, name)
            if value is not None:
                _positive(f"shifting.{name}", value)

    def to_core(self) -> dict[str, Any]:
        out: dict[str, Any] = {} if self.model is None else {"model": self.model}
        for name in ("coefficient", "surface_threshold"):
            if (value := getattr(self, name)) is not None:
                out[name] = float(value)
        return out

    def check_dim(self, dim: int) -> None:
        """The threshold against the bulk's particle divergence ``dim``."""
        t = self.surface_threshold
        if t is not None and not 0.0 < t < dim:
            raise SceneError(
                f"shifting.surface_threshold: must lie strictly between 0 and dim = {dim} (the "
                f"particle divergence inside the water), got {t!r}")


@dataclass(frozen=True, kw_only=True)
class TensileCorrection(Option):
    """Monaghan's (2000) artificial pressure against the tensile instability, as DualSPHysics
    applies it to the cubic spline (``TensileCorrection`` in
    ``crates/sph-core/src/physics/tensile.rs``): each pair's pressure term in the momentum
    equation, fluid-fluid and fluid-wall, gains ``(R_a + R_b) (W_ab / W(h/1.5))^4`` with
    ``R = eps |P| / rho^2``, ``eps = epsilon_pos`` where ``P > 0`` and ``epsilon_neg`` where
    ``P < 0``. Off by default; ``kernel = "cubic_spline"`` only (refused with the Wendland
    kernel). ``W(dp)`` is taken at ``h/1.5``, DualSPHysics' choice, whatever ``h/dp``.

    Attributes:
        model: ``"monaghan"`` (the only law).
        epsilon_pos: ``eps`` at positive pressure [-] (DualSPHysics: 0.01).
        epsilon_neg: ``eps`` at negative pressure, where water is under tension [-]
            (Monaghan 2000, DualSPHysics: 0.2).
    """

    FIELD: ClassVar[str] = "tensile_correction"
    MODELS: ClassVar[tuple[str, ...]] = ("monaghan",)
    KERNELS: ClassVar[tuple[str, ...]] = ("cubic_spline",)
    """The kernels the correction is defined for (the core's ``tensile::corrects``)."""

    model: str | None = None
    epsilon_pos: float | None = None
    epsilon_neg: float | None = None

    def check(self) -> None:
        if self.model is not None:
            _choice("tensile_correction.model", self.model, self.MODELS)
        for name in ("epsilon_pos", "epsilon_neg"):
            if (value := getattr(self, name)) is not None:
                _non_negative(f"tensile_correction.{name}", value)

    def check_kernel(self, kernel: str) -> None:
        """Refuse a kernel the correction is not defined for (the core's check)."""
        if kernel not in self.KERNELS:
            raise SceneError(
                f"tensile_correction: Monaghan's (2000) correction is defined for kernel = "
                f"\"cubic_spline\" only (as DualSPHysics applies it), not for kernel = {kernel!r}; "
                "leave tensile_correction out or use the cubic spline")


@dataclass(frozen=True, kw_only=True)
class RiemannSolver(Option):
    """Riemann-solver SPH with the low-dissipation limiter (Zhang, Hu & Adams 2017, J. Comput.
    Phys. 335; ``crates/sph-core/src/physics/riemann.rs``): each pair's pressure and continuity
    terms come from a linearised (acoustic) Riemann problem along the pair, whose dissipation
    replaces the artificial viscosity (in momentum, on approaching pairs only, quadratic in the
    approach speed through the limiter) and the density diffusion (in continuity, without its
    hydrostatic part). Off by default; it needs ``viscosity`` laminar or laminar_sps (water's
    own viscosity is still added), ``diffusion`` none, the symplectic integrator (Verlet's
    leapfrog amplifies the solver's density dissipation) and ``force_precision`` f64, and is
    refused otherwise, naming the field.

    Attributes:
        model: ``"acoustic"`` (the linearised solver, the only one).
        limiter: ``eta`` of the limiter ``beta = min(eta max(U_a - U_b, 0) / c, 1)`` [-]
            (Zhang et al.: 3); 0 drops the momentum's dissipation, a large value gives the
            full acoustic solver.
    """

    FIELD: ClassVar[str] = "riemann"
    MODELS: ClassVar[tuple[str, ...]] = ("acoustic",)

    model: str | None = None
    limiter: float | None = None

    def check(self) -> None:
        if self.model is not None:
            _choice("riemann.model", self.model, self.MODELS)
        if self.limiter is not None:
            _non_negative("riemann.limiter", self.limiter)

    def check_scene(self, viscosity: str, diffusion: str, integrator: str,
                    force_precision: str, tensile_correction: bool) -> None:
        """Refuse the options the solver replaces or cannot run with (the core's check), given
        the model names the scene resolves to."""
        if viscosity == "artificial":
            raise SceneError(
                "viscosity: the Riemann solver's limiter replaces the artificial viscosity "
                "(Zhang et al. 2017); with riemann use viscosity 'laminar' or 'laminar_sps'")
        if diffusion != "none":
            raise SceneError(
                "diffusion: the Riemann solver's continuity diffuses density itself; with "
                "riemann use diffusion 'none'")
        if integrator == "verlet":
            raise SceneError(
                "integrator: the Verlet scheme's leapfrog amplifies the Riemann solver's density "
                "dissipation; with riemann use the symplectic integrator")
        if force_precision != "f64":
            raise SceneError("force_precision: the Riemann solver's force loop is f64 only; "
                             "use f64")
        if tensile_correction:
            raise SceneError("tensile_correction: is a correction of the classic pressure "
                             "term; the Riemann solver's force loop has none")


@dataclass(frozen=True, kw_only=True)
class KernelCorrection(Option):
    """Kernel gradient correction of the pressure term (Bonet & Lok 1999;
    ``crates/sph-core/src/physics/kgc.rs``): inside the water each fluid particle's pressure
    gradient is the corrected gradient of the pressure difference,
    ``-(1/rho_a) sum_b V_b (P_b - P_a) B_a^-1 grad W``, exact for a linear pressure on any
    particle set; particles whose correction matrix is ill-conditioned (at the free surface)
    keep the plain symmetric term. It runs the pair-at-a-time force loop and one more neighbour
    pass per force evaluation. Off by default; refused with ``force_precision`` f32, the tensile
    correction and the Riemann solver.

    Attributes:
        min_eigenvalue: smallest eigenvalue of the correction matrix ``B_a`` (1 inside the
            water, about 0.5 on a flat surface) from which a particle is corrected [-], in
            (0, 1] (the core's default: 0.75, Marrone et al.'s (2010) free-surface band).
    """

    FIELD: ClassVar[str] = "kernel_correction"
    POSITIVE: ClassVar[tuple[str, ...]] = ("min_eigenvalue",)

    min_eigenvalue: float | None = None

    def check(self) -> None:
        super().check()
        if self.min_eigenvalue is not None and self.min_eigenvalue > 1.0:
            raise SceneError(f"kernel_correction.min_eigenvalue: must be at most 1 (the "
                             f"eigenvalue inside the water), got {self.min_eigenvalue!r}")


@dataclass(frozen=True, kw_only=True)
class Dbc(Option):
    """Dynamic boundary condition (Crespo et al. 2007): wall particles integrate continuity
    from their fluid neighbours, their density floored at rho0."""

    FIELD: ClassVar[str] = "boundary"
    TAG: ClassVar[str] = "dbc"


@dataclass(frozen=True, kw_only=True)
class Adami(Option):
    """Adami, Hu & Adams (2012) walls: at every force evaluation each wall particle takes the
    pressure extrapolated from its fluid neighbours (with the paddle's acceleration)."""

    FIELD: ClassVar[str] = "boundary"
    TAG: ClassVar[str] = "adami"


SLIP_MODES: tuple[str, ...] = ("wall_velocity", "no_slip", "free_slip")
"""The velocities a modified-DBC wall shows the fluid (``Slip`` in
``crates/sph-core/src/scene/numerics.rs``)."""


@dataclass(frozen=True, kw_only=True)
class Mdbc(Option):
    """Modified dynamic boundary condition (English et al. 2022): each wall particle takes the
    density at its ghost node (its mirror image through the wall surface, from the solids'
    geometry), interpolated from the fluid with first-order corrected SPH and extrapolated
    back along the normal; smooth wall pressures and no DBC gap.

    Attributes:
        slip: the velocity the wall shows the fluid: ``"wall_velocity"`` (its own, zero for a
            fixed wall), ``"no_slip"`` (``2 v_wall - v_ghost``) or ``"free_slip"`` (the fluid's
            tangential velocity, the normal one mirrored); one of :data:`SLIP_MODES`.
    """

    FIELD: ClassVar[str] = "boundary"
    TAG: ClassVar[str] = "mdbc"

    slip: str | None = None

    def check(self) -> None:
        if self.slip is not None:
            _choice("boundary.slip", self.slip, SLIP_MODES)


VISCOSITIES: tuple[type[Option], ...] = (Artificial, Laminar, LaminarSps)
DIFFUSIONS: tuple[type[Option], ...] = (NoDiffusion, Molteni, Fourtakas)
INTEGRATORS: tuple[type[Option], ...] = (Symplectic, Verlet)
BOUNDARIES: tuple[type[Option], ...] = (Dbc, Adami, Mdbc)

BOUNDARY_MODELS: tuple[str, ...] = tuple(cls.TAG for cls in BOUNDARIES)
"""Wall boundary models the core knows, by name (one class each in :data:`BOUNDARIES`)."""

OPTION_CLASSES: dict[str, tuple[type[Option], ...]] = {
    "viscosity": VISCOSITIES,
    "diffusion": DIFFUSIONS,
    "integrator": INTEGRATORS,
    "boundary": BOUNDARIES,
    "shifting": (Shifting,),
    "tensile_correction": (TensileCorrection,),
    "riemann": (RiemannSolver,),
    "kernel_correction": (KernelCorrection,),
}
"""The builder fields that hold an option, and the classes each takes."""

TAGS: dict[type, str] = {cls: cls.TAG for classes in OPTION_CLASSES.values()
                         for cls in classes if cls.TAG}
"""The ``type`` of each model class in a scene file."""

SETTABLE_PARAMETERS: dict[str, tuple[str, ...]] = {
    name: tuple(dict.fromkeys(f.name for cls in classes for f in dataclasses.fields(cls)))
    for name, classes in OPTION_CLASSES.items()
}
"""The parameters each option field offers to ``--set FIELD.PARAMETER=...``."""


def _by_tag(field: str, tag: Any) -> type[Option]:
    classes = {cls.TAG: cls for cls in OPTION_CLASSES[field]}
    if not isinstance(tag, str) or tag not in classes:
        hint = did_you_mean(tag, classes) if isinstance(tag, str) else ""
        raise SceneError(f"{field}: unknown value {tag!r}{hint}; allowed: "
                         f"{', '.join(repr(t) for t in classes)}")
    return classes[tag]


def _from_table(field: str, table: Mapping[str, Any]) -> Option:
    params = dict(table)
    classes = OPTION_CLASSES[field]
    cls = _by_tag(field, params.pop("type", None)) if classes[0].TAG else classes[0]
    names = {f.name for f in dataclasses.fields(cls)}
    for key in params:
        if key not in names:
            model = f" model {cls.TAG!r}" if cls.TAG else ""
            raise SceneError(f"{field}.{key}: not a parameter of {field}{model} (its "
                             f"parameters: {', '.join(sorted(names)) or 'none'})")
    return cls(**params)


def option(field: str, value: Any) -> Option | None:
    """The option of the builder field ``field`` from any of its forms (see the module
    docstring); None stays None (the core's default)."""
    if value is None or isinstance(value, OPTION_CLASSES[field]):
        return value
    if isinstance(value, str) and OPTION_CLASSES[field][0].TAG:
        return _by_tag(field, value)()
    if isinstance(value, str) and hasattr(OPTION_CLASSES[field][0], "MODELS"):
        return OPTION_CLASSES[field][0](model=value)  # an off-by-default option's law
    if isinstance(value, Mapping):
        return _from_table(field, value)
    if field == "shifting" and isinstance(value, (int, float)) and not isinstance(value, bool):
        return Shifting(coefficient=value)
    names = " or ".join(cls.__name__ for cls in OPTION_CLASSES[field])
    raise SceneError(f"{field}: expected {names}, a model name or a table, got {value!r}")


def option_keys(field: str) -> list[str]:
    """The ``--set`` keys of an option field: the field (its model) and each parameter."""
    return [field, *(f"{field}.{p}" for p in SETTABLE_PARAMETERS[field])]


def from_settings(field: str, current: Any, items: Mapping[str, str]) -> Option | None:
    """The option ``field`` after ``--set`` items (dotted key -> text): ``FIELD=MODEL`` picks a
    model with the core's parameters (``none``/``auto`` clears an optional option, unless the
    field has a model of that name: ``diffusion=none`` is :class:`NoDiffusion`), each
    ``FIELD.PARAMETER=VALUE`` sets one parameter of the model chosen (the case's, else the
    core's default model).

    Raises:
        OverrideError: a parameter the model does not have, or a value of the wrong type.
    """
    try:
        value = option(field, current)
        if field in items:
            text = items[field]
            word = text.strip().lower()
            cleared = (word in ("none", "null", "auto")
                       and word not in {cls.TAG for cls in OPTION_CLASSES[field]})
            typed = Override(field, text).typed(float if field == "shifting" else str)
            value = None if cleared else option(field, typed)
        prefix = f"{field}."
        params = {k[len(prefix):]: t for k, t in items.items() if k.startswith(prefix)}
        if not params:
            return value
        if value is None:
            tag = core_default(f"{field}.{OPTION_CLASSES[field][0].TAG_KEY}") \
                if OPTION_CLASSES[field][0].TAG else None
            value = option(field, tag) if tag is not None else OPTION_CLASSES[field][0]()
        hints = typing.get_type_hints(type(value))
        names = {f.name for f in dataclasses.fields(value)}
        changes = {}
        for name, text in params.items():
            if name not in names:
                model = f" model {value.TAG!r}" if value.TAG else ""
                raise OverrideError(f"{prefix}{name}: not a parameter of the {field}{model} "
                                    f"(its parameters: {', '.join(sorted(names)) or 'none'})")
            changes[name] = Override(prefix + name, text).typed(hints[name])
        return dataclasses.replace(value, **changes)
    except SceneError as exc:
        raise OverrideError(str(exc)) from None


# ------------------------------------------------------------------------------------------------
# presets: the numerics the built-in cases choose on purpose


VERIFICATION: Mapping[str, Any] = {"viscosity": Artificial(alpha=0.02)}
"""The dam break and the still tank (:class:`~watersim.DamBreak`, :class:`~watersim.Tank`):
artificial viscosity 0.02 instead of the core's 0.01, in the 0.01-0.1 range recommended for
free-surface flows and a low value, since it also damps the physical flow, but above 0.01 for
the coarse resolutions these cases run at. It is not tuned to any data set."""

FLUME: Mapping[int, Mapping[str, Any]] = {
    2: {"coefh": 1.5, "boundary": "adami"},
    3: {"coefh": 1.2, "boundary": "adami"},
}
"""Every flume (:class:`~watersim.FlumeScene`), by dimension, for wave propagation:

- ``coefh = 1.5`` in 2D, 1.2 in 3D (``h = 2.1 dp`` in both; DualSPHysics' 3D wave cases use
  1.2): at coarse resolution it carries a regular wave much further than ``coefh = 1``
  (measured in 2D, d = 0.3 m, T = 1.2 s, H = 0.06 m, dp = 0.02 m, H/dp = 3: wave height at one
  wavelength 92 % of the target against 79 % with ``coefh = 1``; ``coefh = 2`` gives the same
  92 % at twice the cost). The time step grows with h, which pays back most of the extra
  neighbours in 2D.
- ``boundary = "adami"`` (Adami et al. 2012; the dam break keeps DBC): a DBC wall's density
  remembers the water it has seen, so a crest cannot climb a wall that started dry and the
  waterline on a wall is pumped down (docs/wave-flume.md, "Walls that remember"). Measured:
  flume3d's wave at a side wall had 25 % of its height with DBC and the same height as on the
  centre line with Adami's walls; flume2d at H/dp = 5 keeps 98 % / 95 % / 92 % of the height at
  1 / 2 / 3 L instead of 94 % / 91 % / 88 %.

The viscosity is the core's, artificial with alpha = 0.01: that of seed 001 (Roselli et al.,
Table 2) and of DualSPHysics wave cases (Altomare et al. 2017)."""

FLUME_CASE: Mapping[str, Any] = {"coefsound": 10.0}
"""The built-in flume cases (:mod:`watersim.flume_cases`): ``c0 = 10 sqrt(g d)`` at the paddle
depth d, ten times the shallow-water wave speed, density variations about 1 % of rho0;
Monaghan's rule c0 >= 10 |v|max holds for non-breaking waves and, from the deeper paddle depth,
for the breakers of kimmoun2d and stansby2d too. It halves the number of steps against the
core's 20."""

FLUME2D_ALPHA = 0.003
"""Artificial viscosity of the flat-floor regular-wave case flume2d [-]. Its viscous decay of
the wave height per wavelength is about ``2 nu k^2 L / c_g`` (Lamb 1932, section 348) with
``nu = alpha h c0 / 8`` (Monaghan 2005, 2D): with alpha = 0.01 that is 1.8 % per wavelength at
dp = 0.01 m, using up a 5 % height tolerance within three wavelengths; 0.003 costs 0.5 %
(measured at dp = 0.025 m, where the formula gives 4.5 % for 0.01: alpha 0.01 against 0 costs
6.6 % of the height at 1 L and 3.0 % per wavelength from 1 to 2 L)."""

WAVE_CARRYING: Mapping[str, Any] = {
    "viscosity": Artificial(alpha=FLUME2D_ALPHA),
    "integrator": Verlet(),
}
"""A non-breaking wave carried over several wavelengths (flume2d, the second-order validation
flume; docs/wave-flume.md, "How far WaterSim carries a wave"): :data:`FLUME2D_ALPHA`, and the
Verlet integrator, one force evaluation per step against two for Symplectic, at the same
measured decay."""

LOW_DISSIPATION: Mapping[str, Any] = {
    "kernel": "wendland_c4",
    "viscosity": Laminar(wall_factor=0.0),
    "diffusion": Fourtakas(delta=0.05),
    "integrator": Verlet(),
}
"""A non-breaking wave carried over many wavelengths, the combination that measured best on
flume2d-long (docs/physics-options.md, docs/validation/options): the Wendland C4 kernel,
water's viscosity with free-slip walls for it (``wall_factor = 0``), Fourtakas' diffusion at
``delta = 0.05`` (C4 with the Verlet integrator stands no more: at 0.1 the run stops next to
the piston) and Verlet. Measured at H/dp 5: 1.57 % of the height lost per wavelength against
3.1 % with :data:`WAVE_CARRYING` (at H/dp 10: 0.70 %); the focused group of
``examples/focused_group.py`` at 2A/dp 4: the crest at the focus 4.2 % below the linear target
against 11 %; solitary2d's run-up at H/dp 5 4.7 % below Synolakis' law against 10.0 % with the
flume defaults, in 107 s of CPU against 199 (docs/validation/options). Not for breaking waves:
on kimmoun2d the wave breaks later and lower and runs up less than with the flume defaults
(docs/physics-options.md, "Wendland C4")."""

WATER: Mapping[str, Any] = {"viscosity": Laminar()}
"""Water's own viscosity (the core's laminar ``nu``, 1e-6 m^2/s) for the cases whose wave runs
long over a bed or along side walls (kimmoun2d, flume3d): artificial viscosity 0.01 against the
bed damps the wave (docs/wave-flume.md)."""
