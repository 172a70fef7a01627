"""The wave-makers (piston, flap) and the resolved paddle law the core runs."""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from .. import wave_theory as wt
from .._core import SceneError
from ..checks import _choice, _non_negative, _positive
from .checks import _set

RAMPS: tuple[str, ...] = ("linear", "tanh")
"""Start-up ramp shapes of harmonic paddle laws."""


@dataclass(frozen=True)
class PaddleLaw:
    """A resolved paddle law: the core's JSON and what the analysis needs."""

    law: dict[str, Any]
    backward: float
    forward: float
    ramp_duration: float
    period: float | None
    design_height: float | None
    stroke: float | None = None
    second_order_amplitude: float | None = None
    duration: float | None = None
    absorption_target: dict[str, Any] | None = None
    """The core's law of the target surface elevation at the paddle (the wave the law makes,
    by linear theory), None where the wave has no target (a tabulated motion).
    :meth:`_Paddle.absorber` moves it to the absorber's probe."""
    absorption_gain: float | None = None
    """The paddle's displacement rate per metre of elevation at the wave's (peak) frequency,
    ``omega / (H/S)`` [1/s] (Schaffer & Klopman 2000)."""
    absorption_omega: float | None = None
    """The (peak) angular frequency [rad/s] of a harmonic target, at which the gain is set."""
    absorption_wavenumbers: tuple[float | None, ...] | None = None
    """How each component of a harmonic target travels from the paddle to the probe: None for
    a free wave (the paddle's linear solution, evanescent near field included), else the
    wavenumber [rad/m] of a component bound to others (a second-order harmonic, a steady wave's
    higher harmonic), which travels with them."""
    absorption_celerity: float | None = None
    """The speed [m/s] at which a tabulated target (a solitary wave's) travels."""
    absorption_drift_time: float | None = None
    """Time constant of the absorption's drift correction [s]: ten (peak) periods."""
    absorption_mean_time: float | None = None
    """Time constant of the running mean taken off the absorber's difference [s]: two (peak)
    periods, so that a slow rise of the surface (the particles' settling) holds the paddle back
    five times less than over the drift time (``absorption.rs``); None: the drift time (a
    solitary wave, whose mean is its own)."""

    def travel(self) -> float:
        """Peak-to-peak travel of the paddle [m]: a table's range; a harmonic law's range over
        its period, sampled at a twentieth of its shortest component period (the start-up ramp
        only lowers it). The laws' frequencies are whole multiples of a fundamental (the
        harmonics of a regular wave, the spectral lines of a synthesis), the smallest of the
        lowest frequency and the gaps between them."""
        if self.law["type"] == "table":
            return float(np.max(self.law["x"]) - np.min(self.law["x"]))
        parts = np.asarray(self.law["components"], dtype=np.float64).reshape(-1, 3)
        omegas = np.unique(parts[parts[:, 1] > 0.0, 1])
        if omegas.size == 0:
            return 0.0
        fundamental = float(np.min(np.append(np.diff(omegas), omegas[0])))
        t = np.arange(0.0, 2.0 * np.pi / fundamental, 2.0 * np.pi / omegas[-1] / 20.0)
        x = np.sin(np.multiply.outer(t, parts[:, 1]) + parts[:, 2]) @ parts[:, 0]
        return float(np.max(x) - np.min(x))


def _optional_bool(field: str, value: object) -> None:
    if value is not None and not isinstance(value, bool):
        raise SceneError(f"{field}: expected true, false or nothing, got {value!r}")


def _check_order(order: object) -> None:
    if isinstance(order, bool) or order not in (1, 2):
        raise SceneError(f"paddle.order: must be 1 or 2, got {order!r}")


