"""Active wave absorption at the paddle: the target elevation and gain each wave gives the core
(Schaffer & Klopman 2000), and the absorption in runs."""

from __future__ import annotations

import cmath
import math
from types import SimpleNamespace

import numpy as np
import pytest

import watersim as ws
from watersim import wave_theory as wt
from watersim.validation.absorption import (
    ABSORPTION_WAVE,
    SOLITARY_CLOSED_FLUME,
    absorption_measure,
    absorption_period,
    absorption_scene,
    solitary_closed_flume,
    solitary_residual,
)

G = 9.81


def _scene(wave: ws.RegularWave | ws.SolitaryWave | ws.IrregularWave, paddle: object,
           depth: float = 0.3) -> ws.FlumeScene:
    flume = ws.Flume(length=4.0, depth=depth, damping=False)
    return flume.scene(wave, paddle=paddle, dp=0.03)


@pytest.mark.parametrize("paddle", [ws.Piston(), ws.Flap()])
def test_regular_target_is_the_linear_wave_at_the_paddle(paddle: object) -> None:
    wave = ws.RegularWave(height=0.03, period=1.26, phase=0.4)
    law = _scene(wave, paddle).law
    target = law.absorption_target
    assert target is not None and target["type"] == "harmonic"
    (a, w, phi), = target["components"]
    assert a == pytest.approx(0.015) and w == pytest.approx(2 * math.pi / 1.26)
    # in phase with the paddle's velocity: X ~ sin(theta), eta ~ cos(theta)
    assert phi == pytest.approx(0.4 + math.pi / 2)
    assert target["ramp_duration"] == law.ramp_duration
    k = float(wt.wavenumber(1.26, 0.3))
    transfer = (wt.piston_height_to_stroke if isinstance(paddle, ws.Piston)
                else wt.flap_height_to_stroke)(k, 0.3)
    assert law.absorption_gain == pytest.approx(w / float(transfer))


def test_second_order_piston_targets_the_bound_harmonic() -> None:
    wave = ws.RegularWave(height=0.03, period=1.26)
    law = _scene(wave, ws.Piston(order=2)).law
    assert law.absorption_target is not None
    second = law.absorption_target["components"][1]
    k = float(wt.wavenumber(1.26, 0.3))
    assert second[0] == pytest.approx(float(wt.stokes2_second_harmonic_amplitude(0.03, k, 0.3)))
    assert second[1] == pytest.approx(2 * 2 * math.pi / 1.26)


def test_shallow_water_gain_tends_to_sqrt_g_over_d() -> None:
    law = _scene(ws.RegularWave(height=0.002, period=8.0), ws.Piston()).law
    assert law.absorption_gain == pytest.approx(math.sqrt(G / 0.3), rel=0.02)


def test_solitary_target_peaks_at_the_wave_height() -> None:
    law = _scene(ws.SolitaryWave(height=0.06), ws.Piston()).law
    target = law.absorption_target
    assert target is not None and target["type"] == "table"
    assert max(target["x"]) == pytest.approx(0.06, rel=0.02)
    # the gain takes back the whole wave: passing a fixed probe, the returning wave's volume
    # V = d S (Goring's paddle ends S forward) gives int eta dt = V / c, which moves the
    # paddle back by S
    c = float(wt.solitary_celerity(0.06, 0.3))
    assert law.absorption_gain == pytest.approx(c / 0.3)
    # the drift gives the volume back as a long wave below 1 % of H
    passing = float(np.trapezoid(target["x"], target["t"]))
    assert law.absorption_drift_time == pytest.approx(200.0 * passing / 0.06)


def test_irregular_target_has_every_component() -> None:
    law = _scene(ws.IrregularWave(hs=0.03, tp=1.3), ws.Piston()).law
    assert law.absorption_target is not None
    target = np.asarray(law.absorption_target["components"])
    paddle = np.asarray(law.law["components"])
    assert target.shape == paddle.shape
    assert np.allclose(target[:, 1], paddle[:, 1])
    assert np.allclose(target[:, 2], paddle[:, 2] + math.pi / 2)


def test_a_tabulated_motion_has_no_target() -> None:
    law = _scene(ws.TabulatedMotion(t=(0.0, 1.0), x=(0.0, 0.01)), ws.Piston()).law
    assert law.absorption_target is None and law.absorption_gain is None


