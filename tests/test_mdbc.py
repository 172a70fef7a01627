"""Modified DBC walls (``boundary="mdbc"``, English et al. 2022) in still water: the walls'
pressure and the force on a submerged box are hydrostatic."""

from __future__ import annotations

import numpy as np
import pytest

import watersim as ws
from watersim import numerics as nm

DEPTH = 0.4
DP = 0.02
BOX = ((0.3, 0.12), (0.5, 0.24))
"""A box 10 x 6 dp, 8 dp under the surface and 6 dp over the floor."""
SENSORS = ((0.41, 0.23), (0.31, 0.17), (0.49, 0.13), (0.41, 0.13), (0.61, -0.01),
           (0.81, 0.19))
"""Pressure sensors on the walls: the wall particles of the first layer under the box's top,
inside its sides and above its underside, under the floor and behind the far wall, where the
wall model's own pressure is read. (The fluid's Shepard-interpolated pressure half a dp off a
wall averages over water on one side only, lower or deeper than the point: 8 % low half a dp
over the box's top, 5 % high half a dp under it, whatever the wall model.)"""


@pytest.mark.parametrize("slip", [None, "no_slip"])
def test_mdbc_walls_hold_still_water_hydrostatic(slip: str | None) -> None:
    scene = ws.Flume(length=0.8, depth=DEPTH).scene(
        ws.TabulatedMotion(t=(0.0, 1.0), x=(0.0, 0.0)), dp=DP, until=0.1,
        sample_interval=0.01, boundary=nm.Mdbc(slip=slip),
        bodies=[ws.BoxStructure("block", *BOX)],
        gauges=[ws.ForceGauge(structure="block", point=(0.4, 0.18), interval=0.01)])
    assert scene.resolved_scene()["boundary"]["model"] == "mdbc"
    sim = scene.build()
    sim.run()
    force = sim.gauges.records["block"]
    settled = force["t"] >= 0.02
    (lo_x, lo_z), (hi_x, hi_z) = BOX
    rho_g = scene.core_value("rho0") * scene.g
    buoyancy = rho_g * (hi_x - lo_x) * (hi_z - lo_z)
    fx, fz = force["force"][settled, 0].mean(), force["force"][settled, 1].mean()
    print(f"\n{slip}: Fz / rho g V = {fz / buoyancy:.4f}, Fx / rho g V = {fx / buoyancy:.2e}")
    assert abs(fz / buoyancy - 1.0) < 0.02
    assert abs(fx) < 0.01 * buoyancy

    pos, kinds, pressure = sim.positions, sim.kinds, sim.pressures
    ratio = []
    for x, z in SENSORS:
        dist = np.hypot(pos[:, 0] - x, pos[:, 1] - z) + np.where(kinds == 0, np.inf, 0.0)
        i = int(np.argmin(dist))
        assert dist[i] < 0.25 * DP, (x, z)
        ratio.append(pressure[i] / (rho_g * (DEPTH - pos[i, 1])))
    print(f"{slip}: p / rho g (d - z) = {np.round(ratio, 4)}")
    assert np.all(np.abs(np.array(ratio) - 1.0) < 0.02), ratio


def test_buchner_metrics_integrate_and_high_pass() -> None:
    """The Buchner cases' impulse is the trapezoidal integral with interpolated ends, and the
    high-pass RMS is zero for a line and the amplitude over sqrt(2) for a fast sine."""
    from watersim.validation import buchner as bu

    t = np.linspace(0.0, 10.0, 2001)
    assert bu.pressure_impulse(t, 2.0 * t, 1.0, 3.0) == pytest.approx(8.0, rel=1e-12)
    assert bu.high_pass_rms(t, 0.3 + 0.1 * t, 1.0, 0.25) == pytest.approx(0.0, abs=1e-12)
    fast = 0.5 * np.sin(2.0 * np.pi * t / 0.05)  # 0.25 holds five whole periods
    assert bu.high_pass_rms(t, fast, 1.0, 0.25) == pytest.approx(0.5 / np.sqrt(2.0), rel=0.02)
    tr, pr = bu.buchner_reference("pysph")
    assert np.all(np.diff(tr) >= 0.0) and 0.68 < pr[(tr > 2.0) & (tr < 3.5)].max() < 0.70