class _Paddle:
    """What every wave-maker tells the scene (each class overrides what differs)."""

    kind: ClassVar[wt.Paddle]
    """The core's paddle ``kind``, also the paddle's ``type`` in a scene file (:attr:`TAG`)."""
    TAG: ClassVar[str]
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {"ramp": RAMPS}
    """The allowed values of the paddle's string fields."""
    order: int
    ramp_periods: float
    ramp: str
    max_stroke: float | None

    def check(self, depth: float) -> None:
        """Refuse a paddle that does not fit a flume ``depth`` [m] deep."""

    def hinged_transfer(self, k: npt.ArrayLike, depth: float) -> npt.NDArray[np.float64] | None:
        """H/S of this paddle at wavenumbers ``k`` when wave theory's piston or bottom-hinged flap
        does not describe it (a flap hinged above the floor), else None."""
        return None

    def second_order_stroke(self, height: float, period: float, depth: float,
                            g: float) -> tuple[float, float] | None:
        """``(amplitude, phase)`` of the second harmonic of this paddle's regular-wave law when
        wave theory's piston or bottom-hinged flap does not describe it, else None."""
        return None

    def back_room(self, backward: float, top: float, depth: float) -> float:
        """Room the paddle's plate needs behind x = 0 [m] for a law moving ``backward`` [m] at
        the still-water level ``depth``, with walls ``top`` [m] high."""
        return backward

    def harmonic_law(
        self, components: list[list[float]], bound: float, period: float,
        absorption_target: list[list[float]] | None = None, **extra: Any
    ) -> PaddleLaw:
        """The core's ``harmonic`` law, ``X = r(t) sum a sin(omega t + phase)`` over
        ``components`` ``[a, omega, phase]`` with the start-up ramp over ``ramp_periods``
        ``period`` [s]; ``bound`` [m] is the largest excursion either way; the target
        elevation at the paddle is ``absorption_target``'s components with the same ramp;
        ``extra`` the other :class:`PaddleLaw` fields."""
        ramp = self.ramp_periods * period

        def harmonic(parts: list[list[float]]) -> dict[str, Any]:
            return {"type": "harmonic", "components": parts, "ramp_duration": ramp,
                    "ramp_shape": self.ramp}

        return PaddleLaw(
            law=harmonic(components),
            backward=bound,
            forward=bound,
            ramp_duration=ramp,
            period=period,
            absorption_target=None if absorption_target is None else harmonic(absorption_target),
            absorption_drift_time=10.0 * period,
            absorption_mean_time=2.0 * period,
            **extra,
        )

    absorption: bool | None

    def absorbs(self, law: PaddleLaw, beach: bool) -> bool:
        """Whether this paddle absorbs the waves coming back (:attr:`absorption`; by default
        when the flume has a ``beach``, which reflects part of every wave, and the wave has a
        target to absorb against).

        Raises:
            SceneError: absorption asked for a wave without a target (a tabulated motion).
        """
        if self.absorption is None:
            return beach and law.absorption_target is not None
        if self.absorption and law.absorption_target is None:
            raise SceneError("paddle.absorption: this wave (a tabulated motion) has no target "
                             "elevation to absorb against; set paddle.absorption = false")
        return bool(self.absorption)

    @property
    def hinge(self) -> float:
        """The hinge's height above the floor [m] (a flap's; 0 for a piston)."""
        return 0.0

    def absorber(self, law: PaddleLaw, depth: float, probe_offset: float, g: float
                 ) -> dict[str, Any]:
        """The core's ``absorption`` of ``law`` read ``probe_offset`` [m] in front of the face
        (``absorption.rs``). The probe sees the paddle's own wave after the face does and a
        wave coming back before the paddle does, so the target is the generated wave at the
        probe, and the difference is delayed by the lag that makes the correction cancel the
        returning wave at the paddle.

        With ``F`` the paddle's linear elevation at the probe over its progressive wave at the
        face (:func:`watersim.wave_theory.paddle_near_field`), a returning wave ``eta_R`` (at
        the face) and the correction's wave ``eta_c`` give ``2 cos(k x) eta_R + F eta_c`` at
        the probe (the still paddle reflects ``eta_R``); the loop ``eta_c = -L (that)`` absorbs
        it, ``eta_c = -eta_R``, when ``L = 1 / (2 cos(k x) - F)``: ``e^(i k x)`` without a near
        field, a delay of x / c. At the (peak) frequency the core's first-order lag gives the
        phase ``arg L`` and the gain makes up its modulus. A tabulated target is a long wave:
        it is moved, and the difference delayed, by x / c."""
        target = dict(law.absorption_target or {})
        gain, lag = float(law.absorption_gain or 0.0), 0.0
        if target.get("type") == "table":
            assert law.absorption_celerity is not None
            lag = probe_offset / law.absorption_celerity
            target["t"] = [t + lag for t in target["t"]]
        else:
            assert law.absorption_omega is not None and law.absorption_wavenumbers is not None
            parts = []
            for (amplitude, omega, phase), bound in zip(target["components"],
                                                        law.absorption_wavenumbers, strict=True):
                f = (cmath.exp(1j * bound * probe_offset) if bound is not None
                     else self.near_field(omega, depth, probe_offset, g))
                parts.append([amplitude * abs(f), omega, phase - cmath.phase(f)])
            target["components"] = parts
            omega = law.absorption_omega
            k = float(wt.wavenumber_from_omega(omega, depth, g))
            loop = 1.0 / (2.0 * math.cos(k * probe_offset)
                          - self.near_field(omega, depth, probe_offset, g))
            # the core's drift term and the removal of the difference's mean each lead by
            # atan(1 / (omega tau)) and keep omega tau / sqrt(1 + (omega tau)^2) of the
            # amplitude (tau their time constants): the lag and the gain make up for them too
            leads = [1.0 / (omega * float(tau or math.inf))
                     for tau in (law.absorption_drift_time,
                                 law.absorption_mean_time or law.absorption_drift_time)]
            delay = max(0.0, cmath.phase(loop) + sum(map(math.atan, leads)))  # a lag cannot lead
            lag = math.tan(delay) / omega
            gain *= abs(loop) * math.prod(math.hypot(1.0, x) for x in leads) / math.cos(delay)
        core = {"target": target, "gain": gain, "probe_offset": probe_offset,
                "drift_time": law.absorption_drift_time, "lag_time": lag}
        if law.absorption_mean_time is not None:
            core["mean_time"] = law.absorption_mean_time
        return core

    def near_field(self, omega: float, depth: float, x: float, g: float) -> complex:
        """This paddle's linear elevation ``x`` [m] in front of its face at ``omega`` over its
        progressive wave at the face (:func:`watersim.wave_theory.paddle_near_field`)."""
        return wt.paddle_near_field(omega, depth, x, self.kind, self.hinge, g)

    def to_core(self, law: PaddleLaw, depth: float, probe_offset: float | None = None,
                g: float = wt.G) -> dict[str, Any]:
        """The core's paddle JSON driven by ``law`` in water ``depth`` [m] deep; with a
        ``probe_offset`` [m], absorbing the waves coming back (the surface read that far in
        front of the face: :meth:`absorber`)."""
        paddle: dict[str, Any] = {"kind": self.kind, "x": 0.0, "hinge_z": None, "swl_z": None,
                                  "law": law.law}
        if probe_offset is not None:
            paddle["absorption"] = self.absorber(law, depth, probe_offset, g)
        return paddle


