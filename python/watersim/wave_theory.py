"""Wave theory for the numerical wave flume: dispersion, wave-makers, breaking, run-up, spectra.

Every function is vectorised with NumPy: scalars or arrays in (broadcast together), the broadcast
shape out (a NumPy scalar for scalar input). SI units throughout: metres, seconds, radians,
hertz. ``g`` is the gravitational acceleration [m/s^2]. Bad input (NaN, infinite, a depth,
height or period <= 0, an unknown option) raises :class:`ValueError` naming the argument.

Conventions (the same as ``shared/validation/wave_theory/FORMULAS.md``):

- ``d`` is the still-water depth [m], ``H`` the wave height (crest to trough) [m], ``T`` the
  period [s], ``omega = 2 pi / T`` [rad/s], ``k = 2 pi / L`` the wavenumber [rad/m].
- Progressive wave travelling towards +x: ``eta = (H/2) cos(k x - omega t - delta) + ...``.
- Paddle displacement (piston, or a flap at the still-water level): ``X(t) = (S/2) sin(omega t +
  delta) + X2 sin(2 omega t + 2 delta)``, ``S`` the peak-to-peak stroke [m]. With this sign the
  paddle moves forward fastest when the crest leaves it (``eta(0, t) = (H/2) cos(omega t +
  delta)``).
- ``slope`` is ``tan(beta)`` [-], rise over run (1/15 for a 1:15 beach).

Sources cited below as "FORMULAS §n" are sections of
``shared/validation/wave_theory/FORMULAS.md``; "seed 001" is Roselli et al. (the project's
``shared/seeds/001_*``), "seed 000" the project's wave-maker reference sheet.
"""

from __future__ import annotations

import functools
import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt
from scipy import special

__all__ = [
    "CNOIDAL_KD_LIMIT",
    "CNOIDAL_URSELL_LIMIT",
    "CnoidalWave",
    "FLUX_THEORIES",
    "G",
    "KINEMATIC_BREAKING_RATIO",
    "MADSEN_URSELL_LIMIT",
    "MCCOWAN_BREAKING_RATIO",
    "MICHE_COEFFICIENT",
    "REGULAR_THEORIES",
    "STREAM_FUNCTION_KD_LIMIT",
    "STREAM_FUNCTION_MODES",
    "STREAM_FUNCTION_TOLERANCE",
    "IrregularPaddleMotion",
    "RegularPaddleMotion",
    "SCHAFFER_MODES",
    "SecondOrderPaddleMotion",
    "StreamFunctionPaddleMotion",
    "StreamFunctionWave",
    "WaveValidityWarning",
    "breaker_type",
    "celerity",
    "check_wave",
    "cnoidal_piston_motion",
    "cnoidal_wave",
    "choose_regular_theory",
    "chue_runup",
    "deep_water_wavelength",
    "flap_height_to_stroke",
    "flap_motion",
    "flap_stroke",
    "focused_paddle_motion",
    "group_velocity",
    "highest_wave_height",
    "hsu_runup",
    "hughes_runup",
    "hunt_runup",
    "irregular_paddle_motion",
    "iribarren",
    "jonswap_spectrum",
    "kinematic_breaking",
    "linear_momentum_flux_parameter",
    "mccowan_breaking",
    "miche_breaking",
    "miche_height_limit",
    "pierson_moskowitz_spectrum",
    "piston_height_to_stroke",
    "piston_motion",
    "piston_stroke",
    "regular_flux_motion",
    "regular_paddle_motion",
    "second_order_piston_motion",
    "second_order_stroke",
    "schuttrumpf_runup",
    "solitary_celerity",
    "solitary_piston_duration",
    "solitary_piston_motion",
    "solitary_piston_stroke",
    "solitary_wave_elevation",
    "stokes2_elevation",
    "stokes2_second_harmonic_amplitude",
    "stream_function_piston_motion",
    "stream_function_wave",
    "synolakis_runup",
    "ursell_number",
    "warn_if_invalid_wave",
    "wavelength",
    "wavenumber",
    "wavenumber_from_omega",
]

G = 9.81
"""Default gravitational acceleration [m/s^2]."""

MCCOWAN_BREAKING_RATIO = 0.78
"""Depth-limited breaking, McCowan (1894): a wave breaks when H/d > 0.78 (seed 000)."""

MICHE_COEFFICIENT = 0.142
"""Steepness-limited breaking, Miche (1944): H/L > 0.142 tanh(kd) (seed 000: 1/7 ~ 0.142)."""

KINEMATIC_BREAKING_RATIO = 0.85
"""Kinematic breaking onset: crest particle speed u > 0.85 c (seed 000)."""

MADSEN_URSELL_LIMIT = 8.0 * math.pi**2 / 3.0
"""Ursell number ``H L^2 / d^3`` up to which Madsen's second-order generation is used,
8 pi^2 / 3 ~ 26.3 (FORMULAS §3, as in the DualSPHysics-type script it cross-checks)."""

FloatArray = npt.NDArray[np.float64]
FloatLike = FloatArray | np.float64
Paddle = Literal["piston", "flap"]
RampKind = Literal["linear", "tanh"]

_FLOAT_EPS = float(np.finfo(np.float64).eps)


class WaveValidityWarning(UserWarning):
    """A requested wave is outside the validity of the theory or of the paddle generating it."""


# ------------------------------------------------------------------------------------------------
# Input checks


def _finite(name: str, value: npt.ArrayLike) -> FloatArray:
    """``value`` as a float array; ValueError naming ``name`` if it is not numeric or not finite."""
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(
            f"{name}: must be a number or an array of numbers, got {value!r}"
        ) from None
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name}: must be finite (no NaN or inf), got {value!r}")
    return arr


def _positive(name: str, value: npt.ArrayLike) -> FloatArray:
    """``value`` as a float array; ValueError naming ``name`` unless every entry is finite > 0."""
    arr = _finite(name, value)
    if not np.all(arr > 0.0):
        raise ValueError(f"{name}: must be > 0, got {value!r}")
    return arr


def _nonnegative(name: str, value: npt.ArrayLike) -> FloatArray:
    """``value`` as a float array; ValueError naming ``name`` unless every entry is finite >= 0."""
    arr = _finite(name, value)
    if not np.all(arr >= 0.0):
        raise ValueError(f"{name}: must be >= 0, got {value!r}")
    return arr


def _choice(name: str, value: str, allowed: tuple[str, ...]) -> str:
    """``value`` if it is one of ``allowed``; otherwise ValueError naming ``name``."""
    if value not in allowed:
        raise ValueError(f"{name}: must be one of {', '.join(map(repr, allowed))}, got {value!r}")
    return value


def _out(arr: FloatArray) -> FloatArray:
    """Return 0-d results as NumPy scalars and arrays unchanged."""
    return arr[()]


# ------------------------------------------------------------------------------------------------
# Overflow-free hyperbolic helpers (kd may be large in deep water)


def _sech(x: FloatLike) -> FloatArray:
    """sech(x) for x >= 0 without overflow."""
    e = np.exp(-x)
    return 2.0 * e / (1.0 + e * e)


def _two_x_over_sinh_two_x(x: FloatLike) -> FloatArray:
    """``2x / sinh(2x)`` for x > 0 without overflow: ``4 x e^(-2x) / (1 - e^(-4x))``."""
    return 4.0 * x * np.exp(-2.0 * x) / -np.expm1(-4.0 * x)


def _csch_squared(x: FloatLike) -> FloatArray:
    """``1 / sinh(x)^2`` for x > 0 without overflow: ``4 e^(-2x) / (1 - e^(-2x))^2``."""
    return 4.0 * np.exp(-2.0 * x) / np.expm1(-2.0 * x) ** 2


# ------------------------------------------------------------------------------------------------
# Linear dispersion


def wavenumber_from_omega(omega: npt.ArrayLike, depth: npt.ArrayLike, g: float = G) -> FloatArray:
    """Wavenumber k [rad/m] solving the linear dispersion relation ``omega^2 = g k tanh(k d)``.

    FORMULAS §1 (Dean & Dalrymple 1991, ch. 3). The starting value is the explicit approximation
    of Fenton & McKee (1990), ``k d = y / tanh(y^(3/4))^(2/3)`` with ``y = omega^2 d / g``
    (FORMULAS §1, quoted there from memory; it is only a starting value here). Newton's method on
    ``f(x) = x tanh(x) - y``, ``x = k d``, then converges quadratically; it stops once the step is
    below 2 ulp of x, so the relative residual of the dispersion relation is at machine precision
    (about 1e-15) from kd = 1e-3 to kd > 50.

    Args:
        omega: angular frequency [rad/s], > 0.
        depth: still-water depth d [m], > 0.
        g: gravitational acceleration [m/s^2].
    """
    w = _positive("omega", omega)
    d = _positive("depth", depth)
    g_ = float(_positive("g", g))
    y = w * w * np.broadcast_to(d, np.broadcast_shapes(w.shape, d.shape)) / g_
    x = y / np.tanh(y**0.75) ** (2.0 / 3.0)
    for _ in range(50):
        th = np.tanh(x)
        step = (x * th - y) / (th + x * (1.0 - th * th))
        x = x - step
        if np.all(np.abs(step) <= 2.0 * _FLOAT_EPS * x):
            break
    return _out(x / d)


def wavenumber(period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G) -> FloatArray:
    """Wavenumber k [rad/m] of a linear wave of period ``period`` [s] in depth ``depth`` [m].

    See :func:`wavenumber_from_omega` (FORMULAS §1).
    """
    T = _positive("period", period)
    return wavenumber_from_omega(2.0 * np.pi / T, depth, g)


def wavelength(period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G) -> FloatArray:
    """Linear wavelength L = 2 pi / k [m] (FORMULAS §1)."""
    return _out(2.0 * np.pi / np.asarray(wavenumber(period, depth, g)))


def deep_water_wavelength(period: npt.ArrayLike, g: float = G) -> FloatArray:
    """Deep-water wavelength ``L0 = g T^2 / (2 pi)`` [m] (seed 001, below Eq. 2)."""
    T = _positive("period", period)
    return _out(float(_positive("g", g)) * T * T / (2.0 * np.pi))


def celerity(period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G) -> FloatArray:
    """Phase speed ``c = omega / k = L / T`` [m/s] (FORMULAS §1 and §4)."""
    T = _positive("period", period)
    k = np.asarray(wavenumber(T, depth, g))
    return _out(2.0 * np.pi / (T * k))


def group_velocity(period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G) -> FloatArray:
    """Group velocity ``c_g = (c / 2) (1 + 2 k d / sinh(2 k d))`` [m/s].

    Dean & Dalrymple (1991), ch. 4 (derivative of the dispersion relation of FORMULAS §1).
    """
    T = _positive("period", period)
    d = _positive("depth", depth)
    k = np.asarray(wavenumber(T, d, g))
    c = 2.0 * np.pi / (T * k)
    return _out(0.5 * c * (1.0 + _two_x_over_sinh_two_x(k * d)))


def ursell_number(
    height: npt.ArrayLike, period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G
) -> FloatArray:
    """Ursell number ``U = H L^2 / d^3`` [-] with the linear wavelength L (FORMULAS §3)."""
    H = _positive("height", height)
    d = _positive("depth", depth)
    L = np.asarray(wavelength(period, d, g))
    return _out(H * L * L / d**3)


# ------------------------------------------------------------------------------------------------
# Biesel transfer functions and regular paddle motion


def piston_height_to_stroke(k: npt.ArrayLike, depth: npt.ArrayLike) -> FloatArray:
    """Piston transfer function ``H/S = 2 (cosh 2kd - 1) / (sinh 2kd + 2kd)`` [-].

    Biesel & Suquet (1951); FORMULAS §2. S is the peak-to-peak stroke. Evaluated in the
    equivalent overflow-free form ``2 tanh(kd) / (1 + 2kd / sinh 2kd)``. Limits: kd in shallow
    water, 2 in deep water.

    Args:
        k: wavenumber [rad/m], > 0.
        depth: still-water depth d [m], > 0.
    """
    kd = _positive("k", k) * _positive("depth", depth)
    return _out(2.0 * np.tanh(kd) / (1.0 + _two_x_over_sinh_two_x(kd)))


def flap_height_to_stroke(k: npt.ArrayLike, depth: npt.ArrayLike) -> FloatArray:
    """Bottom-hinged flap: ``H/S = 4 (sinh kd / kd)(kd sinh kd - cosh kd + 1)/(sinh 2kd + 2kd)``.

    Biesel & Suquet (1951); FORMULAS §2 (written there from memory of Dean & Dalrymple 1991 and
    checked through its limits). S is the stroke at the still-water level. Evaluated as
    ``2 (kd tanh kd - (1 - sech kd)) / (kd (1 + 2kd / sinh 2kd))``, with
    ``1 - sech x = 2 sinh^2(x/2) / cosh x`` for small x to avoid cancellation. Limits: kd/2 in
    shallow water, 2 in deep water.

    Args:
        k: wavenumber [rad/m], > 0.
        depth: still-water depth d [m], > 0 (the hinge is on the bed).
    """
    kd = _positive("k", k) * _positive("depth", depth)
    small = np.minimum(kd, 1.0)
    one_minus_sech = np.where(
        kd < 1.0, 2.0 * np.sinh(0.5 * small) ** 2 / np.cosh(small), 1.0 - _sech(kd)
    )
    ratio = 2.0 * (kd * np.tanh(kd) - one_minus_sech) / (kd * (1.0 + _two_x_over_sinh_two_x(kd)))
    return _out(ratio)


def piston_stroke(
    height: npt.ArrayLike, period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G
) -> FloatArray:
    """Peak-to-peak piston stroke ``S = H / (H/S)`` [m] for a first-order wave (FORMULAS §2)."""
    H = _positive("height", height)
    k = wavenumber(period, depth, g)
    return _out(H / np.asarray(piston_height_to_stroke(k, depth)))


def flap_stroke(
    height: npt.ArrayLike, period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G
) -> FloatArray:
    """Peak-to-peak flap stroke at the still-water level ``S = H / (H/S)`` [m] (FORMULAS §2)."""
    H = _positive("height", height)
    k = wavenumber(period, depth, g)
    return _out(H / np.asarray(flap_height_to_stroke(k, depth)))


def _madsen_second_order_amplitude(height: FloatLike, kd: FloatLike, depth: FloatLike) -> FloatLike:
    """``X2 = H^2/(32 d) (3 cosh kd / sinh^3 kd - 2 / m1)`` [m], m1 the piston H/S (FORMULAS §3)."""
    m1 = 2.0 * np.tanh(kd) / (1.0 + _two_x_over_sinh_two_x(kd))
    cosh_over_sinh3 = _csch_squared(kd) / np.tanh(kd)
    return height * height / (32.0 * depth) * (3.0 * cosh_over_sinh3 - 2.0 / m1)


