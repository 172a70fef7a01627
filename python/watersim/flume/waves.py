"""The waves a flume makes: regular, irregular, solitary, or a tabulated paddle motion."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
import numpy.typing as npt

from .. import wave_theory as wt
from .._core import SceneError
from ..checks import _choice, _integer, _non_negative, _number, _positive
from .checks import _finite_tuple, _set, _strictly_increasing
from .paddles import Paddle, PaddleLaw

if TYPE_CHECKING:
    from .scene import FlumeScene

SPECTRA: dict[str, str] = {
    "jonswap": "jonswap",
    "pm": "pierson-moskowitz",
    "pierson-moskowitz": "pierson-moskowitz",
}
"""Spectrum names accepted by :class:`IrregularWave`, and their :mod:`wave_theory` names."""


SOLITARY_MAX_H_OVER_D = 0.83
"""Highest solitary wave, H/d about 0.83 (Longuet-Higgins & Fenton 1974): a taller one does not
exist, and Goring's paddle motion for it is meaningless."""


class _Wave:
    """What every wave tells the scene: its paddle law, defaults and checks (each wave overrides
    what differs)."""

    TAG: ClassVar[str]
    """The wave's ``type`` in a scene file."""
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {}
    """The allowed values of the wave's string fields."""

    @property
    def design_height(self) -> float | None:
        """Height used to size the flume [m], None if unknown."""
        return None

    def check(self, paddle: Paddle, depth: float) -> None:
        """Refuse a paddle the generation theory of this wave does not cover."""
        if paddle.order == 2:
            raise SceneError(
                "paddle.order: second-order (Madsen 1971) generation is for regular waves only; "
                "use order=1"
            )

    def warn(self, paddle: Paddle, depth: float, g: float) -> None:
        """Warn of a wave beyond the theory of its generation (none to check by default)."""

    def front_speed(self, depth: npt.NDArray[np.float64], g: float) -> npt.NDArray[np.float64]:
        """Speed of a non-periodic wave's front at the local still-water ``depth`` [m/s]:
        ``sqrt(g d)``."""
        return np.asarray(np.sqrt(g * depth))

    def describe(self, scene: FlumeScene) -> dict[str, Any]:
        """What :meth:`FlumeScene.describe` reports about this wave besides the law."""
        return {}


@dataclass(frozen=True)
class RegularWave(_Wave):
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

    TAG: ClassVar[str] = "regular"

    def __post_init__(self) -> None:
        _set(self, "height", _positive("wave.height", self.height))
        _set(self, "period", _positive("wave.period", self.period))
        _set(self, "phase", _number("wave.phase", self.phase))

    @property
    def design_height(self) -> float:
        return self.height

    def check(self, paddle: Paddle, depth: float) -> None:
        """Every paddle makes a regular wave, at first or second order."""

    def warn(self, paddle: Paddle, depth: float, g: float) -> None:
        wt.warn_if_invalid_wave(self.height, self.period, depth, paddle.order, paddle.kind, g)

    def law(self, paddle: Paddle, depth: float, g: float) -> PaddleLaw:
        """Biesel's first-order stroke, with Madsen's (1971) second harmonic for order 2."""
        try:
            law = wt.regular_paddle_motion(
                self.height, self.period, depth, paddle.kind, paddle.order, self.phase, g
            )
        except ValueError as exc:  # pragma: no cover - inputs are checked above
            raise SceneError(f"wave: {exc}") from None
        stroke = law.stroke
        transfer = paddle.hinged_transfer(law.wavenumber, depth)
        if transfer is not None:
            stroke = self.height / float(transfer)
        components = [[0.5 * stroke, law.omega, law.phase]]
        # the target at the paddle: X = (S/2) sin(theta) makes eta = (H/2) cos(theta) there (the
        # elevation is in phase with the paddle's velocity), plus Stokes' bound second harmonic
        # (H/2 cos + a2 cos 2theta, crest at theta = 0) where the paddle generates it
        target = [[0.5 * self.height, law.omega, law.phase + 0.5 * math.pi]]
        if law.second_order_amplitude != 0.0:
            components.append([law.second_order_amplitude, 2.0 * law.omega, 2.0 * law.phase])
            bound = float(wt.stokes2_second_harmonic_amplitude(self.height, law.wavenumber, depth))
            target.append([bound, 2.0 * law.omega, 2.0 * law.phase + 0.5 * math.pi])
        return paddle.harmonic_law(
            components, sum(abs(c[0]) for c in components), self.period,
            design_height=self.height, stroke=stroke,
            second_order_amplitude=law.second_order_amplitude,
            absorption_target=target, absorption_gain=law.omega * stroke / self.height,
        )

    def default_sample_interval(self, depth: float, g: float) -> float:
        return min(self.period / 40.0, 0.05)

    def default_until(self, scene: FlumeScene, far: float) -> float:
        """Ten periods at ``far`` [m] after the ramp and the wave's arrival."""
        return scene.law.ramp_duration + scene.arrival_time(far) + 10.0 * self.period

    def describe(self, scene: FlumeScene) -> dict[str, Any]:
        wavelength = scene.wavelength
        if wavelength is None:
            return {}
        depth = scene.flume.depth
        return {
            "steepness": self.height / wavelength,
            "ursell": float(wt.ursell_number(self.height, self.period, depth, scene.g)),
            "kd": 2.0 * math.pi / wavelength * depth,
        }


