"""Error metrics of the validation cases: pure functions of arrays, no simulation.

Every function takes plain NumPy inputs (positions, pressures, time series, gauge results) and
returns numbers, so each one is unit-tested on synthetic inputs whose error is known
(``tests/test_validation.py``). Units are SI; "relative" errors are fractions (0.05 = 5 %).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .. import wave_theory as wt
from ..measure import (
    MartinMoyce,
    MartinMoyceHeight,
    checked_series,
    front_error,
    load_martin_moyce_height,
)

__all__ = [
    "ColumnHeightError",
    "DampedOscillation",
    "ShiftedFrontError",
    "column_height_error",
    "damped_oscillation_fit",
    "front_error_best_shift",
    "harmonic_amplitude_errors",
    "harmonic_spread",
    "harmonic_spread_local_bound",
    "height_loss_per_wavelength",
    "hydrostatic_pressure_error",
    "mean_level_drift",
    "relative_phase_error",
    "relative_error",
    "spurious_velocity",
    "standing_wave_mode_amplitude",
    "standing_wave_period",
    "stokes3_wavelength",
    "surface_profile",
    "wavelength_from_phases",
]

FloatArray = npt.NDArray[np.float64]


def relative_error(value: float, reference: float) -> float:
    """``|value / reference - 1|`` [-]; NaN when either is missing or the reference is 0."""
    if value is None or reference is None or not reference or not math.isfinite(value):
        return math.nan
    return abs(float(value) / float(reference) - 1.0)


# ------------------------------------------------------------------------------------------------
# still water


def hydrostatic_pressure_error(
    z: npt.ArrayLike, pressure: npt.ArrayLike, depth: float, rho0: float, g: float
) -> tuple[float, float]:
    """Pressure on a vertical line against the hydrostatic ``p = rho0 g (depth - z)``.

    Args:
        z: (M,) heights above the floor of the sample points [m].
        pressure: (M,) interpolated pressure at those points [Pa].
        depth: still-water depth d [m]; rho0: density [kg/m^3]; g: gravity [m/s^2].

    Returns:
        (RMS, max) of ``|p - rho0 g (d - z)|`` over the points, divided by the bottom pressure
        ``rho0 g d`` [-].
    """
    zz = np.asarray(z, dtype=np.float64).ravel()
    pp = np.asarray(pressure, dtype=np.float64).ravel()
    if zz.shape != pp.shape or zz.size == 0:
        raise ValueError("z, pressure: need two non-empty arrays of the same length")
    scale = rho0 * g * depth
    if not scale > 0.0:
        raise ValueError(f"rho0 g depth: must be positive, got {scale!r}")
    err = np.abs(pp - rho0 * g * (depth - zz)) / scale
    return float(np.sqrt(np.mean(err**2))), float(np.max(err))


def spurious_velocity(velocities: npt.ArrayLike, depth: float, g: float) -> float:
    """Largest fluid speed of a tank that should be at rest, over ``sqrt(g d)`` [-].

    Args:
        velocities: (N, dim) fluid velocities [m/s].
        depth: still-water depth d [m]; g: gravity [m/s^2].
    """
    v = np.asarray(velocities, dtype=np.float64)
    if v.ndim != 2 or v.shape[0] == 0:
        raise ValueError(f"velocities: expected a non-empty (N, dim) array, got shape {v.shape}")
    return float(np.max(np.linalg.norm(v, axis=1)) / math.sqrt(g * depth))


# ------------------------------------------------------------------------------------------------
# dam break


@dataclass(frozen=True)
class ShiftedFrontError:
    """Front error after the best constant time shift.

    Attributes:
        rms_rel_error: RMS relative front error with the shift applied [-].
        shift_s: the shift added to the simulated times [s] (positive: the simulation was ahead
            and is delayed).
        n_points: reference points compared at that shift.
    """

    rms_rel_error: float
    shift_s: float
    n_points: int


def front_error_best_shift(
    t: npt.ArrayLike,
    x_front: npt.ArrayLike,
    width: float,
    g: float = 9.81,
    reference: str | MartinMoyce = "lethe",
    x_max: float | None = None,
    max_shift: float | None = None,
) -> ShiftedFrontError:
    """RMS front error against Martin & Moyce after removing the best constant time shift.

    The raw comparison (:func:`watersim.measure.front_error`) mixes two things: the gate of the
    experiment opened in a finite time (so the measured front lags any instant release), and the
    shape of the simulated front curve. A constant shift s of the simulated times removes the
    first; what is left measures the second and is the quantity expected to converge with dp.
    The shift is searched on a grid of 0.1 % of ``max_shift`` and refined by a parabola through
    the three best grid points.

    Args:
        t, x_front, width, g, reference, x_max: as :func:`~watersim.measure.front_error`.
        max_shift: search range ``[-max_shift, +max_shift]`` [s]; default
            ``0.5 sqrt(width / g)``.
    """
    ts = np.asarray(t, dtype=np.float64).ravel()
    xs = np.asarray(x_front, dtype=np.float64).ravel()
    span = 0.5 * math.sqrt(width / g) if max_shift is None else float(max_shift)
    if not span > 0.0:
        raise ValueError(f"max_shift: must be positive, got {max_shift!r}")

    def rms(shift: float) -> tuple[float, int]:
        try:
            err = front_error(ts + shift, xs, width, g, reference, x_max)
        except ValueError:
            return math.inf, 0
        # a shift that leaves fewer than 3 points is not a fair comparison
        return (err.rms_rel_error if err.n_points >= 3 else math.inf), err.n_points

    grid = np.linspace(-span, span, 2001)
    values = np.array([rms(s)[0] for s in grid])
    if not np.any(np.isfinite(values)):
        raise ValueError("t: no time shift leaves three reference points in the simulated range")
    i = int(np.argmin(values))
    best = float(grid[i])
    if 0 < i < grid.size - 1 and np.all(np.isfinite(values[i - 1 : i + 2])):
        y0, y1, y2 = values[i - 1 : i + 2]
        denom = y0 - 2.0 * y1 + y2
        if denom > 0.0:
            step = grid[1] - grid[0]
            candidate = best + 0.5 * step * (y0 - y2) / denom
            if rms(candidate)[0] < y1:
                best = candidate
    value, n = rms(best)
    return ShiftedFrontError(rms_rel_error=float(value), shift_s=best, n_points=n)


@dataclass(frozen=True)
class ColumnHeightError:
    """Simulated residual column height against Martin & Moyce (1952).

    Attributes:
        rms_rel_error: RMS over the compared points of ``(h_sim(t_i) - h_i) / h_i`` [-].
        max_rel_error: largest ``|h_sim(t_i) - h_i| / h_i`` [-].
        mean_rel_error: mean signed relative error [-] (negative: the simulated column is lower,
            it drains ahead of the experiment).
        n_points: reference points compared.
        t_max_s: last reference time compared [s].
    """

    rms_rel_error: float
    max_rel_error: float
    mean_rel_error: float
    n_points: int
    t_max_s: float


def column_height_error(
    t: npt.ArrayLike,
    height: npt.ArrayLike,
    width: float,
    g: float = 9.81,
    reference: MartinMoyceHeight | None = None,
    shift: float = 0.0,
) -> ColumnHeightError:
    """Residual column height at the back wall against Martin & Moyce (1952), unshifted.

    The residual height falls slowly at first (the top of the column starts at rest), so it is
    less sensitive than the front to how the column was released; it is the second quantity the
    paper tabulates. The reference points compared are those at or before the last simulated
    time (and at or after the first); at each reference time t_i the simulated height is linearly
    interpolated.

    Args:
        t: (K,) sample times [s], strictly increasing.
        height: (K,) residual height at the back wall [m]
            (:func:`watersim.measure.water_column_height`).
        width: column width a [m]; the reference's height is ``n^2 a``.
        g: gravitational acceleration [m/s^2].
        reference: the data (:func:`watersim.measure.load_martin_moyce_height` by default).
        shift: added to the simulated times [s] before comparing (0: the data as they are; the
            dam-break case passes the front's best shift as a diagnostic).

    Raises:
        ValueError: inputs of different lengths, non-increasing times, a non-positive width, or
            no reference point in the simulated time range.
    """
    ts, hs = checked_series(t, height, "height", width, shift)
    ref = load_martin_moyce_height() if reference is None else reference
    t_ref, h_ref = ref.dimensional(width, g)
    inside = (t_ref >= ts[0]) & (t_ref <= ts[-1] * (1.0 + 1e-12))
    if not np.any(inside):
        raise ValueError(f"t: the simulated range {ts[0]:g}-{ts[-1]:g} s holds no tabulated "
                         f"height (first at {t_ref.min():g} s)")
    t_i, h_i = t_ref[inside], h_ref[inside]
    rel = (np.interp(t_i, ts, hs) - h_i) / h_i
    return ColumnHeightError(rms_rel_error=float(np.sqrt(np.mean(rel**2))),
                             max_rel_error=float(np.max(np.abs(rel))),
                             mean_rel_error=float(np.mean(rel)), n_points=int(t_i.size),
                             t_max_s=float(t_i[-1]))


# ------------------------------------------------------------------------------------------------
# standing wave


def standing_wave_period(length: float, depth: float, g: float = 9.81, mode: int = 1) -> float:
    """Linear period of mode ``n`` of a closed tank, ``omega^2 = g k tanh(k d)``, ``k = n pi / l``.

    Args:
        length: tank length l [m]; depth: still-water depth d [m]; mode: n >= 1.

    Returns:
        The period 2 pi / omega [s].
    """
    if mode < 1:
        raise ValueError(f"mode: must be at least 1, got {mode!r}")
    k = mode * math.pi / length
    return 2.0 * math.pi / math.sqrt(g * k * math.tanh(k * depth))


def surface_profile(
    positions_fluid: npt.ArrayLike, dp: float, x_min: float, x_max: float
) -> tuple[FloatArray, FloatArray]:
    """Free surface of a 2D fluid: the highest particle of each column of width dp, plus dp/2.

    Args:
        positions_fluid: (N, 2) fluid positions [m].
        dp: particle spacing, the column width [m].
        x_min, x_max: the range of x cut into columns [m].

    Returns:
        (x centres, surface heights) [m]; empty columns are left out.
    """
    pos = np.asarray(positions_fluid, dtype=np.float64)
    if pos.ndim != 2 or pos.shape[1] != 2:
        raise ValueError(f"positions_fluid: expected shape (N, 2), got {pos.shape}")
    n = max(int(round((x_max - x_min) / dp)), 1)
    edges = np.linspace(x_min, x_max, n + 1)
    idx = np.clip(np.searchsorted(edges, pos[:, 0], side="right") - 1, 0, n - 1)
    top = np.full(n, -np.inf)
    np.maximum.at(top, idx, pos[:, 1])
    keep = np.isfinite(top)
    centres = 0.5 * (edges[1:] + edges[:-1])
    return centres[keep], top[keep] + 0.5 * dp


def standing_wave_mode_amplitude(
    x: npt.ArrayLike, eta: npt.ArrayLike, length: float, mode: int = 1
) -> float:
    """Amplitude of mode ``n`` (``cos(n pi x / l)``) of a surface ``eta(x)`` on ``[0, l]``.

    The least-squares projection ``sum(eta' w) / sum(w^2)`` with ``w = cos(k x)`` and eta' the
    surface minus its mean: for columns covering the tank evenly (as :func:`surface_profile`
    gives them) it is the midpoint sum of ``(2/l) int eta cos(k x) dx``, and a missing column
    does not leak the mean level into the mode.
    """
    xx = np.asarray(x, dtype=np.float64).ravel()
    ee = np.asarray(eta, dtype=np.float64).ravel()
    if xx.shape != ee.shape or xx.size < 2:
        raise ValueError("x, eta: need two arrays of the same length, at least 2 points")
    k = mode * math.pi / length
    weights = np.cos(k * xx)
    return float(np.sum((ee - ee.mean()) * weights) / np.sum(weights**2))


@dataclass(frozen=True)
class DampedOscillation:
    """``y(t) = amplitude exp(-decay t) cos(omega t + phase) + offset``.

    Attributes:
        omega: angular frequency [rad/s]; period: 2 pi / omega [s].
        decay: amplitude decay rate [1/s]; log_decrement: ``decay * period`` [-].
        amplitude, phase, offset: the other fitted parameters.
    """

    omega: float
    decay: float
    amplitude: float
    phase: float
    offset: float

    @property
    def period(self) -> float:
        return 2.0 * math.pi / self.omega

    @property
    def log_decrement(self) -> float:
        return self.decay * self.period


def damped_oscillation_fit(
    t: npt.ArrayLike, y: npt.ArrayLike, omega_guess: float
) -> DampedOscillation:
    """Least-squares fit of a damped cosine to a time series (scipy ``curve_fit``).

    Args:
        t: (K,) times [s]; y: (K,) values.
        omega_guess: starting angular frequency [rad/s] (e.g. linear theory).

    Raises:
        ValueError: fewer than 8 samples or a fit that does not converge.
    """
    from scipy.optimize import curve_fit  # type: ignore[import-untyped]

    tt = np.asarray(t, dtype=np.float64).ravel()
    yy = np.asarray(y, dtype=np.float64).ravel()
    if tt.shape != yy.shape or tt.size < 8:
        raise ValueError("t, y: need two arrays of the same length, at least 8 samples")

    def model(tv: FloatArray, a: float, w: float, gam: float, ph: float, c: float) -> FloatArray:
        return a * np.exp(-gam * (tv - tt[0])) * np.cos(w * (tv - tt[0]) + ph) + c

    a0 = 0.5 * float(np.max(yy) - np.min(yy))
    c0 = float(np.mean(yy))
    ph0 = 0.0 if yy[0] >= c0 else math.pi
    try:
        popt, _ = curve_fit(model, tt, yy, p0=[a0, omega_guess, 0.0, ph0, c0], maxfev=20000)
    except RuntimeError as exc:
        raise ValueError(f"y: the damped-oscillation fit did not converge ({exc})") from None
    a, w, gam, ph, c = (float(v) for v in popt)
    if a < 0.0:
        a, ph = -a, ph + math.pi
    w = abs(w)
    # express the phase at t = 0 rather than at t[0]
    ph = (ph - w * tt[0] + math.pi) % (2.0 * math.pi) - math.pi
    return DampedOscillation(omega=w, decay=gam, amplitude=a, phase=ph, offset=c)


# ------------------------------------------------------------------------------------------------
# progressive waves


def stokes3_wavelength(period: float, depth: float, height: float, g: float = 9.81) -> float:
    """Wavelength [m] from the third-order Stokes dispersion relation.

    ``omega^2 = g k tanh(kd) [1 + (9 - 10 s^2 + 9 s^4) / (8 s^4) (k a)^2]``, ``s = tanh(kd)``,
    a = H/2 (the first-order amplitude), solved for k at the given period by fixed-point
    iteration from the linear k. Fenton (1985) "A fifth-order Stokes theory for steady waves",
    J. Waterway Port Coastal Ocean Eng. 111(2), 216-234 (its third-order term; also Whitham
    1974, section 13.13). Stokes' second order does not change the dispersion relation, so its
    wavelength is the linear one.
    """
    omega = 2.0 * math.pi / period
    k = float(wt.wavenumber(period, depth, g))
    a = 0.5 * height
    for _ in range(100):
        s = math.tanh(k * depth)
        factor = 1.0 + (9.0 - 10.0 * s**2 + 9.0 * s**4) / (8.0 * s**4) * (k * a) ** 2
        k_new = float(wt.wavenumber_from_omega(omega / math.sqrt(factor), depth, g))
        if abs(k_new - k) < 1e-13 * k:
            k = k_new
            break
        k = k_new
    return 2.0 * math.pi / k


def wavelength_from_phases(
    x: npt.ArrayLike, phase: npt.ArrayLike, k_guess: float
) -> float:
    """Wavelength [m] of a progressive wave from first-harmonic phases at gauges along x.

    With ``eta = a cos(omega t + phi)`` (the convention of
    :func:`watersim.analysis.harmonic_analysis`), a wave travelling towards +x has
    ``phi(x) = phi0 - k x``. The phases are unwrapped in order of x, each step taking the
    multiple of 2 pi closest to ``-k_guess dx`` (so a gap of one wavelength is resolved if the
    true k is within 50 % of the guess), and k is minus the least-squares slope.

    Args:
        x: (G,) gauge positions [m], at least 2 distinct.
        phase: (G,) first-harmonic phases [rad].
        k_guess: expected wavenumber [1/m] (linear theory).
    """
    xx = np.asarray(x, dtype=np.float64).ravel()
    pp = np.asarray(phase, dtype=np.float64).ravel()
    if xx.shape != pp.shape or np.unique(xx).size < 2:
        raise ValueError("x, phase: need arrays of the same length with at least 2 distinct x")
    order = np.argsort(xx, kind="stable")
    xx, pp = xx[order], pp[order]
    unwrapped = [pp[0]]
    for j in range(1, xx.size):
        expected = unwrapped[-1] - k_guess * (xx[j] - xx[j - 1])
        n = round((expected - pp[j]) / (2.0 * math.pi))
        unwrapped.append(pp[j] + 2.0 * math.pi * n)
    slope = np.polyfit(xx, np.asarray(unwrapped), 1)[0]
    if not slope < 0.0:
        raise ValueError("phase: the phases do not decrease along x (no wave travelling to +x)")
    return float(2.0 * math.pi / -slope)


def height_loss_per_wavelength(
    x: npt.ArrayLike, height: npt.ArrayLike, wavelength: float
) -> float:
    """Fraction of the wave height lost per wavelength travelled, from heights along the flume.

    Fits ``H(x) = H0 exp(-mu x)`` by least squares on ``log H`` and returns
    ``1 - exp(-mu L)`` (negative if the height grows).
    """
    xx = np.asarray(x, dtype=np.float64).ravel()
    hh = np.asarray(height, dtype=np.float64).ravel()
    if xx.shape != hh.shape or xx.size < 2 or np.any(hh <= 0.0):
        raise ValueError("x, height: need 2+ positive heights at distinct x")
    mu = -np.polyfit(xx, np.log(hh), 1)[0]
    return float(1.0 - math.exp(-mu * wavelength))


def harmonic_spread(amplitudes: Sequence[float], reference: float) -> float:
    """``(max - min) / reference`` of a harmonic's amplitude at gauges along the flume [-].

    A second harmonic generated correctly is bound to the first and has the same amplitude
    everywhere over a flat floor; a spurious free second harmonic travels at its own speed and
    beats with the bound one, so the amplitude varies along the flume. ``reference`` is the
    Stokes bound amplitude (:func:`watersim.wave_theory.stokes2_second_harmonic_amplitude`).
    """
    a = np.asarray([v for v in amplitudes if v is not None and math.isfinite(v)], dtype=float)
    if a.size < 2:
        raise ValueError("amplitudes: need at least 2 finite values")
    if not reference > 0.0:
        raise ValueError(f"reference: must be positive, got {reference!r}")
    return float((a.max() - a.min()) / reference)


def harmonic_amplitude_errors(
    simulated: npt.ArrayLike, measured: npt.ArrayLike, scale: float
) -> FloatArray:
    """RMS over gauges of ``a_sim - a_meas`` per harmonic, divided by ``scale`` [-].

    Args:
        simulated, measured: (G, N) amplitudes [m] of N harmonics at G gauges.
        scale: the normalising amplitude [m] (e.g. the incident first-harmonic amplitude H/2).

    Returns:
        (N,) relative RMS errors.
    """
    s = np.asarray(simulated, dtype=np.float64)
    m = np.asarray(measured, dtype=np.float64)
    if s.shape != m.shape or s.ndim != 2 or s.shape[0] == 0:
        raise ValueError(f"simulated, measured: need two (G, N) arrays, got {s.shape}, {m.shape}")
    return np.sqrt(np.mean((s - m) ** 2, axis=0)) / scale


def relative_phase_error(simulated: npt.ArrayLike, measured: npt.ArrayLike) -> float:
    """RMS [rad] of the phase differences between gauges, simulated against measured.

    The experiment's clock and the simulation's differ by an unknown offset, so the phases are
    compared relative to their mean: ``d_j = wrap(phi_sim_j - phi_meas_j)`` and the error is the
    RMS of ``wrap(d_j - circular mean of d)``.
    """
    s = np.asarray(simulated, dtype=np.float64).ravel()
    m = np.asarray(measured, dtype=np.float64).ravel()
    if s.shape != m.shape or s.size < 2:
        raise ValueError("simulated, measured: need two arrays of the same length, 2+ values")
    d = np.angle(np.exp(1j * (s - m)))
    mean = np.angle(np.mean(np.exp(1j * d)))
    return float(np.sqrt(np.mean(np.angle(np.exp(1j * (d - mean))) ** 2)))


def harmonic_spread_local_bound(
    a1: Sequence[float], a2: Sequence[float], k: float, depth: float
) -> float:
    """``(max - min) / mean`` of ``a2 / a2_bound(a1)`` along the flume [-].

    Like :func:`harmonic_spread`, but each gauge's second-harmonic amplitude ``a2`` [m] is
    divided by the Stokes bound amplitude of its *own* first harmonic ``a1`` [m]
    (:func:`watersim.wave_theory.stokes2_second_harmonic_amplitude` with H = 2 a1), so a wave
    that loses height along the flume (its bound harmonic falls as H^2) shows no spread; only
    a free second harmonic, beating with the bound one, does.
    """
    x1 = np.asarray(a1, dtype=float).ravel()
    x2 = np.asarray(a2, dtype=float).ravel()
    if x1.shape != x2.shape:
        raise ValueError("a1, a2: need the same number of gauges")
    ok = np.isfinite(x1) & np.isfinite(x2) & (x1 > 0.0)
    if np.count_nonzero(ok) < 2:
        raise ValueError("a1, a2: need at least 2 gauges with finite, positive amplitudes")
    bound = np.asarray(wt.stokes2_second_harmonic_amplitude(2.0 * x1[ok], k, depth))
    ratio = x2[ok] / bound
    return float((ratio.max() - ratio.min()) / ratio.mean())


def mean_level_drift(
    eta: npt.ArrayLike, t: npt.ArrayLike, period: float
) -> tuple[float, float]:
    """Drift of the mean water level over a regular-wave record: ``(slope, change)``.

    The record (uniform times ``t`` [s], elevation ``eta`` [m]) is cut into whole periods from
    its start; the mean of each period is the mean water level of that wave (a whole period
    removes the oscillation exactly for a periodic signal). ``slope`` is the least-squares
    slope of those means against time [m/s]; ``change`` is the slope times the record's
    length [m], the rise (positive) or fall of the level over the record. Needs 2+ periods.
    """
    ee = np.asarray(eta, dtype=float).ravel()
    tt = np.asarray(t, dtype=float).ravel()
    if ee.shape != tt.shape or tt.size < 4:
        raise ValueError("eta, t: need two arrays of the same length (4+ samples)")
    if not period > 0.0:
        raise ValueError(f"period: must be positive, got {period!r}")
    dt = (tt[-1] - tt[0]) / (tt.size - 1)
    per = round(period / dt)
    n = tt.size // per if per > 0 else 0
    if n < 2:
        raise ValueError(f"eta: the record holds fewer than 2 periods of {period} s")
    means = ee[: n * per].reshape(n, per).mean(axis=1)
    centres = tt[: n * per].reshape(n, per).mean(axis=1)
    slope = float(np.polyfit(centres, means, 1)[0])
    return slope, float(slope * n * per * dt)
