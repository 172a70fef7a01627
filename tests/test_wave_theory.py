"""watersim.wave_theory against independent values, limits and the printed source formulas.

Reference values marked "mpmath" were computed once, outside this suite, with mpmath at 40
significant digits directly from the printed formulas of shared/validation/wave_theory/
FORMULAS.md (findroot on the dispersion relation; the cosh/sinh forms of §2-§4), so they do not
share any code or rewriting with the module under test.
"""

from __future__ import annotations

import csv
import math
from importlib import resources

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from watersim import wave_theory as wt

G = 9.81

# ------------------------------------------------------------------------------------------------
# Dispersion

# (T [s], d [m], k [rad/m]) by mpmath findroot of omega^2 = g k tanh(k d), g = 9.81.
MPMATH_DISPERSION = [
    (1.0, 0.5, 4.1528452520722599096),
    (2.0, 1.0, 1.204743244600718658),
    (1.275, 0.705, 2.6046389859819055343),
    (2.02, 0.4, 1.6812441792762890076),
    (10.0, 5.0, 0.092836039143902012451),
    (20.0, 0.5, 0.14196937191813942268),
    (0.5, 10.0, 16.097214109829738828),
]


@given(
    kd=st.floats(min_value=1e-3, max_value=50.0),
    depth=st.floats(min_value=1e-2, max_value=1e3),
)
def test_dispersion_residual_is_at_machine_precision(kd: float, depth: float) -> None:
    k_true = kd / depth
    omega = math.sqrt(G * k_true * math.tanh(kd))
    k = float(wt.wavenumber_from_omega(omega, depth))
    residual = abs(omega**2 - G * k * math.tanh(k * depth)) / omega**2
    assert residual < 1e-12
    assert k == pytest.approx(k_true, rel=1e-12)


@pytest.mark.parametrize(("period", "depth", "k_ref"), MPMATH_DISPERSION)
def test_dispersion_matches_independent_high_precision_roots(
    period: float, depth: float, k_ref: float
) -> None:
    assert float(wt.wavenumber(period, depth)) == pytest.approx(k_ref, rel=1e-14)


def test_dispersion_is_vectorised_and_broadcasts() -> None:
    periods = np.array([[1.0, 2.0], [1.275, 2.02]])
    depths = np.array([0.5, 1.0])
    k = wt.wavenumber(periods, depths)
    assert k.shape == (2, 2)
    assert k[0, 0] == pytest.approx(MPMATH_DISPERSION[0][2], rel=1e-14)
    assert k[0, 1] == pytest.approx(MPMATH_DISPERSION[1][2], rel=1e-14)
    assert np.ndim(wt.wavenumber(2.0, 1.0)) == 0


def test_deep_and_shallow_water_limits() -> None:
    T = 1.0
    omega = 2 * math.pi / T
    assert float(wt.wavenumber(T, 1000.0)) == pytest.approx(omega**2 / G, rel=1e-14)
    assert float(wt.wavelength(T, 1000.0)) == pytest.approx(float(wt.deep_water_wavelength(T)))
    # Shallow: k -> omega / sqrt(g d); relative correction ~ (kd)^2 / 6.
    T, d = 200.0, 0.1
    k_shallow = 2 * math.pi / T / math.sqrt(G * d)
    assert float(wt.wavenumber(T, d)) == pytest.approx(k_shallow, rel=1e-5)
    assert float(wt.celerity(T, d)) == pytest.approx(math.sqrt(G * d), rel=1e-5)
    assert float(wt.group_velocity(T, d)) == pytest.approx(math.sqrt(G * d), rel=1e-5)
    assert float(wt.group_velocity(1.0, 1000.0)) == pytest.approx(
        0.5 * float(wt.celerity(1.0, 1000.0)), rel=1e-12
    )