@dataclass(frozen=True)
class Piston(_Paddle):
    """A piston wave-maker: the paddle translates along x.

    Attributes:
        order: 1 (Biesel) or 2: Madsen's (1971) second-order correction for a regular wave
            (whose ``theory`` may choose another law: ``"auto"``, the stream-function law beyond
            Madsen's Ursell number), the components' sub- and superharmonics for an irregular or
            focused wave.
        ramp_periods: start-up ramp length in wave periods (peak periods for irregular waves);
            0 for none. Tabulated and solitary motions have no ramp.
        ramp: ``"linear"`` (``min(1, t / T_r)``) or ``"tanh"`` (``tanh(4 t / T_r)``).
        absorption: active wave absorption (Schaffer & Klopman 2000): the paddle also moves with
            the water of the waves coming back from the flume, measured in front of it, so
            that they leave instead of being reflected again; ``None`` (default): on when the
            flume has a beach, ``False``: off.
        max_stroke: the largest peak-to-peak travel the wave-maker has [m]; a wave needing more
            is refused before anything runs, naming its size (``wave.height``, ...). ``None``:
            no limit but the flume's length.
    """

    order: int = 1
    ramp_periods: float = 2.0
    ramp: str = "linear"
    absorption: bool | None = None
    max_stroke: float | None = None

    kind: ClassVar[wt.Paddle] = "piston"
    TAG: ClassVar[str] = kind

    def __post_init__(self) -> None:
        _optional_bool("paddle.absorption", self.absorption)
        _check_order(self.order)
        _set(self, "ramp_periods", _non_negative("paddle.ramp_periods", self.ramp_periods))
        _choice("paddle.ramp", self.ramp, self.CHOICES["ramp"])
        if self.max_stroke is not None:
            _set(self, "max_stroke", _positive("paddle.max_stroke", self.max_stroke))


