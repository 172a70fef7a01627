"""watersim.analysis on synthetic signals whose answers are known exactly."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from watersim import analysis as an
from watersim import wave_theory as wt

# ------------------------------------------------------------------------------------------------
# Zero crossings


def known_wave_train(troughs, crests, periods, dt=1e-3, t0=0.3):
    """Waves starting at a down-crossing: -trough sin on the first half, -crest sin on the second.

    Each wave i is ``-b_i sin(2 pi tau / T_i)`` for tau < T_i/2 and ``-c_i sin(2 pi tau / T_i)``
    after, so its zero-down-crossing height is b_i + c_i and period T_i exactly. A short flat
    positive lead-in starts the record above zero.
    """
    t_parts, eta_parts = [np.arange(0.0, t0, dt)], [np.full(round(t0 / dt), 0.01)]
    start = t0
    for b, c, T in zip(troughs, crests, periods, strict=True):
        tau = np.arange(0.0, T, dt)
        wave = -np.where(tau < T / 2, b, c) * np.sin(2 * np.pi * tau / T)
        t_parts.append(start + tau)
        eta_parts.append(wave)
        start += T
    t_parts.append(np.array([start, start + dt]))
    eta_parts.append(np.array([0.0, -0.01]))
    return np.concatenate(t_parts), np.concatenate(eta_parts)


def test_zero_down_crossing_heights_and_periods_of_a_known_irregular_signal() -> None:
    troughs = np.array([0.05, 0.02, 0.08, 0.03, 0.06, 0.04])
    crests = np.array([0.04, 0.03, 0.07, 0.02, 0.05, 0.06])
    periods = np.array([1.0, 0.8, 1.4, 0.9, 1.2, 1.1])
    t, eta = known_wave_train(troughs, crests, periods)
    waves = an.zero_crossing_waves(eta, t, mean_level=0.0)
    heights = troughs + crests
    np.testing.assert_allclose(waves.heights, heights, rtol=1e-5)
    np.testing.assert_allclose(waves.periods, periods, atol=1e-9)
    np.testing.assert_allclose(waves.crest_elevations, crests, rtol=1e-5)
    np.testing.assert_allclose(waves.trough_elevations, -troughs, rtol=1e-5)
    np.testing.assert_allclose(waves.crest_times, waves.start_times + 0.75 * periods, atol=2e-3)
    assert waves.mean_height == pytest.approx(heights.mean(), rel=1e-5)
    assert waves.significant_height == pytest.approx(np.mean([0.15, 0.11]), rel=1e-5)  # 2 of 6
    assert waves.max_height == pytest.approx(0.15, rel=1e-5)
    assert waves.mean_period == pytest.approx(periods.mean(), abs=1e-9)


def test_zero_up_crossing_waves() -> None:
    t = np.arange(0.0, 10.0, 0.01)
    eta = 0.1 * np.sin(2 * np.pi * t / 2.0 + 0.5) + 0.3
    waves = an.zero_crossing_waves(eta, t, kind="up")
    assert waves.mean_level == pytest.approx(0.3, abs=2e-3)
    np.testing.assert_allclose(waves.heights, 0.2, rtol=1e-4)
    np.testing.assert_allclose(waves.periods, 2.0, atol=1e-4)
    assert waves.heights.size == 4


def test_zero_crossing_needs_a_complete_wave() -> None:
    t = np.linspace(0, 1, 50)
    with pytest.raises(ValueError, match=r"^eta:"):
        an.zero_crossing_waves(np.sin(np.pi * t), t)


# ------------------------------------------------------------------------------------------------
# Harmonics


@given(
    amplitudes=st.lists(st.floats(min_value=1e-4, max_value=0.1), min_size=4, max_size=4),
    phases=st.lists(st.floats(min_value=-3.1, max_value=3.1), min_size=4, max_size=4),
    mean=st.floats(min_value=-0.05, max_value=0.05),
    window=st.sampled_from(["rectangular", "hann"]),
)
def test_harmonic_amplitudes_and_phases_of_a_sum_of_harmonics(
    amplitudes: list[float], phases: list[float], mean: float, window: str
) -> None:
    T, dt = 1.6, 0.02
    t = 3.7 + np.arange(0, 2000) * dt  # 25 periods, not starting at a period boundary
    eta = mean + sum(
        a * np.cos(2 * np.pi * (n + 1) * t / T + p)
        for n, (a, p) in enumerate(zip(amplitudes, phases, strict=True))
    )
    h = an.harmonic_analysis(eta, t, T, n_harmonics=5, window=window)
    np.testing.assert_allclose(h.frequencies, np.arange(1, 6) / T)
    np.testing.assert_allclose(h.amplitudes[:4], amplitudes, atol=1e-12)
    np.testing.assert_allclose(np.angle(np.exp(1j * (h.phases[:4] - phases))), 0.0, atol=1e-8)
    assert h.amplitudes[4] < 1e-12
    assert float(h.mean) == pytest.approx(mean, abs=1e-12)
    assert h.n_periods == 25


def test_harmonics_of_a_gauge_matrix() -> None:
    T = 2.0
    t = np.arange(0, 40, 0.05)
    amps = np.array([0.01, 0.02, 0.03])
    eta = amps * np.cos(2 * np.pi * t[:, None] / T - np.array([0.0, 1.0, 2.0]))
    eta += 0.2 * amps * np.cos(4 * np.pi * t[:, None] / T)
    h = an.harmonic_analysis(eta, t, T, n_harmonics=2, n_periods=10)
    assert h.amplitudes.shape == (2, 3)
    np.testing.assert_allclose(h.amplitudes[0], amps, rtol=1e-12)
    np.testing.assert_allclose(h.amplitudes[1], 0.2 * amps, rtol=1e-12)
    np.testing.assert_allclose(h.phases[0], [0.0, -1.0, -2.0], atol=1e-12)
    assert h.window_start == pytest.approx(20.0)


# ------------------------------------------------------------------------------------------------
# Incident / reflected separation


def incident_and_reflected(t, x, f, k, a_i, a_r, phi_i, phi_r):
    """eta(t, x) of incident (towards +x) and reflected components; arrays over components."""
    f, k = np.atleast_1d(f), np.atleast_1d(k)
    arg = 2 * np.pi * np.multiply.outer(t, f)[:, None, :]
    kx = np.multiply.outer(x, k)[None, :, :]
    return np.sum(a_i * np.cos(arg - kx + phi_i) + a_r * np.cos(arg + kx + phi_r), axis=2)


@pytest.mark.parametrize("n_gauges", [2, 3])
def test_regular_wave_reflection_coefficient(n_gauges: int) -> None:
    T, d, kr = 1.5, 0.6, 0.3
    k = float(wt.wavenumber(T, d))
    L = 2 * np.pi / k
    x = 5.0 + np.array([0.0, 0.12 * L, 0.31 * L])[:n_gauges]
    t = np.arange(0, 60, 0.02)
    eta = incident_and_reflected(t, x, 1 / T, k, 0.04, kr * 0.04, 0.7, -2.0)
    # A bound second harmonic travelling with the incident wave must not disturb the result.
    eta += 0.004 * np.cos(4 * np.pi * t[:, None] / T - 2 * k * x + 1.4)
    eta += np.random.default_rng(3).normal(0.0, 4e-4, eta.shape)
    separate = an.goda_suzuki if n_gauges == 2 else an.mansard_funke
    r = separate(eta, t, x, d, period=T)
    assert r.reflection_coefficient == pytest.approx(kr, rel=0.01)
    assert r.incident_amplitudes[0] == pytest.approx(0.04, rel=0.005)
    assert r.incident_phases[0] == pytest.approx(0.7, abs=0.01)
    assert r.reflected_phases[0] == pytest.approx(-2.0, abs=0.05)


@pytest.mark.parametrize("n_gauges", [2, 3])
def test_irregular_wave_reflection_coefficient(n_gauges: int) -> None:
    d, tp, kr = 0.5, 1.6, 0.25
    dt = 0.04
    n = 5000  # 200 s: every component below sits on an FFT frequency of the record
    paddle = wt.irregular_paddle_motion(0.08, tp, d, seed=11, repeat_period=n * dt)
    band = (0.7 / tp, 1.4 / tp)
    keep = (paddle.frequencies >= band[0]) & (paddle.frequencies <= band[1])
    f, k, a = paddle.frequencies[keep], paddle.wavenumbers[keep], paddle.wave_amplitudes[keep]
    rng = np.random.default_rng(5)
    phi_r = rng.uniform(0, 2 * np.pi, f.size)
    lp = float(wt.wavelength(tp, d))
    x = np.array([2.0, 2.0 + 0.2 * lp, 2.0 + 0.3 * lp])[:n_gauges]
    t = np.arange(n) * dt
    eta = incident_and_reflected(t, x, f, k, a, kr * a, paddle.phases[keep], phi_r)
    separate = an.goda_suzuki if n_gauges == 2 else an.mansard_funke
    r = separate(eta, t, x, d, frequency_band=band)
    assert np.all(r.valid)
    assert r.reflection_coefficient == pytest.approx(kr, rel=0.01)
    on_components = np.isin(np.round(r.frequencies * n * dt), np.round(f * n * dt))
    np.testing.assert_allclose(r.incident_amplitudes[on_components], a, rtol=1e-6)


def test_gauges_half_a_wavelength_apart_are_flagged() -> None:
    T, d = 1.5, 0.6
    k = float(wt.wavenumber(T, d))
    x = np.array([0.0, 0.51 * 2 * np.pi / k])
    t = np.arange(0, 30, 0.02)
    eta = incident_and_reflected(t, x, 1 / T, k, 0.04, 0.01, 0.0, 0.0)
    with pytest.warns(an.GaugeSpacingWarning, match="L/2"):
        r = an.goda_suzuki(eta, t, x, d, period=T)
    assert not r.valid[0]
    assert math.isnan(r.reflection_coefficient)


def test_reflection_input_checks() -> None:
    t = np.arange(0, 10, 0.1)
    eta = np.zeros((t.size, 2))
    with pytest.raises(ValueError, match=r"^eta:"):
        an.mansard_funke(eta, t, [0, 1, 2], 1.0, period=2.0)
    with pytest.raises(ValueError, match=r"^positions:"):
        an.goda_suzuki(eta, t, [0.0, 0.0], 1.0, period=2.0)
    with pytest.raises(ValueError, match=r"^period:"):
        an.goda_suzuki(eta, t, [0.0, 0.3], 1.0)
    with pytest.raises(ValueError, match=r"^t:"):
        an.goda_suzuki(eta, t[:-1], [0.0, 0.3], 1.0, period=2.0)


# ------------------------------------------------------------------------------------------------
# Phase averaging


def test_phase_average_recovers_a_periodic_signal_under_noise() -> None:
    # 50 samples per period, so every phase falls on a sample (no interpolation of the noise).
    T, sigma = 1.275, 0.01
    dt = T / 50
    t = np.arange(0, 140 * 50) * dt

    def clean(time):
        return 0.05 * np.cos(2 * np.pi * time / T) + 0.015 * np.cos(4 * np.pi * time / T - 0.5)

    eta = clean(t) + np.random.default_rng(0).normal(0.0, sigma, t.size)
    avg = an.phase_average(eta, t, T, n_waves=128)
    assert avg.n_waves == 128
    assert avg.phases.size == 50
    assert avg.phases[0] == 0.0 and avg.phases[-1] == pytest.approx(2 * np.pi * 49 / 50)
    # The mean of 128 waves is within 4.5 standard errors of the clean signal at every phase.
    assert np.max(np.abs(avg.mean - clean(avg.times))) < 4.5 * sigma / math.sqrt(128)
    np.testing.assert_allclose(avg.std, sigma, rtol=0.25)
    assert avg.first_wave_start == pytest.approx((139 - 128) * T)


def test_phase_average_of_fields() -> None:
    T = 2.0
    t = np.arange(0.0, 21.0, 0.1)
    field = np.cos(2 * np.pi * t / T)[:, None, None] * np.arange(6.0).reshape(1, 2, 3)
    avg = an.phase_average(field, t, T)
    assert avg.mean.shape == (20, 2, 3)
    assert avg.n_waves == 10
    np.testing.assert_allclose(
        avg.mean, np.cos(avg.phases)[:, None, None] * np.arange(6.0).reshape(1, 2, 3), atol=1e-12
    )
    np.testing.assert_allclose(avg.std, 0.0, atol=1e-7)


def test_phase_average_rejects_too_many_waves() -> None:
    t = np.arange(0.0, 10.0, 0.1)
    with pytest.raises(ValueError, match=r"^n_waves:"):
        an.phase_average(np.sin(t), t, 2.0, n_waves=10)


# ------------------------------------------------------------------------------------------------
# Envelopes and set-up


def test_envelopes_and_setup() -> None:
    t = np.arange(0.0, 20.0, 0.01)
    amplitude = np.array([0.05, 0.06, 0.03])
    setup = np.array([-0.002, 0.0, 0.01])
    eta = setup + amplitude * np.sin(2 * np.pi * t[:, None] / 2.0)
    env = an.water_level_envelopes(eta, still_water_level=0.0)
    np.testing.assert_allclose(env.maximum, setup + amplitude, rtol=1e-6)
    np.testing.assert_allclose(env.minimum, setup - amplitude, rtol=1e-6)
    np.testing.assert_allclose(env.setup, setup, atol=1e-12)
    np.testing.assert_allclose(env.mid_level, setup, atol=1e-9)


# ------------------------------------------------------------------------------------------------
# Breaking onset


def test_breaking_onset_from_gauges() -> None:
    T = 2.0
    t = np.arange(0.0, 20.0, 0.01)
    positions = np.array([10.0, 11.0, 12.0, 13.0, 14.0])
    depths = np.array([0.40, 0.30, 0.20, 0.12, -0.02])
    heights = np.array([0.10, 0.14, 0.17, 0.10, 0.0])  # H/d: 0.25, 0.47, 0.85, 0.83, dry
    eta = 0.5 * heights * np.cos(2 * np.pi * t[:, None] / T - positions)
    order = np.array([3, 0, 4, 2, 1])  # gauges need not be given in x order
    onset = an.breaking_onset_from_gauges(
        eta[:, order], t, positions[order], depths[order], slope=1 / 10, period=T
    )
    assert onset is not None
    assert onset.position == 12.0
    assert onset.index == 3
    assert onset.wave_height == pytest.approx(0.17, rel=1e-4)
    first_crest = t[np.argmax(eta[: round(T / 0.01) + 200, 2])]
    assert onset.time >= first_crest - 1e-9
    xi = (1 / 10) / math.sqrt(0.17 / float(wt.deep_water_wavelength(T)))  # 0.61
    assert onset.iribarren == pytest.approx(xi, rel=1e-4)
    assert onset.breaker_type == "plunging"
    calm = an.breaking_onset_from_gauges(eta[:, :2], t, positions[:2], depths[:2])
    assert calm is None


def test_breaking_onset_from_crest_kinematics() -> None:
    crest_x = np.linspace(8.0, 12.0, 41)
    crest_t = np.linspace(0.0, 4.0, 41)
    celerity = np.full(41, 1.2)
    speed = np.linspace(0.6, 1.2, 41)  # exceeds 0.85 * 1.2 = 1.02 first at index 28 (1.02 + ...)
    onset = an.breaking_onset_from_crests(
        crest_x, crest_t, speed, celerity, wave_height=0.14, slope=1 / 15, period=1.275
    )
    assert onset is not None
    i = int(np.flatnonzero(speed > 1.02)[0])
    assert onset.index == i
    assert onset.position == pytest.approx(crest_x[i])
    assert onset.time == pytest.approx(crest_t[i])
    assert onset.breaker_type == "spilling"  # xi = 0.28 for the seed 001 flume
    assert an.breaking_onset_from_crests(crest_x, crest_t, 0.5 * speed, celerity) is None
    with pytest.raises(ValueError, match=r"^crest_speed:"):
        an.breaking_onset_from_crests(crest_x, crest_t, speed[:-1], celerity)


def _water(dp: float, length: float = 2.0, depth: float = 0.3) -> np.ndarray:
    """A still lattice of fluid particles (x, z), spacing dp."""
    x, z = np.meshgrid(np.arange(0.0, length, dp) + dp / 2, np.arange(0.0, depth, dp) + dp / 2)
    return np.c_[x.ravel(), z.ravel()]


def test_overturned_surface_finds_a_jet_over_air_and_nothing_else() -> None:
    dp = 0.02
    water = _water(dp)
    assert an.overturned_surface(water, dp) is None
    # a jet four columns wide, 4 dp above the surface particles (3 dp of air), from x = 1.0
    jet = np.array([[1.0 + dp * (i + 0.5), 0.29 + 4 * dp] for i in range(4)])
    found = an.overturned_surface(np.r_[water, jet], dp)
    assert found is not None
    assert (found.x_min, found.x_max) == pytest.approx((1.0, 1.08))
    assert (found.n_columns, found.n_particles) == (4, 4)
    assert (found.z_gap_bottom, found.z_gap_top) == pytest.approx((0.29, 0.37))
    # the same in 3D coordinates (x, y, z): only x and z count
    xyz = np.c_[np.r_[water, jet][:, 0], np.zeros(len(water) + 4), np.r_[water, jet][:, 1]]
    assert an.overturned_surface(xyz, dp) == found
    # spray: one drop, or two drops in columns apart, or a jet with too little air below it
    assert an.overturned_surface(np.r_[water, jet[:1]], dp) is None
    assert an.overturned_surface(np.r_[water, jet[[0, 2]]], dp) is None
    low = jet - [0.0, 1.5 * dp]  # 1.5 dp of air: a wavy surface, not a jet
    assert an.overturned_surface(np.r_[water, low], dp) is None
    assert an.overturned_surface(np.r_[water, low], dp, min_gap=1.0) is not None
    # a void above one particle caught next to the bed is not an overturn
    lone = np.array([[0.51, 0.01], [0.53, 0.01], [0.51, 0.10], [0.53, 0.10], [0.51, 0.12],
                     [0.53, 0.12]])
    assert an.overturned_surface(lone, dp) is None
    assert an.overturned_surface(np.r_[lone, lone[:2] + [0.0, dp]], dp) is not None
    # a void inside the water is closed on both sides: not an overturn
    void = water[~((np.abs(water[:, 0] - 1.04) < 0.03) & (np.abs(water[:, 1] - 0.15) < 0.05))]
    assert an.overturned_surface(void, dp) is None
    assert an.overturned_surface(void[void[:, 0] < 1.07], dp) is not None  # opened ahead
    # outside the window it is not seen
    assert an.overturned_surface(np.r_[water, jet], dp, x_range=(1.2, 2.0)) is None
    # a window edge inside a column does not make a half-empty column (rows shifted by
    # +-dp/4 in turn: cutting a column in its middle would leave every other row, 2 dp apart)
    shift = np.where(np.round(water[:, 1] / dp - 0.5) % 2 == 0, -0.25 * dp, 0.25 * dp)
    rows = water + np.c_[shift, np.zeros_like(shift)]
    loose = {"min_gap": 0.5, "min_columns": 1, "min_particles": 1}
    assert an.overturned_surface(rows, dp, **loose) is None
    assert an.overturned_surface(rows, dp, x_range=(1.01, 1.5), **loose) is None
    inside = an.overturned_surface(np.r_[water, jet], dp, x_range=(0.995, 1.2))
    assert inside is not None and inside.x_min == pytest.approx(0.995)
    # the widest of two overhangs
    jet2 = np.array([[1.5 + dp * (i + 0.5), 0.29 + 5 * dp] for i in range(6)])
    wide = an.overturned_surface(np.r_[water, jet, jet2], dp)
    assert wide is not None and wide.n_columns == 6 and wide.x_min == pytest.approx(1.5)
    with pytest.raises(ValueError, match=r"^positions:"):
        an.overturned_surface(water[:, :1], dp)
    with pytest.raises(ValueError, match=r"^dp:"):
        an.overturned_surface(water, 0.0)
    with pytest.raises(ValueError, match=r"^x_range:"):
        an.overturned_surface(water, dp, x_range=(2.0, 1.0))


# ------------------------------------------------------------------------------------------------
# Run-up


def test_runup_per_wave_of_a_known_series() -> None:
    T, dt = 1.275, 0.005
    peaks = np.array([0.05, 0.07, 0.06, 0.09, 0.04, 0.08])
    t = np.arange(0.0, peaks.size * T + 0.3, dt)
    wave = np.minimum(np.floor(t / T).astype(int), peaks.size - 1)
    phase = (t % T) / T
    swl = 0.02
    runup = swl + peaks[wave] * np.sin(np.pi * phase) ** 2 - 0.01
    r = an.runup_per_wave(runup, t, T, still_water_level=swl)
    # Samples every 0.005 s straddle the peaks: 1e-5 m of sampling error.
    np.testing.assert_allclose(r.values, peaks - 0.01, atol=1e-5)
    np.testing.assert_allclose(r.window_starts, np.arange(peaks.size) * T)
    assert r.mean == pytest.approx(np.mean(peaks - 0.01), abs=1e-5)
    assert r.std == pytest.approx(np.std(peaks), abs=1e-5)
    last3 = an.runup_per_wave(runup, t, T, still_water_level=swl, n_waves=3)
    np.testing.assert_allclose(last3.values, peaks[-3:] - 0.01, atol=1e-5)


# ------------------------------------------------------------------------------------------------
# Spectrum


def test_spectrum_of_a_synthesised_jonswap_sea() -> None:
    hs, tp, dt = 0.1, 2.0, 0.1
    paddle = wt.irregular_paddle_motion(hs, tp, 1.0, seed=4, frequency_range=(0.4, 5.0))
    t = np.arange(0.0, paddle.repeat_period, dt)  # 256 Tp, one repeat period
    eta = paddle.target_elevation(t)
    spec = an.wave_spectrum(eta, t, segment_duration=32 * tp)
    assert spec.hm0 == pytest.approx(hs, rel=0.02)
    assert spec.tp == pytest.approx(tp, rel=0.05)
    assert 0.7 * tp < spec.tm01 < tp


# ------------------------------------------------------------------------------------------------
# Bad input


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: an.zero_crossing_waves([0.0, 1.0, float("nan")], [0, 1, 2]), "eta"),
        (lambda: an.zero_crossing_waves([0.0, 1.0, -1.0], [0, 1]), "t"),
        (lambda: an.zero_crossing_waves([0.0, 1.0, -1.0], [0, 2, 1]), "t"),
        (lambda: an.zero_crossing_waves([0.0, 1.0, -1.0], [0, 1, 2], kind="sideways"), "kind"),
        (lambda: an.harmonic_analysis(np.zeros(100), np.arange(100.0), 0.0), "period"),
        (lambda: an.harmonic_analysis(np.zeros(100), np.arange(100.0), -2.0), "period"),
        (lambda: an.harmonic_analysis(np.zeros(3), [0, 1, 3], 1.0), "t"),
        (
            lambda: an.harmonic_analysis(np.zeros(100), np.arange(100.0), 10.0, n_harmonics=0),
            "n_harmonics",
        ),
        (
            lambda: an.harmonic_analysis(np.zeros(100), np.arange(100.0), 10.0, n_periods=11),
            "n_periods",
        ),
        (
            lambda: an.harmonic_analysis(np.zeros(100), np.arange(100.0), 60.0, window="hann"),
            "n_periods",
        ),
        (
            lambda: an.harmonic_analysis(np.zeros(100), np.arange(100.0), 10.0, window="flat"),
            "window",
        ),
        (lambda: an.phase_average(np.zeros(10), np.arange(10.0), float("nan")), "period"),
        (lambda: an.water_level_envelopes([[0.0, float("inf")]]), "eta"),
        (lambda: an.runup_per_wave(np.zeros(10), np.arange(10.0), 20.0), "runup"),
        (
            lambda: an.breaking_onset_from_gauges(
                np.zeros((10, 2)), np.arange(10.0), [0, 1], [1.0]
            ),
            "depths",
        ),
        (
            lambda: an.wave_spectrum(np.zeros(100), np.arange(100.0), segment_duration=1.0),
            "segment_duration",
        ),
        (
            lambda: an.goda_suzuki(np.zeros((10, 2)), np.arange(10.0), [0, 1], -1.0, period=2.0),
            "depth",
        ),
    ],
)
def test_bad_input_raises_value_error_naming_the_argument(call, name: str) -> None:
    with pytest.raises(ValueError, match=rf"^{name}:"):
        call()