def test_kimmoun_flume_wavelength_matches_seed_001() -> None:
    # Seed 001 section 2: T = 1.275 s, d = 0.705 m, measured wavelength 2.41 m at x = 4 m.
    assert float(wt.wavelength(1.275, 0.705)) == pytest.approx(2.41, abs=0.005)
    # Seed 001 section 4 uses L0 = 2.54 m for the same period.
    assert float(wt.deep_water_wavelength(1.275)) == pytest.approx(2.54, abs=0.005)


# ------------------------------------------------------------------------------------------------
# Biesel transfer functions


def biesel_piston_printed(kd: float) -> float:
    return 2 * (math.cosh(2 * kd) - 1) / (math.sinh(2 * kd) + 2 * kd)


def biesel_flap_printed(kd: float) -> float:
    return (
        4
        * (math.sinh(kd) / kd)
        * (kd * math.sinh(kd) - math.cosh(kd) + 1)
        / (math.sinh(2 * kd) + 2 * kd)
    )


@given(kd=st.floats(min_value=0.05, max_value=20.0))
def test_transfer_functions_equal_the_printed_forms(kd: float) -> None:
    assert float(wt.piston_height_to_stroke(kd, 1.0)) == pytest.approx(
        biesel_piston_printed(kd), rel=1e-12
    )
    assert float(wt.flap_height_to_stroke(kd / 2.0, 2.0)) == pytest.approx(
        biesel_flap_printed(kd), rel=1e-11
    )


def test_biesel_limits() -> None:
    kd = np.array([1e-5, 1e-4, 1e-3])
    np.testing.assert_allclose(wt.piston_height_to_stroke(kd, 1.0) / kd, 1.0, rtol=1e-5)
    np.testing.assert_allclose(wt.flap_height_to_stroke(kd, 1.0) / (kd / 2.0), 1.0, rtol=1e-5)
    assert float(wt.piston_height_to_stroke(50.0, 1.0)) == pytest.approx(2.0, rel=1e-14)
    # The flap tends to 2 as 2 (1 - 1/kd): slowly.
    big = np.array([1e2, 1e3, 1e5])
    np.testing.assert_allclose(wt.flap_height_to_stroke(big, 1.0), 2.0 * (1 - 1 / big), rtol=1e-12)
    # No overflow far into deep water (warnings are errors in this suite).
    assert float(wt.piston_height_to_stroke(1e4, 1.0)) == 2.0


def test_strokes_invert_the_transfer_functions() -> None:
    H, T, d = 0.1, 1.5, 0.6
    k = float(wt.wavenumber(T, d))
    assert float(wt.piston_stroke(H, T, d)) == pytest.approx(H / biesel_piston_printed(k * d))
    assert float(wt.flap_stroke(H, T, d)) == pytest.approx(H / biesel_flap_printed(k * d))


# ------------------------------------------------------------------------------------------------
# Madsen second order and the paddle motion law


def test_madsen_correction_on_the_kimmoun_wave() -> None:
    # mpmath, FORMULAS §3 with H = 0.114 m, T = 1.275 s, d = 0.705 m (kd = 1.836).
    law = wt.regular_paddle_motion(0.114, 1.275, 0.705, "piston", order=2)
    assert law.stroke == pytest.approx(0.071173693389393732664, rel=1e-13)
    assert law.second_order_amplitude == pytest.approx(-0.00052471772874319659974, rel=1e-12)
    # Intermediate depth: negative and small against the first harmonic (S/2 = 35.6 mm).
    assert -0.02 < law.second_order_amplitude / (law.stroke / 2) < 0


def test_madsen_correction_is_positive_in_shallow_water() -> None:
    # mpmath, FORMULAS §3, H = 0.05 m, T = 3 s, d = 0.3 m (kd = 0.375).
    law = wt.regular_paddle_motion(0.05, 3.0, 0.3, "piston", order=2)
    assert law.second_order_amplitude == pytest.approx(0.013447068657441028143, rel=1e-12)
    assert wt.regular_paddle_motion(0.05, 3.0, 0.3).second_order_amplitude == 0.0


