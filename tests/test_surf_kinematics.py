"""Surf-zone kinematics from records: the mean flow on a vertical (undertow, transport above
the trough) and the crest celerity along the flume, against synthetic waves whose answers are
known in closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest

from watersim import analysis

G = 9.81


def test_undertow_returns_the_crests_transport() -> None:
    """A long wave ``eta = a cos(omega t)`` over depth h moving the water column with
    ``u = c eta / h + U``: its crests carry ``c a^2 / (2 h) + U a`` above the trough; the
    closed flume's return current U = -c a^2 / (2 h^2) balances it, and is the undertow."""
    h, a, period = 0.3, 0.03, 3.0
    c = math.sqrt(G * h)
    current = -c * a * a / (2 * h * h)
    z = np.linspace(0.0005, 0.36, 360)  # 1 mm apart, from the bed up
    t = np.arange(0.0, 5 * period, period / 400)
    eta = a * np.cos(2 * math.pi * t / period)
    u = np.broadcast_to((c * eta / h + current)[:, None], (t.size, z.size))
    wet = z[None, :] < h + eta[:, None]
    flow = analysis.vertical_mean_flow(u, wet, z, t, period)
    assert flow.n_periods == 5
    assert flow.trough_level == pytest.approx(h - a, abs=1e-3)
    assert flow.undertow == pytest.approx(current, rel=0.02)
    assert flow.flux_above_trough == pytest.approx(c * a * a / (2 * h) + current * a, rel=0.02)
    assert flow.flux_below_trough + flow.flux_above_trough == pytest.approx(0.0, abs=2e-5)
    assert flow.max_u == pytest.approx(c * a / h + current, rel=1e-6)
    assert flow.wet_fraction[0] == 1.0 and flow.wet_fraction[-1] == 0.0


@pytest.mark.parametrize("celerity", [1.2, 1.6])
def test_crest_celerity_of_a_travelling_wave(celerity: float) -> None:
    """A steep, crested travelling wave (three harmonics) past gauges 0.45 m apart, more than
    a third of a wavelength: the crest speed comes back, and its ratio to sqrt(g d)."""
    period = 2.0
    k = 2 * math.pi / (celerity * period)
    x = np.array([1.0, 1.45, 1.9, 2.35, 4.0])
    depth = np.array([0.3, 0.28, 0.26, 0.24, 0.2])
    t = np.arange(0.0, 12 * period, period / 100)
    theta = k * x[None, :] - 2 * math.pi * t[:, None] / period
    eta = 0.03 * np.cos(theta) + 0.012 * np.cos(2 * theta) + 0.004 * np.cos(3 * theta)
    result = analysis.crest_celerity(eta, t, x, depth, period)
    assert result.celerity == pytest.approx(celerity, rel=1e-3)
    speed = np.sqrt(G * 0.5 * (depth[1:] + depth[:-1]))
    assert result.ratio == pytest.approx(celerity / speed, rel=1e-3)
    assert result.x == pytest.approx(0.5 * (x[1:] + x[:-1]))


def test_bad_input_names_the_argument() -> None:
    t = np.arange(0.0, 4.0, 0.01)
    with pytest.raises(ValueError, match="^z: "):
        analysis.vertical_mean_flow(np.zeros((t.size, 2)), np.ones((t.size, 2)), [0.2, 0.1], t,
                                    1.0)
    with pytest.raises(ValueError, match="^x: "):
        analysis.crest_celerity(np.zeros((t.size, 2)), t, [1.0, 0.5], 0.3, 1.0)


def test_a_vertical_is_wet_from_the_bed_to_its_highest_wet_point() -> None:
    """Next to the bed the fluid's kernel sum is about 0.5 in water (the bed's particles fill
    the other half): a point below a wet one is in the water whatever its sum."""
    from watersim.flume.analyse import _water_column

    z = np.array([0.3, 0.1, 0.2, 0.4])  # in any order
    kernel_sum = np.array([[0.9, 0.45, 0.8, 0.1],    # the bed point dips below 0.5
                           [0.2, 0.48, 0.3, 0.0],    # a trough below z = 0.2
                           [0.0, 0.0, 0.0, 0.0]])    # dry
    assert _water_column(kernel_sum, z).tolist() == [[True, True, True, False],
                                                     [False, False, False, False],
                                                     [False, False, False, False]]
