"""A flume and one run in it: the checked scene, its derived quantities and the core scene."""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from .. import numerics as nm
from .. import wave_theory as wt
from .._core import SceneError
from ..checks import _positive
from ..scenes import FluidBlock, Scene
from .bed import BEACH_TYPES, Beach, DampingZone, _bed, _shoreline_segment
from .checks import _TOL, _set, expected
from .gauges import (
    RUNUP_OFFSET_DP,
    SCENE_GAUGE_TYPES,
    Gauge,
    RunupGauge,
    check_gauges,
    gauge_names,
    gauge_specs,
)
from .lattice import MAX_PARTICLES, _lattice_error, _whole, lattice_dp
from .paddles import PADDLE_TYPES, Paddle, PaddleLaw, Piston
from .simulation import FlumeSimulation
from .structures import STRUCTURE_TYPES, Structure, check_structure
from .waves import WAVE_TYPES, Wave

MODEL_TYPES: tuple[type, ...] = (*BEACH_TYPES, *WAVE_TYPES, *PADDLE_TYPES, *SCENE_GAUGE_TYPES,
                                  *STRUCTURE_TYPES)
"""The classes a field of a flume scene takes one of (beach, wave, paddle, gauges,
structures)."""

TAGS: dict[type, str] = {cls: cls.TAG for cls in MODEL_TYPES}  # type: ignore[attr-defined]
"""Each model class's ``type`` in a scene file (the class's ``TAG``)."""

CHOICES: dict[tuple[type, str], tuple[str, ...]] = {
    (cls, field): values
    for cls in (*MODEL_TYPES, RunupGauge)
    for field, values in cls.CHOICES.items()  # type: ignore[attr-defined]
}
"""The allowed values of the models' string fields (each class's ``CHOICES``)."""


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
        zone = self.damping_spec()
        if zone is not None and zone.length is not None:
            if zone.length >= length:
                raise SceneError(
                    f"damping.length: the zone ({zone.length:g} m) is as long as the "
                    f"flume (length = {length:g} m)"
                )
        beach = self.beach
        if beach is None:
            return
        if not isinstance(beach, BEACH_TYPES):
            raise SceneError(
                f"beach: expected a PlaneBeach, a ProfileBeach, a MeshBeach or None, got {beach!r}"
            )
        beach.check_in(self)

    @property
    def dim(self) -> int:
        """2 without a width, 3 with one."""
        return 2 if self.width is None else 3

    def damping_enabled(self) -> bool:
        """Whether the flume has a damping zone (default: only without a beach)."""
        if self.damping is None:
            return self.beach is None
        return self.damping is not False

    def damping_spec(self) -> DampingZone | None:
        """The damping zone as given (the default zone for ``True`` or ``None``), None if off."""
        if not self.damping_enabled():
            return None
        return self.damping if isinstance(self.damping, DampingZone) else DampingZone()

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