def test_piston_motion_law_ramp_and_velocity() -> None:
    H, T, d, n = 0.114, 1.275, 0.705, 2.0
    law = wt.regular_paddle_motion(H, T, d, order=2, phase=0.4)
    t = np.linspace(-1.0, 6 * T, 20001)
    x, u = wt.piston_motion(t, H, T, d, order=2, ramp_periods=n, phase=0.4)
    w = 2 * math.pi / T
    full = law.stroke / 2 * np.sin(w * t + 0.4) + law.second_order_amplitude * np.sin(
        2 * w * t + 0.8
    )
    ramp = np.clip(t / (n * T), 0.0, 1.0)
    np.testing.assert_allclose(x, ramp * full, atol=1e-15)
    assert np.all(x[t <= 0] == 0.0)
    # Velocity is the exact derivative of the displacement, ramp included (away from the ramp's
    # kinks at t = 0 and t = n T).
    dt = t[1] - t[0]
    numeric = np.gradient(x, dt)
    smooth = (np.abs(t - n * T) > 2 * dt) & (np.abs(t) > 2 * dt)
    np.testing.assert_allclose(u[smooth][1:-1], numeric[smooth][1:-1], atol=1e-6)
    # The tanh ramp is smooth and reaches 0.9993 of the motion after n T.
    xt, _ = wt.piston_motion(np.array([n * T]), H, T, d, ramp_periods=n, ramp="tanh")
    x1, _ = wt.piston_motion(np.array([n * T]), H, T, d, ramp_periods=0)
    assert xt[0] == pytest.approx(math.tanh(4.0) * x1[0], rel=1e-12)


def test_flap_motion_uses_the_flap_transfer_function() -> None:
    H, T, d = 0.1, 1.2, 1.0
    x, _ = wt.flap_motion(np.array([T / 4 + 10 * T]), H, T, d, ramp_periods=1)
    assert x[0] == pytest.approx(float(wt.flap_stroke(H, T, d)) / 2, rel=1e-12)


# ------------------------------------------------------------------------------------------------
# Stokes second order


def test_stokes_second_order_against_hand_computed_values() -> None:
    # mpmath, FORMULAS §4 with the (pi H^2 / 8L) cosh kd (2 + cosh 2kd) / sinh^3 kd form:
    # H = 0.1 m, T = 2 s, d = 1 m; eta at x = 0.3 m, t = 0.7 s.
    k = float(wt.wavenumber(2.0, 1.0))
    assert float(wt.stokes2_second_harmonic_amplitude(0.1, k, 1.0)) == pytest.approx(
        0.00297705713602194463, rel=1e-13
    )
    assert float(wt.stokes2_elevation(0.3, 0.7, 0.1, 2.0, 1.0)) == pytest.approx(
        -0.015749811101702521824, rel=1e-12
    )


def test_stokes_second_harmonic_deep_water_limit() -> None:
    k = float(wt.wavenumber(1.0, 100.0))
    assert float(wt.stokes2_second_harmonic_amplitude(0.05, k, 100.0)) == pytest.approx(
        k * 0.05**2 / 8, rel=1e-12
    )


def test_stokes_elevation_at_the_paddle_matches_the_paddle_phase() -> None:
    t = np.linspace(0, 3, 7)
    eta = wt.stokes2_elevation(0.0, t, 0.1, 2.0, 1.0, phase=0.3)
    k = float(wt.wavenumber(2.0, 1.0))
    a2 = float(wt.stokes2_second_harmonic_amplitude(0.1, k, 1.0))
    w = math.pi
    np.testing.assert_allclose(eta, 0.05 * np.cos(w * t + 0.3) + a2 * np.cos(2 * w * t + 0.6))


# ------------------------------------------------------------------------------------------------
# Breaking and breaker type


