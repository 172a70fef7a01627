"""The waves a flume makes: regular, irregular, solitary, or a tabulated paddle motion."""
from __future__ import annotations

from dataclasses import dataclass

from .._core import SceneError
from ..scenes import _choice, _integer, _non_negative, _number, _positive
from .checks import _finite_tuple, _set, _strictly_increasing

SPECTRA: dict[str, str] = {
    "jonswap": "jonswap",
    "pm": "pierson-moskowitz",
    "pierson-moskowitz": "pierson-moskowitz",
}
"""Spectrum names accepted by :class:`IrregularWave`, and their :mod:`wave_theory` names."""


SOLITARY_MAX_H_OVER_D = 0.83
"""Highest solitary wave, H/d about 0.83 (Longuet-Higgins & Fenton 1974): a taller one does not
exist, and Goring's paddle motion for it is meaningless."""



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