def test_the_near_field_is_in_quadrature_and_fades_into_the_progressive_wave() -> None:
    """The linear wave-maker's elevation in front of the face: the piston's closed-form
    evanescent coefficients, ``c_j ~ sinh(2 k_j d) / (k_j (2 k_j d + sinh 2 k_j d))`` (Dean &
    Dalrymple 1991, section 6.2); the near field is in quadrature with the progressive wave,
    ahead of it for a piston and behind it for a flap at kd = 1; gone four depths away."""
    depth, x = 0.4, 0.05
    omega = 2.0 * math.pi / absorption_period()
    k = float(wt.wavenumber_from_omega(omega, depth))
    kj = np.concatenate([[k], 1j * wt._evanescent_wavenumbers(omega, depth, 400, G)])
    c = np.sinh(2.0 * kj * depth) / (kj * (2.0 * kj * depth + np.sinh(2.0 * kj * depth)))
    expected = complex(np.sum(c / c[0] * np.exp(1j * kj * x)))
    assert abs(wt.paddle_near_field(omega, depth, x, "piston") - expected) < 1e-6
    for paddle, sign in (("piston", 1.0), ("flap", -1.0)):
        near = wt.paddle_near_field(omega, depth, x, paddle) - cmath.exp(1j * k * x)
        assert abs(near.real) < 1e-9 and sign * near.imag > 0.02, (paddle, near)
        far = wt.paddle_near_field(omega, depth, 4.0 * depth, paddle)
        assert abs(far - cmath.exp(4j * k * depth)) < 1e-5


def _absorber(wave: ws.RegularWave | ws.SolitaryWave, paddle: ws.Piston | ws.Flap
              ) -> tuple[ws.FlumeScene, dict]:
    scene = _scene(wave, paddle)
    absorption = scene.to_scene()["paddle"]["absorption"]
    assert absorption["probe_offset"] == pytest.approx(2.0 * 0.03)
    return scene, absorption


@pytest.mark.parametrize("paddle", [ws.Piston(absorption=True), ws.Flap(absorption=True)])
def test_the_absorber_targets_the_wave_at_its_probe_and_delays_the_return(paddle: ws.Piston
                                                                          | ws.Flap) -> None:
    """The core reads eta_M 2 dp in front of the face: the target is the paddle's linear wave
    there (its near field included), and the lag and gain make the correction cancel a
    returning wave at the face (``_Paddle.absorber``)."""
    wave = ws.RegularWave(height=0.03, period=1.26, phase=0.4)
    scene, absorption = _absorber(wave, paddle)
    x, omega = absorption["probe_offset"], 2.0 * math.pi / 1.26
    near = paddle.near_field(omega, 0.3, x, G)
    (a, w, phi), = absorption["target"]["components"]
    assert a == pytest.approx(0.015 * abs(near))
    assert phi == pytest.approx(0.4 + math.pi / 2 - cmath.phase(near))
    k = float(wt.wavenumber(1.26, 0.3))
    loop = 1.0 / (2.0 * math.cos(k * x) - near)
    assert 0.0 < cmath.phase(loop) < 2.0 * k * x
    # with the drift term's lead (10 periods: 0.016 rad) and the mean removal's (2 periods:
    # 0.079 rad)
    drift, mean = 1.0 / (10.0 * 2.0 * math.pi), 1.0 / (2.0 * 2.0 * math.pi)
    assert absorption["mean_time"] == pytest.approx(2.0 * 1.26)
    delay = cmath.phase(loop) + math.atan(drift) + math.atan(mean)
    assert math.atan(omega * absorption["lag_time"]) == pytest.approx(delay)
    assert absorption["gain"] == pytest.approx(scene.law.absorption_gain * abs(loop) * math.sqrt(
        (1.0 + drift**2) * (1.0 + mean**2)) / math.cos(delay))


def test_bound_harmonics_and_a_solitary_wave_travel_with_their_wave() -> None:
    _, second = _absorber(ws.RegularWave(height=0.03, period=1.26),
                          ws.Piston(order=2, absorption=True))
    scene = _scene(ws.RegularWave(height=0.03, period=1.26), ws.Piston(order=2))
    k, x = float(wt.wavenumber(1.26, 0.3)), second["probe_offset"]
    at_face = scene.law.absorption_target["components"][1]  # type: ignore[index]
    assert second["target"]["components"][1] == pytest.approx(
        [at_face[0], at_face[1], at_face[2] - 2.0 * k * x])
    scene, solitary = _absorber(ws.SolitaryWave(height=0.06), ws.Piston(absorption=True))
    delay = solitary["probe_offset"] / float(wt.solitary_celerity(0.06, 0.3))
    assert solitary["lag_time"] == pytest.approx(delay)
    assert solitary["target"]["t"] == pytest.approx(
        [t + delay for t in scene.law.absorption_target["t"]])  # type: ignore[index]
    assert solitary["gain"] == scene.law.absorption_gain


