"""Front and column-height measurement on synthetic particle sets, and the front error metric."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from watersim.measure import (
    MARTIN_MOYCE_SETS,
    front_error,
    front_position,
    load_martin_moyce,
    load_martin_moyce_height,
    water_column_height,
)


def lattice(width: float, height: float, dp: float, x0: float = 0.0, depth: float | None = None):
    """Particles at (i + 1/2) dp filling [x0, x0 + width] x [0, height] (x [0, depth] in 3D)."""
    xs = x0 + (np.arange(round(width / dp)) + 0.5) * dp
    zs = (np.arange(round(height / dp)) + 0.5) * dp
    if depth is None:
        gx, gz = np.meshgrid(xs, zs, indexing="ij")
        return np.column_stack([gx.ravel(), gz.ravel()])
    ys = (np.arange(round(depth / dp)) + 0.5) * dp
    gx, gy, gz = np.meshgrid(xs, ys, zs, indexing="ij")
    return np.column_stack([gx.ravel(), gy.ravel(), gz.ravel()])


def test_column_at_rest_measures_its_width_and_height() -> None:
    pos = lattice(1.0, 2.0, 0.02)
    assert front_position(pos, 0.02) == pytest.approx(1.0)
    assert water_column_height(pos, 0.02) == pytest.approx(2.0)
    pos3 = lattice(1.0, 2.0, 0.1, depth=0.3)
    assert front_position(pos3, 0.1) == pytest.approx(1.0)
    assert water_column_height(pos3, 0.1) == pytest.approx(2.0)


def test_droplet_beyond_the_gap_is_ignored_and_near_one_counts() -> None:
    dp = 0.05
    bulk = lattice(1.0, 0.5, dp)
    far = np.array([[1.0 - 0.5 * dp + 2.5 * dp, 0.5 * dp]])  # gap 2.5 dp > 2 dp
    near = np.array([[1.0 - 0.5 * dp + 1.5 * dp, 0.5 * dp]])  # gap 1.5 dp: still connected
    assert front_position(np.vstack([bulk, far]), dp) == pytest.approx(1.0)
    assert front_position(np.vstack([bulk, near]), dp) == pytest.approx(1.0 + 1.5 * dp)
    # a chain of close particles is followed to its end
    chain = np.array([[1.0 - 0.5 * dp + k * 1.9 * dp, 0.5 * dp] for k in range(1, 6)])
    assert front_position(np.vstack([bulk, chain]), dp) == pytest.approx(
        1.0 - 0.5 * dp + 5 * 1.9 * dp + 0.5 * dp
    )


def test_splash_above_the_floor_band_is_ignored() -> None:
    dp = 0.05
    bulk = lattice(1.0, 0.5, dp)
    jet = np.array([[1.0 + 0.5 * dp, 0.9], [1.0 + 1.5 * dp, 0.95]])  # touching in x, but high
    assert front_position(np.vstack([bulk, jet]), dp) == pytest.approx(1.0)
    assert front_position(np.vstack([bulk, jet]), dp, band=1.0) == pytest.approx(1.0 + 2 * dp)


def test_column_height_ignores_a_detached_splash() -> None:
    dp = 0.05
    col = lattice(0.5, 1.0, dp)
    blob = np.array([[0.5 * dp, 1.0 + 3 * dp]])
    assert water_column_height(np.vstack([col, blob]), dp) == pytest.approx(1.0)


def test_wall_offset_and_empty_sets() -> None:
    dp = 0.02
    pos = lattice(1.0, 2.0, dp, x0=-3.0)
    assert front_position(pos, dp, wall_x=-3.0) == pytest.approx(1.0)
    high = lattice(1.0, 2.0, dp) + np.array([0.0, 5.0])
    assert math.isnan(front_position(high, dp))
    with pytest.raises(ValueError, match="positions_fluid"):
        front_position(np.zeros((4, 4)), dp)
    with pytest.raises(ValueError, match="dp"):
        front_position(pos, 0.0)


@settings(max_examples=50, deadline=None)
@given(
    width=st.integers(min_value=2, max_value=40),
    height=st.integers(min_value=2, max_value=40),
    shift=st.floats(min_value=-10.0, max_value=10.0),
    droplet_gap=st.floats(min_value=2.05, max_value=50.0),
    dp=st.sampled_from([0.01, 0.02, 0.05, 0.1]),
)
def test_front_is_shift_invariant_and_ignores_droplets(
    width: int, height: int, shift: float, droplet_gap: float, dp: float
) -> None:
    pos = lattice(width * dp, height * dp, dp, x0=shift)
    droplet = np.array([[shift + width * dp - 0.5 * dp + droplet_gap * dp, 0.5 * dp]])
    rng = np.random.default_rng(width * 1000 + height)
    shuffled = rng.permutation(np.vstack([pos, droplet]))
    assert front_position(shuffled, dp, wall_x=shift) == pytest.approx(width * dp, rel=1e-9)


# ------------------------------------------------------------------------------------------------


def test_reference_sets_load_in_dimensionless_form() -> None:
    assert set(MARTIN_MOYCE_SETS) >= {"lethe", "pysph_a2.25in", "pysph_a1.125in"}
    ref = load_martin_moyce()
    assert ref.name == "lethe"
    assert (ref.tau[0], ref.delta[0]) == (0.0, 1.0)
    assert np.all(np.diff(ref.tau) > 0) and np.all(np.diff(ref.delta) > 0)
    t, x = ref.dimensional(width=1.0, g=9.81)
    assert t[-1] == pytest.approx(2.96 / math.sqrt(2 * 9.81))
    assert x[-1] == pytest.approx(3.67)
    for name in MARTIN_MOYCE_SETS:
        assert load_martin_moyce(name).tau.size >= 10
    with pytest.raises(ValueError, match="lethe"):
        load_martin_moyce("nope")


def test_column_height_reference_loads_in_dimensionless_form() -> None:
    ref = load_martin_moyce_height()
    assert ref.n2 == 2.0 and ref.tau.size == 17
    assert (ref.tau[0], ref.eta[0]) == (0.56, 0.94) and (ref.tau[-1], ref.eta[-1]) == (7.40, 0.06)
    assert np.all(np.diff(ref.tau) > 0) and np.all(np.diff(ref.eta) < 0)
    # read at fixed marks: eta on steps of 1/18 of the initial height, to two decimals
    assert np.allclose(np.round(ref.eta * 18.0), ref.eta * 18.0, atol=0.11)
    t, h = ref.dimensional(width=0.5, g=9.81)
    assert t[0] == pytest.approx(0.56 / math.sqrt(9.81 / 0.5))
    assert h[0] == pytest.approx(0.94 * 2.0 * 0.5)
    # the time is t sqrt(g/a): the top of the column falls slower than free fall from rest
    # (with the front's t sqrt(2g/a) the first point would fall faster than gravity allows)
    assert (1.0 - ref.eta[0]) * 2.0 < 0.5 * ref.tau[0] ** 2
    assert (1.0 - ref.eta[0]) * 2.0 > 0.25 * ref.tau[0] ** 2


def _reference_curve(width: float, g: float, dt: float = 0.001, t_end: float = 0.7):
    t_ref, x_ref = load_martin_moyce().dimensional(width, g)
    t = np.arange(0.0, t_end + dt / 2, dt)
    t = np.union1d(t, t_ref[t_ref <= t_end])
    return t, np.interp(t, t_ref, x_ref)


def test_front_error_is_zero_for_the_reference_itself() -> None:
    t, x = _reference_curve(width=1.0, g=9.81)
    err = front_error(t, x, width=1.0, g=9.81)
    assert err.rms_rel_error < 1e-12
    assert abs(err.mean_lead_s) < 1e-3
    assert err.n_points == 13  # every measured point of the Lethe set up to t = 0.668 s
    assert err.reference == "lethe"


def test_front_error_detects_a_wrong_front() -> None:
    t, x = _reference_curve(width=1.0, g=9.81)
    err = front_error(t, 1.3 * x, width=1.0)
    assert err.rms_rel_error == pytest.approx(0.3, rel=1e-6)
    assert err.mean_rel_error > 0 and err.mean_lead_s > 0.0
    slow = front_error(t, np.ones_like(x), width=1.0)  # a front that never moves
    assert slow.rms_rel_error > 0.4
    assert math.isnan(slow.mean_lead_s)


def test_front_error_reports_a_time_lead() -> None:
    t, x = _reference_curve(width=1.0, g=9.81, t_end=0.75)
    t_ref, x_ref = load_martin_moyce().dimensional(1.0, 9.81)
    early = np.interp(t + 0.05, t_ref, x_ref, right=np.nan)  # the same front 0.05 s earlier
    keep = np.isfinite(early)
    err = front_error(t[keep], early[keep], width=1.0)
    assert err.mean_lead_s == pytest.approx(0.05, abs=2e-3)
    assert err.mean_rel_error > 0.0


def test_front_error_scales_with_width_and_limits() -> None:
    t, x = _reference_curve(width=0.057, g=9.81, dt=0.0001, t_end=0.15)  # a = 2.25 in
    assert front_error(t, x, width=0.057).rms_rel_error < 1e-12
    with pytest.raises(ValueError, match="holds no measured point"):
        front_error([0.0, 0.01], [1.0, 1.0], width=1.0)
    with pytest.raises(ValueError, match="increasing"):
        front_error([0.0, 0.0, 0.1], [1.0, 1.0, 1.1], width=1.0)
    t, x = _reference_curve(width=1.0, g=9.81)
    short = front_error(t, x, width=1.0, x_max=2.0)
    assert short.n_points == 5
