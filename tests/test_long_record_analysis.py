"""The long-record analysis of regular waves on closed-form synthetic records: the breaking
point of the phase-averaged wave, crest and trough velocities on a vertical, and the mean
level's drift over blocks of periods (watersim.analysis; wired into analysis.json by
watersim.flume.analyse)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from watersim import analysis as an

T = 1.275


def test_breaking_point_is_where_the_averaged_wave_crosses_the_ratio() -> None:
    x = np.array([8.0, 9.0, 10.0, 11.0, 12.0, 13.0])
    d = 0.705 - (x - 4.0) / 15.0
    # H/d = 0.5, 0.6, ..., 1.0 by construction: crosses 0.78 between x = 10 and 11
    ratios = np.array([0.5, 0.6, 0.7, 0.8, 0.9, 1.0])
    h = ratios * d
    found = an.breaking_from_phase_averaged_heights(x, h, d)
    assert found is not None
    s = (0.78 - 0.7) / (0.8 - 0.7)
    assert found.position == pytest.approx(10.0 + s)
    assert found.index == 3
    # the height reported is the averaged wave's at that place, not another gauge's
    assert found.wave_height == pytest.approx(h[2] + s * (h[3] - h[2]))
    assert found.depth == pytest.approx(0.705 - (found.position - 4.0) / 15.0)
    assert found.max_height == pytest.approx(h.max())
    assert found.max_height_position == x[int(np.argmax(h))]


def test_no_breaking_below_the_ratio_and_dry_gauges_are_skipped() -> None:
    x = np.array([1.0, 2.0, 3.0])
    assert an.breaking_from_phase_averaged_heights(x, [0.1, 0.2, 0.3], [1.0, 1.0, 1.0]) is None
    # a dry gauge (d <= 0) with a large "height" does not count
    found = an.breaking_from_phase_averaged_heights(x, [0.1, 0.9, 5.0], [1.0, 1.0, 0.0])
    assert found is not None and found.index == 1
    with pytest.raises(ValueError, match="heights, depths"):
        an.breaking_from_phase_averaged_heights(x, [0.1, 0.2], [1.0, 1.0, 1.0])


def test_crest_and_trough_velocity_of_a_linear_wave_on_a_vertical() -> None:
    t = np.arange(0.0, 40 * T, T / 40)
    z = np.linspace(0.05, 0.45, 9)
    omega, amp = 2 * math.pi / T, 0.3
    # u grows with height; the top two points are dry half the period (under the trough)
    u = amp * np.cos(omega * t)[:, None] * (1.0 + z[None, :])
    wet = np.ones_like(u, dtype=bool)
    wet[:, -2:] = np.cos(omega * t)[:, None] > 0.0
    cv = an.crest_velocity(u, wet, t, T, depth=0.4)
    assert cv.crest == pytest.approx(amp * (1 + z[-1]), rel=1e-3)
    # under the trough the highest wet point is z[-3]: the lowest u there
    assert cv.trough == pytest.approx(-amp * (1 + z[-3]), rel=1e-3)
    assert cv.sqrt_gd == pytest.approx(math.sqrt(9.81 * 0.4), rel=1e-3)
    assert cv.n_waves == 39 and cv.crest_per_wave.size == 39
    assert np.allclose(cv.crest_per_wave, amp * (1 + z[-1]), rtol=1e-3)
    # a few samples with no wet point are left out, not read as zero
    dry_moments = wet.copy()
    dry_moments[::7] = False
    assert an.crest_velocity(u, dry_moments, t, T, depth=0.4).crest == pytest.approx(cv.crest,
                                                                                   rel=0.02)
    with pytest.raises(ValueError, match="wet point"):
        an.crest_velocity(u, np.zeros_like(wet), t, T, depth=0.4)


def test_mean_level_blocks_see_a_drift_and_not_the_waves() -> None:
    t = np.arange(0.0, 64 * T, T / 40)
    waves = 0.05 * np.cos(2 * math.pi * t / T + 0.3)
    still = an.mean_level_blocks(waves, t, T, 8)
    assert still.means.size == 7  # 63 whole periods from t = 0 in blocks of 8
    assert still.spread < 1e-4 and abs(still.drift) < 1e-4
    creeping = an.mean_level_blocks(waves + 1e-4 * t, t, T, 8)
    expected = 1e-4 * (creeping.starts[-1] - creeping.starts[0])
    assert creeping.drift == pytest.approx(expected, rel=1e-3)
    assert creeping.spread == pytest.approx(expected, rel=1e-3)
    with pytest.raises(ValueError, match="block_periods"):
        an.mean_level_blocks(waves, t, T, 0)
    with pytest.raises(ValueError, match="fewer than"):
        an.mean_level_blocks(waves, t, T, 100)


def test_flume_analysis_reports_the_long_record_parts(tmp_path: Any) -> None:
    """A tiny beach flume run long enough for steady windows: analysis.json carries the
    phase-averaged breaking profile, the crest celerity, the velocity vertical's crest velocity
    and undertow, and the mean level near the paddle, with units."""
    import watersim as ws
    from watersim.flume.analyse import UNITS

    flume = ws.Flume(length=2.4, depth=0.24, beach=ws.PlaneBeach(toe=1.4, slope=0.3),
                     damping=False)
    vertical = ws.VelocityProbe(points=tuple((0.9, z) for z in (0.05, 0.1, 0.15, 0.2, 0.25)),
                                name="u_v")
    sim = flume.simulation(ws.RegularWave(height=0.03, period=0.6), dp=0.04, until=13.0,
                           gauges=[ws.ElevationGauge(x) for x in (0.3, 0.6, 0.9, 1.2, 1.5)]
                           + [vertical])
    sim.run(sim.setup.until)
    a = sim.analyse()
    pa = a["breaking"]["phase_averaged"]
    assert pa["n_waves"] >= 3 and len(pa["profile"]["x"]) >= 2
    assert all(h > 0 for h in pa["profile"]["height"])
    cel = a["crest_celerity"]
    assert len(cel["ratio"]) >= 3 and all(0.3 < r < 1.5 for r in cel["ratio"] if r is not None)
    (v,) = a["velocity_verticals"]
    assert v["name"] == "u_v" and v["crest_velocity"] > 0 > v["trough_velocity"]
    assert v["sqrt_gD"] == pytest.approx(math.sqrt(9.81 * 0.24), rel=1e-3)
    assert "undertow" in v and len(v["mean_u"]) == 5
    mwl = a["mean_level_near_paddle"]
    assert mwl["gauge"] == "eta_x0.300" and len(mwl["block_means"]) == 8
    assert abs(mwl["spread_over_H"]) < 0.2
    for key in ("crest_velocity", "undertow", "spread", "ratio", "wave_height"):
        assert key in UNITS