def test_breaking_limits() -> None:
    assert wt.mccowan_breaking(0.79, 1.0)
    assert not wt.mccowan_breaking(0.77, 1.0)
    np.testing.assert_array_equal(wt.mccowan_breaking([0.5, 0.9], 1.0), [False, True])
    T, d = 1.0, 10.0  # deep water: H_max = 0.142 L0
    assert float(wt.miche_height_limit(T, d)) == pytest.approx(
        0.142 * float(wt.deep_water_wavelength(T)), rel=1e-6
    )
    assert wt.miche_breaking(0.23, T, d) and not wt.miche_breaking(0.21, T, d)
    np.testing.assert_array_equal(wt.kinematic_breaking([0.8, 0.9], 1.0), [False, True])


def test_iribarren_and_breaker_type_thresholds() -> None:
    xi = wt.iribarren(1 / 15, 0.11, 2.54)
    assert float(xi) == pytest.approx((1 / 15) / math.sqrt(0.11 / 2.54))
    assert wt.breaker_type(0.39) == "spilling"
    assert wt.breaker_type(0.4) == "plunging"
    assert wt.breaker_type(2.0) == "plunging"
    assert wt.breaker_type(2.01) == "collapsing/surging"
    assert list(wt.breaker_type([0.1, 1.0, 3.0])) == ["spilling", "plunging", "collapsing/surging"]


def load_ting_kirby() -> dict[tuple[str, str], str]:
    text = (
        resources.files("watersim.data")
        .joinpath("ting_kirby_parameters_transcribed.csv")
        .read_text("utf-8")
    )
    return {
        (row["case"], row["parameter"]): row["value"] for row in csv.DictReader(text.splitlines())
    }


@pytest.mark.parametrize("case", ["spilling", "plunging"])
def test_breaker_type_of_the_ting_kirby_cases(case: str) -> None:
    # Ting & Kirby's named spilling and plunging cases (shipped data, see data/SOURCES.md). The
    # transcribed H is the incident height on the flat, not the breaking height the thresholds
    # want; shoaling raises H and lowers xi, and both cases stay on their side of 0.4.
    params = load_ting_kirby()
    num, den = params[("both", "beach_slope")].split("/")
    slope = float(num) / float(den)
    height = float(params[(case, "incident_wave_height_H")])
    period = float(params[(case, "wave_period_T")])
    xi = float(wt.iribarren(slope, height, wt.deep_water_wavelength(period)))
    assert wt.breaker_type(xi) == case
    if case == "plunging":
        # The measured break depth 0.157 m is below H / 0.78 even for the incident height.
        assert wt.mccowan_breaking(height, float(params[("plunging", "breaking_point_depth_d")]))


# ------------------------------------------------------------------------------------------------
# Run-up formulas (seed 001 section 1), on the inputs the seed lists under its Table 3:
# xi = 0.31, beta = 0.067 rad, H = 0.11 m, L0 = 2.54 m. The seed's Table 3 percentages cannot be
# reproduced from its own equations (e.g. Eq. 1 gives R/H = xi = 0.31, the table 15.62 %), so the
# expected values below are the printed equations evaluated by hand.

XI, BETA, H_TOE, L0 = 0.31, 0.067, 0.11, 2.54


def test_hunt_runup() -> None:
    assert float(wt.hunt_runup(XI)) == pytest.approx(0.31)


def test_schuttrumpf_runup() -> None:
    # 2.25 tanh(0.5 * 0.31) = 2.25 * 0.1537705 = 0.3459837
    assert float(wt.schuttrumpf_runup(XI)) == pytest.approx(0.3459837, rel=1e-6)


def test_chue_runup_with_the_minus_sign_restored() -> None:
    slope = math.tan(BETA)
    xi0 = slope / (H_TOE / L0) ** 0.4
    expected = (
        1.8 * (1 - 3.1 * H_TOE / L0) * xi0 * (1 - math.exp(-math.sqrt(math.pi / (2 * BETA)) / xi0))
    )
    assert float(wt.chue_runup(H_TOE, L0, slope)) == pytest.approx(expected, rel=1e-12)
    assert float(wt.chue_runup(H_TOE, L0, slope)) == pytest.approx(0.36708, rel=1e-4)


