"""Analysis of wave-flume records: wave heights, harmonics, reflection, phase averages, run-up,
undertow and crest celerity.

Pure NumPy/SciPy on arrays, no simulation. SI units: elevations in metres relative to the
still-water level (z = 0 unless stated), times in seconds, frequencies in hertz, phases in
radians. A gauge matrix is ``(n_samples, n_gauges)``: time along axis 0. Bad input (NaN,
mismatched lengths, a period <= 0, a time axis that is not increasing) raises
:class:`ValueError` naming the argument.

Phase convention for harmonics and wave components: ``eta(t) = a cos(2 pi f t + phase)`` with
the absolute time t of the record, and for travelling waves ``a cos(2 pi f t - k x + phase)``
(incident, towards +x) and ``a cos(2 pi f t + k x + phase)`` (reflected).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from .wave_theory import (
    KINEMATIC_BREAKING_RATIO,
    MCCOWAN_BREAKING_RATIO,
    G,
    _choice,
    _finite,
    _nonnegative,
    _positive,
    breaker_type,
    deep_water_wavelength,
    iribarren,
    wavenumber,
)

__all__ = [
    "BreakingOnset",
    "CrestCelerity",
    "CrestVelocity",
    "MeanLevelBlocks",
    "PhaseAveragedBreaking",
    "GaugeSpacingWarning",
    "Harmonics",
    "Overturn",
    "PhaseAverage",
    "ReflectionAnalysis",
    "RunupPerWave",
    "VerticalMeanFlow",
    "WaterLevelEnvelopes",
    "WaveSpectrum",
    "ZeroCrossingWaves",
    "load_statistics",
    "breaking_onset_from_crests",
    "breaking_onset_from_gauges",
    "crest_celerity",
    "crest_velocity",
    "goda_suzuki",
    "breaking_from_phase_averaged_heights",
    "harmonic_analysis",
    "mansard_funke",
    "mean_level_blocks",
    "overturned_surface",
    "parabola_peak_shift",
    "phase_average",
    "runup_per_wave",
    "vertical_mean_flow",
    "water_level_envelopes",
    "wave_spectrum",
    "zero_crossing_waves",
]

FloatArray = npt.NDArray[np.float64]
Window = Literal["rectangular", "hann"]

# Goda & Suzuki (1976): two gauges resolve incident and reflected waves only when their spacing
# is at least 0.05 L away from a multiple of L/2. The eigenvalue ratio of the least-squares
# normal matrix at that limit, (1 - cos 0.1 pi) / (1 + cos 0.1 pi), is the criterion used for
# any number of gauges (for two gauges it is exactly Goda & Suzuki's rule).
_SPACING_CONDITION_LIMIT = (1.0 - math.cos(0.1 * math.pi)) / (1.0 + math.cos(0.1 * math.pi))


class GaugeSpacingWarning(UserWarning):
    """Gauge spacing too close to a multiple of half a wavelength to separate the waves."""


# ------------------------------------------------------------------------------------------------
# Input checks


def _series(name: str, values: npt.ArrayLike, min_ndim: int = 1) -> FloatArray:
    """A finite float array with time along axis 0 and at least ``min_ndim`` dimensions."""
    arr = _finite(name, values)
    if arr.ndim < min_ndim:
        raise ValueError(
            f"{name}: expected at least {min_ndim} dimension(s), got shape {arr.shape}"
        )
    return arr


def _times(t: npt.ArrayLike, n_samples: int, values_name: str) -> FloatArray:
    """Strictly increasing 1-D sample times [s] of length ``n_samples``."""
    tt = _finite("t", t)
    if tt.ndim != 1:
        raise ValueError(f"t: expected a 1-D array of times, got shape {tt.shape}")
    if tt.size != n_samples:
        raise ValueError(
            f"t: has {tt.size} samples but {values_name} has {n_samples} along its time axis"
        )
    if tt.size < 2 or not np.all(np.diff(tt) > 0.0):
        raise ValueError("t: must hold at least 2 strictly increasing times")
    return tt


def _uniform_step(t: FloatArray) -> float:
    """Sampling interval [s] of uniformly sampled times; ValueError if they are not uniform."""
    dt = (t[-1] - t[0]) / (t.size - 1)
    if np.max(np.abs(np.diff(t) - dt)) > 1e-6 * dt:
        raise ValueError("t: must be uniformly sampled (constant time step) for this analysis")
    return float(dt)


def _scalar_positive(name: str, value: float) -> float:
    arr = _positive(name, value)
    if arr.ndim != 0:
        raise ValueError(f"{name}: must be a scalar, got shape {arr.shape}")
    return float(arr)


def _whole_period_segment(t: FloatArray, period: float, n_periods: int | None) -> tuple[slice, int]:
    """The last ``n_periods`` whole periods of uniformly sampled ``t`` (all that fit if None).

    Returns the slice of those samples and the number of periods.
    """
    dt = _uniform_step(t)
    available = math.floor((t[-1] - t[0] + dt) / period + 1e-9)
    if n_periods is None:
        n_periods = available
    if not isinstance(n_periods, (int, np.integer)) or n_periods < 1:
        raise ValueError(f"n_periods: must be a positive integer, got {n_periods!r}")
    if n_periods > available:
        raise ValueError(
            f"n_periods: the record holds {available} whole period(s) of {period} s,"
            f" {n_periods} requested"
        )
    n = min(round(n_periods * period / dt), t.size)
    return slice(t.size - n, t.size), int(n_periods)


def _whole_waves(
    t: FloatArray, period: float, origin: float, n_waves: int | None, values_name: str
) -> tuple[int, int, int]:
    """The whole periods ``[origin + j T, origin + (j + 1) T]`` inside the record ``t`` [s]:
    ``(first j, last j, n_waves)``, ``n_waves`` defaulting to all of them and checked against
    that count (``values_name`` names the record in the error)."""
    first = math.ceil((t[0] - origin) / period - 1e-9)
    last = math.floor((t[-1] - origin) / period + 1e-9) - 1
    available = last - first + 1
    if available < 1:
        raise ValueError(f"{values_name}: the record holds no whole period of {period} s")
    if n_waves is None:
        n_waves = available
    if not isinstance(n_waves, (int, np.integer)) or not 1 <= n_waves <= available:
        raise ValueError(f"n_waves: must be an integer in 1..{available}, got {n_waves!r}")
    return first, last, int(n_waves)


def _window(kind: str, n: int) -> FloatArray:
    """Window weights: ones, or the periodic Hann window ``0.5 - 0.5 cos(2 pi j / n)``."""
    _choice("window", kind, ("rectangular", "hann"))
    return np.ones(n) if kind == "rectangular" else np.hanning(n + 1)[:-1]


def _complex_amplitudes(
    values: FloatArray, t: FloatArray, frequencies: FloatArray, weights: FloatArray
) -> npt.NDArray[np.complex128]:
    """``B = 2 sum_j w_j eta_j exp(-2 pi i f t_j) / sum_j w_j``: ``eta = Re(B exp(2 pi i f t))``.

    The discrete Fourier transform evaluated exactly at each frequency [Hz]; over a whole number
    of periods it equals the FFT bin of that frequency. Returns shape
    ``(len(frequencies),) + values.shape[1:]``.
    """
    phasors = np.exp(-2j * np.pi * np.multiply.outer(frequencies, t)) * weights
    return 2.0 * np.tensordot(phasors, values, axes=(1, 0)) / weights.sum()


# ------------------------------------------------------------------------------------------------
# Zero-crossing analysis


@dataclass(frozen=True)
class ZeroCrossingWaves:
    """Individual waves of a record, one entry per wave between two successive crossings.

    Attributes:
        kind: ``"down"`` (zero-down-crossing) or ``"up"``.
        mean_level: the level the crossings are counted at [m].
        start_times: crossing time that starts each wave [s] (linear interpolation).
        heights: crest-to-trough height H [m].
        periods: time to the next crossing T [s].
        crest_elevations: highest elevation within the wave [m] (not de-meaned).
        trough_elevations: lowest elevation within the wave [m].
        crest_times: time of the highest sample [s].
    """

    kind: str
    mean_level: float
    start_times: FloatArray
    heights: FloatArray
    periods: FloatArray
    crest_elevations: FloatArray
    trough_elevations: FloatArray
    crest_times: FloatArray

    @property
    def mean_height(self) -> float:
        """Mean wave height [m]."""
        return float(np.mean(self.heights))

    @property
    def significant_height(self) -> float:
        """H_1/3: mean of the highest third of the waves [m] (at least one wave)."""
        n = max(1, round(self.heights.size / 3))
        return float(np.mean(np.sort(self.heights)[-n:]))

    @property
    def max_height(self) -> float:
        """Highest wave H_max [m]."""
        return float(np.max(self.heights))

    @property
    def mean_period(self) -> float:
        """Mean zero-crossing period [s]."""
        return float(np.mean(self.periods))


def zero_crossing_waves(
    eta: npt.ArrayLike,
    t: npt.ArrayLike,
    kind: Literal["down", "up"] = "down",
    mean_level: float | None = None,
) -> ZeroCrossingWaves:
    """Split a surface-elevation record into individual waves by zero crossings.

    A zero-down-crossing wave runs from a crossing of ``mean_level`` going down to the next one
    (trough first), a zero-up-crossing wave between up-crossings (IAHR/PIANC standard
    definitions). Crossing times are linearly interpolated between samples; samples exactly at
    the level count as below it. Incomplete waves at the ends are dropped.

    Args:
        eta: elevation [m], 1-D.
        t: sample times [s], strictly increasing (need not be uniform).
        kind: ``"down"`` or ``"up"``.
        mean_level: level of the crossings [m]; default the record mean.

    Raises:
        ValueError: bad input, or fewer than two crossings (no complete wave).
    """
    x = _series("eta", eta)
    if x.ndim != 1:
        raise ValueError(f"eta: expected a 1-D record, got shape {x.shape}")
    tt = _times(t, x.size, "eta")
    _choice("kind", kind, ("down", "up"))
    level = float(np.mean(x)) if mean_level is None else float(_finite("mean_level", mean_level))
    rel = x - level
    above = rel > 0.0
    if kind == "down":
        idx = np.flatnonzero(above[:-1] & ~above[1:])
    else:
        idx = np.flatnonzero(~above[:-1] & above[1:])
    if idx.size < 2:
        raise ValueError(
            f"eta: fewer than two zero-{kind}-crossings about {level:.6g} m, no complete wave"
        )
    crossing = tt[idx] + rel[idx] / (rel[idx] - rel[idx + 1]) * (tt[idx + 1] - tt[idx])
    crests, troughs, crest_times = [], [], []
    for start, stop in zip(idx[:-1] + 1, idx[1:] + 1, strict=True):
        segment = x[start:stop]
        top = int(np.argmax(segment))
        crests.append(segment[top])
        troughs.append(segment.min())
        crest_times.append(tt[start + top])
    crest = np.asarray(crests)
    trough = np.asarray(troughs)
    return ZeroCrossingWaves(
        kind=kind,
        mean_level=level,
        start_times=crossing[:-1],
        heights=crest - trough,
        periods=np.diff(crossing),
        crest_elevations=crest,
        trough_elevations=trough,
        crest_times=np.asarray(crest_times),
    )


# ------------------------------------------------------------------------------------------------
# Harmonics


@dataclass(frozen=True)
class Harmonics:
    """Harmonic amplitudes and phases: ``eta(t) = mean + sum_n a_n cos(2 pi n f0 t + phi_n)``.

    Attributes:
        frequencies: n f0 for n = 1..N [Hz].
        amplitudes: a_n [m], shape ``(N,) + gauges shape``.
        phases: phi_n [rad] in (-pi, pi], same shape, for the absolute time t of the record.
        mean: mean level over the analysed window [m], gauges shape.
        window_start: first time of the analysed window [s].
        n_periods: number of whole periods analysed.
    """

    frequencies: FloatArray
    amplitudes: FloatArray
    phases: FloatArray
    mean: FloatArray
    window_start: float
    n_periods: int


def harmonic_analysis(
    eta: npt.ArrayLike,
    t: npt.ArrayLike,
    period: float,
    n_harmonics: int = 3,
    n_periods: int | None = None,
    window: Window = "rectangular",
) -> Harmonics:
    """Amplitudes and phases of the first ``n_harmonics`` harmonics of a periodic record.

    The analysed window is the last ``n_periods`` whole periods of the record (all that fit by
    default). The Fourier transform is evaluated exactly at n f0 (f0 = 1/period); when the window
    holds a whole number of samples per period this is the FFT bin of n f0, otherwise leakage is
    of order dt / (n_periods T). ``"hann"`` windowing (amplitude normalised by the window's
    sum) needs at least 2 periods so that harmonics stay off each other's side lobes.

    Args:
        eta: elevation [m], shape ``(n_samples,)`` or ``(n_samples, n_gauges)`` (any trailing
            shape).
        t: uniformly sampled times [s].
        period: fundamental period T [s].
        n_harmonics: number of harmonics N >= 1.
        n_periods: number of whole periods to analyse; default all that fit.
        window: ``"rectangular"`` or ``"hann"``.
    """
    x = _series("eta", eta)
    tt = _times(t, x.shape[0], "eta")
    T = _scalar_positive("period", period)
    if not isinstance(n_harmonics, (int, np.integer)) or n_harmonics < 1:
        raise ValueError(f"n_harmonics: must be a positive integer, got {n_harmonics!r}")
    seg, periods_used = _whole_period_segment(tt, T, n_periods)
    if window == "hann" and periods_used < 2:
        raise ValueError("n_periods: the Hann window needs at least 2 whole periods")
    weights = _window(window, seg.stop - seg.start)
    xs, ts = x[seg], tt[seg]
    freqs = np.arange(1, n_harmonics + 1) / T
    b = _complex_amplitudes(xs, ts, freqs, weights)
    mean = np.tensordot(weights, xs, axes=(0, 0)) / weights.sum()
    return Harmonics(
        frequencies=freqs,
        amplitudes=np.abs(b),
        phases=np.angle(b),
        mean=np.asarray(mean),
        window_start=float(ts[0]),
        n_periods=periods_used,
    )


# ------------------------------------------------------------------------------------------------
# Incident / reflected separation


@dataclass(frozen=True)
class ReflectionAnalysis:
    """Incident and reflected waves resolved from gauges along the flume, per frequency.

    Attributes:
        method: ``"goda-suzuki"`` or ``"mansard-funke"``.
        frequencies: analysed frequencies [Hz].
        incident_amplitudes, reflected_amplitudes: a_I, a_R [m] (NaN where unresolvable).
        incident_phases, reflected_phases: phases at x = 0 [rad] (see the module docstring).
        valid: False where the gauge spacing is within 0.05 L of a multiple of L/2 (those
            frequencies are left out of :attr:`reflection_coefficient`).
    """

    method: str
    frequencies: FloatArray
    incident_amplitudes: FloatArray
    reflected_amplitudes: FloatArray
    incident_phases: FloatArray
    reflected_phases: FloatArray
    valid: npt.NDArray[np.bool_]

    @property
    def reflection_coefficient(self) -> float:
        """``K_r = sqrt(sum a_R^2 / sum a_I^2)`` over the valid frequencies [-] (NaN if none)."""
        if not np.any(self.valid):
            return math.nan
        incident = np.sum(self.incident_amplitudes[self.valid] ** 2)
        reflected = np.sum(self.reflected_amplitudes[self.valid] ** 2)
        return float(np.sqrt(reflected / incident))


def _separate(
    method: str,
    n_gauges: int,
    eta: npt.ArrayLike,
    t: npt.ArrayLike,
    positions: npt.ArrayLike,
    depth: float,
    period: float | None,
    frequency_band: tuple[float, float] | None,
    g: float,
) -> ReflectionAnalysis:
    """Least-squares fit of ``B_p = A_I exp(-i k x_p) + A_R exp(+i k x_p)`` at each frequency.

    B_p is gauge p's complex amplitude (``eta_p = Re(B_p exp(2 pi i f t))``). With two gauges
    the fit is the exact solution of Goda & Suzuki (1976); with three or more it is Mansard &
    Funke's (1980) least squares.
    """
    x = _series("eta", eta, min_ndim=2)
    if x.ndim != 2 or x.shape[1] != n_gauges:
        raise ValueError(f"eta: expected shape (n_samples, {n_gauges}), got {x.shape}")
    tt = _times(t, x.shape[0], "eta")
    xp = _finite("positions", positions)
    if xp.shape != (n_gauges,):
        raise ValueError(f"positions: expected {n_gauges} gauge positions, got shape {xp.shape}")
    if np.unique(xp).size != n_gauges:
        raise ValueError(f"positions: gauge positions must differ, got {xp.tolist()}")
    d = _scalar_positive("depth", depth)
    if period is not None and frequency_band is None:
        T = _scalar_positive("period", period)
        seg, _ = _whole_period_segment(tt, T, None)
        freqs = np.array([1.0 / T])
        b = _complex_amplitudes(x[seg], tt[seg], freqs, np.ones(seg.stop - seg.start))
    elif frequency_band is not None and period is None:
        band = _nonnegative("frequency_band", frequency_band)
        if band.shape != (2,) or not band[0] < band[1]:
            raise ValueError(f"frequency_band: expected (low, high) with low < high, got {band}")
        dt = _uniform_step(tt)
        n = tt.size
        spectrum = np.fft.rfft(x - x.mean(axis=0), axis=0)
        all_freqs = np.fft.rfftfreq(n, dt)
        keep = (all_freqs >= band[0]) & (all_freqs <= band[1]) & (all_freqs > 0.0)
        keep &= all_freqs < 0.5 / dt
        if not np.any(keep):
            raise ValueError(
                f"frequency_band: no FFT frequency of the record (spacing {1 / (n * dt):.4g} Hz)"
                f" lies in {band.tolist()} Hz"
            )
        freqs = all_freqs[keep]
        b = 2.0 / n * spectrum[keep] * np.exp(-2j * np.pi * freqs * tt[0])[:, None]
    else:
        raise ValueError("period: give exactly one of period (regular) or frequency_band")
    k = np.asarray(wavenumber(1.0 / freqs, d, g))
    # Normal equations of the (n_gauges x 2) complex system, one per frequency.
    m = np.stack([np.exp(-1j * np.outer(k, xp)), np.exp(1j * np.outer(k, xp))], axis=2)
    normal = np.einsum("fpi,fpj->fij", m.conj(), m)
    rhs = np.einsum("fpi,fp->fi", m.conj(), b)
    s = np.abs(np.sum(np.exp(2j * np.outer(k, xp)), axis=1))
    condition = (n_gauges - s) / (n_gauges + s)
    valid = condition >= _SPACING_CONDITION_LIMIT
    solvable = condition > 1e-12
    coeffs = np.full((freqs.size, 2), np.nan + 0j)
    if np.any(solvable):
        coeffs[solvable] = np.linalg.solve(normal[solvable], rhs[solvable][..., None])[..., 0]
    if not np.all(valid):
        bad = freqs[~valid]
        warnings.warn(
            f"{method}: gauge spacing is within 0.05 L of a multiple of L/2 at {bad.size} of"
            f" {freqs.size} frequencies ({bad.min():.4g}-{bad.max():.4g} Hz); they are left out"
            " of the reflection coefficient",
            GaugeSpacingWarning,
            stacklevel=3,
        )
    return ReflectionAnalysis(
        method=method,
        frequencies=freqs,
        incident_amplitudes=np.abs(coeffs[:, 0]),
        reflected_amplitudes=np.abs(coeffs[:, 1]),
        incident_phases=np.angle(coeffs[:, 0]),
        reflected_phases=np.angle(coeffs[:, 1]),
        valid=valid,
    )


def goda_suzuki(
    eta: npt.ArrayLike,
    t: npt.ArrayLike,
    positions: npt.ArrayLike,
    depth: float,
    period: float | None = None,
    frequency_band: tuple[float, float] | None = None,
    g: float = G,
) -> ReflectionAnalysis:
    """Incident and reflected waves from two gauges (Goda & Suzuki 1976).

    At each frequency the two gauges' complex amplitudes give the incident and reflected
    amplitudes through linear dispersion at ``depth``. Regular waves: give ``period`` (the
    fundamental is analysed over the whole periods of the record). Irregular waves: give
    ``frequency_band`` (every FFT frequency of the uniformly sampled record in it). Valid when
    the spacing is between 0.05 L and 0.45 L (modulo L/2); frequencies outside are flagged
    invalid and a :class:`GaugeSpacingWarning` is issued.

    Args:
        eta: elevations [m], shape (n_samples, 2).
        t: times [s] (uniform for ``frequency_band``).
        positions: the two gauge positions x [m] (waves incident towards +x).
        depth: still-water depth at the gauges [m].
        period: wave period [s] (regular waves), or
        frequency_band: (low, high) [Hz] (irregular waves).
    """
    return _separate("goda-suzuki", 2, eta, t, positions, depth, period, frequency_band, g)


def mansard_funke(
    eta: npt.ArrayLike,
    t: npt.ArrayLike,
    positions: npt.ArrayLike,
    depth: float,
    period: float | None = None,
    frequency_band: tuple[float, float] | None = None,
    g: float = G,
) -> ReflectionAnalysis:
    """Incident and reflected waves from three gauges by least squares (Mansard & Funke 1980).

    As :func:`goda_suzuki` with three gauges: the least-squares fit of incident and reflected
    complex amplitudes to the three gauges' amplitudes is less sensitive to noise and to any
    single spacing. A frequency is flagged invalid (and warned about) when the gauges are as
    badly placed as a pair within 0.05 L of a multiple of L/2; Mansard & Funke's own spacing
    advice (x12 ~ L/10, L/6 < x13 < L/3) keeps clear of that.

    Args:
        eta: elevations [m], shape (n_samples, 3).
        positions: the three gauge positions x [m].
        Others: see :func:`goda_suzuki`.
    """
    return _separate("mansard-funke", 3, eta, t, positions, depth, period, frequency_band, g)


# ------------------------------------------------------------------------------------------------
# Phase averaging


@dataclass(frozen=True)
class PhaseAverage:
    """Phase-averaged record (seed 001 Eq. 18).

    Attributes:
        phases: phases phi_i in [0, 2 pi) [rad]; phase phi is time ``phase_origin + (j +
            phi / 2 pi) T`` in wave j.
        times: the same as offsets within the period [s].
        mean: ``(1/n_w) sum_j value(t_ij)``, shape ``(n_phases,) + field shape``.
        std: standard deviation over the waves (population, ddof = 0), same shape.
        n_waves: number of waves averaged n_w.
        first_wave_start: start time of the first averaged wave [s].
    """

    phases: FloatArray
    times: FloatArray
    mean: FloatArray
    std: FloatArray
    n_waves: int
    first_wave_start: float


def phase_average(
    values: npt.ArrayLike,
    t: npt.ArrayLike,
    period: float,
    n_waves: int | None = None,
    n_phases: int | None = None,
    phase_origin: float = 0.0,
) -> PhaseAverage:
    """Phase average over n waves, seed 001 Eq. 18: ``v_phi_i = (1/n_w) sum_j v(t_ij)``.

    ``t_ij = phase_origin + (j + phi_i / 2 pi) T``: the same phase phi_i in each of the last
    ``n_waves`` whole periods of the record (Kimmoun & Branger 2007 as used by seed 001, who
    average the last 128 waves). Values between samples are interpolated linearly in time.
    ``phase_origin = 0`` puts phase 0 at the paddle's start (t = 0) and its multiples of T.

    Args:
        values: a series with time along axis 0: ``(n_samples,)`` for a gauge, or
            ``(n_samples, ...)`` for fields (e.g. velocity on a grid).
        t: sample times [s], strictly increasing.
        period: wave period T [s].
        n_waves: number of waves n_w; default all whole periods in the record.
        n_phases: number of phases per period; default the number of samples per period.
        phase_origin: time of phase 0 [s].
    """
    v = _series("values", values)
    tt = _times(t, v.shape[0], "values")
    T = _scalar_positive("period", period)
    origin = float(_finite("phase_origin", phase_origin))
    _, last, n_waves = _whole_waves(tt, T, origin, n_waves, "values")
    if n_phases is None:
        n_phases = max(2, round(T * (tt.size - 1) / (tt[-1] - tt[0])))
    if not isinstance(n_phases, (int, np.integer)) or n_phases < 1:
        raise ValueError(f"n_phases: must be a positive integer, got {n_phases!r}")
    offsets = np.arange(n_phases) * T / n_phases

    def wave_sample(j: int) -> FloatArray:
        """Values at the phases of wave j, linearly interpolated in time."""
        sample_t = np.clip(origin + j * T + offsets, tt[0], tt[-1])
        i = np.clip(np.searchsorted(tt, sample_t, side="right") - 1, 0, tt.size - 2)
        w = ((sample_t - tt[i]) / (tt[i + 1] - tt[i])).reshape((-1,) + (1,) * (v.ndim - 1))
        return (1.0 - w) * v[i] + w * v[i + 1]

    # Sums of deviations from the first wave keep the variance free of cancellation.
    waves = range(last - n_waves + 1, last + 1)
    reference = wave_sample(waves[0])
    total = np.zeros_like(reference)
    total_sq = np.zeros_like(reference)
    for j in waves:
        deviation = wave_sample(j) - reference
        total += deviation
        total_sq += deviation * deviation
    mean_deviation = total / n_waves
    mean = reference + mean_deviation
    variance = np.maximum(total_sq / n_waves - mean_deviation**2, 0.0)
    return PhaseAverage(
        phases=2.0 * np.pi * offsets / T,
        times=offsets,
        mean=mean,
        std=np.sqrt(variance),
        n_waves=int(n_waves),
        first_wave_start=origin + (last - n_waves + 1) * T,
    )


# ------------------------------------------------------------------------------------------------
# Envelopes and set-up


@dataclass(frozen=True)
class WaterLevelEnvelopes:
    """Water-level statistics per gauge along the flume (seed 001 Fig. 8).

    Attributes:
        maximum: crest envelope, max over time [m].
        minimum: trough envelope, min over time [m].
        mean: time-mean level [m].
        mid_level: (maximum + minimum) / 2 [m], the "mean water level" of seed 001 Fig. 8.
        setup: wave set-up (set-down where negative): ``mean - still_water_level`` [m].
    """

    maximum: FloatArray
    minimum: FloatArray
    mean: FloatArray
    mid_level: FloatArray
    setup: FloatArray


def water_level_envelopes(
    eta: npt.ArrayLike, still_water_level: float = 0.0
) -> WaterLevelEnvelopes:
    """Max, min and mean water level of each gauge of a gauge matrix, and the wave set-up.

    Pass the part of the record to analyse (e.g. after the spin-up). A gauge on the beach above
    the water must report the bed level when dry (not NaN).

    Args:
        eta: elevations [m], shape (n_samples, n_gauges) (or 1-D for one gauge).
        still_water_level: still-water level [m] in the same datum.
    """
    x = _series("eta", eta)
    swl = float(_finite("still_water_level", still_water_level))
    mean = x.mean(axis=0)
    top, bottom = x.max(axis=0), x.min(axis=0)
    return WaterLevelEnvelopes(
        maximum=top,
        minimum=bottom,
        mean=mean,
        mid_level=0.5 * (top + bottom),
        setup=mean - swl,
    )


# ------------------------------------------------------------------------------------------------
# Breaking onset


@dataclass(frozen=True)
class BreakingOnset:
    """Where and when waves start to break.

    Attributes:
        criterion: ``"H/d > 0.78"`` (McCowan, from gauges) or ``"u > 0.85 c"`` (kinematic).
        position: x of the onset [m].
        time: time of the onset [s] (crest passage of the first breaking wave).
        index: index of the gauge (in the given order) or of the crest sample.
        wave_height: wave height at the onset [m] (None if not known).
        iribarren: ``tan(beta) / sqrt(H_b / L0)`` [-] when slope and period were given.
        breaker_type: from :func:`watersim.wave_theory.breaker_type` when classified.
    """

    criterion: str
    position: float
    time: float
    index: int
    wave_height: float | None
    iribarren: float | None
    breaker_type: str | None


def _classification(
    slope: float | None, height: float | None, period: float | None, g: float
) -> tuple[float | None, str | None]:
    """(Iribarren number, breaker type) from the breaking height, or (None, None)."""
    if slope is None or period is None or height is None:
        return None, None
    xi = float(iribarren(slope, height, deep_water_wavelength(period, g)))
    return xi, str(breaker_type(xi))


def breaking_onset_from_gauges(
    eta: npt.ArrayLike,
    t: npt.ArrayLike,
    positions: npt.ArrayLike,
    depths: npt.ArrayLike,
    slope: float | None = None,
    period: float | None = None,
    g: float = G,
) -> BreakingOnset | None:
    """Breaking onset from gauge records by the depth-limited criterion H/d > 0.78 (McCowan).

    Each gauge's zero-down-crossing waves (:func:`zero_crossing_waves`) are compared with its
    still-water depth; the onset is the most offshore gauge (smallest x; waves travel towards
    +x) where a wave exceeds 0.78 d, at the crest time of its first such wave. Gauges with depth
    <= 0 (dry beach) or with no complete wave are skipped. With ``slope`` and ``period`` the
    breaker type follows from the Iribarren number of the breaking height and L0 (seed 001
    Table 1).

    Args:
        eta: elevations [m], shape (n_samples, n_gauges).
        t: times [s].
        positions: gauge x [m], shape (n_gauges,).
        depths: still-water depth at each gauge [m] (<= 0 where the bed is above the water).
        slope: beach slope tan(beta) [-], for the breaker type.
        period: wave period T [s], for the breaker type.

    Returns:
        The onset, or None if no wave exceeds the criterion.
    """
    x = _series("eta", eta, min_ndim=2)
    if x.ndim != 2:
        raise ValueError(f"eta: expected shape (n_samples, n_gauges), got {x.shape}")
    tt = _times(t, x.shape[0], "eta")
    xp = _finite("positions", positions)
    dd = _finite("depths", depths)
    if xp.shape != (x.shape[1],):
        raise ValueError(f"positions: expected {x.shape[1]} positions, got shape {xp.shape}")
    if dd.shape != (x.shape[1],):
        raise ValueError(f"depths: expected {x.shape[1]} depths, got shape {dd.shape}")
    for gauge in np.argsort(xp, kind="stable"):
        if dd[gauge] <= 0.0:
            continue
        try:
            waves = zero_crossing_waves(x[:, gauge], tt)
        except ValueError:
            continue
        breaking = np.flatnonzero(waves.heights / dd[gauge] > MCCOWAN_BREAKING_RATIO)
        if breaking.size:
            first = breaking[0]
            height = float(waves.heights[first])
            xi, kind = _classification(slope, height, period, g)
            return BreakingOnset(
                criterion=f"H/d > {MCCOWAN_BREAKING_RATIO}",
                position=float(xp[gauge]),
                time=float(waves.crest_times[first]),
                index=int(gauge),
                wave_height=height,
                iribarren=xi,
                breaker_type=kind,
            )
    return None


def breaking_onset_from_crests(
    crest_x: npt.ArrayLike,
    crest_t: npt.ArrayLike,
    crest_speed: npt.ArrayLike,
    celerity: npt.ArrayLike,
    wave_height: float | None = None,
    slope: float | None = None,
    period: float | None = None,
    g: float = G,
) -> BreakingOnset | None:
    """Breaking onset from crest kinematics: the first crest whose particle speed exceeds 0.85 c.

    Args:
        crest_x: crest positions [m] of a tracked crest (or crests), in time order.
        crest_t: the times [s], increasing.
        crest_speed: horizontal particle speed at the crest u [m/s].
        celerity: local wave celerity c [m/s] at each crest (> 0), e.g. the crest's own speed
            or linear theory at the local depth.
        wave_height: breaking wave height [m], for the breaker type.
        slope: beach slope tan(beta) [-]; period: T [s]: for the breaker type.

    Returns:
        The onset, or None if no crest exceeds the criterion.
    """
    xc = _series("crest_x", crest_x)
    tc = _times(crest_t, xc.size, "crest_x")
    u = _finite("crest_speed", crest_speed)
    c = _positive("celerity", celerity)
    if xc.ndim != 1 or u.shape != xc.shape or c.shape != xc.shape:
        raise ValueError(
            "crest_speed: crest_x, crest_t, crest_speed and celerity must be 1-D of one length,"
            f" got {xc.shape}, {tc.shape}, {u.shape}, {c.shape}"
        )
    hits = np.flatnonzero(u > KINEMATIC_BREAKING_RATIO * c)
    if hits.size == 0:
        return None
    i = int(hits[0])
    height = None if wave_height is None else _scalar_positive("wave_height", wave_height)
    xi, kind = _classification(slope, height, period, g)
    return BreakingOnset(
        criterion=f"u > {KINEMATIC_BREAKING_RATIO} c",
        position=float(xc[i]),
        time=float(tc[i]),
        index=i,
        wave_height=height,
        iribarren=xi,
        breaker_type=kind,
    )


@dataclass(frozen=True)
class Overturn:
    """An overhanging free surface in one particle snapshot: water above air above water.

    Attributes:
        x_min, x_max: horizontal extent of the overhang [m] (edges of its columns).
        z_gap_bottom: top of the water below the air gap [m], in the column with the widest gap.
        z_gap_top: bottom of the overhanging water there [m].
        n_columns: adjacent columns (width ``dp``) that hold the overhang.
        n_particles: particles above the gaps, over those columns.
    """

    x_min: float
    x_max: float
    z_gap_bottom: float
    z_gap_top: float
    n_columns: int
    n_particles: int


def overturned_surface(
    positions: npt.ArrayLike,
    dp: float,
    x_range: tuple[float, float] | None = None,
    min_gap: float = 2.0,
    min_columns: int = 2,
    min_particles: int = 3,
) -> Overturn | None:
    """Find where the free surface overturns (a plunging jet) in one snapshot of fluid particles.

    A plunging breaker throws a jet ahead of the crest that falls onto the water in front: for
    a while a vertical line through the jet meets water, then air, then water. The particles
    are binned into columns of width ``dp`` along x; a column overturns when, sorted by height,
    two consecutive particles are more than ``(1 + min_gap) dp`` apart (at least ``min_gap`` dp
    of air) with water below the gap (two particles at least). The air must open to the side
    of the run of such columns (the highest particle of a neighbouring column is below the
    middle of the gap next to it, or the neighbour is empty): a void inside the water, which
    particle disorder makes, is closed. An overturn needs ``min_columns`` adjacent such columns
    holding at least ``min_particles`` particles above their gaps together, so that single
    drops of spray or a lone particle thrown off a spilling crest do not count. The widest run
    of adjacent columns is returned. The snapshot is a 2D section: positions ``(n, 2)`` as
    (x, z), or ``(n, 3)`` as (x, y, z) for a slice the caller has selected.

    Args:
        positions: fluid particle positions [m].
        dp: particle spacing [m].
        x_range: only the whole columns from x_min up to x_max [m], e.g. the surf zone.
        min_gap: least air gap [dp].
        min_columns: least number of adjacent overturned columns.
        min_particles: least number of particles above the gaps, over the columns.

    Returns:
        The widest overturn, or None.
    """
    pos = _finite("positions", positions)
    if pos.ndim != 2 or pos.shape[1] not in (2, 3):
        raise ValueError(f"positions: expected shape (n, 2) or (n, 3), got {pos.shape}")
    step = _scalar_positive("dp", dp)
    gap_limit = (1.0 + _scalar_positive("min_gap", min_gap)) * step
    if min_columns < 1 or min_particles < 1:
        raise ValueError(f"min_columns, min_particles: must be >= 1, got {min_columns}, "
                         f"{min_particles}")
    x, z = pos[:, 0], pos[:, -1]
    origin = 0.0
    if x_range is not None:
        lo, hi = float(x_range[0]), float(x_range[1])
        if not lo < hi:
            raise ValueError(f"x_range: expected (x_min, x_max) with x_min < x_max, got {x_range}")
        # whole columns from lo: a column cut by the window's edge would look half empty
        origin = lo
        keep = (x >= lo) & (x < lo + math.floor((hi - lo) / step) * step)
        x, z = x[keep], z[keep]
    if x.size == 0:
        return None
    column = np.floor((x - origin) / step).astype(np.int64)
    order = np.lexsort((z, column))
    column, z = column[order], z[order]
    starts = np.flatnonzero(np.r_[True, column[1:] != column[:-1]])
    ends = np.r_[starts[1:], column.size]
    top = {int(column[b - 1]): float(z[b - 1]) for b in ends}  # highest particle per column
    # per overturned column: (column, particles above its lowest gap, gap bottom, gap top)
    found: list[tuple[int, int, float, float]] = []
    for a, b in zip(starts, ends, strict=True):
        zc = z[a:b]
        if zc.size < 2:
            continue
        # water below the gap is at least two particles: a lone particle caught next to the
        # bed (a pocket of the stepped beach) under a void is not the water a jet falls onto
        gaps = np.flatnonzero(np.diff(zc[1:]) > gap_limit) + 1
        if gaps.size:
            g = int(gaps[0])
            found.append((int(column[a]), zc.size - g - 1, float(zc[g]), float(zc[g + 1])))
    best: Overturn | None = None
    i = 0
    while i < len(found):
        j = i
        while j + 1 < len(found) and found[j + 1][0] == found[j][0] + 1:
            j += 1
        run = found[i:j + 1]
        n_above = sum(c[1] for c in run)
        # the air under a jet opens to one side (the water next to the run ends below the
        # middle of the gap); a void inside the water (particle disorder) is closed
        before, after = top.get(run[0][0] - 1), top.get(run[-1][0] + 1)
        mid_first, mid_last = 0.5 * (run[0][2] + run[0][3]), 0.5 * (run[-1][2] + run[-1][3])
        open_air = (before is None or before < mid_first) or (after is None or after < mid_last)
        if open_air and len(run) >= min_columns and n_above >= min_particles and (
                best is None or len(run) > best.n_columns):
            widest = max(run, key=lambda c: c[3] - c[2])
            best = Overturn(x_min=origin + run[0][0] * step,
                            x_max=origin + (run[-1][0] + 1) * step,
                            z_gap_bottom=widest[2], z_gap_top=widest[3],
                            n_columns=len(run), n_particles=n_above)
        i = j + 1
    return best


# ------------------------------------------------------------------------------------------------
# Run-up


@dataclass(frozen=True)
class RunupPerWave:
    """Run-up per wave (seed 001 Fig. 9: distribution, mean and standard deviation).

    Attributes:
        values: highest run-up elevation above the still-water level in each wave period [m].
        window_starts: start of each period window [s].
        mean: mean run-up [m].
        std: standard deviation over the waves [m] (population, ddof = 0).
    """

    values: FloatArray
    window_starts: FloatArray
    mean: float
    std: float


def runup_per_wave(
    runup: npt.ArrayLike,
    t: npt.ArrayLike,
    period: float,
    still_water_level: float = 0.0,
    n_waves: int | None = None,
    phase_origin: float = 0.0,
) -> RunupPerWave:
    """Maximum run-up in each wave period window of a run-up record, with mean and std.

    Windows are ``[phase_origin + j T, phase_origin + (j + 1) T)``; only windows that lie
    entirely within the record count, the last ``n_waves`` of them if given.

    Args:
        runup: vertical elevation of the wet front on the slope [m], 1-D.
        t: times [s], strictly increasing.
        period: wave period T [s].
        still_water_level: still-water level [m] (run-up is measured from it).
        n_waves: use only the last n_waves windows; default all.
        phase_origin: time where the first window boundary falls, modulo T [s].
    """
    r = _series("runup", runup)
    if r.ndim != 1:
        raise ValueError(f"runup: expected a 1-D record, got shape {r.shape}")
    tt = _times(t, r.size, "runup")
    T = _scalar_positive("period", period)
    swl = float(_finite("still_water_level", still_water_level))
    origin = float(_finite("phase_origin", phase_origin))
    _, last, n_waves = _whole_waves(tt, T, origin, n_waves, "runup")
    starts = origin + np.arange(last - n_waves + 1, last + 1, dtype=np.float64) * T
    edges = np.searchsorted(tt, np.append(starts, starts[-1] + T), side="left")
    if np.any(np.diff(edges) == 0):
        raise ValueError("t: some wave period windows hold no sample; the record is too coarse")
    values = np.maximum.reduceat(r[: edges[-1]], edges[:-1]) - swl
    return RunupPerWave(
        values=values,
        window_starts=starts,
        mean=float(values.mean()),
        std=float(values.std()),
    )


# ------------------------------------------------------------------------------------------------
# Spectrum


@dataclass(frozen=True)
class WaveSpectrum:
    """One-sided variance density spectrum of a record and its integral parameters.

    Attributes:
        frequencies: f [Hz].
        density: S(f) [m^2/Hz].
        hm0: ``4 sqrt(m0)`` [m].
        tp: peak period [s] (parabolic interpolation around the highest bin).
        tm01: mean period ``m0 / m1`` [s].
    """

    frequencies: FloatArray
    density: FloatArray
    hm0: float
    tp: float
    tm01: float


def _welch(x: FloatArray, dt: float, nperseg: int) -> tuple[FloatArray, FloatArray]:
    """Welch's averaged periodogram: one-sided density [m^2/Hz] at the rfft frequencies [Hz].

    Periodic Hann window, segments of ``nperseg`` samples overlapping by half, each segment's
    mean removed; scaled so that the density integrates to the variance.
    """
    step = max(1, nperseg // 2)
    starts = np.arange(0, x.size - nperseg + 1, step)
    segments = x[starts[:, None] + np.arange(nperseg)]
    segments = segments - segments.mean(axis=1, keepdims=True)
    w = np.hanning(nperseg + 1)[:-1]
    power = np.abs(np.fft.rfft(segments * w, axis=1)) ** 2 * (dt / np.sum(w * w))
    power[:, 1:] *= 2.0
    if nperseg % 2 == 0:
        power[:, -1] /= 2.0
    return np.fft.rfftfreq(nperseg, dt).astype(np.float64), power.mean(axis=0)


def _trapezoid(y: FloatArray, x: FloatArray) -> float:
    """Trapezoidal integral of y over x."""
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)))


def wave_spectrum(
    eta: npt.ArrayLike, t: npt.ArrayLike, segment_duration: float | None = None
) -> WaveSpectrum:
    """Welch estimate of the variance density spectrum (Hann window, 50 % overlap).

    Args:
        eta: elevation [m], 1-D, uniformly sampled.
        t: times [s].
        segment_duration: length of the Welch segments [s]; default an eighth of the record.
            Longer segments resolve the peak better, shorter ones average more.
    """
    x = _series("eta", eta)
    if x.ndim != 1:
        raise ValueError(f"eta: expected a 1-D record, got shape {x.shape}")
    tt = _times(t, x.size, "eta")
    dt = _uniform_step(tt)
    if segment_duration is None:
        nperseg = max(16, x.size // 8)
    else:
        nperseg = round(_scalar_positive("segment_duration", segment_duration) / dt)
    if not 16 <= nperseg <= x.size:
        raise ValueError(
            f"segment_duration: must span 16 to {x.size} samples, got {nperseg} samples"
        )
    f, s = _welch(x, dt, nperseg)
    m0 = _trapezoid(s, f)
    m1 = _trapezoid(s * f, f)
    peak = int(np.argmax(s))
    f_peak = float(f[peak])
    if 0 < peak < f.size - 1:
        left, mid, right = s[peak - 1], s[peak], s[peak + 1]
        curvature = left - 2.0 * mid + right
        if curvature < 0.0:
            f_peak += 0.5 * (left - right) / curvature * (f[1] - f[0])
    return WaveSpectrum(
        frequencies=f,
        density=s,
        hm0=4.0 * math.sqrt(m0),
        tp=1.0 / f_peak if f_peak > 0.0 else math.inf,
        tm01=m0 / m1 if m1 > 0.0 else math.inf,
    )


# ------------------------------------------------------------------------------------------------
# Surf-zone kinematics: mean flow on a vertical, crest celerity


@dataclass(frozen=True)
class VerticalMeanFlow:
    """The time-averaged horizontal flow on a vertical line of velocity samples.

    Attributes:
        z: heights of the samples [m], increasing.
        mean_u: time mean of u, counting the samples when dry as 0 (so that ``mean_u dz`` is the
            mean volume flux through the height dz) [m/s].
        wet_fraction: share of the samples each point is wet.
        trough_level: top of the points wet in every sample (the trough level to the vertical's
            resolution) [m].
        undertow: depth average of ``mean_u`` from the bed to the trough level [m/s].
        flux_below_trough: ``int mean_u dz`` from the bed to the trough level [m^2/s].
        flux_above_trough: the same above it: the mass transport of the crests (Stokes drift
            and, in the surf zone, the surface roller) [m^2/s].
        max_u: the largest horizontal velocity in the water [m/s].
        n_periods: whole periods averaged.
    """

    z: FloatArray
    mean_u: FloatArray
    wet_fraction: FloatArray
    trough_level: float
    undertow: float
    flux_below_trough: float
    flux_above_trough: float
    max_u: float
    n_periods: int


def vertical_mean_flow(
    u: npt.ArrayLike,
    wet: npt.ArrayLike,
    z: npt.ArrayLike,
    t: npt.ArrayLike,
    period: float,
    bed: float = 0.0,
    n_periods: int | None = None,
) -> VerticalMeanFlow:
    """Undertow and mass transport above the trough from velocities on a vertical (seed 002's
    Table 3 and Figs. 6-7: the time-averaged u(z) and its depth average below the trough).

    Each sample stands for the height between the midpoints to its neighbours (the lowest from
    the bed, the highest up to half a spacing above it). The mean is over the last ``n_periods``
    whole periods (all that fit if None) of the uniformly sampled record.

    Args:
        u: horizontal velocity ``(n_samples, n_points)`` [m/s].
        wet: ``(n_samples, n_points)``, true where the point is in the water (a probe's
            ``kernel_sum >= 0.5``).
        z: heights of the points [m], increasing, above ``bed``.
        t: sample times [s], uniform.
        period: wave period T [s].
        bed: height of the bed under the vertical [m].
        n_periods: whole periods to average.
    """
    mask = np.asarray(wet, dtype=bool)
    raw = np.asarray(u, dtype=np.float64)
    if raw.ndim != 2 or mask.shape != raw.shape:
        raise ValueError(f"u, wet: expected two (n_samples, n_points) arrays, got shapes "
                         f"{raw.shape} and {mask.shape}")
    uu = _series("u", np.where(mask, raw, 0.0), 2)  # a dry point's velocity is not used
    zz = _series("z", z)
    if zz.shape != (uu.shape[1],) or np.any(np.diff(zz) <= 0.0):
        raise ValueError(f"z: expected {uu.shape[1]} increasing heights, got {zz.tolist()}")
    b = float(_finite("bed", bed))
    if zz[0] <= b:
        raise ValueError(f"z: the lowest point ({zz[0]:g} m) must be above the bed ({b:g} m)")
    tt = _times(t, uu.shape[0], "u")
    segment, n = _whole_period_segment(tt, _scalar_positive("period", period), n_periods)
    uu, mask = uu[segment], mask[segment]
    top = zz[-1] + 0.5 * (zz[-1] - zz[-2]) if zz.size > 1 else 2.0 * zz[0] - b
    edges = np.concatenate([[b], 0.5 * (zz[1:] + zz[:-1]), [top]])
    heights = np.diff(edges)
    mean_u = np.mean(np.where(mask, uu, 0.0), axis=0)
    always = np.all(mask, axis=0)
    below = int(np.argmin(always)) if not np.all(always) else zz.size
    trough = float(edges[below])
    flux_below = float(np.sum(mean_u[:below] * heights[:below]))
    return VerticalMeanFlow(
        z=zz,
        mean_u=mean_u,
        wet_fraction=np.mean(mask, axis=0),
        trough_level=trough,
        undertow=flux_below / (trough - b) if below > 0 else math.nan,
        flux_below_trough=flux_below,
        flux_above_trough=float(np.sum(mean_u[below:] * heights[below:])),
        max_u=float(np.max(np.where(mask, uu, -np.inf))) if np.any(mask) else math.nan,
        n_periods=n,
    )


@dataclass(frozen=True)
class CrestCelerity:
    """Crest speed between neighbouring gauges from their phase-averaged waves.

    Attributes:
        x: midpoints between the gauges [m].
        celerity: gauge spacing over the crest's travel time [m/s].
        shallow_water_speed: ``sqrt(g d)`` with d the mean still-water depth of the two gauges
            [m/s].
        ratio: ``celerity / shallow_water_speed``.
        crest_times: time of the phase-averaged crest within the period at each gauge [s].
    """

    x: FloatArray
    celerity: FloatArray
    shallow_water_speed: FloatArray
    ratio: FloatArray
    crest_times: FloatArray


def parabola_peak_shift(left: npt.ArrayLike, mid: npt.ArrayLike, right: npt.ArrayLike
                        ) -> npt.NDArray[np.float64]:
    """Where the parabola through three equally spaced samples peaks, in sample spacings from
    the middle one: ``(left - right) / (2 (left - 2 mid + right))``; 0 where the samples do not
    curve down (no peak between them)."""
    a, b, c = (np.asarray(v, dtype=np.float64) for v in (left, mid, right))
    curvature = a - 2.0 * b + c
    return np.where(curvature < 0.0, 0.5 * (a - c) / np.where(curvature < 0.0, curvature, -1.0),
                    0.0)


def crest_celerity(
    eta: npt.ArrayLike,
    t: npt.ArrayLike,
    x: npt.ArrayLike,
    depth: npt.ArrayLike,
    period: float,
    n_waves: int | None = None,
    g: float = G,
) -> CrestCelerity:
    """Crest celerity along the flume against ``sqrt(g d)`` (seed 002: 70-80 % in the surf
    zone).

    Each gauge's record is phase-averaged over its last ``n_waves`` whole periods
    (:func:`phase_average`); the crest is the phase-averaged maximum, placed between samples by
    a parabola through it and its neighbours. Between neighbouring gauges the crest's travel
    time is the difference of their crest times, taken modulo T nearest to the time at
    ``sqrt(g d)`` (so gauges more than a wavelength apart are followed correctly as long as the
    speed is within half a period of it).

    Args:
        eta: elevations ``(n_samples, n_gauges)`` [m], gauges in increasing x.
        t: sample times [s]; x: gauge positions [m], increasing; depth: still-water depth at
        each gauge [m], > 0; period: T [s]; n_waves: waves to average (default all whole
        periods).
    """
    e = _series("eta", eta, 2)
    xx = _series("x", x)
    if e.ndim != 2 or e.shape[1] != xx.size or xx.size < 2:
        raise ValueError(f"eta: expected (n_samples, {xx.size}) for >= 2 gauges, got {e.shape}")
    if np.any(np.diff(xx) <= 0.0):
        raise ValueError("x: gauge positions must increase")
    d = np.broadcast_to(_positive("depth", depth), xx.shape)
    T = _scalar_positive("period", period)
    average = phase_average(e, t, T, n_waves)
    n = average.times.size
    peak = np.argmax(average.mean, axis=0)
    left = average.mean[(peak - 1) % n, np.arange(xx.size)]
    mid = average.mean[peak, np.arange(xx.size)]
    right = average.mean[(peak + 1) % n, np.arange(xx.size)]
    crest = (peak + parabola_peak_shift(left, mid, right)) * (T / n)
    gap = np.diff(xx)
    speed = np.sqrt(float(_scalar_positive("g", g)) * 0.5 * (d[1:] + d[:-1]))
    lag = np.mod(np.diff(crest), T)
    lag += T * np.round((gap / speed - lag) / T)
    celerity = gap / lag
    return CrestCelerity(x=0.5 * (xx[1:] + xx[:-1]), celerity=celerity,
                         shallow_water_speed=speed, ratio=celerity / speed, crest_times=crest)


# ------------------------------------------------------------------------------------------------
# Long records of regular waves: breaking of the phase-averaged wave, crest velocity, mean-level
# drift (seed 001 averages 128 waves after 128 waves of spin-up)


@dataclass(frozen=True)
class PhaseAveragedBreaking:
    """Where the phase-averaged wave first meets a depth-limited breaking criterion.

    Attributes:
        position: x where ``H / d`` of the phase-averaged wave first reaches ``ratio``, linearly
            interpolated between the last gauge below it and the first at or above it [m].
        wave_height: the phase-averaged wave height at ``position`` (interpolated the same way)
            [m]: the height and the place belong to one wave, the averaged one.
        depth: still-water depth at ``position`` [m].
        index: the first gauge (in the given order) at or above the ratio.
        ratio: the criterion H/d.
        max_height: the largest phase-averaged height among the gauges [m].
        max_height_position: where it is [m].
    """

    position: float
    wave_height: float
    depth: float
    index: int
    ratio: float
    max_height: float
    max_height_position: float


def breaking_from_phase_averaged_heights(
    positions: npt.ArrayLike,
    heights: npt.ArrayLike,
    depths: npt.ArrayLike,
    ratio: float = MCCOWAN_BREAKING_RATIO,
) -> PhaseAveragedBreaking | None:
    """The breaking point of a regular wave train from the heights of its phase-averaged wave
    (crest to trough of :func:`phase_average` at each gauge): the first gauge along +x with
    ``H / d >= ratio`` (McCowan's 0.78 by default), the crossing interpolated linearly from the
    gauge before it. Gauges with ``d <= 0`` or a non-finite height are skipped. None when no
    gauge reaches the ratio.
    """
    x = _finite("positions", positions).ravel()
    h = np.asarray(heights, dtype=np.float64).ravel()
    d = _finite("depths", depths).ravel()
    if not (x.shape == h.shape == d.shape):
        raise ValueError(f"heights, depths: expected {x.size} values each, got {h.size} and "
                         f"{d.size}")
    r = _scalar_positive("ratio", ratio)
    use = [int(i) for i in np.argsort(x, kind="stable") if d[i] > 0.0 and math.isfinite(h[i])]
    if not use:
        return None
    top = max(use, key=lambda i: h[i])
    prev: int | None = None
    for i in use:
        if h[i] / d[i] >= r:
            if prev is None:
                pos, height, depth = x[i], h[i], d[i]
            else:
                q0, q1 = h[prev] / d[prev], h[i] / d[i]
                s = (r - q0) / (q1 - q0)
                pos = x[prev] + s * (x[i] - x[prev])
                height = h[prev] + s * (h[i] - h[prev])
                depth = d[prev] + s * (d[i] - d[prev])
            return PhaseAveragedBreaking(float(pos), float(height), float(depth), i, r,
                                         float(h[top]), float(x[top]))
        prev = i
    return None


@dataclass(frozen=True)
class CrestVelocity:
    """Horizontal velocity under the crest and the trough on a vertical line, regular waves.

    Attributes:
        crest: the largest value of the phase-averaged highest horizontal velocity in the
            water column [m/s] (seed 001: 1.20 sqrt(g D) measured, 1.05 in its SPH).
        trough: the lowest value of the phase-averaged lowest horizontal velocity [m/s]
            (seed 001: -0.40 sqrt(g D) under the troughs).
        crest_per_wave: each wave period's highest velocity in the water column [m/s].
        sqrt_gd: ``sqrt(g D)`` with the still-water depth D [m/s].
        n_waves: whole periods averaged.
    """

    crest: float
    trough: float
    crest_per_wave: FloatArray
    sqrt_gd: float
    n_waves: int


def crest_velocity(
    u: npt.ArrayLike,
    wet: npt.ArrayLike,
    t: npt.ArrayLike,
    period: float,
    depth: float,
    n_waves: int | None = None,
    g: float = G,
) -> CrestVelocity:
    """Crest and trough velocities on a vertical: at each sample the highest and the lowest u
    among the wet points (samples with none are left out), phase-averaged over whole periods
    (:func:`phase_average`), and the highest per period.

    Args:
        u: horizontal velocity [m/s], shape (n_samples, n_points).
        wet: whether each point is in the water, same shape (e.g. kernel sum >= 0.5).
        t: times [s], strictly increasing.
        period: wave period T [s].
        depth: still-water depth D at the vertical [m], for ``sqrt(g D)``.
        n_waves: average the last n_waves periods; default all whole ones.
    """
    uu = _series("u", u, min_ndim=2)
    w = np.asarray(wet, dtype=bool)
    if uu.ndim != 2 or w.shape != uu.shape:
        raise ValueError(f"u, wet: expected two arrays of one shape (n_samples, n_points), "
                         f"got {uu.shape} and {w.shape}")
    tt = _times(t, uu.shape[0], "u")
    D = _scalar_positive("depth", depth)
    # samples with no wet point (a thin swash layer under the lowest point) are left out: the
    # phase average interpolates in time between the samples kept
    keep = w.any(axis=1)
    if np.count_nonzero(keep) < 2:
        raise ValueError("wet: fewer than two samples have a wet point on the vertical")
    uu, w, tt = uu[keep], w[keep], tt[keep]
    top = np.where(w, uu, -np.inf).max(axis=1)
    bottom = np.where(w, uu, np.inf).min(axis=1)
    highest = phase_average(top, tt, period, n_waves)
    lowest = phase_average(bottom, tt, period, n_waves)
    per_wave = runup_per_wave(top, tt, period, 0.0, highest.n_waves)
    return CrestVelocity(
        crest=float(np.max(highest.mean)),
        trough=float(np.min(lowest.mean)),
        crest_per_wave=per_wave.values,
        sqrt_gd=math.sqrt(g * D),
        n_waves=highest.n_waves,
    )


@dataclass(frozen=True)
class MeanLevelBlocks:
    """The mean water level over consecutive blocks of whole periods.

    Attributes:
        starts: start time of each block [s].
        means: the mean level over each block [m].
        block_periods: periods per block.
        spread: ``max(means) - min(means)`` [m]: how far the mean level wanders over the record.
        drift: ``means[-1] - means[0]`` [m].
    """

    starts: FloatArray
    means: FloatArray
    block_periods: int
    spread: float
    drift: float


def mean_level_blocks(
    eta: npt.ArrayLike, t: npt.ArrayLike, period: float, block_periods: int
) -> MeanLevelBlocks:
    """Mean level of a gauge record over consecutive blocks of ``block_periods`` whole periods
    from the first whole period (``[j T, (j + block_periods) T)``, time averages by the
    trapezoid rule), to see whether the level drifts over a long run (a paddle's mean position
    creeping, water lost or reflected set-up building up)."""
    e = _series("eta", eta)
    if e.ndim != 1:
        raise ValueError(f"eta: expected a 1-D record, got shape {e.shape}")
    tt = _times(t, e.size, "eta")
    T = _scalar_positive("period", period)
    if not isinstance(block_periods, (int, np.integer)) or block_periods < 1:
        raise ValueError(f"block_periods: must be a positive integer, got {block_periods!r}")
    first, last, available = _whole_waves(tt, T, 0.0, None, "eta")
    n_blocks = available // int(block_periods)
    if n_blocks < 1:
        raise ValueError(f"eta: the record holds {available} whole periods, fewer than "
                         f"block_periods = {block_periods}")
    starts = (first + np.arange(n_blocks) * block_periods) * T
    means = np.empty(n_blocks)
    # the record's own sampling, at least 16 points a period
    per_period = max(16, round(T / float(np.median(np.diff(tt)))))
    for b, start in enumerate(starts):
        grid = np.linspace(start, start + block_periods * T, per_period * block_periods + 1)
        means[b] = _trapezoid(np.interp(grid, tt, e), grid) / (block_periods * T)
    return MeanLevelBlocks(starts=starts, means=means, block_periods=int(block_periods),
                           spread=float(np.ptp(means)), drift=float(means[-1] - means[0]))


def load_statistics(
    t: npt.ArrayLike, fx: npt.ArrayLike, fz: npt.ArrayLike
) -> dict[str, float | int | None]:
    """Statistics of the wave loads on a structure from its horizontal and vertical force
    records (one force unit: N, or N/m per unit width).

    - ``Fx_max``, ``Fx_min``, ``Fz_max``, ``Fz_min``, ``Fx_mean``, ``Fz_mean``: extremes and
      means over the record;
    - ``impulse``: the impulse of the largest event, the integral of ``Fx - Fx_mean`` over the
      excursion above the mean that holds ``Fx_max`` (trapezoidal, crossings interpolated
      linearly), with ``impulse_start`` and ``impulse_end`` its times;
    - ``Fx_significant``: the mean of the highest third of the per-wave maxima of ``Fx``,
      a wave running from one zero-up-crossing of ``Fx - Fx_mean`` to the next (the
      significant force, as the significant height of the waves that cause it), with
      ``n_waves``; None with fewer than one complete wave.

    Raises:
        ValueError: bad input (NaN, mismatched lengths, time not increasing).
    """
    x = _series("fx", fx)
    z = _series("fz", fz)
    tt = _times(t, x.size, "fx")
    if z.size != x.size:
        raise ValueError(f"fz: expected {x.size} samples like fx, got {z.size}")
    mean = float(np.mean(x))
    out: dict[str, float | int | None] = {
        "Fx_max": float(np.max(x)), "Fx_min": float(np.min(x)),
        "Fz_max": float(np.max(z)), "Fz_min": float(np.min(z)),
        "Fx_mean": mean, "Fz_mean": float(np.mean(z)),
    }
    out.update(_largest_event_impulse(tt, x - mean))
    try:
        waves = zero_crossing_waves(x, tt, kind="up", mean_level=mean)
    except ValueError:
        out["Fx_significant"], out["n_waves"] = None, 0
        return out
    maxima = np.sort(waves.crest_elevations)[::-1]
    third = max(1, maxima.size // 3)
    out["Fx_significant"] = float(np.mean(maxima[:third]))
    out["n_waves"] = int(maxima.size)
    return out


def _largest_event_impulse(t: FloatArray, excess: FloatArray) -> dict[str, float | None]:
    """``impulse``, ``impulse_start``, ``impulse_end`` of the run of positive ``excess`` around
    its largest value (see :func:`load_statistics`)."""
    peak = int(np.argmax(excess))
    if excess[peak] <= 0.0:
        return {"impulse": 0.0, "impulse_start": None, "impulse_end": None}
    first = peak
    while first > 0 and excess[first - 1] > 0.0:
        first -= 1
    last = peak
    while last < excess.size - 1 and excess[last + 1] > 0.0:
        last += 1
    times, values = list(t[first:last + 1]), list(excess[first:last + 1])
    if first > 0:  # the up-crossing, interpolated between the samples around it
        a, b = excess[first - 1], excess[first]
        times.insert(0, t[first - 1] + (t[first] - t[first - 1]) * a / (a - b))
        values.insert(0, 0.0)
    if last < excess.size - 1:
        a, b = excess[last], excess[last + 1]
        times.append(t[last] + (t[last + 1] - t[last]) * a / (a - b))
        values.append(0.0)
    return {"impulse": _trapezoid(np.asarray(values), np.asarray(times)),
            "impulse_start": float(times[0]), "impulse_end": float(times[-1])}