def _ramp(t: FloatArray, ramp_time: float, kind: str) -> tuple[FloatArray, FloatArray]:
    """Ramp factor r(t) and its time derivative [1/s] for a ramp of duration ``ramp_time`` [s].

    ``linear``: r = min(1, t / ramp_time) (seed 000). ``tanh``: r = tanh(4 t / ramp_time), which
    reaches 0.9993 at t = ramp_time and has no kink. Before t = 0, r = 0. ``ramp_time = 0``
    means no ramp (r = 1 for t >= 0).
    """
    tc = np.maximum(t, 0.0)
    if ramp_time == 0.0:
        return np.where(t >= 0.0, 1.0, 0.0), np.zeros_like(tc)
    if kind == "linear":
        rising = (t >= 0.0) & (t < ramp_time)
        return np.minimum(tc / ramp_time, 1.0), np.where(rising, 1.0 / ramp_time, 0.0)
    th = np.tanh(4.0 * tc / ramp_time)
    return th, np.where(t >= 0.0, 4.0 / ramp_time * (1.0 - th * th), 0.0)


@dataclass(frozen=True)
class RegularPaddleMotion:
    """Coefficients of a regular-wave paddle motion law (what the core evaluates each step).

    The law, for t >= 0 (r(t) the ramp of :meth:`motion`)::

        X(t) = r(t) [ (S/2) sin(omega t + phase) + X2 sin(2 omega t + 2 phase + psi) ]
        U(t) = dX/dt (exact derivative, ramp included)

    For a flap, X is the displacement at the still-water level; the rotation about the hinge on
    the bed is ``atan(X / d)``.

    Attributes:
        paddle: ``"piston"`` or ``"flap"``.
        height: target wave height H [m].
        period: wave period T [s].
        depth: still-water depth at the paddle d [m].
        omega: angular frequency 2 pi / T [rad/s].
        wavenumber: linear wavenumber k [rad/m].
        stroke: first-order peak-to-peak stroke S = H / (H/S) [m] (Biesel, FORMULAS §2).
        second_order_amplitude: second-harmonic amplitude X2 [m]: Madsen's (1971) for a piston
            (signed; FORMULAS §3), Schaffer's (1996) for a flap (:func:`second_order_stroke`); 0
            for first-order generation.
        phase: phase ``delta`` [rad].
        second_order_phase: psi [rad], the second harmonic's own phase (0 for a piston).
    """

    paddle: Paddle
    height: float
    period: float
    depth: float
    omega: float
    wavenumber: float
    stroke: float
    second_order_amplitude: float
    phase: float
    second_order_phase: float = 0.0

    def motion(
        self, t: npt.ArrayLike, ramp_periods: float = 2.0, ramp: RampKind = "linear"
    ) -> tuple[FloatArray, FloatArray]:
        """Paddle displacement X [m] and velocity U = dX/dt [m/s] at times ``t`` [s].

        Args:
            t: times [s]; the motion starts at t = 0 (X = 0 before).
            ramp_periods: ramp duration n in periods (ramp over n T); 0 for none.
            ramp: ``"linear"``, r = min(1, t / (n T)) (seed 000), or ``"tanh"``,
                r = tanh(4 t / (n T)), smooth and at 0.9993 after n T.
        """
        tt = _finite("t", t)
        n = float(_nonnegative("ramp_periods", ramp_periods))
        _choice("ramp", ramp, ("linear", "tanh"))
        r, dr = _ramp(tt, n * self.period, ramp)
        w, a1, a2, ph = self.omega, 0.5 * self.stroke, self.second_order_amplitude, self.phase
        ph2 = 2.0 * ph + self.second_order_phase
        base = a1 * np.sin(w * tt + ph) + a2 * np.sin(2.0 * w * tt + ph2)
        base_rate = a1 * w * np.cos(w * tt + ph) + 2.0 * w * a2 * np.cos(2.0 * w * tt + ph2)
        return _out(r * base), _out(dr * base + r * base_rate)


def regular_paddle_motion(
    height: float,
    period: float,
    depth: float,
    paddle: Paddle = "piston",
    order: int = 1,
    phase: float = 0.0,
    g: float = G,
) -> RegularPaddleMotion:
    """Coefficients of the paddle law generating a regular wave of height H and period T.

    First order (Biesel, FORMULAS §2): ``X = (S/2) sin(omega t + phase)`` with S = H / (H/S).
    Second order, piston (Madsen 1971, as used in DualSPHysics by Altomare et al. 2017,
    FORMULAS §3): adds ``X2 sin(2 omega t + 2 phase)`` with
    ``X2 = H^2/(32 d) (3 cosh kd / sinh^3 kd - 2/m1)``, ``m1 = H/S`` of the piston. X2 > 0 in
    shallow water and < 0 in deep water; the sign convention is FORMULAS §3's (the same
    ``sin(2 omega t + 2 delta)`` term as the DualSPHysics-type script it cross-checks).
    Second order, bottom-hinged flap: Schaffer's (1996) ``X2 sin(2 omega t + 2 phase + psi)``
    (:func:`second_order_stroke`).

    Args:
        height: wave height H [m].
        period: wave period T [s].
        depth: still-water depth at the paddle d [m].
        paddle: ``"piston"`` or ``"flap"`` (bottom-hinged).
        order: 1 or 2.
        phase: phase ``delta`` [rad].
        g: gravitational acceleration [m/s^2].
    """
    H = float(_positive("height", height))
    T = float(_positive("period", period))
    d = float(_positive("depth", depth))
    ph = float(_finite("phase", phase))
    _choice("paddle", paddle, ("piston", "flap"))
    if order not in (1, 2):
        raise ValueError(f"order: must be 1 or 2, got {order!r}")
    k = float(wavenumber(T, d, g))
    transfer = piston_height_to_stroke if paddle == "piston" else flap_height_to_stroke
    stroke = H / float(transfer(k, d))
    x2, psi = 0.0, 0.0
    if order == 2 and paddle == "piston":
        x2 = float(_madsen_second_order_amplitude(np.float64(H), np.float64(k * d), np.float64(d)))
    elif order == 2:
        x2, psi = second_order_stroke(H, T, d, "flap", 0.0, g=g)
    return RegularPaddleMotion(
        paddle=paddle,
        height=H,
        period=T,
        depth=d,
        omega=2.0 * math.pi / T,
        wavenumber=k,
        stroke=stroke,
        second_order_amplitude=x2,
        phase=ph,
        second_order_phase=psi,
    )


def piston_motion(
    t: npt.ArrayLike,
    height: float,
    period: float,
    depth: float,
    order: int = 1,
    ramp_periods: float = 2.0,
    phase: float = 0.0,
    ramp: RampKind = "linear",
    g: float = G,
) -> tuple[FloatArray, FloatArray]:
    """Piston displacement X [m] and velocity dX/dt [m/s] at times ``t`` [s], regular wave.

    ``X = r(t) [(S/2) sin(omega t + phase) + X2 sin(2 omega t + 2 phase)]``, X2 = 0 for
    ``order=1`` and Madsen's (1971) correction for ``order=2`` (FORMULAS §2-3); see
    :func:`regular_paddle_motion` and :meth:`RegularPaddleMotion.motion` for the ramp r(t).
    """
    law = regular_paddle_motion(height, period, depth, "piston", order, phase, g)
    return law.motion(t, ramp_periods, ramp)


def flap_motion(
    t: npt.ArrayLike,
    height: float,
    period: float,
    depth: float,
    ramp_periods: float = 2.0,
    phase: float = 0.0,
    ramp: RampKind = "linear",
    g: float = G,
) -> tuple[FloatArray, FloatArray]:
    """Flap displacement at the still-water level X [m] and its rate [m/s], first order.

    ``X = r(t) (S/2) sin(omega t + phase)`` with the flap transfer function (FORMULAS §2).
    """
    law = regular_paddle_motion(height, period, depth, "flap", 1, phase, g)
    return law.motion(t, ramp_periods, ramp)


# ------------------------------------------------------------------------------------------------
# Stokes second order


def stokes2_second_harmonic_amplitude(
    height: npt.ArrayLike, k: npt.ArrayLike, depth: npt.ArrayLike
) -> FloatArray:
    """Bound second-harmonic amplitude ``(k H^2 / 16)(3 coth^3 kd - coth kd)`` [m].

    Stokes second order, FORMULAS §4 (Dean & Dalrymple 1991, ch. 11), equal to
    ``(pi H^2 / 8L) cosh kd (2 + cosh 2kd) / sinh^3 kd``. Deep-water limit k H^2 / 8.
    """
    H = _positive("height", height)
    kk = _positive("k", k)
    coth = 1.0 / np.tanh(kk * _positive("depth", depth))
    return _out(kk * H * H / 16.0 * (3.0 * coth**3 - coth))


def stokes2_elevation(
    x: npt.ArrayLike,
    t: npt.ArrayLike,
    height: float,
    period: float,
    depth: float,
    phase: float = 0.0,
    g: float = G,
) -> FloatArray:
    """Stokes second-order surface elevation eta(x, t) [m] of a progressive wave (towards +x).

    ``eta = (H/2) cos(theta) + a2 cos(2 theta)``, ``theta = k x - omega t - phase``, a2 from
    :func:`stokes2_second_harmonic_amplitude` (FORMULAS §4). At x = 0 the first harmonic is
    ``(H/2) cos(omega t + phase)``, the wave a paddle with the same ``phase`` makes.

    Args:
        x: position [m]; t: time [s] (broadcast together).
        height: wave height H [m] (of the first harmonic); period: T [s]; depth: d [m].
        phase: phase ``delta`` [rad].
    """
    xx = _finite("x", x)
    tt = _finite("t", t)
    H = float(_positive("height", height))
    k = float(wavenumber(period, depth, g))
    w = 2.0 * math.pi / float(period)
    theta = k * xx - w * tt - float(_finite("phase", phase))
    a2 = float(stokes2_second_harmonic_amplitude(H, k, depth))
    return _out(0.5 * H * np.cos(theta) + a2 * np.cos(2.0 * theta))


# ------------------------------------------------------------------------------------------------
# Second-order generation by any paddle: the eigenfunction expansion of Schaffer (1996)

SCHAFFER_MODES = 200
"""Evanescent modes of :func:`second_order_stroke` (at first order and at 2 omega): its result
changes by about 0.3 % from 200 to 400 (the series converge like 1/M, through the paddle's
corner with the free surface)."""


def _evanescent_wavenumbers(omega: float, depth: float, count: int, g: float) -> FloatArray:
    """kappa_n, n = 1..count, of the evanescent modes ``cos(kappa (z + d)) e^(-kappa x)`` at
    frequency omega: the roots of ``omega^2 = -g kappa tan(kappa d)`` in ((n - 1/2) pi, n pi) / d.

    Newton's method on ``x sin x + y cos x`` (x = kappa d, y = omega^2 d / g; no poles), kept
    inside each root's bracket by bisection; 60 steps reach rounding."""
    y = omega * omega * depth / g
    n = np.arange(1, count + 1, dtype=np.float64)
    lo, hi = (n - 0.5) * np.pi, n * np.pi
    x = np.clip(n * np.pi - y / (n * np.pi), lo, hi)
    sign_hi = np.sign(y * np.cos(hi))
    for _ in range(60):
        f = x * np.sin(x) + y * np.cos(x)
        same = np.sign(f) == sign_hi
        hi = np.where(same, x, hi)
        lo = np.where(same, lo, x)
        step = x - f / (np.sin(x) + x * np.cos(x) - y * np.sin(x))
        x = np.where((step > lo) & (step < hi), step, 0.5 * (lo + hi))
    return x / depth


def _first_order_modes(
    omega: float, d: float, paddle: Paddle, hinge: float, modes: int, g: float
) -> tuple[npt.NDArray[np.complex128], tuple[FloatArray, ...], npt.NDArray[np.complex128],
           npt.NDArray[np.complex128]]:
    """The linear wave-maker's eigenfunction expansion at frequency omega (Biesel; Dean &
    Dalrymple 1991, section 6.2): ``phi = sum a_j cosh(k_j (z + d)) e^(i k_j x)`` with time
    factor e^(-i omega t), k_0 the progressive wavenumber and k_j = i kappa_j the ``modes``
    evanescent ones, for a paddle face ``x = f(z) X``, ``X = Re(xi e^(-i omega t))``, xi = 1:
    each a_j the projection of the paddle velocity ``-i omega f`` on its mode.

    Returns ``(k, (s, w, f, f_z), mode, a)``: the wavenumbers; the quadrature nodes (z + d),
    weights, profile and its slope; the modes at the nodes; the amplitudes.
    """
    k = np.concatenate([[float(wavenumber_from_omega(omega, d, g))],
                        1j * _evanescent_wavenumbers(omega, d, modes, g)])
    # composite 16-point Gauss-Legendre over the water column, a panel per half wave of the
    # highest mode, split where the flap's profile has its kink
    nodes, weights = np.polynomial.legendre.leggauss(16)
    ends = [0.0, hinge, d] if paddle == "flap" and hinge > 0.0 else [0.0, d]
    edges = np.unique(np.concatenate(
        [np.linspace(a, b, max(2, math.ceil((modes + 1) * (b - a) / d) + 1))
         for a, b in zip(ends[:-1], ends[1:], strict=False)]))
    half = 0.5 * np.diff(edges)[:, None]
    s = (half * nodes + 0.5 * (edges[1:] + edges[:-1])[:, None]).ravel()  # z + d
    w = (half * weights).ravel()
    if paddle == "piston":
        f, f_z = np.ones_like(s), np.zeros_like(s)
    else:
        above = s > hinge
        f = np.where(above, (s - hinge) / (d - hinge), 0.0)
        f_z = np.where(above, 1.0 / (d - hinge), 0.0)
    mode = np.cosh(np.multiply.outer(k, s))
    # phi_x(0, z) = -i omega xi f
    norms = (mode * mode) @ w
    a = -omega * ((mode * f) @ w) / (k * norms)
    return k, (s, w, f, f_z), mode, a


NEAR_FIELD_DECAY = 1e-10
"""Where :func:`paddle_near_field` stops its evanescent series: the last mode kept has decayed
to this over the distance from the face (at least 8 modes, at most :data:`SCHAFFER_MODES`)."""