def test_hughes_runup() -> None:
    # Linear momentum flux at the toe of the Kimmoun flume (h = 0.705 m, T = 1.275 s).
    kh = MPMATH_DISPERSION[2][2] * 0.705
    rel = H_TOE / 0.705
    mf = 0.5 * rel * math.tanh(kh) / kh + rel**2 / 8 * (1 + 2 * kh / math.sinh(2 * kh))
    assert float(wt.linear_momentum_flux_parameter(H_TOE, 1.275, 0.705)) == pytest.approx(
        mf, rel=1e-12
    )
    assert float(wt.hughes_runup(math.tan(BETA), mf)) == pytest.approx(
        3.84 * math.tan(BETA) * math.sqrt(mf), rel=1e-12
    )


def test_hsu_runup() -> None:
    # Within its fitted range: tan(beta) = 1/3, xi = 1.5 -> 2 * 0.75^(0.36) = 1.80325
    assert float(wt.hsu_runup(1.5, 1 / 3)) == pytest.approx(2 * 0.75**0.36, rel=1e-12)
    assert float(wt.hsu_runup(1.5, 1 / 3)) == pytest.approx(1.80325, rel=1e-5)


def test_synolakis_runup_law() -> None:
    # NTHMP beach cot(beta) = 19.85, H/d = 0.0185: 2.831 * sqrt(19.85) * 0.0185^1.25
    r = float(wt.synolakis_runup(0.0185, 1.0, 1 / 19.85))
    assert r == pytest.approx(2.831 * math.sqrt(19.85) * 0.0185**1.25, rel=1e-12)
    assert r == pytest.approx(0.086057, rel=1e-5)


# ------------------------------------------------------------------------------------------------
# Solitary waves


def test_goring_trajectory_solves_its_implicit_equation() -> None:
    H, d = 0.1, 1.0
    eps = 1 / math.cosh(3.8) ** 2  # Goring's 3.8
    K = math.sqrt(3 * H / (4 * d))
    c = math.sqrt(G * (d + H))
    duration = float(wt.solitary_piston_duration(H, d, eps))
    stroke = float(wt.solitary_piston_stroke(H, d))
    assert stroke == pytest.approx(math.sqrt(16 * H * d / 3))
    assert stroke == pytest.approx(2 * H / K)
    # Goring's duration rule 2 (3.8 + H/d) / (kappa c), kappa = K / d (tanh 3.8 ~ 1).
    assert duration == pytest.approx(2 * (3.8 + H / d) / (K / d * c), rel=2e-3)
    t = np.linspace(-0.5, duration + 0.5, 4001)
    x, u = wt.solitary_piston_motion(t, H, d, eps)
    lam = 3.8 * d / K
    inside = (t > 0) & (t < duration)
    theta = K / d * (c * t[inside] - x[inside] - lam)
    np.testing.assert_allclose(x[inside], H / K * (np.tanh(theta) + math.tanh(3.8)), atol=1e-14)
    # The paddle moves with the depth-averaged velocity c eta / (d + eta).
    eta = H / np.cosh(theta) ** 2
    np.testing.assert_allclose(u[inside], c * eta / (d + eta), rtol=1e-12)
    np.testing.assert_allclose(np.gradient(x, t)[inside][5:-5], u[inside][5:-5], atol=2e-4)
    assert np.all(x[t <= 0] == 0.0)
    assert x[-1] == pytest.approx(stroke * math.tanh(3.8), rel=1e-12)
    assert np.all(np.diff(x) >= 0)