@dataclass(frozen=True)
class IrregularWave(_Wave):
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

    TAG: ClassVar[str] = "irregular"
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {"spectrum": tuple(SPECTRA)}

    def __post_init__(self) -> None:
        _set(self, "hs", _positive("wave.hs", self.hs))
        _set(self, "tp", _positive("wave.tp", self.tp))
        _choice("wave.spectrum", self.spectrum, self.CHOICES["spectrum"])
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

    @property
    def design_height(self) -> float:
        return 1.8 * self.hs

    def law(self, paddle: Paddle, depth: float, g: float) -> PaddleLaw:
        """The spectrum's components through the paddle's transfer function."""
        try:
            motion = wt.irregular_paddle_motion(
                self.hs,
                self.tp,
                depth,
                SPECTRA[self.spectrum],  # type: ignore[arg-type]
                self.gamma,
                self.seed,
                self.random_amplitudes,
                paddle.kind,
                self.frequency_range,  # type: ignore[arg-type]
                self.repeat_period,
                g,
            )
        except ValueError as exc:
            raise SceneError(f"wave: {exc}") from None
        amplitudes = np.asarray(motion.stroke_amplitudes)
        transfer = paddle.hinged_transfer(motion.wavenumbers, depth)
        if transfer is not None:
            amplitudes = np.asarray(motion.wave_amplitudes) / transfer
        omegas = 2.0 * np.pi * np.asarray(motion.frequencies)
        components = [
            [float(a), float(w), float(p)]
            for a, w, p in zip(amplitudes, omegas, motion.phases, strict=True)
        ]
        # The core sizes the room behind the paddle with the sum of the amplitudes (a bound
        # of any harmonic law), far above the signal's actual extremes for hundreds of
        # components; the tank must satisfy that bound.
        bound = float(np.sum(np.abs(amplitudes)))
        # each component's elevation at the paddle is in phase with its velocity
        target = [
            [float(a), float(w), float(p) + 0.5 * math.pi]
            for a, w, p in zip(motion.wave_amplitudes, omegas, motion.phases, strict=True)
        ]
        peak = int(np.argmin(np.abs(np.asarray(motion.frequencies) - 1.0 / self.tp)))
        gain = float(omegas[peak] * amplitudes[peak] / motion.wave_amplitudes[peak])
        return paddle.harmonic_law(components, bound, self.tp, design_height=1.8 * self.hs,
                                   absorption_target=target, absorption_gain=gain)

    def default_sample_interval(self, depth: float, g: float) -> float:
        return min(self.tp / 40.0, 0.05)

    def default_until(self, scene: FlumeScene, far: float) -> float:
        """Fifty peak periods at ``far`` [m] after the ramp and the waves' arrival."""
        return scene.law.ramp_duration + scene.arrival_time(far) + 50.0 * self.tp

    def describe(self, scene: FlumeScene) -> dict[str, Any]:
        return {"height": None, "hs": self.hs, "tp": self.tp, "spectrum": self.spectrum}