def paddle_near_field(
    omega: float, depth: float, x: float, paddle: Paddle = "piston", hinge_height: float = 0.0,
    g: float = G,
) -> complex:
    """The linear wave-maker's surface elevation ``x`` [m] in front of its mean face, over that
    of its progressive wave at the face: ``F = sum_j c_j e^(i k_j x) / c_0``, time factor
    e^(-i omega t), from :func:`_first_order_modes` (progressive wave and evanescent near field;
    Dean & Dalrymple 1991, section 6.2). An elevation ``a sin(omega t + phase)`` of the
    progressive wave at the face is ``|F| a sin(omega t + phase - arg F)`` at x. Far from the
    face F tends to ``e^(i k x)``; near it the evanescent modes add a share in quadrature with
    it, which a piston and a flap give with opposite signs (tests/test_wave_laws.py).

    Args:
        omega: angular frequency [rad/s], > 0.
        depth: still-water depth [m], > 0.
        x: distance in front of the face [m], > 0 (the series does not converge at the face).
        paddle: ``"piston"`` or ``"flap"`` hinged ``hinge_height`` [m] above the bed.
    """
    d = float(_positive("depth", depth))
    distance = float(_positive("x", x))
    _choice("paddle", paddle, ("piston", "flap"))
    # kappa_n > (n - 1/2) pi / d: the modes that decay to NEAR_FIELD_DECAY over x
    wanted = math.ceil(-math.log(NEAR_FIELD_DECAY) * d / (math.pi * distance) + 0.5)
    modes = min(SCHAFFER_MODES, max(8, wanted))
    k, _, _, a = _first_order_modes(float(_positive("omega", omega)), d, paddle,
                                    float(hinge_height), modes, g)
    c = a * np.cosh(k * d)
    return complex(np.sum(c / c[0] * np.exp(1j * k * distance)))


def second_order_stroke(
    height: float,
    period: float,
    depth: float,
    paddle: Paddle = "flap",
    hinge_height: float = 0.0,
    modes: int = SCHAFFER_MODES,
    g: float = G,
) -> tuple[float, float]:
    """Second-harmonic paddle motion cancelling the free second harmonic of a regular wave:
    Schaffer's (1996) second-order wave-maker theory for a piston or a flap hinged
    ``hinge_height`` above the bed, by its eigenfunction expansion (evanescent modes included).

    The paddle face is ``x = f(z) X(t)``, f = 1 for a piston and ``(z - l) / (d - l)`` above a
    flap's hinge l (0 below), so X is the displacement at the still-water level; the first-order
    motion ``X1 = (S/2) sin(omega t)`` makes ``eta = (H/2) cos(omega t)`` at the paddle (S from
    the transfer function). First order: the potential is the progressive mode plus ``modes``
    evanescent ones, their amplitudes the projections of the paddle velocity ``f dX1/dt`` on
    each mode (Biesel). Second order, at 2 omega: every pair of first-order modes forces the
    free surface (the second-order combined surface condition,
    ``phi_tt + g phi_z = -d/dt |grad phi|^2 + (1/g) phi_t d/dz (phi_tt + g phi_z)`` at z = 0),
    each with its bound (particular) solution ``cosh(q (z + d)) e^(i q x)``, q the sum of the
    pair's wavenumbers; the paddle condition, expanded about x = 0, asks
    ``phi2_x = f dX2/dt - f X1 phi1_xx + f' X1 phi1_z``. The free progressive wave at 2 omega is
    the projection of (paddle velocity - bound velocity) at x = 0 on its eigenfunction
    ``cosh(K (z + d))`` (orthogonal to the evanescent ones); X2 is chosen to make it zero.
    The projections are Gauss-Legendre quadratures (split at the hinge).

    Limits (tests/test_wave_laws.py): a piston tends to Madsen's (1971) amplitude in shallow
    water (0.1 % at kd = 0.18), a flap to the depth-integrated form of Madsen's argument with
    its displacement profile; as kd grows the evanescent near field changes X2's size and
    gives it a phase (Schaffer 1996: the new terms matter where the paddle's motion fits the
    wave's velocity profile badly).

    Returns:
        ``(amplitude, phase)`` [m, rad]: ``X2 = amplitude sin(2 omega t + phase)`` (add
        ``2 delta`` for the law's phase delta).
    """
    H = float(_positive("height", height))
    T = float(_positive("period", period))
    d = float(_positive("depth", depth))
    _choice("paddle", paddle, ("piston", "flap"))
    hinge = float(_nonnegative("hinge_height", hinge_height))
    if paddle == "flap" and hinge >= d:
        raise ValueError(f"hinge_height: must be below the still-water level, got {hinge!r}")
    omega = 2.0 * math.pi / T
    k, (s, w, f, f_z), mode, a = _first_order_modes(omega, d, paddle, hinge, modes, g)
    big_k = float(wavenumber_from_omega(2.0 * omega, d, g))
    mode_z = k[:, None] * np.sinh(np.multiply.outer(k, s))
    cosh_kd, sinh_kd = np.cosh(k * d), np.sinh(k * d)
    xi = (0.5 * H) / (1j * omega / g * a[0] * cosh_kd[0])  # eta = (H/2) cos(omega t) at x = 0
    a = a * xi
    # second-order free-surface forcing of each pair (i, j), and its bound solution
    ki, kj = k[:, None], k[None, :]
    pair = a[:, None] * a[None, :]
    forcing = pair * (1j * omega * (-ki * kj * cosh_kd[:, None] * cosh_kd[None, :]
                                    + ki * sinh_kd[:, None] * kj * sinh_kd[None, :])
                      - 1j * omega / (2.0 * g) * cosh_kd[:, None]
                      * kj * (g * kj * cosh_kd[None, :] - omega * omega * sinh_kd[None, :]))
    q = ki + kj
    bound = forcing / (g * q * np.sinh(q * d) - 4.0 * omega * omega * np.cosh(q * d))
    # projections on cosh(K (z + d)) over the depth: of the bound velocity (closed form) ...
    overlap = ((q * np.sinh(q * d) * math.cosh(big_k * d) - big_k * np.cosh(q * d)
                * math.sinh(big_k * d)) / (q * q - big_k * big_k))
    bound_flux = np.sum(1j * q * bound * overlap)
    # ... and of the paddle's terms (phi_xx = -k^2 phi for every mode)
    free_mode = np.cosh(big_k * s)
    phi_xx = (-(k * k) * a) @ mode
    phi_z = a @ mode_z
    paddle_flux = ((-0.5 * xi * f * phi_xx + 0.5 * xi * f_z * phi_z) * free_mode) @ w
    xi2 = (paddle_flux - bound_flux) / (2j * omega * ((f * free_mode) @ w))
    # X2 = Re(xi2 e^(-2 i omega t)) = Im(xi2) sin(2 omega t) + Re(xi2) cos(2 omega t)
    return float(abs(xi2)), float(math.atan2(xi2.real, xi2.imag))


# ------------------------------------------------------------------------------------------------
# Steady nonlinear waves: Fourier (stream-function) theory

StreamCurrent = Literal["stokes", "euler"]

STREAM_FUNCTION_KD_LIMIT = 1.5
"""kd up to which the stream-function paddle law's higher harmonics (from the depth-averaged
flux) are trusted: :func:`check_wave` warns beyond it."""

STREAM_FUNCTION_MODES: tuple[int, ...] = (32, 24, 16, 64, 128)
"""Numbers of Fourier modes N :func:`stream_function_wave` tries in turn, until Newton's method
converges to a single-crested surface on which the series meets the surface conditions between
the collocation points too (:data:`STREAM_FUNCTION_TOLERANCE`). 32 resolve the waves of a flume
up to L/d ~ 30 (seed 002's wave, L/d = 13, has its surface coefficients below 1e-7 H there); a
steep wave in deep water needs fewer (with 32 its highest modes are below rounding and the
system is singular); longer, solitary-like waves need 64 or more."""

STREAM_FUNCTION_TOLERANCE = 1e-4
"""Largest error of the surface conditions midway between the collocation points that
:func:`stream_function_wave` accepts: of the stream function relative to Q, of Bernoulli's
constant relative to g d (1e-4 d of surface height: 0.03 mm in seed 002's 0.34 m)."""


def highest_wave_height(wavelength: npt.ArrayLike, depth: npt.ArrayLike) -> FloatArray:
    """Height of the highest steady wave of length L in depth d [m].

    Williams' (1981) results as fitted by Fenton (1990, "Nonlinear wave theories", The Sea 9,
    eq. 32): ``H/d = (0.141063 r + 0.0095721 r^2 + 0.0077829 r^3) / (1 + 0.0788340 r +
    0.0317567 r^2 + 0.0093407 r^3)``, ``r = L/d``; 0.833 for a solitary wave, H/L -> 0.141 in
    deep water.
    """
    d = _positive("depth", depth)
    r = _positive("wavelength", wavelength) / d
    num = 0.141063 * r + 0.0095721 * r**2 + 0.0077829 * r**3
    den = 1.0 + 0.0788340 * r + 0.0317567 * r**2 + 0.0093407 * r**3
    return _out(d * num / den)