def test_solitary_wave_profile() -> None:
    H, d = 0.05, 0.5
    c = float(wt.solitary_celerity(H, d))
    x = np.linspace(-5, 15, 2001)
    eta = wt.solitary_wave_elevation(x, 2.0, H, d, x0=1.0)
    crest = x[np.argmax(eta)]
    assert crest == pytest.approx(1.0 + 2.0 * c, abs=0.01)
    assert eta.max() == pytest.approx(H, rel=1e-4)
    K = math.sqrt(3 * H / (4 * d))
    assert float(wt.solitary_wave_elevation(1.0 + d / K, 0.0, H, d, x0=1.0)) == pytest.approx(
        H / math.cosh(1.0) ** 2
    )


# ------------------------------------------------------------------------------------------------
# Irregular waves


def test_spectra_integrate_to_hs() -> None:
    f = np.linspace(0.0, 20.0, 400001)
    for gamma in (1.0, 3.3, 7.0):
        s = wt.jonswap_spectrum(f, 0.2, 2.0, gamma)
        m0 = np.sum(0.5 * (s[1:] + s[:-1]) * np.diff(f))
        assert 4 * math.sqrt(m0) == pytest.approx(0.2, rel=1e-6)
    np.testing.assert_allclose(
        wt.jonswap_spectrum(f, 0.2, 2.0, 1.0),
        wt.pierson_moskowitz_spectrum(f, 0.2, 2.0),
        rtol=1e-10,
    )
    s = wt.jonswap_spectrum(f, 0.2, 2.0)
    assert f[np.argmax(s)] == pytest.approx(0.5, abs=1e-4)


def test_irregular_synthesis_is_seeded_and_goes_through_the_transfer_function() -> None:
    a = wt.irregular_paddle_motion(0.1, 2.0, 0.5, seed=7)
    b = wt.irregular_paddle_motion(0.1, 2.0, 0.5, seed=7)
    c = wt.irregular_paddle_motion(0.1, 2.0, 0.5, seed=8)
    np.testing.assert_array_equal(a.phases, b.phases)
    assert not np.allclose(a.phases, c.phases)
    # Every frequency is a multiple of 1 / repeat_period, within (0.5, 3) fp.
    n = a.frequencies * a.repeat_period
    np.testing.assert_allclose(n, np.round(n), atol=1e-9)
    assert a.frequencies.min() >= 0.25 and a.frequencies.max() <= 1.5
    k = wt.wavenumber(1 / a.frequencies, 0.5)
    np.testing.assert_allclose(
        a.stroke_amplitudes, a.wave_amplitudes / wt.piston_height_to_stroke(k, 0.5)
    )
    flap = wt.irregular_paddle_motion(0.1, 2.0, 0.5, seed=7, paddle="flap")
    np.testing.assert_allclose(
        flap.stroke_amplitudes, a.wave_amplitudes / wt.flap_height_to_stroke(k, 0.5)
    )
    # Deterministic amplitudes carry the spectrum's energy in the band (~1.5 % of m0 is outside).
    hm0 = 4 * math.sqrt(np.sum(a.wave_amplitudes**2) / 2)
    assert hm0 == pytest.approx(0.1, rel=0.01)
    rand = wt.irregular_paddle_motion(0.1, 2.0, 0.5, seed=7, random_amplitudes=True)
    np.testing.assert_array_equal(rand.phases, a.phases)
    assert 4 * math.sqrt(np.sum(rand.wave_amplitudes**2) / 2) == pytest.approx(0.1, rel=0.1)


def test_irregular_motion_sum_and_velocity() -> None:
    m = wt.irregular_paddle_motion(0.05, 1.5, 0.4, seed=1, repeat_period=30.0)
    t = np.linspace(0, 12, 6001)
    x, u = m.motion(t, ramp_time=3.0)
    by_hand = sum(
        s * np.sin(2 * np.pi * f * t + p)
        for s, f, p in zip(m.stroke_amplitudes, m.frequencies, m.phases, strict=True)
    )
    np.testing.assert_allclose(x, np.clip(t / 3.0, 0, 1) * by_hand, atol=1e-12)
    smooth = np.abs(t - 3.0) > 0.01
    np.testing.assert_allclose(np.gradient(x, t)[smooth][1:-1], u[smooth][1:-1], atol=2e-4)