@dataclass(frozen=True)
class SolitaryWave(_Wave):
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

    TAG: ClassVar[str] = "solitary"

    def __post_init__(self) -> None:
        _set(self, "height", _positive("wave.height", self.height))
        trunc = _positive("wave.truncation", self.truncation)
        if trunc >= 1.0:
            raise SceneError(f"wave.truncation: must be < 1, got {self.truncation!r}")
        _set(self, "truncation", trunc)
        _set(self, "delay", _non_negative("wave.delay", self.delay))
        _integer("wave.samples", self.samples, 2)

    @property
    def design_height(self) -> float:
        return self.height

    def check(self, paddle: Paddle, depth: float) -> None:
        super().check(paddle, depth)
        if paddle.kind != "piston":
            raise SceneError("paddle: a solitary wave (Goring 1978) needs a Piston")
        if self.height > SOLITARY_MAX_H_OVER_D * depth:
            raise SceneError(
                f"wave.height: H/d = {self.height / depth:.3g} is above the highest solitary "
                f"wave, H/d = {SOLITARY_MAX_H_OVER_D} (Longuet-Higgins & Fenton 1974)"
            )

    def law(self, paddle: Paddle, depth: float, g: float) -> PaddleLaw:
        """Goring's (1978) piston motion, tabulated."""
        try:
            duration = float(wt.solitary_piston_duration(self.height, depth, self.truncation, g))
            t = np.linspace(0.0, duration, self.samples)
            x, _ = wt.solitary_piston_motion(t, self.height, depth, self.truncation, g)
        except ValueError as exc:
            raise SceneError(f"wave: {exc}") from None
        x_arr = np.asarray(x, dtype=np.float64)
        # Goring's paddle moves with the depth-averaged velocity of the wave over it,
        # dX/dt = c eta / (d + eta): the elevation at the paddle is eta = d U / (c - U)
        c = float(wt.solitary_celerity(self.height, depth, g))
        u = np.gradient(x_arr, t)
        eta = depth * u / (c - u)
        return PaddleLaw(
            law={"type": "table", "t": (t + self.delay).tolist(), "x": x_arr.tolist()},
            backward=0.0,
            forward=float(x_arr.max()),
            ramp_duration=self.delay,
            period=None,
            design_height=self.height,
            stroke=float(x_arr[-1]),
            duration=duration,
            absorption_target={"type": "table", "t": (t + self.delay).tolist(),
                               "x": eta.tolist()},
            # linear long waves: U = sqrt(g/d) eta
            absorption_gain=math.sqrt(g / depth),
            absorption_drift_time=10.0 * duration,
        )

    def default_sample_interval(self, depth: float, g: float) -> float:
        return min(math.sqrt(depth / g) / 4.0, 0.05)

    def default_until(self, scene: FlumeScene, far: float) -> float:
        """The motion, then the time to cross the flume and come back."""
        assert scene.law.duration is not None
        c = float(wt.solitary_celerity(self.height, scene.flume.depth, scene.g))
        return self.delay + scene.law.duration + 2.0 * scene.flume.length / c

    def front_speed(self, depth: npt.NDArray[np.float64], g: float) -> npt.NDArray[np.float64]:
        """``sqrt(g (d + H))``, the solitary wave's celerity."""
        return np.asarray(np.sqrt(g * (depth + self.height)))


@dataclass(frozen=True)
class TabulatedMotion(_Wave):
    """A paddle displacement series (e.g. a measured wave-maker record), linearly interpolated
    by the core and held at its first and last values outside the table.

    For a flap, ``x`` is the displacement at the still-water level.

    Attributes:
        t: times [s], strictly increasing.
        x: displacement of the paddle face from rest [m] (positive towards the far wall).
    """

    t: tuple[float, ...]
    x: tuple[float, ...]

    TAG: ClassVar[str] = "tabulated"

    def __post_init__(self) -> None:
        t = _finite_tuple("wave.t", self.t, 2)
        x = _finite_tuple("wave.x", self.x, 2)
        if len(t) != len(x):
            raise SceneError(f"wave.x: has {len(x)} values but wave.t has {len(t)}")
        _strictly_increasing("wave.t", t)
        _set(self, "t", t)
        _set(self, "x", x)

    def law(self, paddle: Paddle, depth: float, g: float) -> PaddleLaw:
        """The table itself."""
        xs = np.asarray(self.x)
        return PaddleLaw(
            law={"type": "table", "t": list(self.t), "x": list(self.x)},
            backward=max(0.0, float(-xs.min())),
            forward=max(0.0, float(xs.max())),
            ramp_duration=0.0,
            period=None,
            design_height=None,
            duration=self.t[-1],
        )

    def default_sample_interval(self, depth: float, g: float) -> float:
        return 0.02

    def default_until(self, scene: FlumeScene, far: float) -> float:
        """The table's end plus one crossing at ``sqrt(g d)``."""
        return self.t[-1] + scene.flume.length / math.sqrt(scene.g * scene.flume.depth)


Wave = RegularWave | IrregularWave | SolitaryWave | TabulatedMotion

WAVE_TYPES: tuple[type, ...] = (RegularWave, IrregularWave, SolitaryWave, TabulatedMotion)
"""The wave classes a :class:`FlumeScene` takes."""