@dataclass(frozen=True, kw_only=True)
class FlumeScene(Scene):
    """Everything about one flume run: the flume, the wave, the paddle, the gauges and every
    numerical parameter (those of :class:`~watersim.SceneBuilder`). A preset of
    :class:`~watersim.Scene`, as the dam break and the tank are: the flume makes the tank and
    the still water, and it takes ``bodies``, more ``fluid`` and ``gauges`` like any scene.

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
        gauges: gauge objects, of any class of :data:`~watersim.flume.gauges.Gauge` (every
            gauge but the run-up gauge).
        bodies: fixed solid bodies in the flume, the structures (any body of
            :mod:`watersim.bodies` but the half-space, or a :class:`ProfileStructure`), named
            for a force gauge: the core's obstacles after the beach.
        fluid: water besides the still water up to ``flume.depth`` (which the flume fills
            itself): :class:`~watersim.FluidBlock` boxes, for example a basin behind a seawall
            or water standing on a beach; at rest at t = 0 like the rest.
        runup: ``True`` for an automatic run-up gauge along the beach, a :class:`RunupGauge`,
            ``False`` for none; ``None`` (default): automatic when the beach reaches the SWL.
        sample_interval: default sampling interval of the gauges [s].
        energy_growth_limit: not used: the core's energy monitor skips scenes with a paddle
            (``density_band`` and ``lost_fraction_limit`` do apply); must stay unset.

    The numerics every flume chooses (``coefh`` by dimension and Adami's walls, for wave
    propagation) are :data:`watersim.numerics.FLUME`, with the measurements behind them; the
    rest is the core's (artificial viscosity 0.01, the value of seed 001 and of DualSPHysics'
    wave cases).
    """

    _DIM_DEFAULTS: ClassVar[Mapping[int, Mapping[str, Any]]] = nm.FLUME
    _ENERGY_MONITOR: ClassVar[bool] = False  # every flume has a paddle

    dim: int | None = None  # type: ignore[assignment]
    flume: Flume
    wave: Wave
    paddle: Paddle = dataclasses.field(default_factory=Piston)
    gauges: Sequence[Gauge] = ()
    bodies: Sequence[Structure] = ()  # type: ignore[assignment]
    fluid: Sequence[FluidBlock] = ()  # type: ignore[assignment]
    runup: bool | RunupGauge | None = None
    sample_interval: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.flume, Flume):
            raise SceneError(f"flume: expected a Flume, got {self.flume!r}")
        if not isinstance(self.wave, WAVE_TYPES):
            raise SceneError(f"wave: expected {expected(WAVE_TYPES)}, got {self.wave!r}")
        if not isinstance(self.paddle, PADDLE_TYPES):
            raise SceneError(f"paddle: expected a Piston or a Flap, got {self.paddle!r}")
        if self.tank is not None:
            raise SceneError("tank: a flume makes its own tank from `flume` (length, width, "
                             "height); use watersim.Scene for another geometry")
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
        if self.gravity is not None:
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
        self.wave.warn(self.paddle, self.flume.depth, self.g)

    # -- checks ---------------------------------------------------------------------------------

    PLACE: ClassVar[str] = "flume"
    """What the gauges' messages call the scene's extent."""
    FLUID_CLASSES: ClassVar[tuple[type, ...]] = (FluidBlock,)
    BODY_CLASSES: ClassVar[tuple[type, ...]] = STRUCTURE_TYPES

    def extent(self, axis: int) -> tuple[float, float]:
        """``(low, high)`` [m] of the water's extent along horizontal ``axis`` (0: x, from the
        paddle at rest to the far wall; 1: y, across a 3D flume)."""
        if axis == 0:
            return 0.0, self.flume.length
        assert self.flume.width is not None
        return 0.0, self.flume.width

    @property
    def level(self) -> float:
        """The level elevations are measured from [m above the floor]: the still water's."""
        return self.flume.depth

    def tank_size(self) -> tuple[float, ...]:
        """The flume's inner size from the paddle at rest [m]: (length, [width,] height)."""
        flume = self.flume
        if flume.width is None:
            return (flume.length, self.tank_height)
        return (flume.length, flume.width, self.tank_height)

    def fluid_boxes(self) -> list[tuple[tuple[float, ...], tuple[float, ...]]]:
        """The still water up to ``flume.depth``, then the ``fluid`` blocks."""
        flume = self.flume
        top = ((flume.length, flume.depth) if flume.width is None
               else (flume.length, flume.width, flume.depth))
        return [((0.0,) * len(top), top), *super().fluid_boxes()]

    def obstacle_index(self, structure: str) -> int | None:
        """The core's index of the obstacle of the structure named ``structure`` (the beach,
        if any, is obstacle 0), None if there is no such structure."""
        first = 0 if self.flume.beach is None else 1
        for i, s in enumerate(self.bodies):
            if s.name == structure:
                return first + i
        return None

    def _check_wave_and_paddle(self) -> None:
        """Combinations of wave and paddle the generation theory does not cover."""
        self.paddle.check(self.flume.depth)
        self.wave.check(self.paddle, self.flume.depth)

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
        across = 1.0 if flume.width is None else flume.width / dp
        n_fluid = flume.length / dp * flume.depth / dp * across
        if not n_fluid <= MAX_PARTICLES:  # first: the lattice check overflows on 1e306 layers
            raise SceneError(f"dp: {dp:g} m would need about {n_fluid:.3g} fluid particles; "
                             "use a larger dp")
        self._check_lattice()
        self.wave.check_resolved(dp, flume.depth, self.g)
        law = self.law
        if not (math.isfinite(law.forward) and math.isfinite(law.backward)):
            raise SceneError(f"wave: the paddle motion is not finite (excursion {law.forward!r} m)")
        limit = self.paddle.max_stroke
        if limit is not None and law.travel() > limit:
            raise SceneError(
                f"wave.{self.wave.SIZE}: the paddle would travel {law.travel():.4g} m peak to "
                f"peak, more than its stroke (paddle.max_stroke = {limit:g} m)"
            )
        self.wave.check_in(self)
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
        beach = flume.beach
        if np.max(_bed(px, pz, np.linspace(0.0, reach, 50))) > 0.0 or (
                beach is not None and beach.rises_within(flume, reach, dp)):
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
        self._check_symmetry()
        for i, structure in enumerate(self.bodies):
            check_structure(structure, self, f"bodies[{i}]")
        self._check_fluid_blocks(self.tank_size(), dp)
        names = check_gauges(self, self.gauges)
        runup = self.runup_gauge
        if runup is not None:
            if runup.name in names:
                raise SceneError(f"runup.name: {runup.name!r} is also the name of a gauge")
            assert runup.start is not None and runup.end is not None
            for label, point in (("runup.start", runup.start), ("runup.end", runup.end)):
                self.check_point(label, point)
        elif self.runup not in (None, False):
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

    def check_point(self, label: str, point: Sequence[float], vertical: bool = True) -> None:
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
        return self.wave.design_height

    @property
    def wavelength(self) -> float | None:
        """Linear wavelength at the paddle depth [m] for the (peak) period, or None."""
        if self.period is None:
            return None
        return float(wt.wavelength(self.period, self.flume.depth, self.g))

    @property
    def tank_height(self) -> float:
        """Height of the tank walls [m]: the flume's, or ``depth + max(depth/2, 3 H)`` rounded up
        to a whole dp (and at least the highest point of a profile beach)."""
        flume = self.flume
        if flume.height is not None:
            return flume.height
        h = self.design_height or 0.0
        height = flume.depth + max(0.5 * flume.depth, 3.0 * h)
        if flume.beach is not None:
            height = flume.beach.wall_top(height)
        dp = float(self.dp)  # type: ignore[arg-type]
        return math.ceil(height / dp - 1e-9) * dp

    @functools.cached_property
    def bed_profile(self) -> tuple[list[float], list[float]]:
        """Bed vertices ``(x, z)`` [m] of the beach (empty lists for a flat floor); for a
        :class:`MeshBeach`, along the flume's centre line."""
        beach = self.flume.beach
        if beach is None:
            return [], []
        return beach.profile_in(self.flume, self.tank_height)

    def bed(self, x: npt.ArrayLike, y: npt.ArrayLike | None = None) -> npt.NDArray[np.float64]:
        """Bed height above the floor at ``x`` [m] (under ``(x, y)`` for a :class:`MeshBeach`,
        ``y`` defaulting to the centre line; the other beaches are uniform across)."""
        beach = self.flume.beach
        if beach is None:
            return np.zeros_like(np.asarray(x, dtype=np.float64))
        return beach.bed_in(self.flume, self.bed_profile, x, y)

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
        return beach.iribarren_slope(self.bed_profile, self.flume.depth)

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
        zone = flume.damping_spec()
        if zone is None:
            return None
        length = zone.length
        if length is None:
            wl = self.wavelength
            length = wl if wl is not None else 0.25 * flume.length
        return flume.length - length, zone.strength

    @functools.cached_property
    def law(self) -> PaddleLaw:
        """The paddle law (the core's JSON) and its extent. An absorbing paddle also moves with
        the waves coming back: its room either way grows by what absorbing the wave fully
        reflected by a far wall takes, the law's largest excursion (a harmonic law's
        ``2 sqrt(sum a_i^2)``, four standard deviations of an irregular signal, below the sum of
        its amplitudes that bounds the law itself)."""
        # an absurd wave overflows the theory's formulas: the non-finite excursion that results
        # is refused, naming the wave, by _validate_geometry
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            law = self.wave.law(self.paddle, self.flume.depth, self.g)
        if not self.paddle.absorbs(law, self.flume.beach is not None):
            return law
        extra = max(law.forward, law.backward)
        if law.law["type"] == "harmonic":
            # math.hypot scales, so an absurd amplitude's square does not overflow
            amplitudes = [float(c[0]) for c in law.law["components"]]
            extra = min(extra, 2.0 * math.hypot(*amplitudes))
        return dataclasses.replace(law, forward=law.forward + extra,
                                   backward=law.backward + extra)

    @property
    def absorbs(self) -> bool:
        """Whether the paddle absorbs the waves coming back (``paddle.absorption``)."""
        return self.law.absorption_target is not None and self.paddle.absorbs(
            self.law, self.flume.beach is not None)

    @property
    def back_x(self) -> float:
        """x of the tank's back wall face [m]: a whole number of dp behind the paddle face, far
        enough for the paddle plate and its largest backward excursion (for a flap, the
        excursion of the plate's top, which swings further than the still-water level)."""
        dp = float(self.dp)  # type: ignore[arg-type]
        back = self.paddle.back_room(self.law.backward, self.tank_height, self.flume.depth)
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
        return self.wave.default_sample_interval(self.flume.depth, self.g)

    def _far_x(self) -> float:
        """Where the analysis needs waves: the last gauge, or the shoreline, or the flume end."""
        xs = [x for g in self.gauges for x in g.along_x()]
        if xs:
            return max(xs)
        shore = self.shoreline
        return shore if shore is not None else 0.75 * self.flume.length

    def _default_until(self) -> float:
        return self.wave.default_until(self, self._far_x())

    def arrival_time(self, x: float) -> float:
        """Time for the wave to travel from the paddle to ``x`` [s] (after the ramp).

        Linear group velocity at the local still-water depth for periodic waves (the front of
        a wave train travels at it), ``sqrt(g (d + H))`` for a solitary wave, ``sqrt(g d)``
        otherwise; integrated along the bed, stopping where the depth falls below 1 % of the
        paddle depth (the shoreline).
        """
        depth, g = self.flume.depth, self.g
        xs = np.linspace(0.0, max(float(x), 0.0), 400)
        d_local = np.asarray(self.still_depth(xs))
        wet = d_local > 0.01 * depth
        if not np.any(wet):
            return 0.0
        d_wet = np.where(wet, d_local, 0.01 * depth)
        if self.period is not None:
            speed = np.asarray(wt.group_velocity(self.period, d_wet, g))
        else:
            speed = self.wave.front_speed(d_wet, g)
        inv = np.where(wet, 1.0 / speed, 0.0)
        if xs.size < 2:
            return 0.0
        return float(np.sum(0.5 * (inv[1:] + inv[:-1]) * np.diff(xs)))

    # -- gauges ---------------------------------------------------------------------------------

    def _gauge_names(self) -> list[str]:
        """Names of :attr:`gauges` (defaults by position or index, deduplicated with ``_2``...)."""
        return gauge_names(self, self.gauges)

    @property
    def runup_gauge(self) -> RunupGauge | None:
        """The run-up gauge with its segment resolved (automatic or given), or None."""
        if self.runup is False:
            return None
        spec = self.runup if isinstance(self.runup, RunupGauge) else RunupGauge()
        if spec.start is not None:
            return spec
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
        default = float(self.sample_interval)  # type: ignore[arg-type]
        specs = gauge_specs(self, self.gauges, default)
        runup = self.runup_gauge
        if runup is not None:
            interval = default if runup.interval is None else runup.interval
            specs.append(runup.to_core(self, runup.name, interval))
        return specs

    # -- scene ----------------------------------------------------------------------------------

    def _geometry(self) -> dict[str, Any]:
        flume = self.flume
        size = [float(v) for v in self.tank_size()]
        # the tank reaches behind the paddle's rest position for its backward stroke
        tank = {"min": [self.back_x] + [0.0] * (len(size) - 1), "max": size}
        obstacles: list[dict[str, Any]] = []
        if flume.beach is not None:
            obstacles.append(flume.beach.to_core(self.bed_profile))
        obstacles.extend(s.to_core() for s in self.bodies)
        # the surface read two dp in front of the face: clear of the paddle's own particles
        probe = 2.0 * float(self.dp) if self.absorbs else None  # type: ignore[arg-type]
        paddle = self.paddle.to_core(self.law, flume.depth, probe, self.g)
        scene: dict[str, Any] = {
            "tank": tank,
            "obstacles": obstacles,
            "fluid": [{"min": [float(v) for v in lo], "max": [float(v) for v in hi]}
                      for lo, hi in self.fluid_boxes()],
            "paddle": paddle,
            "gauges": self._gauge_specs(),
        }
        zone = self.damping_zone
        if zone is not None:
            scene["damping"] = {"x_start": zone[0], "x_end": flume.length, "strength": zone[1]}
        return self._symmetry_to_core(scene)

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
            "height": law.design_height,
            "wavelength": self.wavelength,
            "ramp_duration": law.ramp_duration,
            "stroke": law.stroke,
            "second_order_amplitude": law.second_order_amplitude,
            "absorption": self.absorbs,
        }
        info.update(self.wave.describe(self))
        return info