@pytest.mark.slow
def test_before_the_wall_reflection_returns_the_absorber_sees_no_difference() -> None:
    """absorption2d's piston at H/dp 1, absorbing, until the wall's reflection is back at
    the paddle: the lagged difference eta_M - eta_T less its mean, which drives the correction
    (the core's ``paddle_correction``), has a first harmonic below 5 % of the wave's amplitude
    over the whole periods after the ramp. The target at the face, 2 dp behind the probe, left
    11 %."""
    period = absorption_period()
    scene = absorption_scene(ws.Piston(absorption=True), dp=0.04, periods=10.0)
    cg = float(wt.group_velocity(period, scene.flume.depth))
    back = 2.0 * scene.flume.length / cg
    sim = scene.build()
    samples: list[tuple[float, float]] = []

    def record(s: ws.Simulation) -> None:
        _, _, since, lagged, mean = s.core.checkpoint()["paddle_correction"]
        samples.append((since, lagged - mean))

    sim.run(back, callback_every=period / 40.0, callback=record)
    t, driving = (np.asarray(v) for v in zip(*samples, strict=True))
    start = scene.law.ramp_duration + 0.5 * period
    sel = (t >= start) & (t < start + period * math.floor((back - 0.3 * period - start) / period))
    omega = 2.0 * math.pi / period
    basis = np.column_stack([np.cos(omega * t[sel]), np.sin(omega * t[sel]), np.ones(sel.sum())])
    (c, s_, _), *_ = np.linalg.lstsq(basis, driving[sel], rcond=None)
    assert math.hypot(c, s_) < 0.05 * 0.5 * ABSORPTION_WAVE["height"]


def test_absorption2d_measures_the_rereflected_share_of_the_incident_wave() -> None:
    """absorption2d's measure on a synthetic record: an incident wave whose complex amplitude
    gains 6 % of itself at a quarter-period phase once the re-reflection arrives, a reflected
    wave as high as the incident one (the wall), a constant level."""
    scene = absorption_scene(ws.Piston(absorption=True), dp=0.04, periods=30)
    period, depth = scene.period, scene.flume.depth
    assert period is not None
    x = np.array([g.x for g in scene.gauges])
    k, omega = float(wt.wavenumber(period, depth)), 2.0 * math.pi / period
    t = np.arange(0.0, 30.0 * period, period / 40.0)
    a0 = 0.02
    changed = t > 12.0 * period
    incident = np.where(changed, a0 * abs(1.0 + 0.06j), a0)[:, None]
    phase = np.where(changed, math.atan(0.06), 0.0)[:, None]
    eta = (incident * np.cos(omega * t[:, None] - k * x + phase)
           + a0 * np.cos(omega * t[:, None] + k * x + 0.3) + 0.0004)
    sim = SimpleNamespace(gauges=SimpleNamespace(uniform=lambda: (t, eta, None), x=x))
    measured = absorption_measure(sim, scene)  # type: ignore[arg-type]
    assert measured["rereflected"] == pytest.approx(0.06, rel=1e-3)
    assert measured["incident_growth"] == pytest.approx(abs(1.0 + 0.06j) - 1.0, rel=1e-3)
    assert measured["late"]["a_reflected"] == pytest.approx(a0, rel=1e-3)
    assert measured["mean_level_over_H"] == pytest.approx(0.01)
    assert measured["early"]["end"] <= 12.0 * period  # before the change


@pytest.mark.slow
def test_an_absorbing_piston_lets_a_reflected_solitary_wave_out() -> None:
    """The solitary wave of absorption2d (H/d = 0.2 against the wall of a 2 m flume), run
    until the reflected wave has come back to the paddle and a second crossing's time has
    passed: the largest elevation the gauges see after the return."""
    residual = {}
    for absorbing in (False, True):
        scene, back, until = solitary_closed_flume(absorbing, dp=0.025)
        sim = scene.build()
        sim.run(until)
        residual[absorbing] = solitary_residual(sim, back)
    height = SOLITARY_CLOSED_FLUME["height"]
    assert residual[False] > 0.6 * height  # re-reflected by a fixed paddle
    assert residual[True] < 0.25 * residual[False], residual