def _sinh_cosh_ratios(a: FloatArray, b: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``sinh(a) / cosh(b)`` and ``cosh(a) / cosh(b)`` for ``0 <= a`` and ``b >= 0`` without
    overflow (``a`` may exceed ``b``: the crest is above the mean level)."""
    scale = np.exp(a - b) / (1.0 + np.exp(-2.0 * b))
    return scale * -np.expm1(-2.0 * a), scale * (1.0 + np.exp(-2.0 * a))


def _fourier_system(
    z: FloatArray, n: int, height: float, period: float, current: str
) -> tuple[FloatArray, FloatArray]:
    """Residuals and Jacobian of Rienecker & Fenton's (1981) collocation equations.

    Dimensionless with the depth d and g. Unknowns ``z``: kd, the surface heights above the mean
    level eta_m at the n + 1 points ``k X_m = m pi / n`` from crest to trough, B_1..B_n, the mean
    speed U of the fluid in the wave's frame, the volume flux Q under the wave in that frame and
    the Bernoulli constant R. With ``psi = -U y + sum B_j sinh(j k y) / cosh(j k d) cos(j k X)``
    (y up from the bed): the surface is a streamline, ``psi(X_m, 1 + eta_m) = -Q``; Bernoulli's
    equation holds there, ``(u^2 + v^2) / 2 + y = R``; the mean of eta is 0 (trapezoidal rule);
    crest minus trough is the height; and the current criterion: Stokes' (zero mass transport,
    ``Q = c d``) or Euler's (zero mean current at a fixed point, ``U = c``), c = 2 pi / (k T).
    """
    kd = z[0]
    eta = z[1 : n + 2]
    coeffs = z[n + 2 : 2 * n + 2]
    mean_speed, flux, bernoulli = z[2 * n + 2 :]
    j = np.arange(1, n + 1)[:, None]
    angle = j * np.arange(n + 1)[None, :] * (math.pi / n)
    cos, sin = np.cos(angle), np.sin(angle)
    y = 1.0 + eta
    jk = j * kd
    s, c = _sinh_cosh_ratios(jk * y, jk)
    tanh = np.tanh(jk)
    ds_dk = j * (y * c - s * tanh)
    dc_dk = j * (y * s - c * tanh)
    b_cos = coeffs[:, None] * cos
    b_sin = coeffs[:, None] * sin
    psi = -mean_speed * y + (b_cos * s).sum(0) + flux
    u = -mean_speed + (jk * b_cos * c).sum(0)
    v = (jk * b_sin * s).sum(0)
    celerity = 2.0 * math.pi / (kd * period)
    size = 2 * n + 5
    trapezoid = np.ones(n + 1)
    trapezoid[[0, n]] = 0.5
    criterion = flux - celerity if current == "stokes" else mean_speed - celerity
    residual = np.concatenate([
        psi,
        0.5 * (u * u + v * v) + y - bernoulli,
        [trapezoid @ eta / n, eta[0] - eta[n] - height, criterion],
    ])
    jac = np.zeros((size, size))
    kin, dyn = np.arange(n + 1), np.arange(n + 1, 2 * n + 2)
    jac[kin, 0] = (b_cos * ds_dk).sum(0)
    jac[kin, 1 + kin] = u
    jac[: n + 1, n + 2 : 2 * n + 2] = (s * cos).T
    jac[kin, 2 * n + 2] = -y
    jac[kin, 2 * n + 3] = 1.0
    du_dk = (j * b_cos * c + jk * b_cos * dc_dk).sum(0)
    dv_dk = (j * b_sin * s + jk * b_sin * ds_dk).sum(0)
    jac[dyn, 0] = u * du_dk + v * dv_dk
    du_deta = (jk * jk * b_cos * s).sum(0)
    dv_deta = (jk * jk * b_sin * c).sum(0)
    jac[dyn, 1 + kin] = u * du_deta + v * dv_deta + 1.0
    jac[n + 1 : 2 * n + 2, n + 2 : 2 * n + 2] = (u * jk * c * cos + v * jk * s * sin).T
    jac[dyn, 2 * n + 2] = -u
    jac[dyn, 2 * n + 4] = -1.0
    jac[2 * n + 2, 1 : n + 2] = trapezoid / n
    jac[2 * n + 3, 1] = 1.0
    jac[2 * n + 3, n + 1] = -1.0
    jac[2 * n + 4, 2 * n + 3 if current == "stokes" else 2 * n + 2] = 1.0
    jac[2 * n + 4, 0] = celerity / kd
    return residual, jac


def _midpoint_error(z: FloatArray, n: int) -> float:
    """Largest error of the surface conditions of the solution ``z`` of :func:`_fourier_system`
    midway between its collocation points, with the surface there from the cosine series
    through them (relative to Q and, for Bernoulli's equation, to g d)."""
    kd = z[0]
    eta = z[1 : n + 2]
    coeffs = z[n + 2 : 2 * n + 2]
    mean_speed, flux, bernoulli = z[2 * n + 2 :]
    series = _cosine_series(eta)
    middle = (np.arange(n) + 0.5) * (math.pi / n)
    y = 1.0 + np.cos(np.multiply.outer(middle, np.arange(n + 1))) @ series
    j = np.arange(1, n + 1)
    s, c = _sinh_cosh_ratios(np.multiply.outer(y, j * kd), j * kd)
    angle = np.multiply.outer(middle, j)
    psi = -mean_speed * y + (s * np.cos(angle)) @ coeffs + flux
    u = -mean_speed + (c * np.cos(angle)) @ (j * kd * coeffs)
    v = (s * np.sin(angle)) @ (j * kd * coeffs)
    return float(max(np.max(np.abs(psi)) / flux,
                     np.max(np.abs(0.5 * (u * u + v * v) + y - bernoulli))))


def _cosine_series(values: FloatArray) -> FloatArray:
    """Coefficients c_0..c_n of ``sum c_j cos(j theta)`` through ``values`` at ``theta = m pi /
    n``, m = 0..n (the discrete cosine transform with the trapezoidal rule)."""
    n = values.size - 1
    trapezoid = np.ones(n + 1)
    trapezoid[[0, n]] = 0.5
    angle = np.multiply.outer(np.arange(n + 1), np.arange(n + 1)) * (math.pi / n)
    coeffs = (2.0 / n) * (np.cos(angle) @ (trapezoid * values))
    coeffs[[0, n]] *= 0.5
    return coeffs


@functools.lru_cache(maxsize=64)
def _solve_fourier(
    height: float, period: float, modes: int, current: str, steps: int
) -> FloatArray | None:
    """The dimensionless unknowns of :func:`_fourier_system` (d = g = 1), or None if Newton's
    method does not converge. The height is raised in ``steps`` equal steps from the linear wave,
    each solve starting from the extrapolation of the two before (Fenton 1988)."""
    omega = 2.0 * math.pi / period
    kd = float(wavenumber_from_omega(omega, 1.0, 1.0))
    angles = np.arange(modes + 1) * (math.pi / modes)
    solution: FloatArray | None = None
    previous: FloatArray | None = None
    for step in range(1, steps + 1):
        h = height * step / steps
        if solution is None:
            c = omega / kd
            coeffs = np.zeros(modes)
            coeffs[0] = c * 0.5 * h / math.tanh(kd)
            guess = np.concatenate(
                [[kd], 0.5 * h * np.cos(angles), coeffs, [c, c, 0.5 * c * c + 1.0]])
        elif previous is None:
            guess = solution
        else:
            guess = 2.0 * solution - previous
        previous = solution
        z = guess
        for _ in range(40):
            # a diverging iteration overflows; it is caught below as a non-finite step
            with np.errstate(over="ignore", invalid="ignore"):
                residual, jac = _fourier_system(z, modes, h, period, current)
            if not np.all(np.isfinite(jac)) or not np.all(np.isfinite(residual)):
                return None
            if np.max(np.abs(residual)) < 1e-13:
                break
            try:
                step_z = np.linalg.solve(jac, -residual)
            except np.linalg.LinAlgError:
                return None
            z = z + step_z
            if not np.all(np.isfinite(z)) or z[0] <= 0.0:
                return None
            if np.max(np.abs(step_z)) < 1e-12:
                break
        else:
            return None
        solution = z
    return solution


class _SteadyWave:
    """The angular frequency and wavelength of a steady periodic wave's ``period`` and
    ``wavenumber``."""

    period: float
    wavenumber: float

    @property
    def omega(self) -> float:
        """2 pi / T [rad/s]."""
        return 2.0 * math.pi / self.period

    @property
    def wavelength(self) -> float:
        """L = 2 pi / k [m]."""
        return 2.0 * math.pi / self.wavenumber


@dataclass(frozen=True)
class StreamFunctionWave(_SteadyWave):
    """A steady, periodic wave of permanent form by Fourier approximation: Rienecker & Fenton's
    (1981) stream-function method in the form of Fenton (1988, "The numerical solution of steady
    water wave problems", Computers & Geosciences 14).

    In the frame moving with the wave (``X = x - c t``; ``z`` up from the bed, the still water
    at ``z = d``) the flow is steady with the stream function::

        psi(X, z) = -U z + sum_{j=1..N} B_j sinh(j k z) / cosh(j k d) cos(j k X)

    and the surface is ``eta(theta) = sum_{j=0..N} E_j cos(j theta)``, ``theta = k x - omega t``
    (crest at theta = 0, mean 0). The solution satisfies the kinematic and dynamic surface
    conditions at N + 1 points from crest to trough; the Fourier series carries them between.

    Attributes:
        height: H [m]; period: T [s]; depth: d [m]; g: [m/s^2].
        current: ``"stokes"`` (zero mass transport, ``Q = c d``: the wave of a closed flume) or
            ``"euler"`` (zero mean current at a fixed point below the trough, ``U = c``).
        wavenumber: k = 2 pi / L [rad/m] (nonlinear: L is longer than the linear wavelength).
        celerity: c = L / T [m/s].
        elevation_coefficients: E_0..E_N [m].
        stream_coefficients: B_1..B_N [m^2/s].
        mean_speed: U, the mean fluid speed in the wave's frame [m/s].
        volume_flux: Q, the volume flux per unit width in the wave's frame [m^2/s].
        bernoulli: R, the Bernoulli constant in the wave's frame, with g z [m^2/s^2].
    """

    height: float
    period: float
    depth: float
    g: float
    current: StreamCurrent
    wavenumber: float
    celerity: float
    elevation_coefficients: FloatArray
    stream_coefficients: FloatArray
    mean_speed: float
    volume_flux: float
    bernoulli: float

    @property
    def eulerian_current(self) -> float:
        """Mean current at a fixed point below the trough, ``c - U`` [m/s]."""
        return self.celerity - self.mean_speed

    @property
    def mass_transport_velocity(self) -> float:
        """Depth-averaged mean velocity (mass transport), ``c - Q / d`` [m/s]."""
        return self.celerity - self.volume_flux / self.depth

    def _phase(self, x: npt.ArrayLike, t: npt.ArrayLike) -> FloatArray:
        return self.wavenumber * _finite("x", x) - self.omega * _finite("t", t)

    def elevation(self, x: npt.ArrayLike, t: npt.ArrayLike) -> FloatArray:
        """Surface elevation above the still-water level eta(x, t) [m]."""
        theta = np.asarray(self._phase(x, t))
        j = np.arange(self.elevation_coefficients.size)
        return _out(np.cos(np.multiply.outer(theta, j)) @ self.elevation_coefficients)

    def _modes(
        self, x: npt.ArrayLike, z: npt.ArrayLike, t: npt.ArrayLike
    ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
        """``z``, ``sinh(j k z) / cosh(j k d)``, ``cosh(j k z) / cosh(j k d)``, the phases ``j
        theta`` and ``j k`` (last axis j = 1..N) at (x, z, t)."""
        theta = np.asarray(self._phase(x, t))
        zz = np.asarray(_nonnegative("z", z))
        theta, zz = np.broadcast_arrays(theta, zz)
        j = np.arange(1, self.stream_coefficients.size + 1)
        jk = j * self.wavenumber
        s, c = _sinh_cosh_ratios(np.multiply.outer(zz, jk), jk * self.depth)
        return zz, s, c, np.multiply.outer(theta, j), jk

    def stream_function(self, x: npt.ArrayLike, z: npt.ArrayLike, t: npt.ArrayLike) -> FloatArray:
        """psi [m^2/s] in the wave's frame at (x, z) [m] at time t [s] (z up from the bed); on
        the surface it equals ``-Q``."""
        zz, s, _, angle, _ = self._modes(x, z, t)
        return _out(-self.mean_speed * zz + (s * np.cos(angle)) @ self.stream_coefficients)

    def velocity(
        self, x: npt.ArrayLike, z: npt.ArrayLike, t: npt.ArrayLike
    ) -> tuple[FloatArray, FloatArray]:
        """Fluid velocity (u, w) [m/s] in the laboratory frame at (x, z) [m], time t [s] (z up
        from the bed, below the surface)."""
        _, s, c, angle, jk = self._modes(x, z, t)
        weights = jk * self.stream_coefficients
        u = self.celerity - self.mean_speed + (c * np.cos(angle)) @ weights
        w = (s * np.sin(angle)) @ weights
        return _out(u), _out(w)


def _highest_steady_wave(H: float, T: float, d: float, g: float) -> tuple[float, str]:
    """The highest wave of period T in depth d (Williams 1981, at the linear wavelength) and
    the refusal naming ``height``, raised at once when H is beyond any steady wave: a nonlinear
    wave is longer than the linear one, and its highest wave higher, but by less than a quarter
    (Stokes' c^2 = g/k (1 + (k a)^2) at the deep-water limit ka = 0.44)."""
    h_max = float(highest_wave_height(wavelength(T, d, g), d))
    refusal = (f"height: no steady wave of H = {H:g} m (H/d = {H / d:.3g}) and T = {T:g} s in "
               f"d = {d:g} m: the highest is about H = {h_max:.3g} m (Williams 1981)")
    if H > 1.25 * h_max:
        raise ValueError(refusal)
    return h_max, refusal


def stream_function_wave(
    height: float,
    period: float,
    depth: float,
    modes: int | None = None,
    current: StreamCurrent = "stokes",
    g: float = G,
) -> StreamFunctionWave:
    """The steady wave of height H and period T in depth d by Fourier approximation.

    Rienecker & Fenton (1981) as set out by Fenton (1988): N + 1 collocation points from crest to
    trough, Newton's method with the exact Jacobian, the height raised from the linear wave in
    steps of at most a tenth of the highest wave (:func:`highest_wave_height` at the linear
    wavelength) and of at most 50 in Ursell number, each converged to a step below 1e-12 or
    residuals below 1e-13 (dimensionless with d and g).

    Args:
        height: H [m]; period: T [s]; depth: d [m].
        modes: number of Fourier modes N (>= 4); ``None``: the first of
            :data:`STREAM_FUNCTION_MODES` that resolves the wave.
        current: ``"stokes"`` (zero mass transport: a closed flume) or ``"euler"``.
        g: gravitational acceleration [m/s^2].

    Raises:
        ValueError: naming ``height`` when no single-crested steady wave of that height converges
            (at or beyond the highest wave), or naming another bad argument.
    """
    H = float(_positive("height", height))
    T = float(_positive("period", period))
    d = float(_positive("depth", depth))
    g_ = float(_positive("g", g))
    _choice("current", current, ("stokes", "euler"))
    if modes is not None and (isinstance(modes, bool) or not isinstance(modes, int) or modes < 4):
        raise ValueError(f"modes: must be an integer >= 4, got {modes!r}")
    length = float(wavelength(T, d, g_))
    h_max, refusal = _highest_steady_wave(H, T, d, g_)
    # long waves need smaller steps than their height alone says
    steps = max(1, math.ceil(10.0 * H / h_max), math.ceil(float(ursell_number(H, T, d, g_)) / 50))
    tried = STREAM_FUNCTION_MODES if modes is None else (modes,)
    for n in tried:
        z = _solve_fourier(H / d, T * math.sqrt(g_ / d), n, current, steps)
        # beyond the highest wave (or with too few modes) Newton's method may land on a
        # surface that is not a single crest and trough, or on a wave too high for its length,
        # or the series may not carry the surface conditions between the points
        if (z is not None and np.all(np.diff(z[1 : n + 2]) <= 1e-6 * H / d)
                and H <= float(highest_wave_height(2.0 * math.pi * d / z[0], d))
                and _midpoint_error(z, n) <= STREAM_FUNCTION_TOLERANCE):
            break
    else:
        solitary = ", and a wave this long (L/d > 50) is nearly solitary" if length > 50 * d else ""
        raise ValueError(f"{refusal}; none converges with up to N = {max(tried)} Fourier modes"
                         f"{solitary}")
    speed = math.sqrt(g_ * d)
    k = float(z[0]) / d
    return StreamFunctionWave(
        height=H,
        period=T,
        depth=d,
        g=g_,
        current=current,
        wavenumber=k,
        celerity=2.0 * math.pi / (k * T),
        elevation_coefficients=_cosine_series(z[1 : n + 2]) * d,
        stream_coefficients=z[n + 2 : 2 * n + 2] * d * speed,
        mean_speed=float(z[2 * n + 2]) * speed,
        volume_flux=float(z[2 * n + 3]) * d * speed,
        bernoulli=float(z[2 * n + 4]) * g_ * d,
    )


@dataclass(frozen=True)
class StreamFunctionPaddleMotion:
    """The piston motion generating a :class:`StreamFunctionWave` or a :class:`CnoidalWave`, as
    harmonics of omega.

    The law, for t >= 0 (r(t) the ramp of :meth:`motion`)::

        X(t) = r(t) sum_n stroke_amplitudes[n-1] sin(n (omega t + phase))

    and the wave's elevation at the paddle face is ``sum_n elevation_amplitudes[n-1] cos(n
    (omega t + phase))`` (its crest at the paddle when ``omega t + phase = 0``, with the paddle
    at rest position and moving forward fastest).

    Attributes:
        wave: the target wave.
        phase: phase delta [rad].
        stroke_amplitudes: a_n [m], n = 1, 2, ...
        elevation_amplitudes: e_n [m], n = 1, 2, ...
    """

    wave: StreamFunctionWave | CnoidalWave
    phase: float
    stroke_amplitudes: FloatArray
    elevation_amplitudes: FloatArray

    @property
    def omega(self) -> float:
        """2 pi / T [rad/s]."""
        return self.wave.omega

    @property
    def stroke(self) -> float:
        """Peak-to-peak travel of the paddle [m]."""
        x, _ = self.motion(np.linspace(0.0, self.wave.period, 1025), 0.0)
        return float(np.max(x) - np.min(x))

    def motion(
        self, t: npt.ArrayLike, ramp_periods: float = 2.0, ramp: RampKind = "linear"
    ) -> tuple[FloatArray, FloatArray]:
        """Paddle displacement X [m] and velocity dX/dt [m/s] at times ``t`` [s], with the ramp of
        :meth:`RegularPaddleMotion.motion`."""
        tt = _finite("t", t)
        n = float(_nonnegative("ramp_periods", ramp_periods))
        _choice("ramp", ramp, ("linear", "tanh"))
        r, dr = _ramp(tt, n * self.wave.period, ramp)
        harmonics = np.arange(1, self.stroke_amplitudes.size + 1)
        angle = np.multiply.outer(self.omega * tt + self.phase, harmonics)
        base = np.sin(angle) @ self.stroke_amplitudes
        rate = np.cos(angle) @ (self.stroke_amplitudes * harmonics * self.omega)
        return _out(r * base), _out(dr * base + r * rate)


def stream_function_piston_motion(
    wave: StreamFunctionWave, phase: float = 0.0, samples: int = 2048
) -> StreamFunctionPaddleMotion:
    """The piston motion making ``wave``: the depth-averaged velocity of the wave at the paddle,
    with its first- and second-order parts from wave-maker theory (Zhang & Schaffer 2007's
    ad-hoc unification).

    The paddle moves with the depth-averaged velocity of the target wave at its face, as in
    Goring's (1978) solitary-wave generation: ``dX/dt = q / (d + eta)``, q the wave's volume
    flux per unit width through a fixed section. In the wave's frame the flow is steady with
    flux -Q, so ``q = c (d + eta) - Q = c eta`` for the zero-mass-transport wave of a closed
    flume (``Q = c d``). Along the paddle the phase ``vartheta = omega t - k X`` then obeys
    ``d vartheta / dt = omega (d + eta) / d``, which integrates in closed form: with
    ``I(vartheta) = sum_j (E_j / j) sin(j vartheta)``::

        t = (vartheta + I / d) / omega,      X = I / (k d)

    (X and t return to 0 and T after one wave: the paddle does not drift). The harmonics of X(t)
    and of eta at the paddle are integrals over vartheta (the trapezoidal rule on ``samples``
    points, exact for these periodic integrands to rounding).

    This flux law is exact for long waves, but in finite depth its expansion in H, first
    harmonic ``a / (k d)`` and second ``(a2 / 2 - a^2 / (2 d)) / (k d)`` (a = H/2, a2 Stokes'
    bound harmonic), differs from wave-maker theory (``kd`` against Biesel's H/S: 0.1 % at kd =
    0.5, 6 % at kd = 1; the second harmonic by 2 % at kd = 0.5 and with the wrong sign beyond
    kd ~ 1). Those two parts are replaced by Biesel's stroke and Madsen's (1971) second
    harmonic (:func:`regular_paddle_motion`), so the law tends to Madsen's second-order law as
    H -> 0 at any depth and to the flux law in shallow water. Harmonics below 1e-7 of the
    first are dropped.

    Args:
        wave: a :class:`StreamFunctionWave` with ``current = "stokes"``.
        phase: phase delta [rad].
        samples: quadrature points over one period.
    """
    if wave.current != "stokes":
        raise ValueError("wave: a paddle in a closed flume makes the zero-mass-transport wave "
                         "(current = 'stokes')")
    ph = float(_finite("phase", phase))
    d = wave.depth
    strokes, elevations = _flux_law_harmonics(wave.elevation_coefficients, wave.wavenumber, d,
                                              wave.omega, samples)
    # the flux law's own first- and second-order parts replaced by Biesel's and Madsen's
    second_order = regular_paddle_motion(wave.height, wave.period, d, "piston", 2, 0.0, wave.g)
    k1 = second_order.wavenumber
    a = 0.5 * wave.height
    a2 = float(stokes2_second_harmonic_amplitude(wave.height, k1, d))
    strokes[0] += 0.5 * second_order.stroke - a / (k1 * d)
    if strokes.size > 1:
        flux_second = (0.5 * a2 - a * a / (2.0 * d)) / (k1 * d)
        strokes[1] += second_order.second_order_amplitude - flux_second
    return _flux_paddle_motion(wave, ph, strokes, elevations)


def _flux_law_harmonics(
    coefficients: FloatArray, k: float, depth: float, omega: float, samples: int
) -> tuple[FloatArray, FloatArray]:
    """The harmonics of Goring's flux law ``dX/dt = c eta / (d + eta)`` for the surface
    ``eta(theta) = sum_j coefficients[j] cos(j theta)`` (``coefficients[0]``, the mean, is
    left out) of a wave of wavenumber ``k`` and angular frequency ``omega``: the paddle's
    stroke amplitudes of ``sin(n omega t)`` and the elevation amplitudes of ``cos(n omega t)``
    at its face, n = 1 .. len(coefficients) - 1 (see :func:`stream_function_piston_motion`)."""
    vartheta = 2.0 * math.pi * np.arange(samples) / samples
    j = np.arange(1, coefficients.size)
    e = coefficients[1:]
    integral = np.sin(np.multiply.outer(vartheta, j)) @ (e / j)
    eta = np.cos(np.multiply.outer(vartheta, j)) @ e
    t = (vartheta + integral / depth) / omega
    x = integral / (k * depth)
    # (2/T) int_0^T f(t) g(n omega t) dt with dt = (d + eta) / (omega d) dvartheta
    weight = (1.0 + eta / depth) * (2.0 / samples)
    angle = np.multiply.outer(omega * t, j)
    return (x * weight) @ np.sin(angle), (eta * weight) @ np.cos(angle)


def _flux_paddle_motion(
    wave: StreamFunctionWave | CnoidalWave, phase: float, strokes: FloatArray,
    elevations: FloatArray,
) -> StreamFunctionPaddleMotion:
    """The motion with harmonics below 1e-7 of the first dropped."""
    keep = int(np.max(np.nonzero(np.abs(strokes) > 1e-7 * abs(strokes[0]))[0])) + 1
    return StreamFunctionPaddleMotion(
        wave=wave,
        phase=phase,
        stroke_amplitudes=strokes[:keep],
        elevation_amplitudes=elevations[:keep],
    )


# ------------------------------------------------------------------------------------------------
# Cnoidal waves (first order)

CNOIDAL_URSELL_LIMIT = 500.0
"""Ursell number ``H L^2 / d^3`` (linear L) beyond which ``"auto"`` takes the cnoidal law
instead of the stream-function law: there the Fourier method needs 64 modes or more (with 32
it resolves H/d = 0.3 at L/d = 40, U = 476, but not H/d = 0.4 at the same length, U = 635)
and the wave is nearly solitary (elliptic parameter m > 1 - 1e-7)."""

CNOIDAL_KD_LIMIT = math.pi / 4.0
"""kd up to which first-order cnoidal theory is used, d/L < 1/8 (Wiegel 1960; Dean &
Dalrymple 1991, ch. 11): :func:`check_wave` warns beyond it."""


@dataclass(frozen=True)
class CnoidalWave(_SteadyWave):
    """A first-order cnoidal wave (Korteweg & de Vries 1895; Wiegel 1960; Svendsen 2006,
    "Introduction to nearshore hydrodynamics", ch. 6) about still water, travelling towards +x::

        eta = eta_t + H cn^2(K(m) theta / pi | m),    theta = k x - omega t

    (crest at theta = 0), with the trough ``eta_t = H ((1 - E/K) / m - 1)`` that makes the mean
    level zero, the wavelength ``L = sqrt(16 d^3 m / (3 H)) K(m)`` (so ``H L^2 / d^3 = 16/3 m
    K^2``) and the celerity ``c = sqrt(g d) [1 + H/(m d) (1 - m/2 - 3E/(2K))]``, K and E the
    complete elliptic integrals of the parameter m. As m -> 0 it is the linear wave with the
    long-wave dispersion ``c = sqrt(g d) (1 - (kd)^2 / 6)``; as m -> 1 the solitary wave ``H
    sech^2(sqrt(3H/(4d^3)) (x - c t))``, ``c = sqrt(g d) (1 + H/(2d))``.

    Attributes:
        height: H [m]; period: T [s]; depth: d [m]; g: [m/s^2].
        parameter: the elliptic parameter m (0 < m < 1) [-].
        complement: 1 - m, held apart for waves near the solitary limit [-].
        wavenumber: k = 2 pi / L [rad/m].
        celerity: c = L / T [m/s].
        trough: eta_t, the trough's elevation above still water (negative) [m].
        elevation_coefficients: E_0..E_N of ``eta = sum_j E_j cos(j theta)`` [m] (E_0 = 0 to
            rounding), to 1e-12 H.
    """

    height: float
    period: float
    depth: float
    g: float
    parameter: float
    complement: float
    wavenumber: float
    celerity: float
    trough: float
    elevation_coefficients: FloatArray

    @property
    def ursell_number(self) -> float:
        """``H L^2 / d^3`` with the cnoidal wavelength, ``16/3 m K(m)^2`` [-]."""
        return self.height * self.wavelength**2 / self.depth**3

    def elevation(self, x: npt.ArrayLike, t: npt.ArrayLike) -> FloatArray:
        """Surface elevation above the still-water level eta(x, t) [m], from the elliptic
        function itself (not the series)."""
        theta = self.wavenumber * _finite("x", x) - self.omega * _finite("t", t)
        return _out(_cnoidal_surface(theta, self.height, self.parameter, self.complement,
                                     self.trough))


def _elliptic_integrals(m: float, complement: float) -> tuple[float, float]:
    """K(m) and E(m), K from 1 - m near the solitary limit."""
    return float(special.ellipkm1(complement)), float(special.ellipe(m))


def _cnoidal_surface(theta: FloatArray, height: float, m: float, complement: float,
                     trough: float) -> FloatArray:
    K, _ = _elliptic_integrals(m, complement)
    # cn^2 has period 2K: reduce theta to (-pi, pi] first, where ellipj is most accurate
    reduced = np.angle(np.exp(1j * np.asarray(theta, dtype=np.float64)))
    _, cn, _, _ = special.ellipj(K * reduced / math.pi, m)
    return np.asarray(trough + height * cn * cn)


def cnoidal_wave(height: float, period: float, depth: float, g: float = G) -> CnoidalWave:
    """The first-order cnoidal wave (:class:`CnoidalWave`) of height H and period T in depth d.

    The parameter m solves ``L(m) = c(m) T``: in units of d and sqrt(d/g), ``T' = sqrt(16 m /
    (3 H')) K(m) / (c(m) / sqrt(g d))``. The right-hand side is infinite where the first-order
    celerity vanishes (small m: a wave too short and high for the long-wave expansion) and as m
    -> 1, with one minimum between; the physical root is the one on the long-wave side of the
    minimum (c -> sqrt(g d) as H -> 0), found by bisection in log m (m < 1/2) and log(1 - m).

    Raises:
        ValueError: naming ``height`` beyond the highest steady wave (as
            :func:`stream_function_wave`), ``period`` when T is below the minimum (no
            first-order cnoidal wave of that height and period; the stream-function law makes
            it), or another bad argument.
    """
    H = float(_positive("height", height))
    T = float(_positive("period", period))
    d = float(_positive("depth", depth))
    g_ = float(_positive("g", g))
    _highest_steady_wave(H, T, d, g_)
    h = H / d
    tau = T * math.sqrt(g_ / d)

    def parameter(s: npt.ArrayLike) -> tuple[FloatArray, FloatArray]:
        # m and 1 - m from s: m = e^s / 2 for s < 0, 1 - m = e^-s / 2 beyond (m = 1/2 at 0)
        ss = np.asarray(s, dtype=np.float64)
        small = 0.5 * np.exp(np.minimum(ss, 0.0))
        near_one = 0.5 * np.exp(-np.maximum(ss, 0.0))
        return np.where(ss < 0.0, small, 1.0 - near_one), np.where(ss < 0.0, 1.0 - small, near_one)

    def period_of(s: npt.ArrayLike) -> FloatArray:
        m, p = parameter(s)
        K = special.ellipkm1(p)
        factor = 1.0 + h / m * (1.0 - 0.5 * m - 1.5 * special.ellipe(m) / K)
        with np.errstate(divide="ignore"):
            return np.where(factor > 0.0, np.sqrt(16.0 * m / (3.0 * h)) * K / factor, np.inf)

    # m from 1e-16 (where the factor is negative for any H/d > 1e-16) to 1 - 1e-300
    grid = np.linspace(-36.0, 690.0, 6000)
    periods = period_of(grid)
    lowest = int(np.argmin(periods))
    if not tau > periods[lowest]:
        raise ValueError(
            f"period: no first-order cnoidal wave of H = {H:g} m and T = {T:g} s in d = {d:g} m: "
            f"at this height the shortest is T = {periods[lowest] * math.sqrt(d / g_):.3g} s "
            f"(Ursell number {float(ursell_number(H, T, d, g_)):.1f}, cnoidal range above "
            f"{MADSEN_URSELL_LIMIT:.1f}: the long-wave expansion does not hold; the "
            "stream-function law makes the wave)"
        )
    if tau > periods[-1]:
        raise ValueError(f"period: T = {T:g} s is too long for double precision (1 - m < 1e-300)")
    above = lowest + int(np.argmax(periods[lowest:] >= tau))
    root = _bisect(lambda q: float(period_of(q)) - tau, float(grid[above - 1]),
                   float(grid[above]))
    m, p = (float(v) for v in parameter(root))
    K, E = _elliptic_integrals(m, p)
    length = math.sqrt(16.0 * d**3 * m / (3.0 * H)) * K
    trough = H * ((1.0 - E / K) / m - 1.0)
    # the surface's cosine series, on enough points that the last quarter is below 1e-12 H
    samples = 1024
    while True:
        theta = 2.0 * math.pi * np.arange(samples) / samples
        spectrum = np.fft.rfft(_cnoidal_surface(theta, H, m, p, trough)) / samples
        coefficients = 2.0 * spectrum.real
        coefficients[0] = spectrum[0].real
        if np.max(np.abs(coefficients[samples // 8 :])) < 1e-12 * H or samples >= 1 << 18:
            break
        samples *= 2
    significant = np.nonzero(np.abs(coefficients) >= 1e-12 * H)[0]
    return CnoidalWave(
        height=H,
        period=T,
        depth=d,
        g=g_,
        parameter=m,
        complement=p,
        wavenumber=2.0 * math.pi / length,
        celerity=length / T,
        trough=trough,
        elevation_coefficients=coefficients[: int(significant[-1]) + 1],
    )


def _bisect(f: Callable[[float], float], a: float, b: float) -> float:
    """The root of ``f`` between ``a`` and ``b`` (f(a) < 0 <= f(b)), to rounding."""
    fa = f(a)
    for _ in range(200):
        mid = 0.5 * (a + b)
        if mid in (a, b):
            break
        fm = f(mid)
        if (fm < 0.0) == (fa < 0.0):
            a, fa = mid, fm
        else:
            b = mid
    return 0.5 * (a + b)


def cnoidal_piston_motion(
    wave: CnoidalWave, phase: float = 0.0, samples: int = 4096
) -> StreamFunctionPaddleMotion:
    """The piston motion making a cnoidal ``wave``: Goring's (1978) flux law ``dX/dt = c eta /
    (d + eta)``, the depth-averaged velocity of a long wave at the paddle face (exact for
    the long waves cnoidal theory describes), integrated in closed form as in
    :func:`stream_function_piston_motion` but without Biesel's and Madsen's corrections to its
    first two harmonics (0.1 % of the first at kd = 0.5).

    Args:
        wave: a :class:`CnoidalWave`.
        phase: phase delta [rad].
        samples: quadrature points over one period.
    """
    ph = float(_finite("phase", phase))
    n = max(samples, 4 * wave.elevation_coefficients.size)
    strokes, elevations = _flux_law_harmonics(wave.elevation_coefficients, wave.wavenumber,
                                              wave.depth, wave.omega, n)
    return _flux_paddle_motion(wave, ph, strokes, elevations)


# ------------------------------------------------------------------------------------------------
# Breaking limits, Iribarren number, breaker type


def mccowan_breaking(height: npt.ArrayLike, depth: npt.ArrayLike) -> npt.NDArray[np.bool_]:
    """True where ``H / d > 0.78`` (McCowan 1894; seed 000, depth-limited breaking)."""
    return (_nonnegative("height", height) / _positive("depth", depth) > MCCOWAN_BREAKING_RATIO)[()]


def miche_height_limit(period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G) -> FloatArray:
    """Steepness-limited height ``H_max = 0.142 L tanh(k d)`` [m] (Miche 1944; seed 000)."""
    d = _positive("depth", depth)
    k = np.asarray(wavenumber(period, d, g))
    return _out(MICHE_COEFFICIENT * 2.0 * np.pi / k * np.tanh(k * d))


def miche_breaking(
    height: npt.ArrayLike, period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G
) -> npt.NDArray[np.bool_]:
    """True where ``H / L > 0.142 tanh(k d)`` (Miche 1944; seed 000)."""
    H = _nonnegative("height", height)
    return (H > np.asarray(miche_height_limit(period, depth, g)))[()]


def kinematic_breaking(
    crest_speed: npt.ArrayLike, celerity: npt.ArrayLike
) -> npt.NDArray[np.bool_]:
    """True where the crest particle speed exceeds 0.85 times the wave celerity (seed 000).

    Args:
        crest_speed: horizontal particle speed at the crest u [m/s].
        celerity: local wave celerity c [m/s], > 0.
    """
    u = _finite("crest_speed", crest_speed)
    return (u > KINEMATIC_BREAKING_RATIO * _positive("celerity", celerity))[()]


def iribarren(slope: npt.ArrayLike, height: npt.ArrayLike, l0: npt.ArrayLike) -> FloatArray:
    """Iribarren number (surf similarity) ``xi = tan(beta) / sqrt(H / L0)`` [-].

    Seed 001 Eq. 2 (Iribarren 1949; Battjes 1974). ``L0 = g T^2 / (2 pi)`` is the deep-water
    wavelength (:func:`deep_water_wavelength`). Which H: for :func:`breaker_type` the height at
    the break point (Battjes 1974 via the Coastal Wiki "Surf similarity parameter" page, which
    gives the thresholds of seed 001 Table 1 for H and L at the break point, L = g T^2 / 2 pi);
    for the run-up formulas of seed 001 the finite-depth height near the toe of the slope.

    Args:
        slope: tan(beta) [-], > 0.
        height: wave height H [m], > 0.
        l0: deep-water wavelength L0 [m], > 0.
    """
    s = _positive("slope", slope)
    return _out(s / np.sqrt(_positive("height", height) / _positive("l0", l0)))


def breaker_type(xi: npt.ArrayLike) -> str | npt.NDArray[np.str_]:
    """Breaker type from the Iribarren number (seed 001 Table 1; seed 000).

    ``xi < 0.4``: ``"spilling"``; ``0.4 <= xi <= 2.0``: ``"plunging"``; ``xi > 2.0``:
    ``"collapsing/surging"`` (seed 001's table prints "> 0.2" for surging, a typo for 2.0 as
    seed 000 and Battjes 1974 give). Compute xi with the breaking wave height and the deep-water
    wavelength (see :func:`iribarren`).

    Returns:
        A string for a scalar ``xi``, else an array of strings of ``xi``'s shape.
    """
    x = _nonnegative("xi", xi)
    kinds = np.where(x < 0.4, "spilling", np.where(x <= 2.0, "plunging", "collapsing/surging"))
    return str(kinds) if kinds.ndim == 0 else kinds


# ------------------------------------------------------------------------------------------------
# Run-up formulas of seed 001 (Roselli et al., section 1)


def hunt_runup(xi: npt.ArrayLike) -> FloatArray:
    """Hunt (1959): relative run-up ``R / H = xi`` [-] (seed 001 Eq. 1).

    R is the maximum run-up above the still-water level [m], xi from :func:`iribarren` with the
    wave height near the toe and L0. Seed 001: suitable for xi < 2.5, less accurate above 2.
    """
    return _out(np.array(_nonnegative("xi", xi)))


def schuttrumpf_runup(xi: npt.ArrayLike, a: float = 2.25, b: float = 0.5) -> FloatArray:
    """Schuttrumpf (2001): ``R / H = a tanh(b xi)`` [-], a = 2.25, b = 0.5 (seed 001 Eq. 3).

    For breaking and non-breaking waves; xi as in :func:`hunt_runup`.
    """
    x = _nonnegative("xi", xi)
    return _out(float(_positive("a", a)) * np.tanh(float(_positive("b", b)) * x))


def chue_runup(height: npt.ArrayLike, l0: npt.ArrayLike, slope: npt.ArrayLike) -> FloatArray:
    """Chue (1980): ``R/H = 1.8 (1 - 3.1 H/L0) xi0 (1 - exp(-sqrt(pi/(2 beta)) / xi0))`` [-].

    Seed 001 Eqs. 4-5, with ``xi0 = tan(beta) / (H/L0)^0.4`` and beta the slope angle [rad]. The
    seed prints the exponent without its minus sign, ``exp(+sqrt(pi/(2 beta))/xi0)``, which makes
    R/H negative for every slope (about -4e8 on a 1:15 beach); the minus sign is restored
    here so that the factor in brackets tends to 1 on gentle slopes, which is the reading used.

    Args:
        height: wave height H near the toe [m]; l0: deep-water wavelength L0 [m];
        slope: tan(beta) [-].
    """
    H = _positive("height", height)
    L0 = _positive("l0", l0)
    s = _positive("slope", slope)
    steepness = H / L0
    xi0 = s / steepness**0.4
    beta = np.arctan(s)
    return _out(
        1.8 * (1.0 - 3.1 * steepness) * xi0 * (1.0 - np.exp(-np.sqrt(np.pi / (2.0 * beta)) / xi0))
    )


def linear_momentum_flux_parameter(
    height: npt.ArrayLike, period: npt.ArrayLike, depth: npt.ArrayLike, g: float = G
) -> FloatArray:
    """Maximum depth-integrated wave momentum flux ``(M_F / (rho g h^2))_max`` [-], linear theory.

    ``(1/2)(H/h) tanh(kh)/(kh) + (1/8)(H/h)^2 (1 + 2kh/sinh 2kh)``: the dynamic pressure and
    ``rho u^2`` of linear theory integrated over the depth under the crest, the parameter of
    Hughes (2004) used by :func:`hughes_runup`. Derived here from Airy theory; Hughes also gives
    a fit to nonlinear (Fourier) waves, which was not available to check and is not implemented.

    Args:
        height: wave height H at the toe [m]; period: T [s]; depth: toe depth h [m].
    """
    H = _positive("height", height)
    h = _positive("depth", depth)
    kh = np.asarray(wavenumber(period, h, g)) * h
    rel = H / h
    return _out(
        0.5 * rel * np.tanh(kh) / kh + 0.125 * rel * rel * (1.0 + _two_x_over_sinh_two_x(kh))
    )


def hughes_runup(slope: npt.ArrayLike, momentum_flux_parameter: npt.ArrayLike) -> FloatArray:
    """Hughes (2004), non-breaking waves: ``R / H = 3.84 tan(beta) sqrt(M_F / (rho g h^2))`` [-].

    Seed 001 Eq. 6. The seed prints ``3.84 tanh(M_F/(rho g h^2))^(1/2)``; its next sentence says
    the formula depends on the slope through tan(beta), so "tanh" is read as ``tan(beta)`` times
    the square root. Seed 001 notes that it fails on steep slopes (beta > 30 deg).

    Args:
        slope: tan(beta) [-].
        momentum_flux_parameter: ``(M_F / (rho g h^2))_max`` [-], e.g. from
            :func:`linear_momentum_flux_parameter`.
    """
    s = _positive("slope", slope)
    m = _nonnegative("momentum_flux_parameter", momentum_flux_parameter)
    return _out(3.84 * s * np.sqrt(m))


def hsu_runup(xi: npt.ArrayLike, slope: npt.ArrayLike) -> FloatArray:
    """Hsu et al. (2012): ``R / H = 2 (0.5 xi)^(0.04 / tan^2 beta)`` [-] (seed 001 Eq. 7).

    Fitted for 1/5 <= tan(beta) <= 1/2 and xi <= 3 (Hsu et al. 2012, abstract); on gentler
    slopes the exponent grows as 1/tan^2 and R/H collapses towards 0 (about 2e-7 on 1:15), so it
    is meaningless there.
    """
    x = _nonnegative("xi", xi)
    s = _positive("slope", slope)
    return _out(2.0 * (0.5 * x) ** (0.04 / (s * s)))


# ------------------------------------------------------------------------------------------------
# Solitary waves


def _solitary_shape(height: FloatLike, depth: FloatLike) -> FloatLike:
    """``K = sqrt(3 H / (4 d))`` [-], the dimensionless solitary-wave shape factor (FORMULAS §5)."""
    return np.sqrt(0.75 * height / depth)


def solitary_celerity(height: npt.ArrayLike, depth: npt.ArrayLike, g: float = G) -> FloatArray:
    """Solitary-wave celerity ``c = sqrt(g (d + H))`` [m/s] (Goring 1978)."""
    H = _positive("height", height)
    return _out(np.sqrt(float(_positive("g", g)) * (_positive("depth", depth) + H)))


def solitary_wave_elevation(
    x: npt.ArrayLike, t: npt.ArrayLike, height: float, depth: float, x0: float = 0.0, g: float = G
) -> FloatArray:
    """Solitary wave ``eta = H sech^2(K (x - x0 - c t) / d)`` [m], ``K = sqrt(3H/(4d))``.

    FORMULAS §5 (Synolakis 1987 initial condition, the NTHMP benchmark form) travelling towards
    +x at ``c = sqrt(g (d + H))`` (Goring 1978); the crest is at x0 at t = 0.
    """
    xx = _finite("x", x)
    tt = _finite("t", t)
    H = float(_positive("height", height))
    d = float(_positive("depth", depth))
    K = float(_solitary_shape(np.float64(H), np.float64(d)))
    c = float(solitary_celerity(H, d, g))
    arg = np.abs(K * (xx - float(_finite("x0", x0)) - c * tt) / d)
    return _out(H * _sech(arg) ** 2)


def solitary_piston_stroke(height: npt.ArrayLike, depth: npt.ArrayLike) -> FloatArray:
    """Total piston stroke of Goring's (1978) solitary-wave generation ``S = sqrt(16 H d / 3)`` [m].

    ``S = 2 H / K`` with ``K = sqrt(3 H / (4 d))``; the truncated motion of
    :func:`solitary_piston_motion` covers ``S tanh(A)`` of it.
    """
    H = _positive("height", height)
    return _out(np.sqrt(16.0 * H * _positive("depth", depth) / 3.0))


def _goring_start(truncation: float) -> float:
    """``A = arccosh(1 / sqrt(eps))``: the start and end phase where eta = eps H (Goring 1978)."""
    eps = float(_positive("truncation", truncation))
    if eps >= 1.0:
        raise ValueError(f"truncation: must be < 1, got {truncation!r}")
    return math.acosh(1.0 / math.sqrt(eps))


def solitary_piston_duration(
    height: npt.ArrayLike, depth: npt.ArrayLike, truncation: float = 0.002, g: float = G
) -> FloatArray:
    """Duration of Goring's solitary-wave piston motion [s].

    ``(2 A d / K + S tanh A) / c`` with ``A = arccosh(1/sqrt(truncation))``: the motion starts
    and ends where the generated elevation is ``truncation * H``. Goring's (1978) rule
    ``2 (3.8 + H/d) / (kappa c)`` (kappa = K/d) is the case truncation = 0.002 (A = 3.8).
    """
    H = _positive("height", height)
    d = _positive("depth", depth)
    A = _goring_start(truncation)
    K = _solitary_shape(H, d)
    c = np.asarray(solitary_celerity(H, d, g))
    S = 2.0 * H / K
    return _out((2.0 * A * d / K + S * math.tanh(A)) / c)


def solitary_piston_motion(
    t: npt.ArrayLike, height: float, depth: float, truncation: float = 0.002, g: float = G
) -> tuple[FloatArray, FloatArray]:
    """Goring (1978) piston motion generating a solitary wave: displacement X [m], velocity [m/s].

    The paddle moves with the depth-averaged velocity under the wave, ``dX/dt = c eta / (d +
    eta)``, with ``eta = H sech^2(theta)``, which integrates to the implicit trajectory::

        X(t) = (H / K) [tanh(theta) + tanh(A)],   theta = (K / d) (c t - X(t) - lambda)

    with ``K = sqrt(3H/(4d))``, ``c = sqrt(g (d + H))``, ``A = arccosh(1 / sqrt(truncation))``
    and ``lambda = A d / K``, so that X(0) = 0 and the motion starts and ends where eta is
    ``truncation * H``. Form of Goring (1978) as transcribed in a public Fortran wave-maker
    routine (``XP(T) = H/K [tanh(X(T)) + tanh(K lambda / D)]``); velocity
    ``dX/dt = c (H/d) / (cosh^2(theta) + H/d)``. The implicit equation is solved by Newton's
    method (its derivative ``1 + (H/d) sech^2 theta`` is >= 1, so it converges from any start).
    Before t = 0 X = 0; after the duration (:func:`solitary_piston_duration`) X holds still.

    Args:
        t: times [s]; height: H [m]; depth: d [m].
        truncation: eta / H at which the motion starts and stops (Goring's 3.8 <-> 0.002).
    """
    tt = _finite("t", t)
    H = float(_positive("height", height))
    d = float(_positive("depth", depth))
    A = _goring_start(truncation)
    K = float(_solitary_shape(np.float64(H), np.float64(d)))
    c = float(solitary_celerity(H, d, g))
    t_end = float(solitary_piston_duration(H, d, truncation, g))
    lam = A * d / K
    half = H / K
    tc = np.clip(tt, 0.0, t_end)
    x = half * (np.tanh(K / d * (c * tc - lam)) + math.tanh(A))
    for _ in range(60):
        theta = K / d * (c * tc - x - lam)
        th = np.tanh(theta)
        residual = x - half * (th + math.tanh(A))
        step = residual / (1.0 + H / d * (1.0 - th * th))
        x = x - step
        if np.all(np.abs(step) <= 4.0 * _FLOAT_EPS * (2.0 * half)):
            break
    theta = K / d * (c * tc - x - lam)
    sech2 = _sech(np.abs(theta)) ** 2
    velocity = c * (H / d) * sech2 / (1.0 + H / d * sech2)
    moving = (tt > 0.0) & (tt < t_end)
    return _out(np.where(tt > 0.0, x, 0.0)), _out(np.where(moving, velocity, 0.0))


def synolakis_runup(
    height: npt.ArrayLike, depth: npt.ArrayLike, slope: npt.ArrayLike
) -> FloatArray:
    """Synolakis (1987) solitary-wave run-up law ``R / d = 2.831 sqrt(cot beta) (H/d)^(5/4)`` [-].

    FORMULAS §6; non-breaking run-up only (on the 1:19.85 beach of the NTHMP benchmark,
    FORMULAS §5 says breaking occurs for H/d > 0.045). Returns R / d; R is the vertical run-up
    above the still-water level.

    Args:
        height: solitary wave height H [m]; depth: offshore depth d [m]; slope: tan(beta) [-].
    """
    H = _positive("height", height)
    d = _positive("depth", depth)
    return _out(2.831 * np.sqrt(1.0 / _positive("slope", slope)) * (H / d) ** 1.25)


# ------------------------------------------------------------------------------------------------
# Irregular waves


def pierson_moskowitz_spectrum(frequency: npt.ArrayLike, hs: float, tp: float) -> FloatArray:
    """Pierson-Moskowitz spectrum in its (Hs, Tp) form, ``S(f)`` [m^2/Hz].

    ``S(f) = (5/16) Hs^2 fp^4 f^-5 exp(-(5/4)(fp/f)^4)``, fp = 1/Tp (Pierson & Moskowitz 1964,
    in the Bretschneider/ITTC form, e.g. DNV-RP-C205 section 3.5.5). Its zeroth moment is exactly
    ``Hs^2 / 16``, so ``Hm0 = 4 sqrt(m0) = Hs``. S(0) = 0.

    Args:
        frequency: f [Hz], >= 0.
        hs: significant wave height Hm0 [m]; tp: peak period [s].
    """
    f = _nonnegative("frequency", frequency)
    Hs = float(_positive("hs", hs))
    fp = 1.0 / float(_positive("tp", tp))
    # In u = fp / f: S = (5/16) Hs^2 / fp * u^5 exp(-1.25 u^4); below f = fp/10 S < 1e-5000.
    u = fp / np.maximum(f, 0.1 * fp)
    s = 5.0 / 16.0 * Hs * Hs / fp * u**5 * np.exp(-1.25 * u**4)
    return _out(np.where(f > 0.1 * fp, s, 0.0))


def _jonswap_peak_factor(f_over_fp: FloatLike, gamma: float) -> FloatArray:
    """``gamma^r``, ``r = exp(-(f/fp - 1)^2 / (2 sigma^2))``, sigma 0.07 below fp, 0.09 above."""
    sigma = np.where(f_over_fp <= 1.0, 0.07, 0.09)
    return gamma ** np.exp(-((f_over_fp - 1.0) ** 2) / (2.0 * sigma * sigma))


@functools.lru_cache(maxsize=32)
def _jonswap_normalisation(gamma: float) -> float:
    """Factor making the JONSWAP zeroth moment ``Hs^2 / 16`` exactly.

    In u = f / fp with Hs = 1, the Pierson-Moskowitz part integrates in closed form,
    ``int_0^u (5/16) v^-5 exp(-1.25 v^-4) dv = exp(-1.25 u^-4) / 16``. Outside 0.5 <= u <= 3 the
    peak factor differs from 1 by less than 1e-10, so those tails use the closed form and
    [0.5, 1] and [1, 3] use 200-point Gauss-Legendre quadrature (the peak factor's second
    derivative jumps at u = 1).
    """
    nodes, weights = np.polynomial.legendre.leggauss(200)

    def integral(a: float, b: float) -> float:
        u = 0.5 * (b - a) * nodes + 0.5 * (a + b)
        pm = 5.0 / 16.0 * u**-5 * np.exp(-1.25 * u**-4)
        return 0.5 * (b - a) * float(np.sum(weights * pm * _jonswap_peak_factor(u, gamma)))

    def pm_cumulative(u: float) -> float:
        return math.exp(-1.25 * u**-4) / 16.0

    total = pm_cumulative(0.5) + integral(0.5, 1.0) + integral(1.0, 3.0) + 1.0 / 16.0
    return (1.0 / 16.0) / (total - pm_cumulative(3.0))


def jonswap_spectrum(
    frequency: npt.ArrayLike, hs: float, tp: float, gamma: float = 3.3
) -> FloatArray:
    """JONSWAP spectrum in its (Hs, Tp, gamma) form, ``S(f)`` [m^2/Hz].

    ``S(f) = C(gamma) S_PM(f) gamma^r``, ``r = exp(-(f - fp)^2 / (2 sigma^2 fp^2))``, sigma =
    0.07 for f <= fp and 0.09 above (Hasselmann et al. 1973; DNV-RP-C205 section 3.5.5). The
    normalising factor C(gamma) is computed by quadrature so that ``4 sqrt(m0) = Hs`` exactly
    (DNV's closed form ``1 - 0.287 ln gamma`` approximates it). gamma = 1 gives
    Pierson-Moskowitz.

    Args:
        frequency: f [Hz], >= 0; hs: Hm0 [m]; tp: peak period [s]; gamma: peak enhancement >= 1.
    """
    g_ = float(_finite("gamma", gamma))
    if g_ < 1.0:
        raise ValueError(f"gamma: must be >= 1, got {gamma!r}")
    f = _nonnegative("frequency", frequency)
    base = np.asarray(pierson_moskowitz_spectrum(f, hs, tp))
    return _out(_jonswap_normalisation(g_) * base * _jonswap_peak_factor(f * float(tp), g_))


@dataclass(frozen=True)
class IrregularPaddleMotion:
    """Components of an irregular paddle motion (what the core sums each step).

    The law, for t >= 0 (r(t) the ramp of :meth:`motion`)::

        X(t) = r(t) sum_i stroke_amplitudes[i] sin(2 pi frequencies[i] t + phases[i])
        U(t) = dX/dt

    and the target linear wave is ``eta(x, t) = sum_i wave_amplitudes[i] cos(2 pi f_i t -
    k_i x + phases[i])`` (the paddle at x = 0). The signal repeats with ``repeat_period``.

    Attributes:
        paddle: ``"piston"`` or ``"flap"`` (flap: displacement at the still-water level).
        depth: still-water depth at the paddle [m].
        repeat_period: 1 / frequency spacing [s]; every frequency is a multiple of its inverse.
        frequencies: component frequencies f_i [Hz].
        wavenumbers: linear wavenumbers k_i [rad/m].
        wave_amplitudes: target wave amplitudes a_i [m].
        stroke_amplitudes: paddle amplitudes a_i / (H/S)(k_i d), i.e. half strokes [m].
        phases: phases [rad].
    """

    paddle: Paddle
    depth: float
    repeat_period: float
    frequencies: FloatArray
    wavenumbers: FloatArray
    wave_amplitudes: FloatArray
    stroke_amplitudes: FloatArray
    phases: FloatArray

    def motion(
        self, t: npt.ArrayLike, ramp_time: float = 0.0, ramp: RampKind = "linear"
    ) -> tuple[FloatArray, FloatArray]:
        """Paddle displacement X [m] and velocity dX/dt [m/s] at times ``t`` [s].

        Args:
            t: times [s] (any shape).
            ramp_time: ramp duration [s] (0: none); ramp: ``"linear"`` or ``"tanh"`` as in
                :meth:`RegularPaddleMotion.motion`.
        """
        tt = _finite("t", t)
        rt = float(_nonnegative("ramp_time", ramp_time))
        _choice("ramp", ramp, ("linear", "tanh"))
        r, dr = _ramp(tt, rt, ramp)
        w = 2.0 * np.pi * self.frequencies
        arg = np.multiply.outer(tt, w) + self.phases
        base = np.sin(arg) @ self.stroke_amplitudes
        rate = np.cos(arg) @ (self.stroke_amplitudes * w)
        return _out(r * base), _out(dr * base + r * rate)

    def target_elevation(self, t: npt.ArrayLike, x: float = 0.0) -> FloatArray:
        """Target linear surface elevation [m] at ``x`` [m] from the paddle, times ``t`` [s]."""
        tt = _finite("t", t)
        xx = float(_finite("x", x))
        arg = np.multiply.outer(tt, 2.0 * np.pi * self.frequencies) - self.wavenumbers * xx
        return _out(np.cos(arg + self.phases) @ self.wave_amplitudes)


def irregular_paddle_motion(
    hs: float,
    tp: float,
    depth: float,
    spectrum: Literal["jonswap", "pierson-moskowitz"] = "jonswap",
    gamma: float = 3.3,
    seed: int = 0,
    random_amplitudes: bool = False,
    paddle: Paddle = "piston",
    frequency_range: tuple[float, float] = (0.5, 3.0),
    repeat_period: float | None = None,
    g: float = G,
) -> IrregularPaddleMotion:
    """Seeded, reproducible synthesis of an irregular wave through the paddle transfer function.

    Components sit at every multiple of ``1 / repeat_period`` in ``frequency_range`` (in units
    of the peak frequency 1/Tp). Amplitudes ``a_i = sqrt(2 S(f_i) df)`` (deterministic) or, with
    ``random_amplitudes``, ``a_i = sqrt(2 S(f_i) df E_i)`` with E_i standard exponential, so a_i
    is Rayleigh distributed with the same mean energy (random-amplitude scheme, e.g. Tucker et
    al. 1984). Phases are uniform in [0, 2 pi). Both come from ``numpy.random.default_rng(seed)``
    (phases first, then the exponentials), so a seed always gives the same phases. Each
    component's stroke amplitude is ``a_i / (H/S)(k_i d)`` with the first-order Biesel transfer
    function of the paddle (FORMULAS §2; Liu & Frigaard 2001 describe this linear synthesis).

    The energy outside ``frequency_range`` is left out: with the default (0.5, 3.0) fp that is
    about 1.5 % of m0 for Pierson-Moskowitz (Hm0 0.8 % low); widen the range to reduce it.

    Args:
        hs: significant wave height Hm0 [m]; tp: peak period [s]; depth: depth at the paddle [m].
        spectrum: ``"jonswap"`` (:func:`jonswap_spectrum`) or ``"pierson-moskowitz"``.
        gamma: JONSWAP peak enhancement factor (ignored for Pierson-Moskowitz).
        seed: seed of the random generator.
        random_amplitudes: draw Rayleigh amplitudes instead of deterministic ones.
        paddle: ``"piston"`` or ``"flap"``.
        frequency_range: (low, high) component frequencies in units of 1/Tp.
        repeat_period: repeat period of the synthesised signal [s], i.e. 1 / frequency spacing;
            default 256 Tp.
    """
    Hs = float(_positive("hs", hs))
    Tp = float(_positive("tp", tp))
    d = float(_positive("depth", depth))
    _choice("paddle", paddle, ("piston", "flap"))
    if repeat_period is None:
        period_rep = 256.0 * Tp
        if not math.isfinite(period_rep):
            raise ValueError(f"tp: {Tp!r} s overflows the default repeat period of 256 Tp")
    else:
        period_rep = float(_positive("repeat_period", repeat_period))
    f, density, df = _spectral_lines(Hs, Tp, spectrum, gamma, frequency_range, period_rep)
    rng = np.random.default_rng(seed)
    phases = rng.uniform(0.0, 2.0 * np.pi, f.size)
    energy = rng.standard_exponential(f.size) if random_amplitudes else np.ones(f.size)
    amplitudes = np.sqrt(2.0 * density * df * energy)
    return _through_the_paddle(paddle, d, period_rep, f, amplitudes, phases, g)


def _spectral_lines(
    hs: float, tp: float, spectrum: str, gamma: float, frequency_range: tuple[float, float],
    repeat_period: float,
) -> tuple[FloatArray, FloatArray, float]:
    """Frequencies f_i [Hz] at every multiple of ``1 / repeat_period`` in ``frequency_range``
    (units of 1/Tp), the spectral density there [m^2/Hz] and the spacing df [Hz]."""
    _choice("spectrum", spectrum, ("jonswap", "pierson-moskowitz"))
    lo, hi = (float(v) for v in _positive("frequency_range", frequency_range))
    if not lo < hi:
        raise ValueError(f"frequency_range: low must be < high, got {frequency_range!r}")
    df = 1.0 / repeat_period
    first = math.ceil(lo / tp / df - 1e-9)
    last = math.floor(hi / tp / df + 1e-9)
    if last < first:
        raise ValueError(
            f"repeat_period: {repeat_period!r} s leaves no component in frequency_range"
            f" {frequency_range!r}"
        )
    f = np.arange(first, last + 1, dtype=np.float64) * df
    if spectrum == "jonswap":
        density = np.asarray(jonswap_spectrum(f, hs, tp, gamma))
    else:
        density = np.asarray(pierson_moskowitz_spectrum(f, hs, tp))
    return f, density, df


def _through_the_paddle(
    paddle: Paddle, depth: float, repeat_period: float, f: FloatArray, amplitudes: FloatArray,
    phases: FloatArray, g: float,
) -> IrregularPaddleMotion:
    """The components (f, amplitude, phase) of a target wave as paddle strokes, each through
    the paddle's first-order Biesel transfer function."""
    k = np.asarray(wavenumber(1.0 / f, depth, g))
    transfer = piston_height_to_stroke if paddle == "piston" else flap_height_to_stroke
    strokes = amplitudes / np.asarray(transfer(k, depth))
    return IrregularPaddleMotion(
        paddle=paddle,
        depth=depth,
        repeat_period=repeat_period,
        frequencies=f,
        wavenumbers=k,
        wave_amplitudes=amplitudes,
        stroke_amplitudes=strokes,
        phases=phases,
    )


def focused_paddle_motion(
    amplitude: float,
    tp: float,
    depth: float,
    focus_x: float,
    focus_time: float,
    spectrum: Literal["jonswap", "pierson-moskowitz"] = "jonswap",
    gamma: float = 3.3,
    paddle: Paddle = "piston",
    frequency_range: tuple[float, float] = (0.5, 3.0),
    repeat_period: float | None = None,
    g: float = G,
) -> IrregularPaddleMotion:
    """A focused wave group: NewWave (Tromans, Anaturk & Hagemeijer 1991) by linear focusing.

    The components of :func:`irregular_paddle_motion`'s spectral lines with amplitudes in
    proportion to the spectrum, ``a_i = A S(f_i) / sum_j S(f_j)`` (the shape of the linear
    wave's autocorrelation, the expected shape of a large crest), and every crest at ``focus_x``
    at ``focus_time``: ``eta = sum a_i cos(k_i (x - x_f) - omega_i (t - t_f))``, so the phase of
    each component at the paddle is ``k_i x_f - omega_i t_f`` and the linear crest at the focus
    is ``sum a_i = A``. The group repeats after ``repeat_period`` (default ``max(64 Tp,
    4 t_f)``, so no neighbouring group reaches the flume while the focused one runs).

    Args:
        amplitude: linear crest amplitude A at the focus [m]; tp: peak period [s];
        depth: depth at the paddle [m]; focus_x: x_f [m] from the paddle at rest;
        focus_time: t_f [s]; spectrum, gamma, frequency_range: as
        :func:`irregular_paddle_motion`; paddle: ``"piston"`` or ``"flap"``.
    """
    A = float(_positive("amplitude", amplitude))
    Tp = float(_positive("tp", tp))
    d = float(_positive("depth", depth))
    x_f = float(_finite("focus_x", focus_x))
    t_f = float(_finite("focus_time", focus_time))
    _choice("paddle", paddle, ("piston", "flap"))
    if repeat_period is None:
        period_rep = max(64.0 * Tp, 4.0 * abs(t_f))
    else:
        period_rep = float(_positive("repeat_period", repeat_period))
    f, density, _ = _spectral_lines(1.0, Tp, spectrum, gamma, frequency_range, period_rep)
    amplitudes = A * density / np.sum(density)
    k = np.asarray(wavenumber(1.0 / f, d, g))
    phases = k * x_f - 2.0 * np.pi * f * t_f
    return _through_the_paddle(paddle, d, period_rep, f, amplitudes, phases, g)


@dataclass(frozen=True)
class SecondOrderPaddleMotion:
    """The second-order (sub- and superharmonic) components of a spectral piston motion.

    ``X2(t) = sum_i stroke_amplitudes[i] sin(2 pi frequencies[i] t + stroke_phases[i])``, and
    the bound second-order elevation at the paddle is ``sum_i elevation_amplitudes[i]
    sin(2 pi frequencies[i] t + elevation_phases[i])``.

    Attributes:
        frequencies: sum and difference frequencies [Hz] (multiples of 1 / repeat period).
        stroke_amplitudes, stroke_phases: [m], [rad].
        elevation_amplitudes, elevation_phases: [m], [rad].
        wavenumbers: the wavenumber [rad/m] the bound wave at each frequency travels with,
            ``k_n +- k_m`` of its pairs weighted by their elevation amplitudes.
    """

    frequencies: FloatArray
    stroke_amplitudes: FloatArray
    stroke_phases: FloatArray
    elevation_amplitudes: FloatArray
    elevation_phases: FloatArray
    wavenumbers: FloatArray


def second_order_piston_motion(
    motion: IrregularPaddleMotion, g: float = G, drop: float = 1e-6
) -> SecondOrderPaddleMotion:
    """Second-order piston motion of a spectral wave: for every pair of components the sub- and
    superharmonic stroke that makes no free wave at their difference and sum frequency.

    Each pair (n, m) of first-order components (``eta = Re(A e^(i (k x - omega t)))`` at the
    paddle, piston strokes by Biesel) forces the free surface at ``omega_n +- omega_m`` (the
    second-order combined surface condition, as in :func:`second_order_stroke`); its bound
    wave has the wavenumber ``k_n +- k_m``. The paddle's second-order motion supplies the
    bound wave's depth-integrated flux less the first-order paddle's ``X1 d(eta1)/dt`` (Madsen's
    1971 argument for each pair): without the evanescent near field, the limit Schaffer (1996)
    shows his full theory tends to. Checks (tests/test_wave_laws.py): a single component gives
    Madsen's second harmonic and Stokes' bound harmonic exactly; two close components give the
    set-down under their group of Longuet-Higgins & Stewart (1962). Pairs falling on the same
    frequency are added; components below ``drop`` times the largest first-order stroke (both
    stroke and elevation) are dropped.

    Args:
        motion: a piston's :class:`IrregularPaddleMotion` (irregular or focused).
        g: gravitational acceleration [m/s^2].
        drop: relative amplitude below which a component is left out.
    """
    if motion.paddle != "piston":
        raise ValueError("paddle: second-order spectral generation is for a piston")
    h = motion.depth
    omega = 2.0 * np.pi * motion.frequencies
    k = motion.wavenumbers
    elevation = motion.wave_amplitudes * np.exp(-1j * motion.phases)  # A_n
    stroke = 1j * motion.stroke_amplitudes * np.exp(-1j * motion.phases)  # X1 = Re(xi e^-iwt)
    potential = -1j * g * elevation / omega
    u = 1j * k * potential  # at z = 0: phi_x, phi_z, phi_t, d/dz (phi_tt + g phi_z)
    w = potential * omega**2 / g
    phi_t = -1j * omega * potential
    curvature = potential * k * (g * k - omega**2 * np.tanh(k * h))
    rate = -1j * omega * elevation  # d(eta1)/dt at the paddle
    size = round(2.0 * float(np.max(motion.frequencies)) * motion.repeat_period) + 1
    strokes = np.zeros(size, dtype=np.complex128)
    bounds = np.zeros(size, dtype=np.complex128)
    travel = np.zeros(size)
    weight = np.zeros(size)
    n, m = np.triu_indices(omega.size)
    higher = omega[n] > omega[m]
    for sign in (1.0, -1.0):
        if sign > 0:
            i, j = n, m
        else:  # the difference omega_i - omega_j > 0
            distinct = omega[n] != omega[m]
            i = np.where(higher, n, m)[distinct]
            j = np.where(higher, m, n)[distinct]
        conj = (lambda z: z) if sign > 0 else np.conj
        self_pair = np.where(i == j, 0.5, 1.0)
        w2 = omega[i] + sign * omega[j]
        k2 = k[i] + sign * k[j]
        gradient = u[i] * conj(u[j]) + w[i] * conj(w[j])
        forcing = self_pair * (1j * w2 * gradient + (phi_t[i] * conj(curvature[j])
                                                      + conj(phi_t[j]) * curvature[i]) / (2 * g))
        bound = forcing / (g * k2 * np.tanh(k2 * h) - w2 * w2)
        paddle = 0.5 * self_pair * (stroke[i] * conj(rate[j]) + conj(stroke[j]) * rate[i])
        xi2 = (1j * bound * np.tanh(k2 * h) - paddle) / (-1j * w2 * h)
        eta2 = -(1j * w2 * -bound + 0.5 * self_pair * gradient + 0.5 * self_pair
                 * (elevation[i] * conj(-1j * omega[j] * w[j])
                    + conj(elevation[j]) * (-1j * omega[i] * w[i]))) / g
        index = np.rint(w2 / (2.0 * np.pi) * motion.repeat_period).astype(np.int64)
        np.add.at(strokes, index, xi2)
        np.add.at(bounds, index, eta2)
        np.add.at(travel, index, np.abs(eta2) * k2)
        np.add.at(weight, index, np.abs(eta2))
    floor = drop * float(np.max(motion.stroke_amplitudes))
    keep = np.nonzero((np.abs(strokes) > floor) | (np.abs(bounds) > floor))[0]
    keep = keep[keep > 0]
    # Re(z e^(-i omega t)) = |z| sin(omega t + pi/2 - arg z)
    return SecondOrderPaddleMotion(
        frequencies=keep / motion.repeat_period,
        stroke_amplitudes=np.abs(strokes[keep]),
        stroke_phases=0.5 * np.pi - np.angle(strokes[keep]),
        elevation_amplitudes=np.abs(bounds[keep]),
        elevation_phases=0.5 * np.pi - np.angle(bounds[keep]),
        wavenumbers=travel[keep] / np.maximum(weight[keep], np.finfo(float).tiny),
    )


# ------------------------------------------------------------------------------------------------
# Validity of a requested regular wave


RegularTheory = Literal["linear", "stokes2", "stream_function", "cnoidal"]

REGULAR_THEORIES: tuple[str, ...] = ("auto", "linear", "stokes2", "stream_function", "cnoidal")
"""The regular-wave generation theories: ``"linear"`` (Biesel), ``"stokes2"`` (Madsen's 1971
second order), ``"stream_function"`` (:func:`stream_function_piston_motion`), ``"cnoidal"``
(:func:`cnoidal_piston_motion`) and ``"auto"`` (:func:`choose_regular_theory`)."""

FLUX_THEORIES: tuple[str, ...] = ("stream_function", "cnoidal")
"""The theories whose piston follows the wave's depth-averaged velocity (Goring's flux law)."""


def regular_flux_motion(
    theory: Literal["stream_function", "cnoidal"], height: float, period: float, depth: float,
    phase: float = 0.0, g: float = G,
) -> StreamFunctionPaddleMotion:
    """The piston motion of a flux-law ``theory`` for the regular wave (H, T, d)."""
    _choice("theory", theory, FLUX_THEORIES)
    if theory == "cnoidal":
        return cnoidal_piston_motion(cnoidal_wave(height, period, depth, g), phase)
    return stream_function_piston_motion(stream_function_wave(height, period, depth, g=g), phase)


def choose_regular_theory(
    height: float, period: float, depth: float, order: int = 1, paddle: Paddle = "piston",
    g: float = G,
) -> RegularTheory:
    """The generation theory ``"auto"`` picks for a regular wave.

    Within Madsen's range (Ursell number ``H L^2 / d^3`` up to 8 pi^2 / 3 ~ 26.3, FORMULAS §3)
    the paddle's ``order`` decides, first (``"linear"``) or second order (``"stokes2"``), as
    always; beyond it, in the cnoidal range where a second-order law makes spurious free
    harmonics, a piston takes the stream-function law, and beyond :data:`CNOIDAL_URSELL_LIMIT`
    (500), where the Fourier series needs many modes and the wave is nearly solitary, the
    cnoidal law (a flap keeps its order and :func:`check_wave` warns).
    """
    ursell = float(ursell_number(height, period, depth, g))
    if paddle == "piston" and ursell > MADSEN_URSELL_LIMIT:
        return "cnoidal" if ursell > CNOIDAL_URSELL_LIMIT else "stream_function"
    return "stokes2" if order == 2 else "linear"


def _cnoidal_range_problems(ursell: float, kd: float) -> list[str]:
    """Why first-order cnoidal theory does not describe a wave of this Ursell number and kd."""
    problems = []
    if ursell < MADSEN_URSELL_LIMIT:
        problems.append(
            f"Ursell number H L^2/d^3 = {ursell:.1f} is below 8 pi^2/3 ="
            f" {MADSEN_URSELL_LIMIT:.1f}: cnoidal theory is for longer waves (range U >"
            f" {MADSEN_URSELL_LIMIT:.1f}); theory 'stokes2' or 'stream_function' fits"
        )
    if kd > CNOIDAL_KD_LIMIT:
        problems.append(
            f"kd = {kd:.2f} > pi/4 = {CNOIDAL_KD_LIMIT:.2f} (d/L > 1/8): beyond first-order"
            f" cnoidal theory (Ursell number {ursell:.1f}); theory 'stream_function' fits"
        )
    return problems


def check_wave(
    height: float,
    period: float,
    depth: float,
    order: int = 1,
    paddle: Paddle = "piston",
    g: float = G,
    theory: RegularTheory | None = None,
) -> list[str]:
    """Reasons why a requested regular wave is outside the validity of its generation, if any.

    ``theory`` is the generation theory (``None``: ``"linear"`` for ``order`` 1, ``"stokes2"``
    for 2). Checks, in this order:

    1. (linear and second order) Ursell number ``H L^2 / d^3`` above 8 pi^2 / 3 ~ 26.3, the
       limit used with Madsen's second-order generation (FORMULAS §3): beyond second-order
       Stokes theory (cnoidal range).
    2. (linear and second order) Stokes second-order profile with a secondary crest in the
       trough: the bound second harmonic exceeds a quarter of the first harmonic amplitude
       (``a2 > H/8``), where the expansion of FORMULAS §4 no longer describes the wave.
    3. (stream function) kd above 1.5: the stream-function law's third and higher harmonics
       come from the depth-averaged (long-wave) flux, which misrepresents them in deeper water
       (its first two harmonics are Biesel's and Madsen's at any depth). (cnoidal) Ursell
       number below 26.3 (Stokes range: the first-order cnoidal wave carries the long-wave
       dispersion) or kd above pi/4 (d/L > 1/8, Wiegel 1960).
    4. Breaking at the paddle: ``H/d > 0.78`` (McCowan) or ``H > 0.142 L tanh(kd)`` (Miche).
    5. Paddle against depth (water-depth classes of Dean & Dalrymple 1991, ch. 3): a piston
       in deep water (kd > pi) moves the whole column although the wave motion decays with
       depth (a flap matches it); a flap in shallow water (kd < pi/10) needs about twice the
       stroke of a piston (H/S -> kd/2 against kd).

    Returns:
        One message per problem found; an empty list when the wave is fine.
    """
    H = float(_positive("height", height))
    T = float(_positive("period", period))
    d = float(_positive("depth", depth))
    if theory is None:
        theory = "stokes2" if order == 2 else "linear"
    _choice("theory", theory, REGULAR_THEORIES[1:])
    law = regular_paddle_motion(H, T, d, paddle, 1, 0.0, g)
    k = law.wavenumber
    kd = k * d
    L = 2.0 * math.pi / k
    problems: list[str] = []
    ursell = float(ursell_number(H, T, d, g))
    if theory == "cnoidal":
        problems += _cnoidal_range_problems(ursell, kd)
    elif theory != "stream_function":
        if ursell > MADSEN_URSELL_LIMIT:
            problems.append(
                f"Ursell number H L^2/d^3 = {ursell:.1f} exceeds 8 pi^2/3 ="
                f" {MADSEN_URSELL_LIMIT:.1f}: the wave (H = {H} m, T = {T} s, d = {d} m) is"
                " beyond second-order Stokes theory (cnoidal range); the generated wave will"
                " carry spurious free harmonics (a piston with the stream-function law makes it)"
            )
        a2 = float(stokes2_second_harmonic_amplitude(H, k, d))
        if a2 > 0.125 * H:
            problems.append(
                f"Stokes second harmonic a2 = {a2:.4g} m exceeds a quarter of the first"
                f" harmonic (H/8 = {0.125 * H:.4g} m): the second-order profile has a secondary"
                " crest, the expansion is not valid"
            )
    elif kd > STREAM_FUNCTION_KD_LIMIT:
        problems.append(
            f"kd = {kd:.2f} > {STREAM_FUNCTION_KD_LIMIT}: the stream-function paddle law's"
            " harmonics above the second come from the depth-averaged (long-wave) flux, which"
            " is not valid in this depth; use theory 'stokes2' unless the Ursell number"
            f" ({ursell:.1f}) is high"
        )
    if H / d > MCCOWAN_BREAKING_RATIO:
        problems.append(
            f"H/d = {H / d:.3f} > {MCCOWAN_BREAKING_RATIO} (McCowan): the wave breaks at the paddle"
        )
    h_miche = MICHE_COEFFICIENT * L * math.tanh(kd)
    if H > h_miche:
        problems.append(
            f"H = {H} m > 0.142 L tanh(kd) = {h_miche:.4g} m (Miche): the wave is too steep and"
            " breaks at the paddle"
        )
    if paddle == "piston" and kd > math.pi:
        problems.append(
            f"kd = {kd:.2f} > pi (deep water, d/L > 1/2): a piston moves the whole depth although"
            " the wave motion decays with depth; a flap suits deep water better"
        )
    if paddle == "flap" and kd < math.pi / 10.0:
        problems.append(
            f"kd = {kd:.3f} < pi/10 (shallow water, d/L < 1/20): a flap needs about twice the"
            f" stroke of a piston (S = {law.stroke:.4g} m); use a piston"
        )
    return problems


def warn_if_invalid_wave(
    height: float,
    period: float,
    depth: float,
    order: int = 1,
    paddle: Paddle = "piston",
    g: float = G,
    theory: RegularTheory | None = None,
) -> list[str]:
    """Emit each message of :func:`check_wave` as a :class:`WaveValidityWarning`; return them."""
    problems = check_wave(height, period, depth, order, paddle, g, theory)
    for message in problems:
        warnings.warn(message, WaveValidityWarning, stacklevel=2)
    return problems