# ------------------------------------------------------------------------------------------------
# Validity checks


def test_check_wave_accepts_the_kimmoun_wave() -> None:
    assert wt.check_wave(0.114, 1.275, 0.705, order=2) == []


def test_check_wave_flags_each_problem() -> None:
    # kd = 4.0 > pi: deep water for a piston; H = 0.2 m is below Miche's 0.22 m there.
    (msg,) = wt.check_wave(0.2, 1.0, 1.0)
    assert "deep water" in msg and "piston" in msg
    assert any("Miche" in m for m in wt.check_wave(0.25, 1.0, 1.0, paddle="flap"))
    assert any("McCowan" in m for m in wt.check_wave(0.2, 4.0, 0.25))
    assert any("Ursell" in m for m in wt.check_wave(0.1, 3.0, 0.3, order=2))
    assert any("secondary crest" in m for m in wt.check_wave(0.1, 3.0, 0.3))
    assert any(
        "flap" in m and "shallow" in m for m in wt.check_wave(0.01, 10.0, 0.5, paddle="flap")
    )


def test_warn_if_invalid_wave_emits_wave_validity_warnings() -> None:
    with pytest.warns(wt.WaveValidityWarning) as record:
        problems = wt.warn_if_invalid_wave(0.2, 4.0, 0.25)
    assert [str(w.message) for w in record] == problems
    assert any("McCowan" in m for m in problems)


# ------------------------------------------------------------------------------------------------
# Bad input


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: wt.wavenumber(-1.0, 1.0), "period"),
        (lambda: wt.wavenumber(0.0, 1.0), "period"),
        (lambda: wt.wavenumber(1.0, -0.5), "depth"),
        (lambda: wt.wavenumber([1.0, float("nan")], 1.0), "period"),
        (lambda: wt.wavenumber_from_omega(1.0, float("inf")), "depth"),
        (lambda: wt.piston_height_to_stroke(1.0, 0.0), "depth"),
        (lambda: wt.piston_motion([0.0, 1.0], 0.0, 1.0, 1.0), "height"),
        (lambda: wt.piston_motion([0.0, float("nan")], 0.1, 1.0, 1.0), "t"),
        (lambda: wt.piston_motion([0.0], 0.1, 1.0, 1.0, ramp_periods=-1), "ramp_periods"),
        (lambda: wt.piston_motion([0.0], 0.1, 1.0, 1.0, ramp="cubic"), "ramp"),
        (lambda: wt.regular_paddle_motion(0.1, 1.0, 1.0, order=3), "order"),
        (lambda: wt.regular_paddle_motion(0.1, 1.0, 1.0, "wedge"), "paddle"),
        (lambda: wt.jonswap_spectrum(0.5, 0.1, 2.0, gamma=0.5), "gamma"),
        (lambda: wt.jonswap_spectrum(-0.5, 0.1, 2.0), "frequency"),
        (lambda: wt.breaker_type(-1.0), "xi"),
        (lambda: wt.iribarren("steep", 0.1, 2.0), "slope"),
        (lambda: wt.solitary_piston_motion([0.0], 0.1, 1.0, truncation=2.0), "truncation"),
        (lambda: wt.irregular_paddle_motion(0.1, 2.0, 0.5, spectrum="bretschneider"), "spectrum"),
        (
            lambda: wt.irregular_paddle_motion(0.1, 2.0, 0.5, frequency_range=(3, 1)),
            "frequency_range",
        ),
        (lambda: wt.check_wave(0.1, -2.0, 1.0), "period"),
    ],
)
def test_bad_input_raises_value_error_naming_the_argument(call, name: str) -> None:
    with pytest.raises(ValueError, match=rf"^{name}:"):
        call()