@dataclass(frozen=True)
class Flap(_Paddle):
    """A flap wave-maker: the paddle rotates about a horizontal hinge at height ``hinge_z``;
    below the hinge it is a fixed wall. Its displacement X is set at the still-water level
    (``theta = atan(X / (depth - hinge_z))``).

    Attributes:
        hinge_z: hinge height above the floor [m]; ``None``: on the floor (a bottom-hinged flap).
        order: 1 (Biesel) or 2 (Schaffer's 1996 second-order correction, regular waves only:
            :func:`watersim.wave_theory.second_order_stroke`).
        ramp_periods: start-up ramp length in wave periods; 0 for none.
        ramp: ``"linear"`` or ``"tanh"``.
        absorption: active wave absorption, as :class:`Piston`'s.
        max_stroke: the largest peak-to-peak travel at the still-water level the wave-maker has
            [m] (see :class:`Piston`).
    """

    hinge_z: float | None = None
    order: int = 1
    ramp_periods: float = 2.0
    ramp: str = "linear"
    absorption: bool | None = None
    max_stroke: float | None = None

    kind: ClassVar[wt.Paddle] = "flap"
    TAG: ClassVar[str] = kind

    def __post_init__(self) -> None:
        _optional_bool("paddle.absorption", self.absorption)
        if self.hinge_z is not None:
            _set(self, "hinge_z", _non_negative("paddle.hinge_z", self.hinge_z))
        _check_order(self.order)
        _set(self, "ramp_periods", _non_negative("paddle.ramp_periods", self.ramp_periods))
        _choice("paddle.ramp", self.ramp, self.CHOICES["ramp"])
        if self.max_stroke is not None:
            _set(self, "max_stroke", _positive("paddle.max_stroke", self.max_stroke))

    @property
    def hinge(self) -> float:
        """The hinge's height above the floor [m] (0 for a bottom-hinged flap)."""
        return self.hinge_z or 0.0

    def check(self, depth: float) -> None:
        if self.hinge_z is not None and self.hinge_z >= depth:
            raise SceneError(
                f"paddle.hinge_z: the hinge ({self.hinge_z:g} m) must be below the still-water "
                f"level (depth = {depth:g} m)"
            )

    def hinged_transfer(self, k: npt.ArrayLike, depth: float) -> npt.NDArray[np.float64] | None:
        if self.hinge > 0.0:
            return flap_height_to_stroke_hinged(k, depth, self.hinge)
        return None

    def second_order_stroke(self, height: float, period: float, depth: float,
                            g: float) -> tuple[float, float] | None:
        if self.hinge > 0.0:
            return wt.second_order_stroke(height, period, depth, "flap", self.hinge, g=g)
        return None

    def back_room(self, backward: float, top: float, depth: float) -> float:
        # the plate's top swings further than the still-water level
        return backward * ((top - self.hinge) / (depth - self.hinge))

    def to_core(self, law: PaddleLaw, depth: float, probe_offset: float | None = None,
                g: float = wt.G) -> dict[str, Any]:
        return {**super().to_core(law, depth, probe_offset, g), "hinge_z": float(self.hinge),
                "swl_z": float(depth)}


Paddle = Piston | Flap

PADDLE_TYPES: tuple[type, ...] = (Piston, Flap)
"""The paddle classes a :class:`FlumeScene` takes."""


def flap_height_to_stroke_hinged(
    k: npt.ArrayLike, depth: float, hinge_height: float
) -> npt.NDArray[np.float64]:
    """Biesel transfer function H/S of a flap hinged ``hinge_height`` above the bed [-].

    Linear wave-maker theory (Biesel & Suquet 1951; Dean & Dalrymple 1991, ch. 6): for a paddle
    whose horizontal displacement is ``(S/2) f(z)`` (z up from the bed, f = 1 at the surface),
    ``H/S = 4 sinh(kd) / (sinh 2kd + 2kd) * k int_0^d f(z) cosh(kz) dz``. With the flap's
    ``f = (z - l)/(d - l)`` above the hinge l and 0 below, the integral is
    ``[k(d - l) sinh kd - cosh kd + cosh kl] / (k (d - l))``. For l = 0 this is the bottom-hinged
    flap of :func:`watersim.wave_theory.flap_height_to_stroke`, which is used then; f = 1 gives
    the piston.

    Args:
        k: wavenumber [rad/m]; depth: still-water depth d [m]; hinge_height: l, 0 <= l < d [m].
    """
    kk = np.asarray(k, dtype=np.float64)
    if hinge_height == 0.0:
        return np.asarray(wt.flap_height_to_stroke(kk, depth), dtype=np.float64)
    kd = kk * depth
    span = kk * (depth - hinge_height)
    integral = (span * np.sinh(kd) - np.cosh(kd) + np.cosh(kk * hinge_height)) / span
    return np.asarray(4.0 * np.sinh(kd) / (np.sinh(2.0 * kd) + 2.0 * kd) * integral)
